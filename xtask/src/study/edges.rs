//! The edge study behind docs/sampling.md: the error of pixel values against analytic
//! truth on edges that are sharp, moving, out of focus, or both.
//!
//! The edge errors come from whole renders ([`render`]) of scenes written as text and
//! parsed like scene files, filtered with a one-pixel box so that a pixel's value is the plain mean of its
//! samples' coverage.
//!
//! Analytic truth for an edge. In raster space (pixels, y down) the half-plane
//! `n . p <= c` (unit `n`) moves by `v t` over the shutter (t uniform in [0, 1)) and is seen
//! through a thin lens that shifts it by `rho l` for the lens point `l` in the unit disk. A
//! point `p` is covered when `n . p <= c + (n . v) t + rho (n . l)`, where `n . l` has the
//! semicircle density `(2/pi) sqrt(1 - x^2)` on [-1, 1]. The pixel's true value is the mean of
//! `A(c + (n . v) t + rho x)` over t and x, where `A(c')` is the area of the pixel on the side
//! `n . p <= c'`: a piecewise quadratic in closed form ([`pixel_area`]). The mean over t is
//! exact with its antiderivative (a piecewise cubic), the mean over x is a 2048-point
//! midpoint rule in `x = sin(theta)`, whose integrand is smooth (error below 1e-7).

use rayon::prelude::*;
use reyes_render::{RenderError, RenderOptions, render};
use reyes_sampling::SplitMix64;

use super::patterns::Sampler;

/// Which effect blurs the edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EdgeCase {
    /// A still edge, pinhole camera: pixel integral over position only.
    Static,
    /// A moving edge: integral over position and time.
    Motion,
    /// An edge out of focus: integral over position and lens.
    Defocus,
    /// An edge both moving and out of focus: position, time and lens at once.
    Combined,
}

impl EdgeCase {
    /// Every case.
    pub const ALL: [EdgeCase; 4] =
        [EdgeCase::Static, EdgeCase::Motion, EdgeCase::Defocus, EdgeCase::Combined];

    /// Name for titles.
    pub fn label(self) -> &'static str {
        match self {
            EdgeCase::Static => "static edge",
            EdgeCase::Motion => "motion-blurred edge",
            EdgeCase::Defocus => "defocused edge",
            EdgeCase::Combined => "moving and defocused edge",
        }
    }

    fn moves(self) -> bool {
        matches!(self, EdgeCase::Motion | EdgeCase::Combined)
    }

    fn defocused(self) -> bool {
        matches!(self, EdgeCase::Defocus | EdgeCase::Combined)
    }
}

/// Sizes of the edge study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeStudy {
    /// Square image side in pixels (the camera has a 90 degree field of view).
    pub image: u32,
    /// Random edges (one render each) per case, sampler and sample count.
    pub edges: usize,
    /// Seed of the edges (each edge's render also gets its own hider seed).
    pub seed: u64,
    /// Distance an edge moves over the shutter, pixels.
    pub motion_px: f64,
    /// Radius of the circle of confusion, pixels.
    pub blur_px: f64,
}

impl Default for EdgeStudy {
    fn default() -> Self {
        EdgeStudy { image: 32, edges: 48, seed: 1, motion_px: 3.0, blur_px: 2.0 }
    }
}

/// One edge in raster space: the half-plane `n . p <= c`, moving by `v` pixels over the
/// shutter and blurred by a circle of confusion of radius `rho` pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    /// Unit normal (pointing out of the covered side).
    pub n: [f64; 2],
    /// Offset.
    pub c: f64,
    /// Motion over the shutter, pixels.
    pub v: [f64; 2],
    /// Circle of confusion radius, pixels.
    pub rho: f64,
}

/// Depth of the edge's plane.
const EDGE_Z: f64 = 4.0;

impl EdgeStudy {
    /// The study's edges for `case`: random orientation, passing within a quarter of the
    /// image of its centre; random direction of motion. The same for every sampler.
    pub fn edges(&self, case: EdgeCase) -> Vec<Edge> {
        let mut rng = SplitMix64::from_state(reyes_sampling::hash(self.seed, &[0xed9e]));
        let half = self.image as f64 / 2.0;
        (0..self.edges)
            .map(|_| {
                let ang = rng.next_f64() * std::f64::consts::TAU;
                let n = [ang.cos(), ang.sin()];
                let p =
                    [half + (rng.next_f64() - 0.5) * half, half + (rng.next_f64() - 0.5) * half];
                let mang = rng.next_f64() * std::f64::consts::TAU;
                let v = if case.moves() {
                    [self.motion_px * mang.cos(), self.motion_px * mang.sin()]
                } else {
                    [0.0, 0.0]
                };
                Edge {
                    n,
                    c: n[0] * p[0] + n[1] * p[1],
                    v,
                    rho: if case.defocused() { self.blur_px } else { 0.0 },
                }
            })
            .collect()
    }

    /// Pixels per unit at depth 1.
    fn k(&self) -> f64 {
        self.image as f64 / 2.0
    }

    /// World point on the edge's plane seen at raster `(u, v)`.
    fn world(&self, u: f64, v: f64) -> [f64; 3] {
        let (h, k) = (self.image as f64 / 2.0, self.k());
        [(u - h) * EDGE_Z / k, (h - v) * EDGE_Z / k, EDGE_Z]
    }

    /// The scene text of one edge: a white bilinear patch covering the half-plane (far past
    /// the image on three sides), deformed linearly by `v` over the shutter when it moves,
    /// seen through a lens focused at half its depth when it is out of focus. The patch is flat
    /// and its edge straight, so micropolygon size changes nothing but speed: a shading rate
    /// of 64 (8 x 8 pixel micropolygons) keeps the hider's misses few.
    /// `extra` is appended to the hider's fields (e.g. `, adaptive: (max_level: 2)`).
    pub fn scene_text(
        &self,
        edge: &Edge,
        sampler: Sampler,
        n: u32,
        seed: u64,
        extra: &str,
    ) -> String {
        let big = 3.0 * self.image as f64;
        let [nx, ny] = edge.n;
        let (d, p0) = ([-ny, nx], [nx * edge.c, ny * edge.c]);
        let corners = |shift: [f64; 2]| {
            let a = [p0[0] - big * d[0] + shift[0], p0[1] - big * d[1] + shift[1]];
            let b = [p0[0] + big * d[0] + shift[0], p0[1] + big * d[1] + shift[1]];
            let q = |p: [f64; 2]| {
                let w = self.world(p[0], p[1]);
                format!("({:.9}, {:.9}, {:.9})", w[0], w[1], w[2])
            };
            let back = |p: [f64; 2]| [p[0] - big * nx, p[1] - big * ny];
            format!("{}, {}, {}, {}", q(a), q(b), q(back(a)), q(back(b)))
        };
        let points = corners([0.0, 0.0]);
        let deform = if edge.v != [0.0, 0.0] {
            format!(
                ", deform: [(time: 0.0, points: [{points}]), (time: 1.0, points: [{}])]",
                corners(edge.v)
            )
        } else {
            String::new()
        };
        let lens = if edge.rho > 0.0 {
            // rho = R k |1/z - 1/fd| with fd = z/2: R = rho z / k; f = 1, N = 1 / (2R).
            let r = edge.rho * EDGE_Z / self.k();
            format!(
                "Some((focal_length: 1.0, f_stop: {:.9}, focal_distance: {:.9}))",
                0.5 / r,
                EDGE_Z / 2.0
            )
        } else {
            "None".into()
        };
        format!(
            "Scene(image: (width: {w}, height: {w}),
               camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 90.0, lens: {lens}),
               hider: (pixel_samples: ({n}, {n}), {fields}{extra}, filter: (kind: Box, width: 1.0),
                       seed: {seed}, shading_rate: 64.0),
               objects: [(shape: BilinearPatch(points: ({points})),
                          material: Constant(color: (1.0, 1.0, 1.0)){deform})])",
            w = self.image,
            fields = sampler.scene_fields(),
        )
    }

    /// Per-pixel errors (rendered alpha minus the analytic value) of every pixel the edge
    /// passes over (analytic value strictly between 0 and 1), one list per edge.
    pub fn errors_by_edge(
        &self,
        case: EdgeCase,
        sampler: Sampler,
        n: u32,
    ) -> Result<Vec<Vec<f64>>, RenderError> {
        Ok(self.errors_and_samples(case, sampler, n, "")?.0)
    }

    /// [`EdgeStudy::errors_by_edge`] with `extra` hider fields, and the samples every render
    /// took in all (NS per pixel plus adaptive sampling's extra samples), summed over edges.
    pub fn errors_and_samples(
        &self,
        case: EdgeCase,
        sampler: Sampler,
        n: u32,
        extra: &str,
    ) -> Result<(Vec<Vec<f64>>, u64), RenderError> {
        let per_edge: Vec<(Vec<f64>, u64)> = self
            .edges(case)
            .par_iter()
            .enumerate()
            .map(|(i, edge)| {
                let seed = reyes_sampling::hash(self.seed, &[i as u64, 0x5eed]) % 1_000_000;
                let text = self.scene_text(edge, sampler, n, seed, extra);
                let scene = reyes_scene::parse(&text, std::path::Path::new("study.ron"))
                    .unwrap_or_else(|e| panic!("study scene does not parse: {e}\n{text}"));
                let rendered = render(&scene, &RenderOptions::default())?;
                let samples =
                    (self.image * self.image * n * n) as u64 + rendered.stats.hider.extra_samples;
                let film = rendered.film;
                let mut errs = Vec::new();
                for y in 0..self.image {
                    for x in 0..self.image {
                        let want = edge_coverage(edge, x, y);
                        if want > 1e-9 && want < 1.0 - 1e-9 {
                            let got = film.pixel(x, y).map_or(0.0, |p| p[3] as f64);
                            errs.push(got - want);
                        }
                    }
                }
                Ok((errs, samples))
            })
            .collect::<Result<_, RenderError>>()?;
        let samples = per_edge.iter().map(|e| e.1).sum();
        Ok((per_edge.into_iter().map(|e| e.0).collect(), samples))
    }

    /// Adaptive sampling on `case`: the RMSE, and the mean samples per pixel spent over the
    /// whole image, with `n x n` base samples of `sampler` and `extra` adaptive fields.
    pub fn measure_adaptive(
        &self,
        case: EdgeCase,
        sampler: Sampler,
        n: u32,
        extra: &str,
    ) -> Result<(Measured, f64), RenderError> {
        let (errs, samples) = self.errors_and_samples(case, sampler, n, extra)?;
        let spp = samples as f64 / (self.edges * (self.image * self.image) as usize) as f64;
        Ok((Measured::from_edges(&errs), spp))
    }

    /// Root-mean-square error over every pixel of every edge.
    #[cfg(test)]
    pub fn rmse(&self, case: EdgeCase, sampler: Sampler, n: u32) -> Result<f64, RenderError> {
        Ok(self.measure(case, sampler, n)?.rmse)
    }

    /// RMSE with its standard error (see [`Measured::from_edges`]).
    pub fn measure(
        &self,
        case: EdgeCase,
        sampler: Sampler,
        n: u32,
    ) -> Result<Measured, RenderError> {
        Ok(Measured::from_edges(&self.errors_by_edge(case, sampler, n)?))
    }
}

/// An RMSE and its standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Root-mean-square error over all pixels of all edges.
    pub rmse: f64,
    /// Its standard error, treating edges (not pixels, which are correlated along an edge) as
    /// the independent units: the squared errors' total over the pixel count is a ratio
    /// estimator, whose variance is `sum_e (S_e - mse n_e)^2 / (E (E-1) nbar^2)` over edges
    /// `e` with `n_e` pixels and squared-error sum `S_e`; then `se(rmse) = se(mse) / (2 rmse)`.
    pub se: f64,
}

impl Measured {
    /// From per-edge error lists.
    pub fn from_edges(edges: &[Vec<f64>]) -> Measured {
        let n: usize = edges.iter().map(Vec::len).sum();
        let sums: Vec<(f64, f64)> =
            edges.iter().map(|e| (e.iter().map(|x| x * x).sum::<f64>(), e.len() as f64)).collect();
        let mse = sums.iter().map(|s| s.0).sum::<f64>() / n.max(1) as f64;
        let rmse = mse.sqrt();
        let k = edges.len() as f64;
        let nbar = n as f64 / k;
        let var = if k > 1.0 {
            sums.iter().map(|(s, m)| (s - mse * m).powi(2)).sum::<f64>()
                / (k * (k - 1.0) * nbar * nbar)
        } else {
            f64::NAN
        };
        Measured { rmse, se: var.sqrt() / (2.0 * rmse) }
    }
}

/// `max(s, 0)^k / k!` summed with the signs of the corners of a box spline: for `a, b > 0`,
/// the area (k = 2) or its antiderivative (k = 3) of the unit square below `a x + b y = c`.
fn corner_sum(c: f64, a: f64, b: f64, k: i32) -> f64 {
    let r = |s: f64| if s > 0.0 { s.powi(k) } else { 0.0 };
    let fact = if k == 2 { 2.0 } else { 6.0 };
    if a < 1e-9 {
        // Limit a -> 0: one dimension, A = ramp(c)/b differences.
        let r1 = |s: f64| if s > 0.0 { s.powi(k - 1) } else { 0.0 };
        return (r1(c) - r1(c - b)) / (b * fact / (k as f64));
    }
    if b < 1e-9 {
        return corner_sum(c, b, a, k);
    }
    (r(c) - r(c - a) - r(c - b) + r(c - a - b)) / (fact * a * b)
}

/// Area of pixel `[x, x+1] x [y, y+1]` on the side `n . p <= c` (`n` a unit vector).
pub fn pixel_area(n: [f64; 2], c: f64, x: u32, y: u32) -> f64 {
    let (a, b) = (n[0], n[1]);
    // Reflect so both components are >= 0: a x' with x' = 1 - x adds a to the offset.
    let c = c - a * x as f64 - b * y as f64 - a.min(0.0) - b.min(0.0);
    corner_sum(c, a.abs(), b.abs(), 2).clamp(0.0, 1.0)
}

/// Antiderivative in `c` of [`pixel_area`] (zero far on the uncovered side).
fn pixel_area_integral(n: [f64; 2], c: f64, x: u32, y: u32) -> f64 {
    let (a, b) = (n[0], n[1]);
    let c0 = c - a * x as f64 - b * y as f64 - a.min(0.0) - b.min(0.0);
    corner_sum(c0, a.abs(), b.abs(), 3)
}

/// The exact value of pixel `(x, y)` for `edge`: its area covered, averaged over the shutter
/// (uniform) and the lens (uniform on the disk). See the module documentation.
pub fn edge_coverage(edge: &Edge, x: u32, y: u32) -> f64 {
    let w = edge.n[0] * edge.v[0] + edge.n[1] * edge.v[1];
    let over_time = |c: f64| {
        if w.abs() < 1e-9 {
            pixel_area(edge.n, c, x, y)
        } else {
            (pixel_area_integral(edge.n, c + w, x, y) - pixel_area_integral(edge.n, c, x, y)) / w
        }
    };
    if edge.rho == 0.0 {
        return over_time(edge.c);
    }
    // Mean over x = n . l with density (2/pi) sqrt(1 - x^2): x = sin(theta), weight
    // (2/pi) cos^2(theta) d theta on [-pi/2, pi/2].
    let m = 2048;
    let h = std::f64::consts::PI / m as f64;
    let mut sum = 0.0;
    for i in 0..m {
        let th = -std::f64::consts::FRAC_PI_2 + (i as f64 + 0.5) * h;
        let wgt = th.cos().powi(2);
        sum += wgt * over_time(edge.c + edge.rho * th.sin());
    }
    (sum * h * 2.0 / std::f64::consts::PI).clamp(0.0, 1.0)
}

/// Least-squares slope of `ln y` against `ln x`.
pub fn fit_slope(xs: &[f64], ys: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let lx: Vec<f64> = xs.iter().map(|x| x.ln()).collect();
    let ly: Vec<f64> = ys.iter().map(|y| y.ln()).collect();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Area by Sutherland-Hodgman clipping, for checking the closed form.
    fn clipped(n: [f64; 2], c: f64, x: f64, y: f64) -> f64 {
        let sq = [(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)];
        let f = |p: (f64, f64)| n[0] * p.0 + n[1] * p.1 - c;
        let mut out: Vec<(f64, f64)> = Vec::new();
        for k in 0..4 {
            let (p, q) = (sq[k], sq[(k + 1) % 4]);
            let (fp, fq) = (f(p), f(q));
            if fp <= 0.0 {
                out.push(p);
            }
            if (fp < 0.0) != (fq < 0.0) && fp != fq {
                let t = fp / (fp - fq);
                out.push((p.0 + t * (q.0 - p.0), p.1 + t * (q.1 - p.1)));
            }
        }
        let m = out.len();
        (0..m)
            .map(|k| out[k].0 * out[(k + 1) % m].1 - out[(k + 1) % m].0 * out[k].1)
            .sum::<f64>()
            .abs()
            / 2.0
    }

    #[test]
    fn pixel_area_matches_clipping() {
        let mut rng = SplitMix64::from_state(3);
        for _ in 0..2000 {
            let ang = rng.next_f64() * std::f64::consts::TAU;
            let n = [ang.cos(), ang.sin()];
            let (x, y) = ((rng.next_f64() * 8.0) as u32, (rng.next_f64() * 8.0) as u32);
            let c = n[0] * (x as f64 + 2.0 * rng.next_f64() - 0.5)
                + n[1] * (y as f64 + 2.0 * rng.next_f64() - 0.5);
            let a = pixel_area(n, c, x, y);
            let b = clipped(n, c, x as f64, y as f64);
            assert!((a - b).abs() < 1e-9, "{n:?} {c} ({x},{y}): {a} vs {b}");
        }
        // Axis-aligned normals take the one-dimensional limit.
        assert!((pixel_area([1.0, 0.0], 3.25, 3, 0) - 0.25).abs() < 1e-12);
        assert!((pixel_area([0.0, -1.0], -2.5, 0, 2) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn blurred_coverage_is_the_mean_over_time_and_lens() {
        // Brute force: average the exact area over a fine grid of times and lens points.
        let edge = Edge { n: [0.6, 0.8], c: 4.3, v: [2.0, -1.0], rho: 1.5 };
        let (x, y) = (2u32, 3u32);
        let m = 400;
        let (mut sum, mut count) = (0.0, 0.0);
        for i in 0..m {
            let t = (i as f64 + 0.5) / m as f64;
            for j in 0..m {
                for k in 0..m / 8 {
                    let lx = -1.0 + 2.0 * (j as f64 + 0.5) / m as f64;
                    let ly = -1.0 + 2.0 * (k as f64 + 0.5) / (m / 8) as f64;
                    if lx * lx + ly * ly > 1.0 {
                        continue;
                    }
                    let shift = edge.n[0] * (edge.v[0] * t + edge.rho * lx)
                        + edge.n[1] * (edge.v[1] * t + edge.rho * ly);
                    sum += pixel_area(edge.n, edge.c + shift, x, y);
                    count += 1.0;
                }
            }
        }
        let brute = sum / count;
        let exact = edge_coverage(&edge, x, y);
        assert!((brute - exact).abs() < 2e-3, "{brute} vs {exact}");
    }

    #[test]
    fn rendered_edges_converge_to_the_analytic_values() {
        // Guards the raster-to-world mapping, the motion and the lens set-up: with 16 x 16
        // jittered samples the error is a few thousandths; a misplaced edge would be ~0.3.
        let study = EdgeStudy { image: 24, edges: 3, ..EdgeStudy::default() };
        for case in EdgeCase::ALL {
            let e = study.rmse(case, Sampler::Fig6, 16).unwrap();
            assert!(e < 0.02, "{case:?}: rmse {e}");
        }
    }

    #[test]
    fn jittered_beats_random_on_the_static_edge_at_16_samples() {
        // At 16 samples per pixel random sampling has per-pixel RMS error
        // sqrt(A(1-A)/16) ~ 0.09 on edge pixels, stratified sampling about a third of that.
        let study = EdgeStudy { image: 24, edges: 8, ..EdgeStudy::default() };
        let jittered = study.rmse(EdgeCase::Static, Sampler::Fig6, 4).unwrap();
        let random = study.rmse(EdgeCase::Static, Sampler::Random, 4).unwrap();
        assert!(jittered < 0.7 * random, "FIG. 6 {jittered} vs random {random}");
        let sobol = study.rmse(EdgeCase::Static, Sampler::Sobol, 4).unwrap();
        assert!(sobol < 0.7 * random, "Sobol {sobol} vs random {random}");
    }

    #[test]
    fn the_joint_sampler_beats_jitter_on_the_moving_edge_at_64_samples() {
        // The full study measures an RMSE ratio of about 0.69 +- 0.013 (64 edges). With 12
        // edges the ratio's standard error is about sqrt(64/12) times that, 0.03; requiring
        // below 0.85 leaves five of them, while a joint sampler no better than jitter (ratio
        // 1, as Owen-Sobol's decorrelated time was) fails.
        let study = EdgeStudy { edges: 12, ..EdgeStudy::default() };
        let fig6 = study.rmse(EdgeCase::Motion, Sampler::Fig6, 8).unwrap();
        let joint = study.rmse(EdgeCase::Motion, Sampler::SobolJoint, 8).unwrap();
        assert!(joint < 0.85 * fig6, "joint {joint} vs FIG. 6 {fig6}");
    }

    #[test]
    fn adaptive_sampling_counts_its_samples_and_lowers_the_error() {
        // 8 x 8 base samples with one level of refinement on a static edge: at least the base
        // samples are spent, and the error falls below uniform 8 x 8's (stratified theory: the
        // refined quadrants the edge crosses have half the side, so about 2^(-3/2) of the
        // error; edge pixels whose 64 samples all agree are not refined and keep theirs, so
        // only 0.8 is required; no refinement would give 1).
        let study = EdgeStudy { image: 24, edges: 6, ..EdgeStudy::default() };
        let (m, spp) = study
            .measure_adaptive(
                EdgeCase::Static,
                Sampler::SobolJoint,
                8,
                ", adaptive: (max_level: 1)",
            )
            .unwrap();
        let (uniform, spp0) =
            study.measure_adaptive(EdgeCase::Static, Sampler::SobolJoint, 8, "").unwrap();
        assert_eq!(spp0, 64.0);
        assert!(spp > 64.0 && spp < 256.0, "{spp} samples per pixel");
        assert!(m.rmse < 0.8 * uniform.rmse, "adaptive {} vs uniform {}", m.rmse, uniform.rmse);
    }

    #[test]
    fn slope_of_a_power_law() {
        let xs = [1.0, 4.0, 16.0, 64.0];
        let ys: Vec<f64> = xs.iter().map(|x: &f64| 3.0 * x.powf(-0.75)).collect();
        assert!((fit_slope(&xs, &ys) + 0.75).abs() < 1e-12);
    }
}
