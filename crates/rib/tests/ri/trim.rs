//! `TrimCurve` on `NuPatch` (issue #33), end to end from RIB: a flat NuPatch filling a known
//! raster square with a circular hole made of four exact rational quadratic arcs covers the
//! square's area minus the circle's, within sampling error; pixels wholly in the hole are
//! empty and pixels wholly outside it covered; the trimmed edge is at the curve whatever the
//! dicing; motion blur, depth of field and the ray-tracing hider trim too; and every
//! malformed `TrimCurve` is one error line at the request.
//!
//! The frame: 100 x 100 pixels, orthographic, screen window [-1, 1]^2, so a world unit is 50
//! pixels. The patch spans world [-0.8, 0.8]^2, raster [10, 90]^2 (6400 square pixels), its
//! `(u, v)` over [0, 1]^2 mapped linearly (80 pixels per unit of u or v). The hole is the
//! circle of radius 0.25 about (0.5, 0.5) in `(u, v)`: radius R = 20 pixels about raster
//! (50, 50), area pi R^2.

use reyes_render::{RenderOptions, Rendered, render};
use reyes_scene::Shape;

use super::{rib, scene};

/// Raster radius and centre of the hole.
const R: f64 = 20.0;
const C: f64 = 50.0;

/// The `TrimCurve` of the exact circle of radius `r` about `(cu, cv)`
/// ([`reyes_scene::TrimLoop::circle`]: one loop of one order-3 curve), as RIB writes it: the
/// homogeneous points `(u w, v w, w)` as the `u`, `v` and `w` arrays.
fn circle(cu: f64, cv: f64, r: f64) -> String {
    let ring = reyes_scene::TrimLoop::circle(cu as f32, cv as f32, r as f32);
    let c = &ring.curves[0];
    let list = |k: usize| c.points.iter().map(|p| p[k].to_string()).collect::<Vec<_>>().join(" ");
    let knots = c.knot.iter().map(f32::to_string).collect::<Vec<_>>().join(" ");
    format!(
        "TrimCurve [1] [{}] [{knots}] [{}] [{}] [{}] [{}] [{}] [{}]",
        c.order,
        c.min,
        c.max,
        c.points.len(),
        list(0),
        list(1),
        list(2)
    )
}

/// The flat bilinear NuPatch over world [-0.8, 0.8]^2 at depth 5.
const PATCH: &str = "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [-0.8 -0.8 5  0.8 -0.8 5  -0.8 0.8 5  0.8 0.8 5]";

/// The frame with `options` before the world and `body` in it.
fn frame(options: &str, body: &str) -> String {
    format!(
        "Format 100 100 1
Projection \"orthographic\"
ScreenWindow -1 1 -1 1
PixelSamples 4 4
PixelFilter \"box\" 1 1
{options}
WorldBegin
Surface \"constant\"
{body}
WorldEnd
"
    )
}

/// The trimmed patch in `frame`, with `attributes` before it.
fn trimmed(options: &str, attributes: &str) -> String {
    frame(options, &format!("{attributes}\n{}\n{PATCH}", circle(0.5, 0.5, 0.25)))
}

fn draw(text: &str) -> Rendered {
    render(&scene(text), &RenderOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// Alpha of every pixel, row by row.
fn alpha(r: &Rendered) -> Vec<f64> {
    r.film.rgba().iter().map(|p| f64::from(p[3])).collect()
}

/// The exact covered area, square pixels.
fn exact_area() -> f64 {
    80.0 * 80.0 - std::f64::consts::PI * R * R
}

/// The tolerance of the total coverage of a 4 x 4-sampled frame whose edges are the patch's
/// square and the hole's circle, moved over a band `sweep` pixels wide (by motion, or by the
/// circle of confusion; 0 when still and sharp). Derivation: a sample's hit is a Bernoulli
/// indicator (variance <= 1/4) weighted 1/16 of a pixel, and it varies only if its stratum
/// (a cell of side h = 1/4 pixel) meets an edge at some time and lens position. A curve of
/// length L meets at most 4 ceil(L / h) cells (each piece of length <= h lies in a 2 x 2
/// block of cells); swept over a band of width `sweep`, at most (L + 2h)(sweep + 2h) / h^2
/// more. Samples are independent (FIG. 6: a new jitter in every stratum of every pixel), so
/// the total's standard error is at most sqrt(cells / 4) / 16; the tolerance is 5 of those
/// plus the biases: crack-free grids' sides are pushed out by `OVERLAP` = 1e-3 pixel (at
/// most that times the perimeters; a seam inside the patch covers a sample once however
/// the grids overlap), and the trim polyline is within 2^-20 of the (u, v) domain, 80 *
/// 2^-20 pixel, of the circle.
fn tolerance(sweep: f64) -> f64 {
    let h = 0.25;
    let (hole, square) = (2.0 * std::f64::consts::PI * R, 4.0 * 80.0);
    let cut = |l: f64| {
        4.0 * (l / h).ceil()
            + if sweep > 0.0 { (l + 2.0 * h) * (sweep + 2.0 * h) / (h * h) } else { 0.0 }
    };
    let sigma = ((cut(hole) + cut(square)) / 4.0).sqrt() / 16.0;
    let overlap = 1e-3 * (hole + square);
    let flatten = hole * 80.0 * (2.0f64).powi(-20);
    5.0 * sigma + overlap + flatten
}

/// Pixels wholly inside the hole are empty and pixels wholly inside the patch and outside
/// the hole are covered, exactly (but the rounding of the box filter's normalised weights),
/// a margin of 0.01 pixel left for the overlap and the polyline.
fn check_pixels(a: &[f64], what: &str) {
    let (mut empty, mut full) = (0, 0);
    for y in 0..100usize {
        for x in 0..100usize {
            let (x0, y0) = (x as f64, y as f64);
            let corners = [(x0, y0), (x0 + 1.0, y0), (x0, y0 + 1.0), (x0 + 1.0, y0 + 1.0)];
            let far = corners.iter().map(|&(px, py)| (px - C).hypot(py - C)).fold(0.0, f64::max);
            let near = (x0.max(C.min(x0 + 1.0)) - C).hypot(y0.max(C.min(y0 + 1.0)) - C);
            let in_square = (10..90).contains(&x) && (10..90).contains(&y);
            let value = a[y * 100 + x];
            if far < R - 0.01 {
                assert_eq!(value, 0.0, "{what}: pixel ({x}, {y}) in the hole has alpha {value}");
                empty += 1;
            } else if in_square && near > R + 0.01 {
                assert!(
                    (value - 1.0).abs() < 1e-6,
                    "{what}: pixel ({x}, {y}) outside the hole has alpha {value}"
                );
                full += 1;
            } else if !((9..91).contains(&x) && (9..91).contains(&y)) {
                assert_eq!(value, 0.0, "{what}: pixel ({x}, {y}) off the patch has alpha {value}");
            }
        }
    }
    // Most of the hole's 1257 and the ring's 5143 square pixels are whole pixels.
    assert!(empty > 1100 && full > 4800, "{what}: {empty} empty, {full} covered");
}

/// The total coverage of `r` against the exact area, within `tolerance(sweep)`.
fn check_total(r: &Rendered, sweep: f64, what: &str) -> f64 {
    let total: f64 = alpha(r).iter().sum();
    let (want, tol) = (exact_area(), tolerance(sweep));
    eprintln!(
        "{what}: coverage {total:.3}, exact {want:.3}, error {:.3} (tolerance {tol:.3})",
        total - want
    );
    assert!((total - want).abs() <= tol, "{what}: coverage {total}, exact {want} (+- {tol})");
    total
}

#[test]
fn trim_curve_sets_the_loops_that_later_nupatches_carry_until_attribute_end() {
    let text = frame(
        "",
        &format!(
            "AttributeBegin\n{}\n{PATCH}\nSphere 0.1 -0.1 0.1 360\nAttributeEnd\n{PATCH}",
            circle(0.5, 0.5, 0.25)
        ),
    );
    let s = scene(&text);
    let trims: Vec<usize> = s
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            Shape::NuPatch { trim, .. } => Some(trim.len()),
            _ => None,
        })
        .collect();
    assert_eq!(trims, [1, 0], "the first patch is trimmed, the one after AttributeEnd not");
    let Shape::NuPatch { trim, trim_outside, .. } = &s.objects[0].shape else { panic!() };
    assert!(!trim_outside);
    let c = &trim[0].curves[0];
    assert_eq!((c.order, c.knot.len(), c.points.len(), c.min, c.max), (3, 12, 9, 0.0, 1.0));
    assert_eq!(c.points[1][2], std::f32::consts::FRAC_1_SQRT_2);
    // The sense attribute keeps the inside instead.
    let text = frame(
        "",
        &format!(
            "Attribute \"trimcurve\" \"sense\" \"outside\"\n{}\n{PATCH}",
            circle(0.5, 0.5, 0.25)
        ),
    );
    let s = scene(&text);
    assert!(matches!(&s.objects[0].shape, Shape::NuPatch { trim_outside: true, .. }));
}

#[test]
fn a_circular_hole_removes_its_exact_area_within_sampling_error() {
    let r = draw(&trimmed("", ""));
    let total = check_total(&r, 0.0, "still");
    check_pixels(&alpha(&r), "still");
    // The hole is what the trim took away: the untrimmed patch is diced into the same
    // micropolygons and sampled at the same samples, so the square's edges cancel.
    let whole: f64 = alpha(&draw(&frame("", PATCH))).iter().sum();
    let hole = whole - total;
    let want = std::f64::consts::PI * R * R;
    assert!((hole - want).abs() <= tolerance(0.0), "hole {hole}, exact {want}");
    // Work: cells wholly in the hole were dropped by the dicer, and the hider tested only
    // the samples of the micropolygons the circle crosses.
    let (d, h) = (r.stats.dice, r.stats.hider);
    assert!(d.trimmed > 0 && d.trim_boundary > 0, "{d:?}");
    assert!(h.trim_tests > 0 && h.trimmed > 0 && h.trim_tests < h.hits + h.misses, "{h:?}");
}

#[test]
fn outside_sense_keeps_the_disk_alone() {
    let r = draw(&trimmed("", "Attribute \"trimcurve\" \"sense\" \"outside\""));
    let total: f64 = alpha(&r).iter().sum();
    let want = std::f64::consts::PI * R * R;
    assert!((total - want).abs() <= tolerance(0.0), "disk {total}, exact {want}");
}

#[test]
fn the_trimmed_edge_is_at_the_curve_not_at_the_dice() {
    // ShadingRate 256: micropolygons of 16 x 16 pixels, so a trim decided per micropolygon
    // would miss by about a quarter of the hole's perimeter times 16 pixels (hundreds of
    // square pixels); the per-sample test keeps the same tolerance as fine dicing.
    let r = draw(&trimmed("", "ShadingRate 256"));
    assert!(r.stats.micropolygons <= 64, "{} micropolygons", r.stats.micropolygons);
    check_total(&r, 0.0, "coarse");
    check_pixels(&alpha(&r), "coarse");
}

#[test]
fn moving_and_defocused_trimmed_patches_keep_their_area() {
    // Moving 8 pixels right over the shutter: every time's picture has the area.
    let moving = frame(
        "Shutter 0 1",
        &format!(
            "{}\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0.16 0 0\nMotionEnd\n{PATCH}",
            circle(0.5, 0.5, 0.25)
        ),
    );
    let r = draw(&moving);
    check_total(&r, 8.0, "moving");
    // The pixels the hole covers at every time are empty: within R - 4 of its middle.
    let a = alpha(&r);
    for (x, y) in [(54usize, 50usize), (50, 40), (58, 60), (54, 35)] {
        assert_eq!(a[y * 100 + x], 0.0, "moving: ({x}, {y})");
    }
    // Out of focus, through a perspective camera of 90 degrees that maps the patch moved to
    // world [-4, 4]^2 at depth 5 onto the same raster square (the plane faces the camera, so
    // the map is affine and areas are kept). Lens: f-stop 2, focal length 1, focused at 2.5;
    // the circle of confusion at depth 5 is (f / N) |1/d - 1/z| = 0.1 screen units, 5 pixels,
    // across; the band is taken twice that.
    let patch =
        "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [-4 -4 5  4 -4 5  -4 4 5  4 4 5]";
    let blurred = format!(
        "Format 100 100 1
Projection \"perspective\" \"fov\" [90]
ScreenWindow -1 1 -1 1
PixelSamples 4 4
PixelFilter \"box\" 1 1
DepthOfField 2 1 2.5
WorldBegin
Surface \"constant\"
{}
{patch}
WorldEnd
",
        circle(0.5, 0.5, 0.25)
    );
    let r = draw(&blurred);
    check_total(&r, 10.0, "defocused");
    assert_eq!(alpha(&r)[50 * 100 + 50], 0.0);
}

#[test]
fn adaptive_sampling_trims_its_extra_samples() {
    // The patent's reduced-scale repetition refines the pixels the hole's edge crosses; its
    // extra samples go through the same per-sample trim. Refinement only adds stratified
    // samples within pixels the edge crosses (none far from an edge), so the still frame's
    // tolerance and pixel checks hold.
    let mut s = scene(&trimmed("", ""));
    s.hider.adaptive = reyes_scene::Adaptive { max_level: 2, threshold: 0.1 };
    let r = render(&s, &RenderOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert!(r.stats.hider.refined_pixels > 0 && r.stats.hider.extra_samples > 0);
    let plain = draw(&trimmed("", "")).stats.hider;
    assert!(r.stats.hider.trim_tests > plain.trim_tests, "{:?}", r.stats.hider);
    check_total(&r, 0.0, "adaptive");
    check_pixels(&alpha(&r), "adaptive");
}

#[test]
fn the_ray_tracing_hider_trims_the_same_hole() {
    let r = draw(&trimmed("Hider \"raytrace\"", ""));
    check_total(&r, 0.0, "ray traced");
    check_pixels(&alpha(&r), "ray traced");
}

/// The one-line error of `text`.
fn error(text: &str) -> String {
    let e = rib(text).map(|_| ()).expect_err("must fail").to_string();
    assert_eq!(e.lines().count(), 1, "{e}");
    e
}

#[test]
fn every_malformed_trim_curve_is_one_line_at_the_request() {
    let good_knots = "[0 0 1 1]";
    let line = |args: &str| frame("", &format!("TrimCurve {args}\n{PATCH}"));
    // The TrimCurve is on line 9 of `frame`'s text, at column 1.
    let cases = [
        (
            "[0] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]".to_string(),
            "ncurves[0] must be >= 1 (a loop has curves), got 0",
        ),
        (
            format!("[1] [2 2] {good_knots} [0] [1] [2] [0 1] [0 1] [1 1]"),
            "order must have one value per curve, the sum of ncurves = 1, got 2",
        ),
        (
            format!("[1] [2] {good_knots} [] [1] [2] [0 1] [0 1] [1 1]"),
            "min must have one value per curve, the sum of ncurves = 1, got 0",
        ),
        (
            format!("[1] [2] {good_knots} [0] [1 1] [2] [0 1] [0 1] [1 1]"),
            "max must have one value per curve, the sum of ncurves = 1, got 2",
        ),
        (
            format!("[1] [2] {good_knots} [0] [1] [] [0 1] [0 1] [1 1]"),
            "n must have one value per curve, the sum of ncurves = 1, got 0",
        ),
        (
            format!("[1] [1] {good_knots} [0] [1] [2] [0 1] [0 1] [1 1]"),
            "order[0] must be >= 2, got 1",
        ),
        (
            format!("[1] [3] {good_knots} [0] [1] [2] [0 1] [0 1] [1 1]"),
            "n[0] must be >= order[0] (3), got 2",
        ),
        (
            "[1] [2] [0 0 1] [0] [1] [2] [0 1] [0 1] [1 1]".to_string(),
            "knot must have n[k] + order[k] values for every curve, 4 in all, got 3",
        ),
        (
            format!("[1] [2] {good_knots} [0] [1] [2] [0] [0 1] [1 1]"),
            "u must have n[k] values for every curve, 2 in all, got 1",
        ),
        (
            format!("[1] [2] {good_knots} [0] [1] [2] [0 1] [0 1 2] [1 1]"),
            "v must have n[k] values for every curve, 2 in all, got 3",
        ),
        (
            format!("[1] [2] {good_knots} [0] [1] [2] [0 1] [0 1] [1]"),
            "w must have n[k] values for every curve, 2 in all, got 1",
        ),
        (
            "[1] [2] [0 1 0 1] [0] [1] [2] [0 1] [0 1] [1 1]".to_string(),
            "trim[0].curves[0].knot[2]: must not decrease, got 0 after 1",
        ),
        (
            format!("[1] [2] {good_knots} [-1] [1] [2] [0 1] [0 1] [1 1]"),
            "trim[0].curves[0].min: must be >= knot[1] (0), the start of the valid range, got -1",
        ),
        (
            format!("[1] [2] {good_knots} [0] [2] [2] [0 1] [0 1] [1 1]"),
            "trim[0].curves[0].max: must be <= knot[2] (1), the end of the valid range, got 2",
        ),
        (
            format!("[1] [2] {good_knots} [0.5] [0.5] [2] [0 1] [0 1] [1 1]"),
            "trim[0].curves[0].max: must be > min (0.5), got 0.5",
        ),
        (
            format!("[1] [2] {good_knots} [0] [1] [2] [0 1] [0 1] [1 0]"),
            "trim[0].curves[0].points[1][2]: the weight w must be > 0, got 0",
        ),
    ];
    for (args, message) in cases {
        let e = error(&line(&args));
        assert_eq!(e, format!("test.rib:9:1: TrimCurve: {message}"), "{args}");
    }
    // A point far outside the patch's domain is known only at the NuPatch (line 10).
    let far = frame(
        "",
        &format!("TrimCurve [1] [2] {good_knots} [0] [1] [2] [0 9] [0 1] [1 1]\n{PATCH}"),
    );
    let e = error(&far);
    assert!(e.starts_with("test.rib:10:1: NuPatch: "), "{e}");
    assert!(e.contains("trim[0].curves[0].points[1]: the point (u, v) = (9, 1) is more than 1 domain extent outside"), "{e}");
    // The sense attribute takes two words.
    let e = error(&frame("", "Attribute \"trimcurve\" \"sense\" \"sideways\""));
    assert_eq!(
        e,
        "test.rib:9:23: Attribute: parameter \"sense\": \"sense\" must be \"inside\" or \"outside\", got \"sideways\""
    );
}
