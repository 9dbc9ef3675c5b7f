//! Exact planar geometry for analytic tests: polygons clipped by half-planes
//! (Sutherland-Hodgman) and their areas (shoelace), in `f64`; and the bound on stratified
//! sampling's coverage error that those areas test.
//!
//! Invariant: exact up to `f64` rounding for convex clip regions; no sampling anywhere.

/// A polygon as its vertices in order (either winding).
pub type Polygon = Vec<(f64, f64)>;

/// The part of `poly` on the side `a x + b y <= c` (one Sutherland-Hodgman step).
pub fn clip(poly: &[(f64, f64)], a: f64, b: f64, c: f64) -> Polygon {
    let f = |p: (f64, f64)| a * p.0 + b * p.1 - c;
    let mut out = Vec::with_capacity(poly.len() + 1);
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        let (fp, fq) = (f(p), f(q));
        if fp <= 0.0 {
            out.push(p);
        }
        if (fp < 0.0) != (fq < 0.0) && fp != fq {
            let t = fp / (fp - fq);
            out.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
        }
    }
    out
}

/// The unsigned area of a polygon (shoelace).
pub fn area(poly: &[(f64, f64)]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|k| poly[k].0 * poly[(k + 1) % n].1 - poly[(k + 1) % n].0 * poly[k].1)
        .sum::<f64>()
        .abs()
        / 2.0
}

/// The pixel `[x, x+1] x [y, y+1]` as a polygon.
pub fn pixel(x: f64, y: f64) -> Polygon {
    vec![(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)]
}

/// Area of the pixel `[x, x+1] x [y, y+1]` on the side `a x + b y <= c`.
pub fn pixel_below(a: f64, b: f64, c: f64, x: f64, y: f64) -> f64 {
    area(&clip(&pixel(x, y), a, b, c))
}

/// Area of the convex polygon `poly` inside the pixel `[px, px+1] x [py, py+1]`.
pub fn coverage_of_pixel(poly: &[(f64, f64)], px: f64, py: f64) -> f64 {
    let mut p = poly.to_vec();
    for (a, b, c) in
        [(-1.0, 0.0, -px), (1.0, 0.0, px + 1.0), (0.0, -1.0, -py), (0.0, 1.0, py + 1.0)]
    {
        p = clip(&p, a, b, c);
        if p.is_empty() {
            return 0.0;
        }
    }
    area(&p)
}

/// The bound on the RMS coverage error of a pixel an edge crosses, sampled once in each cell
/// of an `n x n` grid: only the cells the edge cuts vary, each a Bernoulli indicator (variance
/// at most 1/4) weighted `1/n^2`, and a line cuts at most `2n - 1` of them, so
/// `RMS <= sqrt(2n - 1) / (2 n^2)`.
pub fn stratified_rms_bound(n: u32) -> f64 {
    ((2 * n - 1) as f64).sqrt() / (2.0 * (n * n) as f64)
}

/// The law of the coverage tests: each RMS coverage error `(n, rms)` measured on an `n x n`
/// grid (grids growing in turn) is within [`stratified_rms_bound`] plus 15% (several standard
/// errors of an estimate from some hundreds of pixels or trials), and the errors shrink as the
/// grids grow. `what` says what each was measured over, for the message.
pub fn assert_stratified(rms: &[(u32, f64)], what: &str) {
    for &(n, r) in rms {
        let bound = stratified_rms_bound(n);
        assert!(
            r <= bound * 1.15,
            "{n}x{n}: rms {r} over {what} above the stratified bound {bound}"
        );
    }
    assert!(rms.windows(2).all(|w| w[0].1 > w[1].1), "error must shrink with samples: {rms:?}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_and_quarter_pixels() {
        assert!((pixel_below(1.0, 0.0, 0.5, 0.0, 0.0) - 0.5).abs() < 1e-15);
        assert!((pixel_below(1.0, 1.0, 1.0, 0.0, 0.0) - 0.5).abs() < 1e-15);
        assert!((pixel_below(1.0, 1.0, 0.5, 0.0, 0.0) - 0.125).abs() < 1e-15);
        assert_eq!(pixel_below(1.0, 0.0, -1.0, 0.0, 0.0), 0.0);
        assert_eq!(pixel_below(1.0, 0.0, 2.0, 0.0, 0.0), 1.0);
        let tri = [(0.0, 0.0), (2.0, 0.0), (0.0, 2.0)];
        assert!((coverage_of_pixel(&tri, 0.0, 0.0) - 1.0).abs() < 1e-15);
        assert!((coverage_of_pixel(&tri, 1.0, 0.0) - 0.5).abs() < 1e-15);
        assert_eq!(coverage_of_pixel(&tri, 1.0, 1.0), 0.0);
    }
}
