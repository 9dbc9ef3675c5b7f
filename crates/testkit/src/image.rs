//! Comparing rendered films.

use reyes_film::Film;

/// Peak signal-to-noise ratio of `b` against `a` over every channel of RGBA (peak 1), in dB.
pub fn psnr(a: &Film, b: &Film) -> f64 {
    let se: f64 = a
        .rgba()
        .iter()
        .zip(b.rgba())
        .map(|(p, q)| (0..4).map(|c| f64::from(p[c] - q[c]).powi(2)).sum::<f64>())
        .sum();
    10.0 * ((a.rgba().len() * 4) as f64 / se.max(1e-30)).log10()
}
