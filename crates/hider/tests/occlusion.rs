//! Occlusion culling in the hider (`HiderConfig::occlusion_cull`): the per-sample composites,
//! colour and depth, are the same bit for bit with and without it, on every path (static,
//! lens, moving, both), for opaque and transparent quads at random; and where exact depths
//! tie, the point the port's `findfront` picks (the first in list order) is still picked,
//! although culling samples the micropolygons in another order.

use reyes_hider::{Frame, Hider, HiderConfig, LensSetup, Micropolygon, Pattern, Scratch, flags};
use reyes_sampling::SplitMix64;

/// One bucket of `size` x `size` pixels: per-sample colours and depths, and the statistics.
fn render(cfg: HiderConfig, size: u32, mps: &[Micropolygon]) -> (Vec<u32>, reyes_hider::Stats) {
    let hider = Hider::new(cfg, Frame::new(size, size, 0, size, size));
    let list: Vec<u32> = (0..mps.len() as u32).collect();
    let mut scratch = Scratch::new();
    let out = hider.render_bucket(0, mps, &list, &mut scratch);
    let mut bits: Vec<u32> = out.rgba.iter().flatten().map(|v| v.to_bits()).collect();
    bits.extend(out.z.iter().map(|v| v.to_bits()));
    (bits, scratch.stats)
}

/// Random quads over a 16-pixel bucket at depths 2 to 10, tilted, some transparent, some
/// moving (in x, y and z), in random order.
fn random_bucket(seed: u64, count: usize, moving: bool) -> Vec<Micropolygon> {
    let mut rng = SplitMix64::from_state(seed);
    let mut next = || rng.next_f64();
    (0..count)
        .map(|_| {
            let (cx, cy) = (next() * 18.0 - 1.0, next() * 18.0 - 1.0);
            let z = 2.0 + next() as f32 * 8.0;
            let p: [[f32; 3]; 4] = std::array::from_fn(|k| {
                let ang = k as f64 * std::f64::consts::FRAC_PI_2 + next() * 0.8;
                let r = 0.5 + next() * 2.5;
                [(cx + r * ang.cos()) as f32, (cy + r * ang.sin()) as f32, z + 0.3 * k as f32]
            });
            let c = [next() as f32, next() as f32, next() as f32];
            let mut m = Micropolygon::opaque(p, [c; 4]);
            if next() < 0.25 {
                m.flags &= !flags::OPAQUE;
                m.trans = [[0.5; 3]; 4];
                m.color = m.color.map(|c| c.map(|x| x * 0.5));
            }
            if moving && next() < 0.6 {
                let s = [(next() * 8.0 - 4.0) as f32, (next() * 8.0 - 4.0) as f32, next() as f32];
                m.speed = [s; 4];
                m.speed[1][2] -= 0.5;
                m.flags |= flags::MOVING;
            }
            m
        })
        .collect()
}

#[test]
fn composites_are_the_same_with_and_without_culling_on_every_path() {
    let mut culled = 0;
    for seed in 0..6u64 {
        for moving in [false, true] {
            let mps = random_bucket(seed, 400, moving);
            for lens in [None, Some(LensSetup::new(0.1, 5.0, 200.0, -200.0))] {
                for pattern in [Pattern::Fig6, Pattern::Regular] {
                    let on = HiderConfig { lens, pattern, seed, ..HiderConfig::default() };
                    let off = HiderConfig { occlusion_cull: false, ..on };
                    let (a, sa) = render(on, 16, &mps);
                    let (b, sb) = render(off, 16, &mps);
                    let what = format!("seed {seed} moving {moving} lens {}", lens.is_some());
                    assert!(a == b, "{what} {pattern:?}: composites differ");
                    assert_eq!((sb.occlusion_culled, sb.occluded_tests), (0, 0));
                    assert!(sa.hits + sa.misses < sb.hits + sb.misses, "{what}: no tests saved");
                    culled += sa.occlusion_culled;
                }
            }
        }
    }
    assert!(culled > 0, "no micropolygon was culled whole");
}

#[test]
fn tied_depths_keep_the_list_order() {
    // One pixel, one regular sample. Three unit-half squares centred on the sample, so the
    // Manhattan distances to their vertices are all 0.5 and `lerpz` is exactly the mean of
    // the vertex depths: C (blue) from depth 3 to 9, exact depth 6; B (green) 4 to 6, exact
    // 5; A (red) flat at 5. In list order A, B, C the sample's list is C, B, A (most recent
    // first). `findfront` starts from C (smallest minz), lerps it to 6, then walks the list
    // and takes the first point nearer than the front: B, at 5, and A (also 5) is not nearer.
    // Culling samples C, B, A (nearest depth first); prepending would make the list A, B, C
    // and show A instead.
    let cfg =
        HiderConfig { nx: 1, ny: 1, pattern: Pattern::Regular, seed: 1, ..HiderConfig::default() };
    let hider = Hider::new(cfg, Frame::new(1, 1, 0, 1, 1));
    let s = hider.bucket_samples(0);
    let (sx, sy) = (s.x[0], s.y[0]);
    assert_eq!((sx, sy), (0.5, 0.5), "the regular sample is at the pixel centre");
    let square = |z: [f32; 4], color: [f32; 3]| {
        let corners = [[-0.25, -0.25], [0.25, -0.25], [0.25, 0.25], [-0.25, 0.25]];
        let v = std::array::from_fn(|k| [sx + corners[k][0], sy + corners[k][1], z[k]]);
        Micropolygon::opaque(v, [color; 4])
    };
    let a = square([5.0; 4], [1.0, 0.0, 0.0]);
    let b = square([4.0, 6.0, 4.0, 6.0], [0.0, 1.0, 0.0]);
    let c = square([3.0, 9.0, 3.0, 9.0], [0.0, 0.0, 1.0]);
    for cull in [false, true] {
        let hider =
            Hider::new(HiderConfig { occlusion_cull: cull, ..cfg }, Frame::new(1, 1, 0, 1, 1));
        let mut scratch = Scratch::new();
        let out = hider.render_bucket(0, &[a, b, c], &[0, 1, 2], &mut scratch);
        assert_eq!(out.rgba[0], [0.0, 1.0, 0.0, 1.0], "culling {cull}: B is seen");
        assert_eq!(out.z[0], 5.0);
    }
}

#[test]
fn an_opaque_wall_culls_what_is_behind_it() {
    // A full-bucket opaque quad in front of 50 quads: all 50 are culled whole once the wall
    // has been sampled, whatever their place in the list, and the image is the wall's.
    let wall = Micropolygon::opaque(
        [[-1.0, -1.0, 1.0], [17.0, -1.0, 1.0], [17.0, 17.0, 1.0], [-1.0, 17.0, 1.0]],
        [[0.2, 0.4, 0.6]; 4],
    );
    let mut mps = random_bucket(3, 50, true);
    mps.insert(25, wall);
    let (a, sa) = render(HiderConfig::default(), 16, &mps);
    let (b, _) = render(HiderConfig { occlusion_cull: false, ..HiderConfig::default() }, 16, &mps);
    assert!(a == b);
    assert_eq!(sa.occlusion_culled, 50);
}
