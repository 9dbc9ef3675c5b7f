//! Hair keeps its true size: curves and points cover their exact projected area, however
//! thin (issue #34), measured as `accuracy.rs` measures small objects.
//!
//! Each test renders a field of copies of one shape (`reyes_testkit::coverage`): one per
//! cell, orthographic, 8 x 8 samples, a 1-pixel box filter, so each cell's summed alpha is an
//! unbiased estimate of the shape's projected area (jittered sampling never biases coverage:
//! every sample is uniform in its stratum, so the chance it sees the shape is the stratum's
//! covered fraction). A ribbon of width `w` along a planar curve of length `l`, seen face on,
//! covers `w l` (its two edges are offset curves whose lengths average to `l`), so no width
//! is too thin to count: the dicer keeps the ribbon's true width whatever the shading rate
//! (one micropolygon across), and the hider's inside test is exact for micropolygons of any
//! width.
//!
//! Tolerance: the 2% bound, or three standard errors of the mean where the shape is
//! so small that its sampling noise is larger than that. The noise is predicted from the
//! stratified estimator: an outline of length `P` pixels crosses about `8 (4 / pi) P = 10.2
//! P` of the 8 x 8 strata of a pixel (`4 / pi`: the mean of `|cos| + |sin|` over directions),
//! each a Bernoulli trial of variance at most 1/4 and weight 1/64, so a cell's standard error
//! is at most `sqrt(10.2 P / 4) / 64` square pixels, and the mean's that over `sqrt(cells)`.
//! The measured spread must be within that prediction (times 1.5 for its own noise).

use reyes_render::{RenderOptions, render};
use reyes_testkit::coverage::{Field, mean_se};

/// The bound on the relative coverage error.
const BOUND: f64 = 0.02;

/// Mean cell area, its standard error, and the cells, of a field of `shape`.
fn field(shape: &str, cells: u32, cell: u32, hider: &str) -> (f64, f64, usize) {
    let field = Field { shape, transform: "", fields: "", hider, cells, cell };
    let film = render(&field.scene(), &RenderOptions::default()).unwrap().film;
    let sums = field.cell_sums(&film);
    let (mean, se) = mean_se(&sums);
    (mean, se, sums.len())
}

/// Checks a field's mean area against `exact`, for shapes whose outlines are `perimeter`
/// pixels long in all: within the 2%, or three predicted standard errors where the
/// shape is so small that the sampling noise exceeds that.
fn check(what: &str, (mean, se, cells): (f64, f64, usize), exact: f64, perimeter: f64) {
    let predicted = (10.2 * perimeter / 4.0).sqrt() / 64.0 / (cells as f64).sqrt();
    let rel = mean / exact - 1.0;
    let bound = BOUND.max(3.0 * predicted / exact);
    eprintln!(
        "{what}: {:+.2}% +- {:.2}% (predicted noise {:.2}%, bound {:.2}%)",
        100.0 * rel,
        100.0 * se / exact,
        100.0 * predicted / exact,
        100.0 * bound
    );
    assert!(se <= 1.5 * predicted, "{what}: noise {se:.5} above the prediction {predicted:.5}");
    assert!(
        rel.abs() <= bound,
        "{what}: area {mean:.4} against {exact:.4} ({:+.2}% +- {:.2}%)",
        100.0 * rel,
        100.0 * se / exact
    );
}

/// A straight camera-facing curve of width `w` and length `l` covers `w l` square pixels,
/// from a tenth of a pixel to 20 pixels wide, at shading rates 1 and 4, linear and cubic.
#[test]
fn straight_curves_cover_width_times_length() {
    for (w, l, cell) in [
        (0.1_f64, 12.0_f64, 16),
        (0.3, 12.0, 16),
        (1.0, 12.0, 16),
        (3.0, 10.0, 16),
        (20.0, 24.0, 32),
    ] {
        // Both kinds at rate 1; the linear one at rate 4 too.
        for rate in [1.0, 4.0] {
            let h = l / 2.0;
            let linear = format!(
                "Curves(kind: Linear, nvertices: [2], points: [({}, 0.3, 0.0), ({h}, 0.3, 0.0)], width: Constant({w}))",
                -h
            );
            // A cubic Bezier along the same line, its points unevenly spaced.
            let cubic = format!(
                "Curves(kind: Cubic, nvertices: [4], points: [({}, 0.3, 0.0), ({}, 0.3, 0.0), ({}, 0.3, 0.0), ({h}, 0.3, 0.0)], width: Varying([{w}, {w}]))",
                -h,
                -0.5 * h,
                0.6 * h
            );
            let kinds = if rate == 1.0 {
                &[("linear", &linear), ("cubic", &cubic)][..]
            } else {
                &[("linear", &linear)][..]
            };
            for (kind, shape) in kinds.iter().copied() {
                let what = format!("{kind} curve {w} px wide at rate {rate}");
                let hider = format!("shading_rate: {rate},");
                check(&what, field(shape, 16, cell, &hider), w * l, 2.0 * (l + w));
            }
        }
    }
}

/// The arc length of the cubic Bezier `p`, by 4096 chords.
fn bezier_length(p: [[f64; 2]; 4]) -> f64 {
    let at = |t: f64| {
        let s = 1.0 - t;
        let b = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
        [0, 1].map(|k| (0..4).map(|i| b[i] * p[i][k]).sum::<f64>())
    };
    let n = 4096;
    (0..n)
        .map(|i| {
            let (a, b) = (at(i as f64 / n as f64), at((i + 1) as f64 / n as f64));
            (a[0] - b[0]).hypot(a[1] - b[1])
        })
        .sum()
}

/// A circle of curve (four Bezier quarters, closed) covers its annulus: width times the
/// curve's length.
#[test]
fn a_circle_of_curve_covers_its_annulus() {
    let (r, w) = (5.0_f64, 0.5_f64);
    let k = 0.552_284_75 * r;
    let quarter = [[r, 0.0], [r, k], [k, r], [0.0, r]];
    let length = 4.0 * bezier_length(quarter);
    // Periodic Bezier: 12 points, step 3, four segments.
    let mut pts = Vec::new();
    for q in 0..4 {
        let (c, s) = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][q];
        for p in &quarter[..3] {
            pts.push(format!("({}, {}, 0.0)", c * p[0] - s * p[1], s * p[0] + c * p[1]));
        }
    }
    let shape = format!(
        "Curves(kind: Cubic, wrap: Periodic, nvertices: [12], points: [{}], width: Constant({w}))",
        pts.join(", ")
    );
    check("circle of curve", field(&shape, 16, 16, ""), w * length, 2.0 * length);
}

/// A field of hairs a tenth of a pixel wide keeps their total area: 24 curved cubic hairs
/// per 24-pixel cell, every cell the same tuft. The hairs lie in lanes 0.9 pixel apart and
/// wander at most 0.3 pixel from their lane's centre, so none crosses another (crossings
/// would make the union smaller than the sum).
#[test]
fn a_field_of_thin_hairs_keeps_its_area() {
    let w = 0.1_f64;
    let mut rng = reyes_testkit::random::Uniform::new(0x4a12);
    let (mut curves, mut total) = (Vec::new(), 0.0);
    for _ in 0..24 {
        let lane = -10.35 + 0.9 * (curves.len() / 4) as f64;
        let y0 = f64::from(rng.range(-8.0, -2.0));
        let mut p = [[lane, y0]; 4];
        for (i, q) in p.iter_mut().enumerate() {
            q[0] = lane + f64::from(rng.range(-0.15, 0.15)) + f64::from(rng.range(-0.15, 0.15));
            q[1] = y0 + 3.0 * i as f64 + f64::from(rng.range(-0.5, 0.5));
        }
        total += bezier_length(p);
        curves.extend(p.iter().map(|q| format!("({}, {}, 0.0)", q[0], q[1])));
    }
    let shape = format!(
        "Curves(kind: Cubic, nvertices: [{}], points: [{}], width: Constant({w}))",
        vec!["4"; 24].join(", "),
        curves.join(", ")
    );
    check("field of 0.1 px hairs", field(&shape, 12, 24, ""), w * total, 2.0 * total);
}

/// A point of width `w` covers `pi (w/2)^2`: its disk is diced as a polygon of the disk's
/// area, whatever its size (the polygon's sides only shape its outline). The noise is that
/// of a disk's edge (perimeter `pi w`).
#[test]
fn a_point_covers_its_disk() {
    for w in [0.2_f64, 0.6, 1.5, 4.0, 12.0] {
        let shape = format!("Points(points: [(0.2, 0.1, 0.0)], width: Constant({w}))");
        let exact = std::f64::consts::PI * (w / 2.0).powi(2);
        let cells = if w < 1.0 { 32 } else { 16 };
        let perimeter = std::f64::consts::PI * w;
        check(&format!("point {w} px wide"), field(&shape, cells, 16, ""), exact, perimeter);
    }
}

/// Many points in one batch keep their area too (they are diced together, one grid per
/// batch): 40 points of varying width per cell, none overlapping.
#[test]
fn a_batch_of_points_keeps_its_area() {
    let mut points = Vec::new();
    let mut widths = Vec::new();
    let (mut exact, mut perimeter) = (0.0, 0.0);
    for k in 0..40 {
        let (x, y) = ((k % 8) as f64 * 1.8 - 6.3, (k / 8) as f64 * 1.8 - 3.6);
        let w = 0.3 + 0.03 * k as f64;
        points.push(format!("({x}, {y}, 0.0)"));
        widths.push(format!("{w}"));
        exact += std::f64::consts::PI * (w / 2.0).powi(2);
        perimeter += std::f64::consts::PI * w;
    }
    let shape =
        format!("Points(points: [{}], width: Vertex([{}]))", points.join(", "), widths.join(", "));
    check("batch of 40 points", field(&shape, 8, 16, ""), exact, perimeter);
}
