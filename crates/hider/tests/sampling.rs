//! Sample patterns as the hider makes them (docs/sampling.md): stratification of FIGS. 3, 5,
//! 6 and 7 and of the Owen-scrambled Sobol (0,2) sampler, its fall-back to FIG. 6, and
//! decorrelation of time, lens and position for every pattern that claims it.

use std::rc::Rc;

use reyes_hider::samples::owen::Scramble;
use reyes_hider::samples::sobol_cells;
use reyes_hider::{BucketSamples, Frame, Hider, HiderConfig, LensShape, Pairing, Pattern, Tables};

const PATTERNS: [Pattern; 7] = [
    Pattern::Regular,
    Pattern::Random,
    Pattern::Fig5,
    Pattern::Fig6,
    Pattern::Fig7,
    Pattern::Sobol,
    Pattern::SobolJoint,
];

/// A 40 x 24 frame of 16 x 16 buckets (so buckets are cut by the image edge) and its hider.
fn hider(cfg: HiderConfig) -> (Frame, Hider) {
    let frame = Frame::new(40, 24, 1, 16, 16);
    (frame, Hider::new(cfg, frame))
}

/// Every pixel of every bucket: (its bucket's samples, bucket-local pixel index, the pixel's
/// samples' sub-pixel offsets).
fn pixels(frame: &Frame, hider: &Hider) -> Vec<(Rc<BucketSamples>, usize, Vec<[f32; 2]>)> {
    let ns = hider.ns();
    let p_count = frame.pixels_per_bucket();
    let mut out = Vec::new();
    for b in 0..frame.bucket_count() {
        let smp = Rc::new(hider.bucket_samples(b));
        for pixel in 0..p_count {
            let (px, py) =
                ((pixel as u32 % frame.bucket_w) as f32, (pixel as u32 / frame.bucket_w) as f32);
            let offs =
                (0..ns).map(|s| [smp.x[pixel * ns + s] - px, smp.y[pixel * ns + s] - py]).collect();
            out.push((Rc::clone(&smp), pixel, offs));
        }
    }
    out
}

#[test]
fn stratified_patterns_put_sample_s_alone_in_stratum_s_of_every_pixel() {
    let sizes = [(1, 1), (2, 2), (3, 5), (4, 4), (7, 3), (8, 8), (16, 16), (4, 2)];
    let stratified = [
        Pattern::Regular,
        Pattern::Fig5,
        Pattern::Fig6,
        Pattern::Fig7,
        Pattern::Sobol,
        Pattern::SobolJoint,
    ];
    for pattern in stratified {
        for (nx, ny) in sizes {
            let (frame, h) =
                hider(HiderConfig { nx, ny, pattern, seed: 11, ..HiderConfig::default() });
            let loc = &h.tables().location;
            for (_, _, offs) in pixels(&frame, &h) {
                let mut seen = vec![false; (nx * ny) as usize];
                for (s, o) in offs.iter().enumerate() {
                    let cx = (o[0] * nx as f32).floor();
                    let cy = (o[1] * ny as f32).floor();
                    assert!(
                        (0.0..nx as f32).contains(&cx) && (0.0..ny as f32).contains(&cy),
                        "{pattern:?} {nx}x{ny}: sample {s} at {o:?} outside its pixel"
                    );
                    assert_eq!([cx / nx as f32, cy / ny as f32], loc[s], "{pattern:?} {nx}x{ny}");
                    let q = (cx as u32 * ny + cy as u32) as usize;
                    assert!(!std::mem::replace(&mut seen[q], true), "{pattern:?}: stratum twice");
                }
            }
        }
    }
}

#[test]
fn random_pattern_is_uniform_and_unstratified() {
    let (frame, h) =
        hider(HiderConfig { nx: 4, ny: 4, pattern: Pattern::Random, ..HiderConfig::default() });
    let all = pixels(&frame, &h);
    let mut doubled = 0;
    let mut bins = [0u32; 16];
    for (_, _, offs) in &all {
        let mut seen = [false; 16];
        for o in offs {
            assert!((0.0..1.0).contains(&o[0]) && (0.0..1.0).contains(&o[1]));
            let q = (o[0] * 4.0) as usize * 4 + (o[1] * 4.0) as usize;
            bins[q] += 1;
            doubled += std::mem::replace(&mut seen[q], true) as u32;
        }
    }
    // With 16 uniform points in 16 cells a pixel almost always has a cell twice
    // (probability 1 - 16!/16^16, about 0.99989).
    assert!(doubled as usize > all.len(), "{doubled} repeats in {} pixels", all.len());
    // Each of the 16 cells gets Binomial(n, 1/16): allow 5 standard deviations.
    let n = (all.len() * 16) as f64;
    let sd = (n / 16.0 * 15.0 / 16.0).sqrt();
    assert!(bins.iter().all(|&b| (b as f64 - n / 16.0).abs() < 5.0 * sd), "{bins:?}");
}

/// Exactly one point of `pts` (in [0,1)^2) in each elementary interval of area 2^-m.
fn assert_02_net(pts: &[[f64; 2]], m: u32, what: &str) {
    assert_eq!(pts.len(), 1 << m, "{what}");
    for a in 0..=m {
        let b = m - a;
        let mut seen = vec![false; 1 << m];
        for p in pts {
            let cx = (p[0] * (1u64 << a) as f64).floor() as usize;
            let cy = (p[1] * (1u64 << b) as f64).floor() as usize;
            assert!(cx < 1 << a && cy < 1 << b, "{what}: point {p:?} outside");
            let c = (cx << b) | cy;
            assert!(
                !std::mem::replace(&mut seen[c], true),
                "{what}: interval 2^-{a} x 2^-{b} #{c} twice"
            );
        }
    }
}

#[test]
fn sobol_sequence_prefixes_are_02_nets() {
    // The sequence itself: for every seed and pixel key the first 4^k points (and every
    // power-of-two prefix) are (0,m,2)-nets, and the first 2^m times one per 1/2^m interval.
    for seed in 0..8u64 {
        for pixel in [0u64, 1, 77, 1 << 40] {
            let sc = Scramble::new(seed, &[pixel, 3]);
            let pts: Vec<[f64; 2]> =
                (0..1024u32).map(|i| sc.point_2d(i).map(|v| v as f64 / 4_294_967_296.0)).collect();
            for m in 0..=10 {
                assert_02_net(
                    &pts[..1 << m],
                    m,
                    &format!("seed {seed} pixel {pixel} prefix 2^{m}"),
                );
            }
            for m in 0..=8u32 {
                let mut seen = vec![false; 1 << m];
                for i in 0..1u32 << m {
                    let k = ((sc.point_1d(i) as u64 * (1u64 << m)) >> 32) as usize;
                    assert!(!std::mem::replace(&mut seen[k], true), "time prefix 2^{m}");
                }
            }
        }
    }
}

#[test]
fn sobol_pixels_are_02_nets_in_position_time_and_lens() {
    for (nx, ny) in [(1u32, 1u32), (2, 2), (4, 4), (8, 8), (16, 16), (4, 2), (2, 8)] {
        let ns = nx * ny;
        let m = ns.trailing_zeros();
        let cfg = HiderConfig {
            nx,
            ny,
            pattern: Pattern::Sobol,
            lens_shape: LensShape::OriginalSquare,
            seed: 4,
            ..HiderConfig::default()
        };
        let (frame, h) = hider(cfg);
        let ns = ns as usize;
        for (smp, pixel, offs) in pixels(&frame, &h) {
            let pts: Vec<[f64; 2]> = offs.iter().map(|o| [o[0] as f64, o[1] as f64]).collect();
            assert_02_net(&pts, m, &format!("{nx}x{ny} positions"));
            // The square lens is the unit square shifted by -0.5/NS (exactly representable).
            let lens: Vec<[f64; 2]> = (0..ns)
                .map(|s| {
                    let k = pixel * ns + s;
                    [(smp.lx[k] + 0.5 / ns as f32) as f64, (smp.ly[k] + 0.5 / ns as f32) as f64]
                })
                .collect();
            assert_02_net(&lens, m, &format!("{nx}x{ny} lens"));
            for tau in 0..ns {
                let s = smp.by_time[pixel * ns + tau] as usize;
                let t = smp.t[pixel * ns + s];
                assert!(t >= tau as f32 / ns as f32 && t < (tau + 1) as f32 / ns as f32);
            }
        }
    }
}

#[test]
fn sobol_falls_back_to_fig6_without_power_of_two_strata() {
    for (nx, ny) in [(3, 3), (4, 3), (5, 1), (6, 6)] {
        assert!(sobol_cells(&Tables::new(nx, ny, 256, true, 0, false, false)).is_none());
        let make = |pattern| {
            let cfg = HiderConfig { nx, ny, pattern, seed: 9, ..HiderConfig::default() };
            hider(cfg).1.bucket_samples(2)
        };
        let b = make(Pattern::Fig6);
        for a in [make(Pattern::Sobol), make(Pattern::SobolJoint)] {
            let (a, b) = ((&a.x, &a.y, &a.t, &a.lx, &a.ly), (&b.x, &b.y, &b.t, &b.lx, &b.ly));
            assert_eq!(a, b, "{nx}x{ny}");
        }
    }
    // For powers of two the original `permute` is a true permutation, so Sobol applies.
    assert!(sobol_cells(&Tables::new(4, 4, 256, true, 0, false, true)).is_some());
}

/// Correlation coefficient of two equally long series.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum::<f64>() / n;
    let sa = (a.iter().map(|x| (x - ma).powi(2)).sum::<f64>() / n).sqrt();
    let sb = (b.iter().map(|y| (y - mb).powi(2)).sum::<f64>() / n).sqrt();
    cov / (sa * sb)
}

/// Sub-pixel x, sub-pixel y, time, lens x, lens y of every sample of a 64 x 64 frame.
fn dimensions(pattern: Pattern, pairing: Pairing, lens_shape: LensShape) -> [Vec<f64>; 5] {
    let cfg = HiderConfig {
        pattern,
        time_pairing: pairing,
        lens_shape,
        seed: 21,
        ..HiderConfig::default()
    };
    let frame = Frame::new(64, 64, 0, 16, 16);
    let h = Hider::new(cfg, frame);
    let mut d: [Vec<f64>; 5] = Default::default();
    for b in 0..frame.bucket_count() {
        let s = h.bucket_samples(b);
        for k in 0..s.x.len() {
            d[0].push(s.x[k] as f64 - (s.x[k] as f64).floor());
            d[1].push(s.y[k] as f64 - (s.y[k] as f64).floor());
            d[2].push(s.t[k] as f64);
            d[3].push(s.lx[k] as f64);
            d[4].push(s.ly[k] as f64);
        }
    }
    d
}

#[test]
fn time_lens_and_position_are_uncorrelated_for_every_decorrelated_pattern() {
    // n = 64 x 64 pixels x 16 samples = 65,536. For independent dimensions the sample
    // correlation coefficient has standard deviation 1/sqrt(n) = 0.0039; allow 4/sqrt(n).
    // (Stratification only lowers that variance: every dimension's marginal is stratified.)
    for pattern in PATTERNS {
        let d = dimensions(pattern, Pairing::Decorrelated, LensShape::Disk);
        let tol = 4.0 / (d[0].len() as f64).sqrt();
        let names = ["x", "y", "t", "lens x", "lens y"];
        for (i, j) in [(0, 2), (1, 2), (0, 3), (1, 4), (0, 4), (1, 3), (2, 3), (2, 4)] {
            let r = correlation(&d[i], &d[j]);
            assert!(
                r.abs() < tol,
                "{pattern:?}: corr({}, {}) = {r} (tolerance {tol})",
                names[i],
                names[j]
            );
        }
    }
}

#[test]
fn original_pairings_are_correlated_and_the_test_can_tell() {
    // Appendix A ties time to the sub-pixel row (3.3) and the square lens to the sub-pixel
    // position (3.8): the same statistic must see it, for the tables and for Sobol alike.
    for pattern in [Pattern::Fig6, Pattern::Sobol, Pattern::SobolJoint] {
        let d = dimensions(pattern, Pairing::Original, LensShape::OriginalSquare);
        let tol = 4.0 / (d[0].len() as f64).sqrt();
        let ty = correlation(&d[1], &d[2]);
        let lx = correlation(&d[0], &d[3]);
        assert!(ty.abs() > 10.0 * tol, "{pattern:?}: time-y correlation {ty}");
        assert!(lx > 0.5, "{pattern:?}: lens-x correlation {lx}");
    }
}

#[test]
fn joint_pixels_have_one_sample_per_time_slice_and_lens_cell() {
    // The invariants the time-slice and lens-slice scans and the filter table rely on, for
    // every lens shape and pairing: sample s in stratum Location[s] (tested above), one time
    // in each [tau/NS, (tau+1)/NS) with `by_time` naming it, and one lens point in each lens
    // cell, `by_lens[lambda]` naming the sample in cell Location[lambda].
    for (nx, ny) in [(1u32, 1u32), (2, 2), (4, 4), (8, 8), (16, 16), (4, 2), (2, 8), (1, 4)] {
        for (pairing, lens_shape) in [
            (Pairing::Decorrelated, LensShape::Disk),
            (Pairing::Original, LensShape::OriginalSquare),
        ] {
            let ns = (nx * ny) as usize;
            let cfg = HiderConfig {
                nx,
                ny,
                pattern: Pattern::SobolJoint,
                time_pairing: pairing,
                lens_shape,
                seed: 6,
                ..HiderConfig::default()
            };
            let (frame, h) = hider(cfg);
            let loc = &h.tables().location;
            let what = format!("{nx}x{ny} {pairing:?} {lens_shape:?}");
            for (smp, pixel, _) in pixels(&frame, &h) {
                for tau in 0..ns {
                    let s = smp.by_time[pixel * ns + tau] as usize;
                    let t = smp.t[pixel * ns + s];
                    assert!(
                        t >= tau as f32 / ns as f32 && t < (tau + 1) as f32 / ns as f32,
                        "{what}"
                    );
                    if pairing == Pairing::Original {
                        assert_eq!(s, tau, "{what}: Appendix A's sample s in time stratum s");
                    }
                }
                let mut seen = vec![false; ns];
                for (lambda, cell) in loc.iter().enumerate() {
                    let s = smp.by_lens[pixel * ns + lambda] as usize;
                    let k = pixel * ns + s;
                    // Back from the lens sample to its unit-square cell.
                    let (u, v) = match lens_shape {
                        LensShape::OriginalSquare => {
                            (smp.lx[k] + 0.5 / ns as f32, smp.ly[k] + 0.5 / ns as f32)
                        }
                        LensShape::Disk => square_of_disk(smp.lx[k], smp.ly[k]),
                    };
                    let (cx, cy) = ((u * nx as f32).floor(), (v * ny as f32).floor());
                    if lens_shape == LensShape::OriginalSquare {
                        assert_eq!(s, lambda, "{what}: Appendix A's lens cell Location[s]");
                    }
                    // The disk's inverse map is a few ulps off on cell edges: compare cells
                    // with the sample's cell centre, not the floor, when it is that close.
                    let near =
                        |w: f32, n: u32| ((w * n as f32) - (w * n as f32).round()).abs() < 1e-4;
                    if !(near(u, nx) || near(v, ny)) {
                        assert_eq!([cx / nx as f32, cy / ny as f32], *cell, "{what}");
                    }
                    let q = (cx as u32 * ny + cy as u32).min(ns as u32 - 1) as usize;
                    assert!(
                        !std::mem::replace(&mut seen[q], true) || near(u, nx) || near(v, ny),
                        "{what}: cell twice"
                    );
                }
            }
        }
    }
}

/// Inverse of the concentric square-to-disk map, back to the unit square.
fn square_of_disk(x: f32, y: f32) -> (f32, f32) {
    let (x, y) = (x as f64, y as f64);
    let r = x.hypot(y);
    if r == 0.0 {
        return (0.5, 0.5);
    }
    let phi = y.atan2(x); // (-pi, pi]
    let q = std::f64::consts::FRAC_PI_4;
    // Region |a| > |b|: phi = (pi/4) b/a with r = a (a > 0: phi in (-pi/4, pi/4]).
    let (a, b) = if phi.abs() <= q {
        (r, r * phi / q)
    } else if phi.abs() >= 3.0 * q {
        let p = if phi > 0.0 { phi - std::f64::consts::PI } else { phi + std::f64::consts::PI };
        (-r, -r * p / q)
    } else if phi > 0.0 {
        // phi = pi/2 - (pi/4) a/b with r = b > 0.
        (r * (2.0 - phi / q), r)
    } else {
        // phi + pi = pi/2 - (pi/4) a/b with r = b < 0.
        (r * (2.0 + phi / q), -r)
    };
    (((a + 1.0) / 2.0) as f32, ((b + 1.0) / 2.0) as f32)
}

#[test]
fn joint_samples_depend_only_on_the_seed_and_the_pixel() {
    // Deterministic, and the same for any bucket layout: each pixel's samples are hashed
    // from its global raster position, so 8 x 8 and 16 x 16 buckets give the same samples.
    let cfg = HiderConfig {
        nx: 4,
        ny: 4,
        pattern: Pattern::SobolJoint,
        seed: 3,
        ..HiderConfig::default()
    };
    let collect = |bw: u32| {
        let frame = Frame::new(32, 32, 0, bw, bw);
        let h = Hider::new(cfg, frame);
        let mut by_pixel = std::collections::BTreeMap::new();
        let p_count = frame.pixels_per_bucket();
        for b in 0..frame.bucket_count() {
            let (left, top) = frame.bucket_origin(b);
            let s = h.bucket_samples(b);
            for pixel in 0..p_count {
                let (px, py) = (pixel as u32 % bw, pixel as u32 / bw);
                let key = (left + px as i32, top + py as i32);
                let v: Vec<[u32; 5]> = (0..16)
                    .map(|q| {
                        let k = pixel * 16 + q;
                        [s.x[k] - px as f32, s.y[k] - py as f32, s.t[k], s.lx[k], s.ly[k]]
                            .map(f32::to_bits)
                    })
                    .collect();
                by_pixel.insert(key, v);
            }
        }
        by_pixel
    };
    let a = collect(8);
    assert_eq!(a, collect(8));
    assert_eq!(a, collect(16));
}
