//! Soft shadows (FIG. 22): a disk light over a disk occluder over a floor.
//!
//! Geometry (all on the y axis): the floor y = 0, an opaque occluding disk of radius
//! `R_O = 2` at height `h = 5`, a disk light of radius `R_L = 1` at height `H = 10` facing
//! down. A floor point at radial distance `r` sees the occluder's shadow of the light: fully
//! hidden inside the umbra radius `(R_O H - R_L h) / (H - h) = 3`, fully lit beyond the
//! penumbra radius `(R_O H + R_L h) / (H - h) = 5`.

use std::f64::consts::PI;

use reyes_shade::Shading;

use crate::common::{floor_point, scene, shade_mean, tracer, white_floor};

const R_L: f64 = 1.0;
const H: f64 = 10.0;
const R_O: f64 = 2.0;
const HO: f64 = 5.0;

fn setup(occluder: bool) -> reyes_scene::Scene {
    let floor = white_floor(20.0);
    let disk = format!(
        ", (shape: Disk(radius: {R_O:?}), \
           transform: [Rotate(angle: 90.0, axis: (1.0, 0.0, 0.0)), Translate((0.0, {HO:?}, 0.0))], \
           material: Matte(color: (1.0, 1.0, 1.0)))"
    );
    scene(&format!(
        "lights: [Area(shape: Disk(center: (0.0, {H:?}, 0.0), normal: (0.0, -1.0, 0.0), radius: {R_L:?}), \
                       intensity: 100.0)], \
         objects: [{floor}{}]",
        if occluder { disk.as_str() } else { "" }
    ))
}

/// The fraction of the light's contribution that reaches the floor point at `(r, 0, 0)`:
/// the integral over the light disk of `w = cos_light cos_floor / d^2 = H^2 / d^4` where the
/// segment to the light passes outside the occluder, over the integral of `w`. Midpoint
/// rule on a 400 x 800 polar grid (its error is far below the test's tolerance: the
/// occluder's edge cuts about 800 of the 320,000 cells, each holding 1/320,000 of the
/// weight, and their errors have random signs).
fn lit_fraction(r: f64) -> f64 {
    let (nr, nt) = (400, 800);
    let (mut lit, mut all) = (0.0, 0.0);
    for i in 0..nr {
        let rho = (i as f64 + 0.5) / nr as f64 * R_L;
        for j in 0..nt {
            let th = (j as f64 + 0.5) / nt as f64 * 2.0 * PI;
            let (qx, qz) = (rho * th.cos(), rho * th.sin());
            let d2 = (qx - r).powi(2) + qz * qz + H * H;
            let w = rho * H * H / (d2 * d2);
            // Where the segment from (r, 0, 0) to (qx, H, qz) crosses y = HO.
            let s = HO / H;
            let (cx, cz) = (r + (qx - r) * s, qz * s);
            all += w;
            if cx * cx + cz * cz >= R_O * R_O {
                lit += w;
            }
        }
    }
    lit / all
}

/// The rendered fraction at radial distance `r`: the floor's shading with the occluder
/// over its shading without, the same strata in both (so each set sees the same light
/// points), averaged over `SETS` independent sets of `N` stratified members.
fn rendered_fraction(with: &Shading, without: &Shading, r: f32) -> f64 {
    const N: u32 = 1024;
    const SETS: u64 = 16;
    let (mut a, mut b) = (0.0, 0.0);
    for set in 0..SETS {
        // Points on a circle of radius r: the shadow is round.
        let angle = set as f32 * 0.4;
        let at = floor_point(0, r * angle.cos(), r * angle.sin(), 0.0);
        a += f64::from(shade_mean(with, &at, N, set).x);
        b += f64::from(shade_mean(without, &at, N, set).x);
    }
    a / b
}

#[test]
fn penumbra_matches_the_covered_fraction_of_the_light() {
    let (s1, s0) = (setup(true), setup(false));
    let (t1, t0) = (tracer(&s1), tracer(&s0));
    let (with, without) = (Shading::new(&s1, &t1), Shading::new(&s0, &t0));
    let umbra = (R_O * H - R_L * HO) / (H - HO);
    let penumbra = (R_O * H + R_L * HO) / (H - HO);
    assert_eq!((umbra, penumbra), (3.0, 5.0));
    for r in [0.0, 1.0, 2.0, 2.95] {
        let f = rendered_fraction(&with, &without, r);
        assert_eq!(f, 0.0, "r = {r} is in the umbra: lit fraction {f}");
    }
    for r in [5.05, 6.0, 8.0] {
        let f = rendered_fraction(&with, &without, r);
        assert!((f - 1.0).abs() < 1e-6, "r = {r} is fully lit: {f}");
    }
    // Tolerance. One set of N = 1024 = 32 x 32 stratified light points estimates the lit
    // fraction with an error from the strata the occluder's edge cuts only (the others are
    // all lit or all dark, whatever their jitter). The edge, a smooth curve in the unit
    // square of length at most ~4 through the concentric map, cuts at most 2 * 4 * 32 = 256
    // of the 32 x 32 strata; each adds a variance at most 1/4 / N^2, so the standard
    // deviation is at most sqrt(256 / 4) / 1024 = 0.0078 per set (pure random sampling
    // would give up to 0.5 / sqrt(1024) = 0.016), and 0.0020 for the mean of 16 sets.
    // Four standard deviations: 0.008. The light-point weights vary by under 10% across
    // the light, which changes none of this materially.
    let tol = 0.008;
    let mut last = -1.0;
    let mut worst: f64 = 0.0;
    for k in 0..=16 {
        let r = 3.0 + 2.0 * k as f64 / 16.0;
        let got = rendered_fraction(&with, &without, r as f32);
        let want = lit_fraction(r);
        worst = worst.max((got - want).abs());
        assert!((got - want).abs() <= tol, "r {r}: rendered {got:.4}, expected {want:.4}");
        assert!(got >= last, "lit fraction must grow with r: {got} after {last} at r {r}");
        last = got;
    }
    eprintln!("penumbra: worst |rendered - expected| = {worst:.5} (tolerance {tol})");
    // The analytic overlap (without the d^-4 weights) at the middle of the penumbra, r = 4:
    // the occluder projects from the floor point onto the light's plane as a disk of radius
    // R_O H / h = 4 centred at distance r (H / h - 1) = 4 from the light's centre; the
    // unit light disk is half covered, to within the curvature of the big disk's edge.
    let mid = lit_fraction(4.0);
    assert!((mid - 0.5).abs() < 0.1, "{mid}");
}
