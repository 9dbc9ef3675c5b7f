//! Reconstruction filter kernels (used by validation and the film's filter table): Appendix A's
//! five here, RenderMan's in [`super::renderman`], one entry point [`weight`] for both.
//!
//! Invariants: every kernel is a pure function of the offset `(dx, dy)` (sample minus pixel
//! centre, in pixels) and the full filter widths in x and y; the result is finite for finite
//! inputs. The filter table normalises the weights afterwards, so only the shape of a kernel
//! matters, never its scale. Our fixed versions of Appendix A's kernels are the default; the
//! original 1985 shapes are selected by the [`Original`] switches. A filter as tall as it is
//! wide computes exactly what the width-only kernels always did.

use crate::{FilterKind, Original};

/// Below this `|r|` the sinc and jinc kernels return their centre value instead of dividing
/// by `r` (Appendix A's `r<.001&&r>-.001`).
const CENTRE_EPS: f64 = 0.001;

/// Weight of a sample at offset `(dx, dy)` from an output pixel centre, for the kernel `kind`
/// of full width `width` in x and `height` in y (pixels).
///
/// The RenderMan kernels (the `Ri` kinds) are [`super::renderman::weight`]. Appendix A's five
/// are defined for one width: for `height != width` the y offset is scaled by
/// `width / height` first, so the kernel keeps its shape and reaches `height / 2` in y (the
/// radial ones become elliptical); for `height == width` nothing is scaled and the weight is
/// bit for bit the width-only one.
///
/// Appendix A's kernels:
/// Port of `FilterRoutine[FilterType](x, y)` (Appendix A 2.3: `boxfilter`, `gaussianfilter`,
/// `sincfilter`, `bartlettfilter`, `besselfilter`), with these deliberate differences unless
/// the matching `original` switch is set (Appendix A 3.16, 3.21 item 9):
///
/// * box: symmetric cut `|dx| <= W/2 && |dy| <= W/2` (`original.box_filter`: the printed
///   `(x > W || y > W) ? 0 : 1` on signed offsets with the full width);
/// * sinc: centre value 2, the limit of `sin(2r)/r` (`original.sinc_filter`: the printed 1);
/// * Bartlett: half-width `W/2` (`original.bartlett_filter`: half-width `W`).
///
/// Gaussian and Bessel are as printed.
pub fn weight(
    kind: FilterKind,
    width: f32,
    height: f32,
    dx: f32,
    dy: f32,
    original: &Original,
) -> f32 {
    // Appendix A's y offset, stretched to the y width (untouched when the widths agree).
    let ay = if height == width { dy } else { dy * (width / height) };
    match kind {
        FilterKind::Box => box_filter(width, dx, ay, original.box_filter),
        FilterKind::Gaussian => gaussian_filter(width, dx, ay),
        FilterKind::Sinc => sinc_filter(dx, ay, original.sinc_filter),
        FilterKind::Bartlett => bartlett_filter(width, dx, ay, original.bartlett_filter),
        FilterKind::Bessel => bessel_filter(dx, ay),
        FilterKind::RiBox
        | FilterKind::RiTriangle
        | FilterKind::RiCatmullRom
        | FilterKind::RiGaussian
        | FilterKind::RiSinc
        | FilterKind::RiDisk
        | FilterKind::RiBessel
        | FilterKind::RiMitchell
        | FilterKind::RiBlackmanHarris => {
            super::renderman::weight(kind, width, height, dx, dy).unwrap_or(0.0)
        }
    }
}

/// Port of `boxfilter` (Appendix A 2.3).
fn box_filter(width: f32, dx: f32, dy: f32, original: bool) -> f32 {
    let inside = if original {
        // As printed: signed offsets against the full width, so negative offsets never cut.
        !(dx > width || dy > width)
    } else {
        let half = 0.5 * width;
        dx.abs() <= half && dy.abs() <= half
    };
    if inside { 1.0 } else { 0.0 }
}

/// Port of `gaussianfilter` (Appendix A 2.3): `exp(-r²) - exp(-(W/2)²)` inside `r <= W/2`.
fn gaussian_filter(width: f32, dx: f32, dy: f32) -> f32 {
    let (x, y, w) = (f64::from(dx), f64::from(dy), f64::from(width));
    let d = x * x + y * y;
    let limit = w * w / 4.0;
    if d > limit { 0.0 } else { ((-d).exp() - (-limit).exp()) as f32 }
}

/// Port of `sinc` (Appendix A 2.3): `sin(2r)/r`, with `centre` for `|r| < .001`.
fn sinc(r: f64, centre: f64) -> f64 {
    if r.abs() < CENTRE_EPS { centre } else { (2.0 * r).sin() / r }
}

/// Port of `sincfilter` (Appendix A 2.3): separable, unwindowed.
fn sinc_filter(dx: f32, dy: f32, original: bool) -> f32 {
    // The limit of sin(2r)/r at 0 is 2; the listing prints `cos(2*r)/1`, i.e. 1.
    let centre = if original { 1.0 } else { 2.0 };
    (sinc(f64::from(dx), centre) * sinc(f64::from(dy), centre)) as f32
}

/// Port of `bartlettfilter` (Appendix A 2.3): separable tent.
fn bartlett_filter(width: f32, dx: f32, dy: f32, original: bool) -> f32 {
    // The listing uses the full width as the half-width (support 2W).
    let half = if original { width } else { 0.5 * width };
    let (ax, ay) = (dx.abs(), dy.abs());
    if half < ax || half < ay { 0.0 } else { (half - ax) * (half - ay) }
}

/// Port of `besselfilter` and `bessel` (Appendix A 2.3): jinc `J1(2r)/r`, value 1 at the
/// centre (its limit), unwindowed.
fn bessel_filter(dx: f32, dy: f32) -> f32 {
    let r = f64::from(dx).hypot(f64::from(dy));
    if r < CENTRE_EPS { 1.0 } else { (bessel_j1(2.0 * r) / r) as f32 }
}

/// Crossover between the power series and the asymptotic expansion of [`bessel_j1`]. At 12
/// the series loses at most about 4 decimal digits to cancellation (largest term ~4e3) and the
/// asymptotic series' smallest term is below 1e-10.
const J1_SERIES_LIMIT: f64 = 12.0;

/// Bessel function of the first kind, order 1: `J1(x)` (the C library's `j1`, which
/// Appendix A's `bessel` calls).
///
/// For `|x| < 12` the power series `Σ (-1)^k (x/2)^(2k+1) / (k! (k+1)!)`; beyond, Hankel's
/// asymptotic expansion `sqrt(2/(πx)) (P cos χ - Q sin χ)`, `χ = x - 3π/4`, summed until
/// its terms stop decreasing. Absolute error is below 1e-10 everywhere. `J1` is odd.
pub fn bessel_j1(x: f64) -> f64 {
    if !x.is_finite() {
        // J1 decays to 0 at infinity; NaN stays NaN.
        return if x.is_nan() { x } else { 0.0 };
    }
    let ax = x.abs();
    let value = if ax < J1_SERIES_LIMIT { j1_series(ax) } else { j1_asymptotic(ax) };
    if x < 0.0 { -value } else { value }
}

/// `J1(x)` by its power series; accurate for `0 <= x < J1_SERIES_LIMIT`.
fn j1_series(x: f64) -> f64 {
    let half = 0.5 * x;
    let q = half * half;
    // term_k = (-1)^k half^(2k+1) / (k! (k+1)!), term_{k+1} = -term_k q / ((k+1)(k+2)).
    let mut term = half;
    let mut sum = term;
    let mut k = 0.0_f64;
    loop {
        term *= -q / ((k + 1.0) * (k + 2.0));
        sum += term;
        k += 1.0;
        if term.abs() <= f64::EPSILON * sum.abs().max(f64::MIN_POSITIVE) || k > 200.0 {
            return sum;
        }
    }
}

/// `J1(x)` by Hankel's asymptotic expansion (A&S 9.2.5, 9.2.9, 9.2.10 with ν = 1); used for
/// `x >= J1_SERIES_LIMIT`.
fn j1_asymptotic(x: f64) -> f64 {
    let mu = 4.0_f64; // 4ν²
    let eight_x = 8.0 * x;
    // a_k = Π_{m=1..k} (μ - (2m-1)²) / (k! (8x)^k); P = a_0 - a_2 + a_4 - ..., Q = a_1 - a_3 + ...
    let mut p = 1.0_f64;
    let mut q = 0.0_f64;
    let mut a = 1.0_f64;
    let mut prev = f64::INFINITY;
    for k in 1..60_u32 {
        let odd = f64::from(2 * k - 1);
        let next = a * (mu - odd * odd) / (f64::from(k) * eight_x);
        if next.abs() >= prev || next == 0.0 {
            break; // the asymptotic series has started to diverge (or terminated)
        }
        prev = next.abs();
        a = next;
        match k % 4 {
            1 => q += a,
            2 => p -= a,
            3 => q -= a,
            _ => p += a,
        }
    }
    let chi = x - 0.75 * std::f64::consts::PI;
    (2.0 / (std::f64::consts::PI * x)).sqrt() * (p * chi.cos() - q * chi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const KINDS: [FilterKind; 5] = [
        FilterKind::Box,
        FilterKind::Gaussian,
        FilterKind::Sinc,
        FilterKind::Bartlett,
        FilterKind::Bessel,
    ];

    fn all_original() -> Original {
        Original {
            box_filter: true,
            bartlett_filter: true,
            sinc_filter: true,
            ..Original::default()
        }
    }

    #[test]
    fn j1_known_values() {
        // Reference values of J1 (tables of Bessel functions; mpmath agrees to all digits).
        for (x, expected) in [
            (1.0, 0.440_050_585_7),
            (2.0, 0.576_724_807_8),
            (5.0, -0.327_579_137_6),
            (10.0, 0.043_472_746_2),
        ] {
            let got = bessel_j1(x);
            assert!((got - expected).abs() < 1e-6, "J1({x}) = {got}, expected {expected}");
            assert!((bessel_j1(-x) + expected).abs() < 1e-6, "J1 is odd at {x}");
        }
    }

    #[test]
    fn j1_both_branches_against_mpmath() {
        // mpmath.besselj(1, x) to 15 digits: both sides of the series/asymptotic crossover.
        for (x, expected) in [
            (0.5, 0.242_268_457_674_874),
            (11.9, -0.228_983_249_661_924),
            (12.0, -0.223_447_104_490_628),
            (12.1, -0.215_748_973_376_925),
            (20.0, 0.066_833_124_175_850),
            (100.0, -0.077_145_352_014_112),
        ] {
            let got = bessel_j1(x);
            assert!((got - expected).abs() < 1e-9, "J1({x}) = {got}, expected {expected}");
        }
    }

    #[test]
    fn j1_zeros() {
        // First zeros of J1 (j_{1,1..4}); the fourth lies in the asymptotic branch.
        for z in [
            3.831_705_970_207_512,
            7.015_586_669_815_619,
            10.173_468_135_062_722,
            13.323_691_936_314_223,
        ] {
            assert!(bessel_j1(z).abs() < 1e-9, "J1({z}) = {}", bessel_j1(z));
        }
        assert_eq!(bessel_j1(0.0), 0.0);
        assert_eq!(bessel_j1(f64::INFINITY), 0.0);
        assert!(bessel_j1(f64::NAN).is_nan());
    }

    #[test]
    fn sinc_centre_is_two_fixed_one_original() {
        let fixed = weight(FilterKind::Sinc, 2.0, 2.0, 0.0, 0.0, &Original::default());
        let orig = weight(FilterKind::Sinc, 2.0, 2.0, 0.0, 0.0, &all_original());
        assert_eq!(fixed, 4.0, "2 x 2 at the centre");
        assert_eq!(orig, 1.0, "1 x 1 at the centre");
        // Off-centre on one axis only: the centre factor alone differs.
        let x = 0.3_f32;
        let s = (2.0 * f64::from(x)).sin() / f64::from(x);
        let fixed = weight(FilterKind::Sinc, 2.0, 2.0, x, 0.0, &Original::default());
        let orig = weight(FilterKind::Sinc, 2.0, 2.0, x, 0.0, &all_original());
        assert!((f64::from(fixed) - 2.0 * s).abs() < 1e-6);
        assert!((f64::from(orig) - s).abs() < 1e-6);
        // The fixed centre is continuous with its neighbourhood; the original is not.
        let near = weight(FilterKind::Sinc, 2.0, 2.0, 0.002, 0.0, &Original::default());
        assert!((near - 4.0).abs() < 1e-4);
    }

    #[test]
    fn bessel_centre_is_one_and_continuous() {
        let o = Original::default();
        assert_eq!(weight(FilterKind::Bessel, 2.0, 2.0, 0.0, 0.0, &o), 1.0);
        let near = weight(FilterKind::Bessel, 2.0, 2.0, 0.002, 0.0, &o);
        assert!((near - 1.0).abs() < 1e-5);
        // Radial: depends on hypot(dx, dy) only.
        let a = weight(FilterKind::Bessel, 2.0, 2.0, 0.6, 0.8, &o);
        let b = weight(FilterKind::Bessel, 2.0, 2.0, 1.0, 0.0, &o);
        assert!((a - b).abs() < 1e-6);
        assert!((f64::from(b) - bessel_j1(2.0)).abs() < 1e-6);
    }

    #[test]
    fn original_box_is_asymmetric_fixed_symmetric() {
        // Appendix A 3.16: W = 1.2, nx = 4, largest offset 1.375.
        let fixed = Original::default();
        let orig = all_original();
        assert_eq!(weight(FilterKind::Box, 1.2, 1.2, 1.375, 0.0, &orig), 0.0);
        assert_eq!(weight(FilterKind::Box, 1.2, 1.2, -1.375, 0.0, &orig), 1.0);
        assert_eq!(weight(FilterKind::Box, 1.2, 1.2, 0.0, 1.375, &orig), 0.0);
        assert_eq!(weight(FilterKind::Box, 1.2, 1.2, 0.0, -1.375, &orig), 1.0);
        for d in [0.375_f32, 0.625, 1.375] {
            let pos = weight(FilterKind::Box, 1.2, 1.2, d, 0.0, &fixed);
            let neg = weight(FilterKind::Box, 1.2, 1.2, -d, 0.0, &fixed);
            assert_eq!(pos, neg, "fixed box symmetric at {d}");
        }
        assert_eq!(weight(FilterKind::Box, 1.2, 1.2, 0.6, -0.6, &fixed), 1.0);
        assert_eq!(weight(FilterKind::Box, 1.2, 1.2, 0.625, 0.0, &fixed), 0.0);
    }

    #[test]
    fn bartlett_half_width() {
        let fixed = Original::default();
        let orig = all_original();
        // Fixed: support |d| <= W/2 = 1, peak (W/2)^2.
        assert_eq!(weight(FilterKind::Bartlett, 2.0, 2.0, 0.0, 0.0, &fixed), 1.0);
        assert_eq!(weight(FilterKind::Bartlett, 2.0, 2.0, 0.5, 0.0, &fixed), 0.5);
        assert_eq!(weight(FilterKind::Bartlett, 2.0, 2.0, 1.5, 0.0, &fixed), 0.0);
        // Original: support |d| <= W = 2, peak W^2.
        assert_eq!(weight(FilterKind::Bartlett, 2.0, 2.0, 0.0, 0.0, &orig), 4.0);
        assert_eq!(weight(FilterKind::Bartlett, 2.0, 2.0, 1.5, 0.0, &orig), 1.0);
        assert_eq!(weight(FilterKind::Bartlett, 2.0, 2.0, 2.5, 0.0, &orig), 0.0);
    }

    #[test]
    fn gaussian_as_printed() {
        let o = Original::default();
        let w = weight(FilterKind::Gaussian, 2.0, 2.0, 0.5, 0.0, &o);
        let expected = (-0.25_f64).exp() - (-1.0_f64).exp();
        assert!((f64::from(w) - expected).abs() < 1e-7);
        assert_eq!(weight(FilterKind::Gaussian, 2.0, 2.0, 1.0, 0.0, &o), 0.0, "zero at r = W/2");
        assert_eq!(weight(FilterKind::Gaussian, 2.0, 2.0, 0.8, 0.8, &o), 0.0, "radial cut");
    }

    proptest! {
        #[test]
        fn fixed_kernels_zero_past_radius(
            width in 0.5_f32..6.0,
            excess in 1e-3_f32..4.0,
            other in -1.0_f32..1.0,
            angle in 0.0_f32..std::f32::consts::TAU,
            swap in any::<bool>(),
            neg in any::<bool>(),
        ) {
            let o = Original::default();
            let half = 0.5 * width;
            // Separable kernels (box, Bartlett): one coordinate past W/2, the other anywhere.
            let far = if neg { -(half + excess) } else { half + excess };
            let near = other * half * 3.0;
            let (dx, dy) = if swap { (near, far) } else { (far, near) };
            prop_assert_eq!(weight(FilterKind::Box, width, width, dx, dy, &o), 0.0);
            prop_assert_eq!(weight(FilterKind::Bartlett, width, width, dx, dy, &o), 0.0);
            // Radial kernel (Gaussian): distance past W/2 in any direction.
            let r = half + excess;
            let (gx, gy) = (r * angle.cos(), r * angle.sin());
            if gx.hypot(gy) > half * (1.0 + 1e-5) {
                prop_assert_eq!(weight(FilterKind::Gaussian, width, width, gx, gy, &o), 0.0);
            }
        }

        #[test]
        fn fixed_kernels_are_even(
            width in 0.5_f32..6.0,
            dx in -4.0_f32..4.0,
            dy in -4.0_f32..4.0,
        ) {
            let o = Original::default();
            for kind in KINDS {
                let w = weight(kind, width, width, dx, dy, &o);
                prop_assert!(w.is_finite());
                prop_assert_eq!(w, weight(kind, width, width, -dx, dy, &o), "{:?}", kind);
                prop_assert_eq!(w, weight(kind, width, width, dx, -dy, &o), "{:?}", kind);
            }
        }
    }
}
