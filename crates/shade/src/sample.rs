//! Sampling geometry of the distributed rays: directions in a cone (glossy reflection and
//! blurry refraction), points of a disk (area lights), and the mirror and Snell directions.
//!
//! Invariant: every function is a pure function of its arguments (the pseudo-random numbers
//! come in as `(u1, u2)` in `[0, 1)^2`, from a `Strata` stream), maps stratified inputs to
//! stratified outputs (each is a measure-preserving map of the unit square onto its domain,
//! so equal-area strata of the square become equal-measure strata of the domain), and
//! returns finite values for finite inputs.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

use glam::{Vec2, Vec3};

/// A direction from the cone of half-angle `max_angle` (radians) around `dir`, uniform over
/// the cone's solid angle, chosen by `(u1, u2)`; the port of Appendix B's `disperseray`.
///
/// The deviation `phi` from `dir` and the azimuth `theta` around it are
/// `cos(phi) = 1 - u1 (1 - cos(max_angle))` and `theta = 2 pi u2`, so the density per unit
/// solid angle is the constant `1 / (2 pi (1 - cos(max_angle)))`; the result keeps the length
/// of `dir` (the frame is any orthonormal frame around `dir / |dir|`, as 3.11 of the
/// Appendix B notes recommends).
///
/// Appendix B differs: it takes `phi = U1 U2 max_angle` (a product of two uniforms), whose
/// density in `phi` is `ln(max_angle / phi) / max_angle` (mean `max_angle / 4`), i.e. per
/// unit solid angle `~ ln(max_angle / phi) / sin(phi)`: a lobe with a sharp core, peaked at
/// the mirror direction, and not a map of the unit square that keeps strata apart. Its
/// azimuth may also cover only half the circle (the OCR reads `drand() * PI`). Here the cone
/// is uniform, so a glossy reflection of half-angle `g` blurs an edge at distance `D` over
/// about `D tan g` (see the crate's tests), and stratified `(u1, u2)` give stratified
/// directions.
///
/// `max_angle <= 0` (or NaN) returns `dir` unchanged; angles above `pi` are taken as `pi`
/// (the whole sphere). A zero `dir` is returned unchanged.
pub fn disperse(dir: Vec3, max_angle: f32, (u1, u2): (f32, f32)) -> Vec3 {
    // Also catches NaN.
    if max_angle.is_nan() || max_angle <= 0.0 {
        return dir;
    }
    let len = dir.length();
    let Some(w) = dir.try_normalize() else {
        return dir;
    };
    let cos_max = max_angle.min(PI).cos();
    let cos_phi = 1.0 - u1 * (1.0 - cos_max);
    let sin_phi = (1.0 - cos_phi * cos_phi).max(0.0).sqrt();
    let (sin_t, cos_t) = (TAU * u2).sin_cos();
    let (e1, e2) = w.any_orthonormal_pair();
    len * (sin_phi * cos_t * e1 + sin_phi * sin_t * e2 + cos_phi * w)
}

/// The point of the unit disk that Shirley and Chiu's concentric map gives `(u1, u2)`:
/// the square `[-1, 1]^2` is cut into four triangles by its diagonals, and each square ring
/// of half-side `r` goes onto the circle of radius `r`, the angle growing linearly along
/// the ring. The map preserves area ratios (Jacobian `pi / 4` everywhere), so uniform and
/// stratified points of the square stay uniform and stratified on the disk, and strata
/// stay compact (unlike the polar map `r = sqrt(u1)`, `theta = 2 pi u2`).
pub fn concentric_disk((u1, u2): (f32, f32)) -> Vec2 {
    let a = 2.0 * u1 - 1.0;
    let b = 2.0 * u2 - 1.0;
    if a == 0.0 && b == 0.0 {
        return Vec2::ZERO;
    }
    let (r, angle) = if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, FRAC_PI_2 - FRAC_PI_4 * (a / b))
    };
    let (s, c) = angle.sin_cos();
    Vec2::new(r * c, r * s)
}

/// The mirror image of the travel direction `i` about the plane of unit normal `n`
/// (either orientation): `i - 2 (i . n) n`.
pub(crate) fn mirror(i: Vec3, n: Vec3) -> Vec3 {
    i - 2.0 * i.dot(n) * n
}

/// The direction of the ray refracted at a surface of unit normal `n` facing against the
/// unit travel direction `i` (`i . n <= 0`), with `eta = n_from / n_to` (Snell's law
/// `sin t = eta sin i`), or `None` at total internal reflection.
pub(crate) fn snell(i: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = (-i.dot(n)).clamp(0.0, 1.0);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k.is_nan() || k < 0.0 {
        return None;
    }
    Some(eta * i + (eta * cos_i - k.sqrt()) * n)
}

/// `dir` brought to the side of the plane of unit normal `n` that `side` says (`+1` the
/// side `n` points to, `-1` the other): a direction on the wrong side, or in the plane, is
/// mirrored about the plane (the tangent plane of the surface), so a dispersed direction
/// that would go through the surface stays in the cone's reflected image instead.
pub(crate) fn to_side(dir: Vec3, n: Vec3, side: f32) -> Vec3 {
    if dir.dot(n) * side > 0.0 { dir } else { mirror(dir, n) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disperse_stays_in_the_cone_and_keeps_length() {
        let dir = Vec3::new(0.3, -2.0, 0.5);
        let max = 10f32.to_radians();
        for i in 0..16 {
            for j in 0..16 {
                let u = ((i as f32 + 0.5) / 16.0, (j as f32 + 0.5) / 16.0);
                let d = disperse(dir, max, u);
                assert!((d.length() - dir.length()).abs() < 1e-5);
                let angle = d.angle_between(dir);
                assert!(angle <= max + 1e-5, "{angle} > {max}");
            }
        }
        assert_eq!(disperse(dir, 0.0, (0.3, 0.7)), dir);
        assert_eq!(disperse(dir, f32::NAN, (0.3, 0.7)), dir);
        assert_eq!(disperse(Vec3::ZERO, 0.5, (0.3, 0.7)), Vec3::ZERO);
    }

    #[test]
    fn disperse_is_uniform_in_solid_angle() {
        // The fraction of directions within angle a of the axis is
        // (1 - cos a) / (1 - cos max): check it on a fine grid of (u1, u2).
        let max = 30f32.to_radians();
        let n = 200;
        let a = 20f32.to_radians();
        let mut inside = 0;
        for i in 0..n {
            for j in 0..n {
                let u = ((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                if disperse(Vec3::Z, max, u).angle_between(Vec3::Z) < a {
                    inside += 1;
                }
            }
        }
        let got = inside as f32 / (n * n) as f32;
        let want = (1.0 - a.cos()) / (1.0 - max.cos());
        // The grid puts the fraction within one row of cells (1/n) of the exact value.
        assert!((got - want).abs() <= 1.0 / n as f32, "{got} vs {want}");
    }

    #[test]
    fn concentric_disk_covers_the_disk_evenly() {
        let n = 100;
        let mut inner = 0;
        for i in 0..n {
            for j in 0..n {
                let p = concentric_disk(((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32));
                assert!(p.length() <= 1.0 + 1e-6);
                if p.length() < 0.5 {
                    inner += 1;
                }
            }
        }
        // Radius 1/2 holds a quarter of the area: exactly the central square of half-side
        // 1/2, i.e. 50 x 50 of the 100 x 100 cells.
        assert_eq!(inner, 2500);
        assert_eq!(concentric_disk((0.5, 0.5)), Vec2::ZERO);
    }

    #[test]
    fn snell_bends_by_the_law_and_reflects_totally() {
        let theta = 40f32.to_radians();
        let i = Vec3::new(theta.sin(), -theta.cos(), 0.0);
        let t = snell(i, Vec3::Y, 1.0 / 1.5).expect("entering glass");
        assert!((t.length() - 1.0).abs() < 1e-5);
        assert!((t.x - theta.sin() / 1.5).abs() < 1e-6, "{t}");
        assert!(t.y < 0.0);
        // Leaving glass at 60 degrees: sin 60 * 1.5 > 1.
        let theta = 60f32.to_radians();
        let i = Vec3::new(theta.sin(), -theta.cos(), 0.0);
        assert!(snell(i, Vec3::Y, 1.5).is_none());
        assert_eq!(mirror(i, Vec3::Y), Vec3::new(i.x, -i.y, 0.0));
        assert_eq!(to_side(Vec3::new(1.0, -0.1, 0.0), Vec3::Y, 1.0), Vec3::new(1.0, 0.1, 0.0));
        assert_eq!(to_side(Vec3::new(1.0, 0.1, 0.0), Vec3::Y, 1.0), Vec3::new(1.0, 0.1, 0.0));
    }
}
