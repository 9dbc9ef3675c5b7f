//! Silhouettes sit on the true outline (issue #36): the pixels a curved outline crosses are
//! covered as much as the exact shape covers them, on average, at the default flatness.
//!
//! Set-up: a field of 4 x 4 white discs of radius 12 pixels (spheres seen along their axis,
//! whose outline is a patch boundary's polyline; spheres tipped 70 degrees, whose outline
//! folds inside grids; flat `Disk`s), one per 32 x 32 cell at sub-pixel offsets, orthographic
//! with one world unit per pixel, 8 x 8 samples and a 1-pixel box filter, so each pixel's
//! alpha is an unbiased estimate of the fraction of it the drawn outline covers. The exact
//! fraction of the true disk is integrated numerically. The mean of (rendered - exact) over
//! the edge pixels (exact value strictly between 0 and 1) is the outline's bias in coverage,
//! about its inward shift in pixels.
//!
//! Tolerance: the bound, |bias| <= 0.003. Each pixel has its own jitter, so edge
//! pixels are independent estimates and the standard error is their spread over sqrt(n); it
//! must be below a third of the bound, so that a bias at the bound shows at 3 standard
//! errors (with about 1,500 edge pixels of noise ~0.02 at 8 x 8 samples it is ~0.0005).

use reyes_film::Film;
use reyes_testkit::coverage::mean_se;
use reyes_testkit::fixtures::parse;
use reyes_testkit::random::Uniform;

const CELLS: u32 = 4;
const CELL: u32 = 32;
const R: f64 = 12.0;

/// The field's render and the discs' centres in raster coordinates.
fn field(shape: &str, transform: &str, hider: &str) -> (Film, Vec<(f64, f64)>) {
    let size = CELLS * CELL;
    let half = size as f64 / 2.0;
    let mut rng = Uniform::new(0x5117_0036);
    let (mut objects, mut centres) = (String::new(), Vec::new());
    for j in 0..CELLS {
        for i in 0..CELLS {
            let c = CELL as f64 / 2.0;
            let x = f64::from(i * CELL) + c - half + rng.range(-0.5, 0.5) as f64;
            let y = half - f64::from(j * CELL) - c + rng.range(-0.5, 0.5) as f64;
            // Raster x = world x + half, raster y = half - world y (the coordinates as f32,
            // as the scene reads them).
            let (xf, yf) = (x as f32, y as f32);
            centres.push((f64::from(xf) + half, half - f64::from(yf)));
            objects.push_str(&format!(
                "(shape: {shape}, transform: [{transform}Translate(({xf}, {yf}, 10.0))],
                  material: Constant(color: (1.0, 1.0, 1.0))),\n"
            ));
        }
    }
    let scene = parse(&format!(
        "Scene(image: (width: {size}, height: {size}),
           camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                    screen_window: Some(({l}, {half}, {l}, {half})), hither: 0.1, yon: 100.0),
           hider: (pixel_samples: (8, 8), filter: (kind: Box, width: 1.0), seed: 36, {hider}),
           objects: [{objects}])",
        l = -half
    ));
    let film = reyes_render::render(&scene, &reyes_render::RenderOptions::default()).unwrap().film;
    (film, centres)
}

/// Exact fraction of pixel `[px, px + 1] x [py, py + 1]` inside the disk of radius `r` about
/// `(cx, cy)`: the overlap of the pixel's column with the chord at x, integrated by the
/// midpoint rule at 4,000 points (error below 1e-6 at the square root's end points).
fn disk_in_pixel(cx: f64, cy: f64, r: f64, px: f64, py: f64) -> f64 {
    let n = 4000;
    let mut sum = 0.0;
    for k in 0..n {
        let x = px + (k as f64 + 0.5) / n as f64;
        let d = r * r - (x - cx).powi(2);
        if d > 0.0 {
            let h = d.sqrt();
            sum += ((cy + h).min(py + 1.0) - (cy - h).max(py)).max(0.0);
        }
    }
    sum / n as f64
}

/// Mean and standard error of (rendered - exact) over the edge pixels.
fn edge_bias(film: &Film, centres: &[(f64, f64)], r: f64) -> (f64, f64, usize) {
    let mut errors = Vec::new();
    for (k, &(cx, cy)) in centres.iter().enumerate() {
        let (i, j) = (k as u32 % CELLS, k as u32 / CELLS);
        for y in j * CELL..(j + 1) * CELL {
            for x in i * CELL..(i + 1) * CELL {
                let (fx, fy) = (f64::from(x), f64::from(y));
                // Only pixels the outline can cross.
                let d = ((fx + 0.5 - cx).hypot(fy + 0.5 - cy) - r).abs();
                if d > 1.0 {
                    continue;
                }
                let exact = disk_in_pixel(cx, cy, r, fx, fy);
                if exact > 0.0 && exact < 1.0 {
                    errors.push(f64::from(film.pixel(x, y).unwrap()[3]) - exact);
                }
            }
        }
    }
    let (mean, se) = mean_se(&errors);
    (mean, se, errors.len())
}

/// The bound on the edge pixels' mean coverage error.
const BOUND: f64 = 0.003;

fn check(what: &str, shape: &str, transform: &str, hider: &str) {
    let (film, centres) = field(shape, transform, hider);
    let (bias, se, n) = edge_bias(&film, &centres, R);
    eprintln!("{what}: edge bias {bias:+.5} +- {se:.5} over {n} pixels");
    assert!(se < BOUND / 3.0, "{what}: too noisy to test ({se:.5})");
    assert!(bias.abs() <= BOUND, "{what}: edge bias {bias:+.5} +- {se:.5} over {n} pixels");
}

#[test]
fn a_spheres_outline_seen_along_its_axis_is_unbiased() {
    check("sphere along its axis", &format!("Sphere(radius: {R})"), "", "");
}

#[test]
fn a_tipped_spheres_outline_is_unbiased() {
    let tip = "Rotate(angle: 70.0, axis: (1.0, 0.0, 0.0)), ";
    check("sphere tipped 70 degrees", &format!("Sphere(radius: {R})"), tip, "");
}

#[test]
fn a_disks_outline_is_unbiased() {
    check("disk", &format!("Disk(radius: {R})"), "", "");
}
