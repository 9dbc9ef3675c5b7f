//! Adaptive sampling (the patent's reduced-scale repetition) against analytic truth: which
//! pixels it refines, the layout and weights of the refined samples, the unbiased coverage of
//! a half-plane, its invariance to the bucket layout, and that it changes nothing when no
//! pixel disagrees.

use reyes_hider::{
    Adaptive, Frame, Hider, HiderConfig, Micropolygon, Pattern, RefinedSample, Scratch, disagree,
};

/// Area of pixel `(x, y)` on the side `a*x + b*y <= c`.
fn area(a: f64, b: f64, c: f64, x: u32, y: u32) -> f64 {
    reyes_testkit::geometry::pixel_below(a, b, c, x as f64, y as f64)
}

/// The half-plane `a*x + b*y <= c` (raster) as one big opaque quad at depth 5.
fn half_plane(a: f64, b: f64, c: f64) -> Micropolygon {
    let (px, py) = (a * c, b * c);
    let (dx, dy) = (-b, a);
    let p =
        |s: f64, back: f64| [(px + s * dx - back * a) as f32, (py + s * dy - back * b) as f32, 5.0];
    Micropolygon::opaque(
        [p(-500.0, 0.0), p(500.0, 0.0), p(500.0, 500.0), p(-500.0, 500.0)],
        [[1.0; 3]; 4],
    )
}

/// One render of a 32 x 32 frame in buckets of `bw`: for every global pixel, its value
/// (area-weighted refined samples, or the plain mean of its own samples) and its refined
/// samples in global coordinates.
fn render(cfg: HiderConfig, mp: &Micropolygon, bw: u32) -> Vec<(f64, Vec<RefinedSample>)> {
    let frame = Frame::new(32, 32, 0, bw, bw);
    let hider = Hider::new(cfg, frame);
    let ns = hider.ns();
    let mut out = vec![(0.0, Vec::new()); 32 * 32];
    let mut scratch = Scratch::new();
    for b in 0..frame.bucket_count() {
        let (left, top) = frame.bucket_origin(b);
        let o = hider.render_bucket(b, std::slice::from_ref(mp), &[0], &mut scratch);
        for pixel in 0..(bw * bw) as usize {
            let (gx, gy) = (left + (pixel as u32 % bw) as i32, top + (pixel as u32 / bw) as i32);
            if gx >= 32 || gy >= 32 {
                continue;
            }
            let own: f64 = o.rgba[pixel * ns..(pixel + 1) * ns].iter().map(|c| c[3] as f64).sum();
            out[(gy * 32 + gx) as usize].0 = own / ns as f64;
        }
        for r in o.refined {
            let (gx, gy) = (left + r.x.floor() as i32, top + r.y.floor() as i32);
            let cell = &mut out[(gy * 32 + gx) as usize];
            cell.0 += (r.weight * r.rgba[3]) as f64;
            let g = RefinedSample { x: r.x + left as f32, y: r.y + top as f32, ..*r };
            cell.1.push(g);
        }
    }
    out
}

fn config(max_level: u32, threshold: f32, seed: u64) -> HiderConfig {
    HiderConfig {
        nx: 4,
        ny: 4,
        pattern: Pattern::SobolJoint,
        adaptive: Some(Adaptive { max_level, threshold }),
        seed,
        ..HiderConfig::default()
    }
}

#[test]
fn refined_pixels_are_those_that_disagree_and_their_leaves_tile_them() {
    let (a, b, c) = (0.6f64, 0.8f64, 16.3f64);
    let mp = half_plane(a, b, c);
    let plain = render(HiderConfig { adaptive: None, ..config(2, 0.1, 1) }, &mp, 16);
    let refined = render(config(2, 0.1, 1), &mp, 16);
    let mut count = 0;
    for (i, ((v0, none), (_, samples))) in plain.iter().zip(&refined).enumerate() {
        assert!(none.is_empty());
        let (x, y) = ((i % 32) as u32, (i / 32) as u32);
        // A pixel of one colour is never refined; one whose samples disagree always is.
        let mixed = *v0 > 0.0 && *v0 < 1.0;
        assert_eq!(!samples.is_empty(), mixed, "pixel {x},{y} value {v0}");
        if samples.is_empty() {
            continue;
        }
        count += 1;
        // Weights: each leaf of level L holds 16 samples of weight 4^-L / 16, and the leaves
        // partition the pixel, so the weights sum to 1; every sample lies in the pixel, and the
        // 16 samples of a leaf are one per stratum of the leaf's own 4 x 4 grid.
        let total: f64 = samples.iter().map(|r| r.weight as f64).sum();
        assert!((total - 1.0).abs() < 1e-5, "pixel {x},{y}: weights sum to {total}");
        for leaf in samples.chunks(16) {
            let w = leaf[0].weight;
            assert!(leaf.iter().all(|r| r.weight == w));
            let side = (w as f64 * 16.0).sqrt(); // 2^-L
            let (lx, ly) = ((leaf[0].x as f64 / side).floor(), (leaf[0].y as f64 / side).floor());
            let mut seen = [false; 16];
            for r in leaf {
                assert!(r.x.floor() as u32 == x && r.y.floor() as u32 == y);
                let u = r.x as f64 / side - lx;
                let v = r.y as f64 / side - ly;
                assert!((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v), "outside its leaf");
                let q = ((u * 4.0) as usize) * 4 + (v * 4.0) as usize;
                assert!(!std::mem::replace(&mut seen[q], true), "two samples in one stratum");
            }
        }
    }
    assert!(count > 20, "only {count} pixels refined");
}

#[test]
fn refined_coverage_is_unbiased_and_more_accurate_than_the_base_samples() {
    // Over many random edges, the area-weighted value of every refined pixel against its exact
    // coverage. Given the quadtree each leaf's mean is stratified and unbiased; the split
    // decision adds a bias (a pixel or leaf whose 16 samples agree keeps them), which this test
    // cannot resolve: the mean signed error must be within 4 standard errors of zero (errors
    // of different pixels treated as independent). And the error must fall: for a pixel whose
    // crossed leaves are all refined to level 2, stratified sampling predicts an RMS about
    // sqrt(256 / 5.5) = 6.8 times below the base 4 x 4 pixel's (about 5.5 of its 16 leaves are
    // crossed, each estimated as well as a base pixel, with weight 1/16). Pixels and leaves
    // whose samples all agree though the edge crosses them stay unrefined and keep the base
    // error, so only a factor 2 is required; no refinement at all would give 1.
    let (mut errs, mut base_errs) = (Vec::new(), Vec::new());
    for trial in 0..24u64 {
        let ang = trial as f64 * 2.399;
        let (a, b) = (ang.cos(), ang.sin());
        let c = a * 16.0 + b * 16.0 + (trial as f64 * 0.37).fract();
        let mp = half_plane(a, b, c);
        let base = render(HiderConfig { adaptive: None, ..config(2, 0.05, trial) }, &mp, 16);
        let refined = render(config(2, 0.05, trial), &mp, 16);
        for (i, ((v0, _), (v, _))) in base.iter().zip(&refined).enumerate() {
            let truth = area(a, b, c, (i % 32) as u32, (i / 32) as u32);
            if truth > 0.0 && truth < 1.0 {
                errs.push(v - truth);
                base_errs.push(v0 - truth);
            }
        }
    }
    let n = errs.len() as f64;
    let mean = errs.iter().sum::<f64>() / n;
    let rms = (errs.iter().map(|e| e * e).sum::<f64>() / n).sqrt();
    let base_rms = (base_errs.iter().map(|e| e * e).sum::<f64>() / n).sqrt();
    let se = rms / n.sqrt();
    assert!(mean.abs() < 4.0 * se, "mean error {mean} (se {se})");
    assert!(rms < base_rms / 2.0, "refined rms {rms} vs base {base_rms}");
}

#[test]
fn refined_samples_depend_only_on_the_pixel_not_the_bucket_layout() {
    let mp = half_plane(0.28, -0.96, -12.0);
    let a = render(config(3, 0.1, 9), &mp, 8);
    let b = render(config(3, 0.1, 9), &mp, 16);
    assert_eq!(a, render(config(3, 0.1, 9), &mp, 8), "deterministic");
    for (p, q) in a.iter().zip(&b) {
        assert_eq!(p.1, q.1);
        assert_eq!(p.0.to_bits(), q.0.to_bits());
    }
}

#[test]
fn nothing_changes_when_no_pixel_disagrees() {
    // A threshold no spread can exceed refines nothing: the per-sample output is the plain
    // render's, bit for bit.
    let mp = half_plane(0.6, 0.8, 16.3);
    let frame = Frame::new(32, 32, 0, 16, 16);
    let run = |cfg: HiderConfig| {
        let hider = Hider::new(cfg, frame);
        let mut scratch = Scratch::new();
        let o = hider.render_bucket(0, std::slice::from_ref(&mp), &[0], &mut scratch);
        (o.rgba.to_vec(), o.refined.len(), scratch.stats.refined_pixels)
    };
    let plain = run(HiderConfig { adaptive: None, ..config(2, 0.1, 4) });
    assert_eq!(run(config(2, 1.0, 4)), plain);
    assert_eq!(run(config(0, 0.0, 4)), plain);
    let (_, refined, pixels) = run(config(2, 0.1, 4));
    assert!(refined > 0 && pixels > 0);
    assert!(!disagree(&[[0.5; 4], [0.55; 4]], 0.1) && disagree(&[[0.5; 4], [0.65; 4]], 0.1));
}
