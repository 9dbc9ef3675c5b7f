//! Temporal sampling against analytic truth: the space-time coverage of a moving edge, the
//! distribution of sample times for each shutter shape, decorrelation of time from sub-pixel
//! position, and piecewise-linear motion segments.

use reyes_hider::{
    Frame, Hider, HiderConfig, Micropolygon, Pairing, Pattern, Scratch, ShutterShape, TimePattern,
    flags,
};

fn moving_rect(x0: f32, x1: f32, y0: f32, y1: f32, dx: f32, time: [f32; 2]) -> Micropolygon {
    let v = [[x0, y0, 5.0], [x1, y0, 5.0], [x1, y1, 5.0], [x0, y1, 5.0]];
    Micropolygon {
        v,
        speed: [[dx, 0.0, 0.0]; 4],
        color: [[1.0; 3]; 4],
        trans: [[0.0; 3]; 4],
        flags: flags::OPAQUE | flags::MOVING,
        csg_tree: 0,
        csg_node: 0,
        glass_opacity: 0.0,
        time,
    }
}

/// Per-pixel coverage (mean alpha of the pixel's samples, a one-pixel box filter) of a
/// 64 x 64 image rendered with one bucket.
fn coverage(cfg: HiderConfig, mps: &[Micropolygon]) -> Vec<f64> {
    let frame = Frame::new(64, 64, 0, 64, 64);
    let hider = Hider::new(cfg, frame);
    let ns = hider.ns();
    let list: Vec<u32> = (0..mps.len() as u32).collect();
    let mut scratch = Scratch::new();
    let out = hider.render_bucket(0, mps, &list, &mut scratch);
    (0..64 * 64)
        .map(|p| {
            out.rgba[p * ns..(p + 1) * ns].iter().map(|s| s[3] as f64).sum::<f64>() / ns as f64
        })
        .collect()
}

/// Exact time-averaged coverage of pixel column [x, x+1] by the interval [a + d*t, b + d*t],
/// with t distributed by `shape`: integrate the overlap length against the density with a
/// fine midpoint rule (the integrand is piecewise linear, so 20,000 steps are exact to ~1e-8).
fn trapezoid(x: f64, a: f64, b: f64, d: f64, shape: ShutterShape) -> f64 {
    let n = 20_000;
    (0..n)
        .map(|i| {
            let t = (i as f64 + 0.5) / n as f64;
            let (lo, hi) = ((a + d * t).max(x), (b + d * t).min(x + 1.0));
            (hi - lo).max(0.0) * shape.density(t as f32) as f64 / n as f64
        })
        .sum()
}

#[test]
fn moving_edge_matches_the_space_time_trapezoid() {
    // A 4-pixel-wide bar moving 8 pixels right over the shutter, covering all 64 rows.
    // Each pixel's coverage is the time-average of its overlap with the bar: a trapezoid
    // profile along the row. Every row is an independent estimate of that profile.
    //
    // Tolerance: a pixel's estimate is the mean of NS = 64 indicator samples, one per spatial
    // stratum and one per time stratum (a Latin-hypercube design in (cell, time)), whose
    // variance is at most NS/(NS-1) times that of NS independent samples (Owen 1997), i.e.
    // <= 1/(4 (NS-1)). Averaged over 64 rows, the column mean has standard deviation
    // <= sqrt(1/(4*63))/8 = 0.0079; four standard deviations is 0.0315.
    for shape in [ShutterShape::Uniform, ShutterShape::Gradual { ramp: 0.3 }] {
        let cfg = HiderConfig { nx: 8, ny: 8, shutter: shape, ..HiderConfig::default() };
        let bar = moving_rect(20.25, 24.25, -1.0, 65.0, 8.0, [0.0, 1.0]);
        let cov = coverage(cfg, &[bar]);
        for x in 14..38 {
            let mean: f64 = (0..64).map(|y| cov[y * 64 + x]).sum::<f64>() / 64.0;
            let exact = trapezoid(x as f64, 20.25, 24.25, 8.0, shape);
            assert!((mean - exact).abs() < 0.0315, "{shape:?} column {x}: {mean} vs {exact}");
        }
    }
}

/// Kolmogorov-Smirnov distance between the sample times of many buckets and a shutter's CDF.
fn ks_distance(cfg: HiderConfig, shape: ShutterShape) -> (f64, usize) {
    let frame = Frame::new(64, 64, 0, 16, 16);
    let hider = Hider::new(cfg, frame);
    let mut times: Vec<f64> = Vec::new();
    for b in 0..frame.bucket_count() {
        times.extend(hider.bucket_samples(b).t.iter().map(|&t| t as f64));
    }
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let cdf = |t: f64| {
        // Integrate the density numerically (piecewise linear: midpoint rule is exact enough).
        let steps = 2000;
        (0..steps)
            .map(|i| {
                shape.density(((i as f64 + 0.5) / steps as f64 * t) as f32) as f64 * t
                    / steps as f64
            })
            .sum::<f64>()
    };
    let mut d: f64 = 0.0;
    for (i, &t) in times.iter().enumerate().step_by(7) {
        let f = cdf(t);
        d = d.max((f - i as f64 / n as f64).abs()).max((f - (i + 1) as f64 / n as f64).abs());
    }
    (d, n)
}

#[test]
fn sample_times_follow_the_shutter_density() {
    // KS test at a fixed seed: for n independent samples the 0.1% critical value of the
    // Kolmogorov distance is 1.95/sqrt(n); stratified samples are closer still. The wrong
    // density (uniform times tested against the gradual shutter and vice versa) must fail.
    let shapes = [
        ShutterShape::Uniform,
        ShutterShape::Gradual { ramp: 0.25 },
        ShutterShape::Gradual { ramp: 0.5 },
    ];
    for shape in shapes {
        let cfg = HiderConfig { shutter: shape, ..HiderConfig::default() };
        let (d, n) = ks_distance(cfg, shape);
        let critical = 1.95 / (n as f64).sqrt();
        assert!(d < critical, "{shape:?}: KS distance {d} >= {critical}");
        let other = if shape == ShutterShape::Uniform { shapes[1] } else { ShutterShape::Uniform };
        let (d_wrong, _) = ks_distance(cfg, other);
        assert!(d_wrong > 5.0 * critical, "{shape:?} vs {other:?}: KS {d_wrong} should reject");
    }
}

/// Correlation coefficient between sample time and sub-pixel y over one bucket.
fn time_y_correlation(pairing: Pairing) -> f64 {
    let cfg = HiderConfig { time_pairing: pairing, ..HiderConfig::default() };
    let hider = Hider::new(cfg, Frame::new(64, 64, 0, 16, 16));
    let s = hider.bucket_samples(5);
    let n = s.t.len() as f64;
    let ys: Vec<f64> = s.y.iter().map(|&y| y as f64 - (y as f64).floor()).collect();
    let ts: Vec<f64> = s.t.iter().map(|&t| t as f64).collect();
    let (my, mt) = (ys.iter().sum::<f64>() / n, ts.iter().sum::<f64>() / n);
    let cov: f64 = ys.iter().zip(&ts).map(|(y, t)| (y - my) * (t - mt)).sum::<f64>() / n;
    let sy = (ys.iter().map(|y| (y - my).powi(2)).sum::<f64>() / n).sqrt();
    let st = (ts.iter().map(|t| (t - mt).powi(2)).sum::<f64>() / n).sqrt();
    cov / (sy * st)
}

#[test]
fn decorrelated_pairing_removes_the_time_position_correlation() {
    // Appendix A (3.3): with 4x4 samples each quarter of the shutter is confined to one
    // sub-pixel row (bit-reversed), so time and sub-pixel y are strongly correlated.
    let original = time_y_correlation(Pairing::Original);
    // 4096 samples: an uncorrelated pair gives |r| of order 1/sqrt(4096) = 0.016.
    let decorrelated = time_y_correlation(Pairing::Decorrelated);
    assert!(original.abs() > 0.3, "original pairing correlation {original}");
    assert!(decorrelated.abs() < 0.05, "decorrelated pairing correlation {decorrelated}");
}

#[test]
fn motion_segments_cover_the_shutter_piecewise() {
    // The same straight motion as one segment or as two segments [0, 0.5) and [0.5, 1):
    // every sample sees the bar in the same place, so the images are identical.
    let cfg = HiderConfig::default();
    let whole = moving_rect(20.0, 24.0, -1.0, 65.0, 8.0, [0.0, 1.0]);
    let first = moving_rect(20.0, 24.0, -1.0, 65.0, 4.0, [0.0, 0.5]);
    let second = moving_rect(24.0, 28.0, -1.0, 65.0, 4.0, [0.5, 1.0]);
    let a = coverage(cfg, &[whole]);
    let b = coverage(cfg, &[first, second]);
    let max_diff = a.iter().zip(&b).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
    // Rounding of v + a*speed differs between the two forms; a sample exactly on an edge may
    // flip, which changes a pixel by 1/NS at most.
    assert!(max_diff <= 1.0 / 16.0 + 1e-9, "{max_diff}");
    let diffs = a.iter().zip(&b).filter(|(p, q)| p != q).count();
    assert!(diffs <= 4, "{diffs} pixels differ");
    // A segment alone exists only in its part of the shutter: column 23 sees the bar for
    // t in [0, 0.5) only, so its coverage is the integral of the overlap over that half.
    // Tolerance: four standard deviations of a 64-row mean of 16-sample estimates,
    // 4 * sqrt(1/(4*15))/8 = 0.065 (see moving_edge_matches_the_space_time_trapezoid).
    let half = coverage(cfg, &[first]);
    for x in 19..30 {
        let m: f64 = (0..64).map(|y| half[y * 64 + x]).sum::<f64>() / 64.0;
        let n = 20_000;
        let exact: f64 = (0..n / 2)
            .map(|i| {
                let t = (i as f64 + 0.5) / n as f64;
                let (lo, hi) =
                    ((20.0 + 8.0 * t).max(x as f64), (24.0 + 8.0 * t).min(x as f64 + 1.0));
                (hi - lo).max(0.0) / n as f64
            })
            .sum();
        assert!((m - exact).abs() < 0.065, "column {x}: {m} vs {exact}");
    }
}

#[test]
fn time_patterns_of_figs_13_to_15() {
    // Per pixel and time stratum tau, the time's offset within its stratum, in strata.
    let offsets = |tp: TimePattern| -> Vec<Vec<f32>> {
        let cfg = HiderConfig { time_pattern: tp, ..HiderConfig::default() };
        let hider = Hider::new(cfg, Frame::new(64, 64, 0, 16, 16));
        let mut per_tau = vec![Vec::new(); 16];
        for b in [0, 5, 10] {
            let s = hider.bucket_samples(b);
            for (tau, offs) in per_tau.iter_mut().enumerate() {
                for pixel in 0..256 {
                    let k = pixel * 16 + s.by_time[pixel * 16 + tau] as usize;
                    let off = s.t[k] * 16.0 - tau as f32;
                    assert!((0.0..1.0).contains(&off), "{tp:?}: time outside its stratum");
                    offs.push(off);
                }
            }
        }
        per_tau
    };
    let spread = |v: &[f32]| {
        v.iter().cloned().fold(f32::NEG_INFINITY, f32::max)
            - v.iter().cloned().fold(f32::INFINITY, f32::min)
    };
    for (tau, v) in offsets(TimePattern::Fig13).iter().enumerate() {
        // One time per stratum in every pixel (up to the rounding of tau/16 + jitter).
        assert!(spread(v) < 1e-4, "FIG. 13 stratum {tau}: spread {}", spread(v));
    }
    for v in offsets(TimePattern::Fig14) {
        assert!(spread(&v) > 0.9, "FIG. 14 must use the whole stratum");
    }
    for v in offsets(TimePattern::Fig15) {
        // A shared reference plus a shift of at most a quarter stratum either way.
        let s = spread(&v);
        assert!(s > 0.3 && s <= 0.5 + 1e-4, "FIG. 15 spread {s}");
    }
}

/// Raster scale (pixels per eye-space unit at depth 1) and centre of the perspective tests.
const F: f64 = 32.0;
const C: f64 = 32.0;

/// A vertical bar of half-width `hw` (eye units) centred at eye x `x0`, depth `z0` at shutter
/// open and `x1`, `z1` at close, reaching far above and below the 64 x 64 image at every
/// depth, projected at both ends as the dicer does (`v` at open, `speed` to close).
/// `tilt` adds that much depth to the bar's right edge (so its vertices' depth ratios differ).
fn receding_bar(x0: f64, z0: f64, x1: f64, z1: f64, hw: f64, tilt: f64) -> Micropolygon {
    let project =
        |x: f64, y: f64, z: f64| [(C + F * x / z) as f32, (C + F * y / z) as f32, z as f32];
    let corner = |x: f64, z: f64, k: usize| {
        let (dx, dy, dz) =
            [(-hw, -40.0, 0.0), (hw, -40.0, tilt), (hw, 40.0, tilt), (-hw, 40.0, 0.0)][k];
        project(x + dx, dy, z + dz)
    };
    let v: [[f32; 3]; 4] = std::array::from_fn(|k| corner(x0, z0, k));
    let end: [[f32; 3]; 4] = std::array::from_fn(|k| corner(x1, z1, k));
    let speed = std::array::from_fn(|k| std::array::from_fn(|a| end[k][a] - v[k][a]));
    Micropolygon { v, speed, ..moving_rect(0.0, 1.0, 0.0, 1.0, 1.0, [0.0, 1.0]) }
}

/// Every hit of a one-bucket 64 x 64 render: (raster x, time) of each sample whose alpha is
/// not zero, and the per-sample RGBA bytes (for comparing renders).
fn render_hits(cfg: HiderConfig, mp: &Micropolygon) -> (Vec<(f64, f64)>, Vec<u32>) {
    let frame = Frame::new(64, 64, 0, 64, 64);
    let hider = Hider::new(cfg, frame);
    let ns = hider.ns();
    let smp = hider.bucket_samples(0);
    let mut scratch = Scratch::new();
    let out = hider.render_bucket(0, std::slice::from_ref(mp), &[0], &mut scratch);
    let bytes = out.rgba.iter().flat_map(|c| c.map(f32::to_bits)).collect();
    let mut hits = Vec::new();
    for pixel in 0..64 * 64 {
        for s in 0..ns {
            if out.rgba[pixel * ns + s][3] > 0.0 {
                let k = pixel * ns + s;
                hits.push((smp.x[k] as f64, smp.t[k] as f64));
            }
        }
    }
    (hits, bytes)
}

#[test]
fn a_point_moving_in_depth_follows_the_projective_path() {
    // A bar whose centre moves linearly in eye space from (x, z) = (-0.5, 2) to (8, 20): its
    // raster centre at time t is C + F X(t)/Z(t) (the closed form), not the straight line
    // between the end positions 24 and 44.8 (at t = 1/2 the two are 8.5 pixels apart). The
    // bar is about 3.2 pixels wide at open and 0.32 at close.
    //
    // Each hit lies uniformly across the bar's width at its own time, so the centroid of a
    // time slice's hits is, in expectation, the mean of the path over those hits' times; its
    // standard error is at most width/sqrt(12 n) (n hits, width the slice's largest; the
    // uniform distribution's variance is width^2/12, and one sample per stratum only lowers
    // it). Four standard errors, plus the width change across the slice, is the tolerance.
    let (x0, z0, x1, z1, hw) = (-0.5, 2.0, 8.0, 20.0, 0.05);
    let path = |t: f64| C + F * (x0 + t * (x1 - x0)) / (z0 + t * (z1 - z0));
    let line = |t: f64| path(0.0) + t * (path(1.0) - path(0.0));
    let width = |t: f64| 2.0 * F * hw / (z0 + t * (z1 - z0));
    let mp = receding_bar(x0, z0, x1, z1, hw, 0.0);
    for pattern in [Pattern::Fig6, Pattern::SobolJoint] {
        for original in [false, true] {
            let cfg = HiderConfig {
                nx: 8,
                ny: 8,
                pattern,
                original_linear_motion: original,
                seed: 2,
                ..HiderConfig::default()
            };
            let (hits, bytes) = render_hits(cfg, &mp);
            // The bounds are conservative: testing every sample finds exactly the same hits.
            let (_, all) = render_hits(HiderConfig { scan_all: true, ..cfg }, &mp);
            assert_eq!(bytes, all, "{pattern:?} original {original}: culling lost samples");
            let expect = |t: f64| if original { line(t) } else { path(t) };
            let other = |t: f64| if original { path(t) } else { line(t) };
            let mut slices = 0;
            for tau in 0..64 {
                let (ta, tb) = (tau as f64 / 64.0, (tau + 1) as f64 / 64.0);
                let slice: Vec<_> = hits.iter().filter(|h| h.1 >= ta && h.1 < tb).collect();
                let n = slice.len() as f64;
                if n < 8.0 {
                    continue;
                }
                slices += 1;
                let centroid = slice.iter().map(|h| h.0).sum::<f64>() / n;
                let want = slice.iter().map(|h| expect(h.1)).sum::<f64>() / n;
                let wrong = slice.iter().map(|h| other(h.1)).sum::<f64>() / n;
                // The bar's width at the slice's start (its widest there): projective, or, on
                // the original's straight path, the straight interpolation of the end widths.
                let w =
                    if original { width(0.0) + ta * (width(1.0) - width(0.0)) } else { width(ta) };
                let tol = 4.0 * w / (12.0 * n).sqrt() + 1e-3;
                assert!(
                    (centroid - want).abs() < tol,
                    "{pattern:?} original {original} slice {tau}: {centroid} vs {want} (tol {tol})"
                );
                // Away from the ends the other path is far outside the tolerance.
                if (8..56).contains(&tau) {
                    assert!((centroid - wrong).abs() > 10.0 * tol, "{pattern:?} slice {tau}");
                }
            }
            assert!(slices >= 60, "{pattern:?}: only {slices} time slices with hits");
        }
    }
}

#[test]
fn perspective_motion_bounds_are_conservative_for_every_path() {
    // Path agreement: the per-slice boxes and row spans under the warp (one depth ratio for
    // all four vertices, and different ratios: a bar tilted in depth, which disables the row
    // narrowing) find exactly the samples an unculled scan finds, with a pinhole and with a
    // lens, receding and approaching.
    let lens = reyes_hider::LensSetup::new(0.2, 6.0, 32.0, 32.0);
    for (x0, z0, x1, z1, tilt) in
        [(-0.5, 2.0, 8.0, 20.0, 0.0), (-0.5, 2.0, 8.0, 20.0, 1.5), (3.0, 15.0, -1.0, 1.5, 0.7)]
    {
        let mp = receding_bar(x0, z0, x1, z1, 0.08, tilt);
        for lens in [None, Some(lens)] {
            for pattern in [Pattern::Fig6, Pattern::SobolJoint] {
                let cfg =
                    HiderConfig { nx: 4, ny: 4, pattern, lens, seed: 8, ..HiderConfig::default() };
                let (h, culled) = render_hits(cfg, &mp);
                let (_, all) = render_hits(HiderConfig { scan_all: true, ..cfg }, &mp);
                assert!(h.len() > 100, "the bar is seen");
                assert_eq!(culled, all, "{x0} {z0} tilt {tilt} lens {}", lens.is_some());
            }
        }
    }
}
