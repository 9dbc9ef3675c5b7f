//! Hider against analytic truth: stratified coverage of known shapes, and the three sampling
//! paths (static, lens, moving) agreeing on the same input.

use reyes_hider::{
    Frame, Hider, HiderConfig, LensSetup, LensShape, Micropolygon, Pairing, Pattern, Scratch, flags,
};
use reyes_sampling::SplitMix64;

fn quad(p: [[f32; 2]; 4], z: f32, color: [f32; 3]) -> Micropolygon {
    Micropolygon::opaque(p.map(|q| [q[0], q[1], z]), [color; 4])
}

/// Area of the unit square [0,1]^2 on the side `a*x + b*y <= c`.
fn clipped_area(a: f64, b: f64, c: f64) -> f64 {
    reyes_testkit::geometry::pixel_below(a, b, c, 0.0, 0.0)
}

/// Uniform numbers in [0, 1) for test inputs.
struct Lcg(SplitMix64);
impl Lcg {
    fn new(seed: u64) -> Lcg {
        Lcg(SplitMix64::from_state(seed))
    }
    fn next(&mut self) -> f64 {
        self.0.next_f64()
    }
}

/// Coverage of a one-pixel image by a half-plane, measured as the mean alpha of the pixel's
/// samples (a 1-pixel box filter), for a random edge through the pixel.
fn coverage_error(n: u32, trial: u64, rng: &mut Lcg) -> f64 {
    // A line through a random point of the pixel at a random angle.
    let (px, py) = (rng.next(), rng.next());
    let ang = rng.next() * std::f64::consts::TAU;
    let (a, b) = (ang.cos(), ang.sin());
    let c = a * px + b * py;
    // The half-plane a*x + b*y <= c as a big quad: along the line +-50, back 50.
    let (dx, dy) = (-b, a);
    let p0 = (px - 50.0 * dx, py - 50.0 * dy);
    let p1 = (px + 50.0 * dx, py + 50.0 * dy);
    let q = |p: (f64, f64)| [(p.0 - 50.0 * a) as f32, (p.1 - 50.0 * b) as f32];
    let mp =
        quad([[p0.0 as f32, p0.1 as f32], [p1.0 as f32, p1.1 as f32], q(p1), q(p0)], 5.0, [1.0; 3]);
    let frame = Frame::new(1, 1, 0, 1, 1);
    let cfg = HiderConfig { nx: n, ny: n, seed: trial, ..HiderConfig::default() };
    let hider = Hider::new(cfg, frame);
    let mut scratch = Scratch::new();
    let out = hider.render_bucket(0, &[mp], &[0], &mut scratch);
    let measured = out.rgba.iter().map(|s| s[3] as f64).sum::<f64>() / out.rgba.len() as f64;
    measured - clipped_area(a, b, c)
}

#[test]
fn stratified_coverage_error_shrinks_within_the_stratified_bound() {
    // Theory: with an n x n grid and one uniform sample per stratum, only the strata the edge
    // cuts contribute variance, each a Bernoulli indicator (variance <= 1/4) weighted 1/n^2.
    // A line cuts at most 2n - 1 cells of an n x n grid, so
    //     Var <= (2n - 1) / 4 / n^4,   RMS <= sqrt(2n - 1) / (2 n^2).
    // (Pure random sampling would give RMS ~ 1/(2n) instead, which is larger for n > 1.)
    // The RMS over T independent trials estimates the true RMS; with T = 400 its relative
    // standard error is below 1/sqrt(2T) ~ 3.5%, so comparing against the bound plus 15%
    // (four standard errors) cannot fail for a correct stratified sampler.
    let trials = 400;
    let mut rms = Vec::new();
    for n in [2u32, 4, 8] {
        let mut rng = Lcg::new(0x5eed + n as u64);
        let sq: f64 = (0..trials).map(|t| coverage_error(n, t, &mut rng).powi(2)).sum();
        rms.push((n, (sq / trials as f64).sqrt()));
    }
    reyes_testkit::geometry::assert_stratified(&rms, &format!("{trials} trials"));
}

/// A bucket of random small quads at random depths, some half transparent.
fn random_bucket(seed: u64, count: usize) -> Vec<Micropolygon> {
    let mut rng = Lcg::new(seed);
    (0..count)
        .map(|_| {
            let (cx, cy) = (rng.next() * 18.0 - 1.0, rng.next() * 18.0 - 1.0);
            let z = 2.0 + rng.next() as f32 * 8.0;
            let p: [[f32; 2]; 4] = std::array::from_fn(|k| {
                let ang = k as f64 * std::f64::consts::FRAC_PI_2 + rng.next() * 0.8;
                let r = 0.5 + rng.next() * 1.5;
                [(cx + r * ang.cos()) as f32, (cy + r * ang.sin()) as f32]
            });
            let mut m = quad(p, z, [rng.next() as f32, rng.next() as f32, rng.next() as f32]);
            for (k, v) in m.v.iter_mut().enumerate() {
                v[2] += 0.3 * k as f32; // tilted, so depth ranges overlap and lerps happen
            }
            if rng.next() < 0.3 {
                m.flags &= !flags::OPAQUE;
                m.trans = [[0.5; 3]; 4];
                m.color = m.color.map(|c| c.map(|x| x * 0.5));
            }
            m
        })
        .collect()
}

fn render(cfg: HiderConfig, mps: &[Micropolygon]) -> (Vec<[f32; 4]>, reyes_hider::Stats) {
    let frame = Frame::new(16, 16, 0, 16, 16);
    let hider = Hider::new(cfg, frame);
    let list: Vec<u32> = (0..mps.len() as u32).collect();
    let mut scratch = Scratch::new();
    let out = hider.render_bucket(0, mps, &list, &mut scratch).rgba.to_vec();
    (out, scratch.stats)
}

#[test]
fn static_lens_and_moving_paths_agree_on_the_same_input() {
    let mps = random_bucket(11, 120);
    let cases = [Pairing::Original, Pairing::Decorrelated]
        .into_iter()
        .flat_map(|p| [Pattern::Fig6, Pattern::SobolJoint].map(move |q| (p, q)));
    for (pairing, pattern) in cases {
        let base = HiderConfig { time_pairing: pairing, pattern, ..HiderConfig::default() };
        let (p_img, p_stats) = render(base, &mps);
        // Path D with a zero-radius lens: every shift is zero.
        let lens0 = HiderConfig { lens: Some(LensSetup::new(0.0, 5.0, 100.0, -100.0)), ..base };
        let (d_img, d_stats) = render(lens0, &mps);
        // Path M with zero motion.
        let moving: Vec<Micropolygon> =
            mps.iter().map(|m| Micropolygon { flags: m.flags | flags::MOVING, ..*m }).collect();
        let (m_img, m_stats) = render(base, &moving);
        assert_eq!(p_img, d_img, "{pairing:?} {pattern:?}: lens path differs");
        assert_eq!(p_img, m_img, "{pairing:?} {pattern:?}: moving path differs");
        assert_eq!(p_stats.hits, d_stats.hits);
        assert_eq!(p_stats.hits, m_stats.hits);
        assert!(p_stats.lerps > 0, "the test must exercise lazy depth");
    }
}

#[test]
fn bound_culling_never_drops_a_hit() {
    // Moving and defocused quads: every hit found by testing all samples must also be found
    // with Appendix A's per-sample sliding bound and bounddof, and the image must not change.
    // Slow (up to 6 pixels per shutter) and fast (up to 60, several times a bucket, where a
    // moving micropolygon's rows are scanned only over the stretch of the slice it can meet
    // them in) quads.
    let mut rng = Lcg::new(99);
    let moving = |rng: &mut Lcg, reach: f64, count: usize| -> Vec<Micropolygon> {
        random_bucket(5, count)
            .into_iter()
            .map(|mut m| {
                let mut s = || (rng.next() * 2.0 * reach - reach) as f32;
                let s = [s(), s(), 0.0];
                m.speed = [s; 4];
                m.speed[2][0] += 0.7; // a little deformation
                m.speed[1][1] -= 0.4;
                m.flags |= flags::MOVING;
                m
            })
            .collect()
    };
    let mps = moving(&mut rng, 6.0, 80);
    let fast = moving(&mut rng, 60.0, 800);
    let still = random_bucket(5, 80);
    for pattern in [Pattern::Fig6, Pattern::Fig7, Pattern::Regular, Pattern::SobolJoint] {
        for lens in [None, Some(LensSetup::new(0.2, 5.0, 200.0, -200.0))] {
            for lens_shape in [LensShape::Disk, LensShape::OriginalSquare] {
                for input in [&mps, &fast, &still] {
                    let cfg = HiderConfig { pattern, lens, lens_shape, ..HiderConfig::default() };
                    let (a, sa) = render(cfg, input);
                    let (b, sb) = render(HiderConfig { scan_all: true, ..cfg }, input);
                    assert_eq!(sa.hits, sb.hits, "{pattern:?} lens {}", lens.is_some());
                    assert_eq!(a, b);
                    assert!(sa.hits + sa.misses < sb.hits + sb.misses, "culling must save tests");
                }
            }
        }
    }
}

#[test]
fn opaque_front_hides_what_is_behind() {
    // Two full-bucket quads: the nearer one, inserted last or first, owns every sample.
    let near = quad([[-1.0, -1.0], [17.0, -1.0], [17.0, 17.0], [-1.0, 17.0]], 2.0, [1.0, 0.0, 0.0]);
    let far = quad([[-1.0, -1.0], [17.0, -1.0], [17.0, 17.0], [-1.0, 17.0]], 4.0, [0.0, 1.0, 0.0]);
    for order in [[near, far], [far, near]] {
        let (img, _) = render(HiderConfig::default(), &order);
        assert!(img.iter().all(|s| *s == [1.0, 0.0, 0.0, 1.0]));
    }
}

#[test]
fn hither_crossing_quad_is_clipped_per_sample() {
    // A quad whose depth goes from 0.05 (left, in front of hither 0.1) to 0.15 across
    // x in [0, 16]: samples with interpolated z < 0.1 (x < 8) are clipped.
    let mut m = quad([[0.0, -1.0], [16.0, -1.0], [16.0, 17.0], [0.0, 17.0]], 0.1, [1.0; 3]);
    m.v[0][2] = 0.05;
    m.v[3][2] = 0.05;
    m.v[1][2] = 0.15;
    m.v[2][2] = 0.15;
    m.flags |= flags::HITHER_YON_CROSSING;
    let (img, _) = render(HiderConfig::default(), &[m]);
    let ns = 16;
    for pixel in 0..256 {
        let x = pixel % 16;
        let cov: f32 = (0..ns).map(|s| img[pixel * ns + s][3]).sum::<f32>() / ns as f32;
        if x <= 5 {
            assert_eq!(cov, 0.0, "pixel x {x} in front of hither must be clipped");
        } else if x >= 10 {
            assert_eq!(cov, 1.0, "pixel x {x} behind hither must be kept");
        }
    }
}

#[test]
fn gouraud_reproduces_vertex_colours_and_varies_smoothly() {
    use reyes_hider::gouraud;
    let mut m = quad([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]], 3.0, [0.0; 3]);
    m.color = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]];
    m.trans = [[0.0; 3], [0.5; 3], [0.25; 3], [1.0; 3]];
    let rel = |x: f32, y: f32| m.v.map(|p| [p[0] - x, p[1] - y, p[2]]);
    // At each vertex: exactly that vertex's colour and transmittance.
    for k in 0..4 {
        let (c, t) = gouraud(&rel(m.v[k][0], m.v[k][1]), &m);
        assert_eq!((c, t), (m.color[k], m.trans[k]), "vertex {k}");
    }
    // Along a line across the quad, values change smoothly: Shepard weights are Lipschitz
    // away from the vertices, so with steps of 1/64 pixel no channel may jump by more than a
    // small multiple of the step (a flat lookup would jump by a whole colour difference, 1).
    let mut prev = gouraud(&rel(0.25, 1.3), &m).0;
    for i in 1..=224 {
        let x = 0.25 + i as f32 / 64.0;
        let c = gouraud(&rel(x, 1.3), &m).0;
        for a in 0..3 {
            assert!((c[a] - prev[a]).abs() < 0.05, "jump at x = {x}: {prev:?} -> {c:?}");
            assert!((0.0..=1.0).contains(&c[a]), "convex combination");
        }
        prev = c;
    }
}
