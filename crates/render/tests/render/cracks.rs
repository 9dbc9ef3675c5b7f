//! Crack-free dicing (docs/geometry.md, "Crack-free dicing"): with back faces culled, the
//! front faces alone must cover a closed surface's silhouette. A sphere centred on the view
//! axis projects to an exact disc (radius `k R / sqrt(d^2 - R^2)` pixels), so every pixel
//! well inside it must have every one of its samples covered: alpha exactly 1 under a
//! one-pixel box filter. Without crack-free dicing samples fall through the cracks between
//! grids diced at different rates, and the same scenes fail (checked here too, so the test
//! can fail). A spinning sphere tests the grids of every motion key.

use reyes_render::{RenderOptions, render};
use reyes_testkit::fixtures::parse;

const W: u32 = 96;
const H: u32 = 80;
const FOV: f32 = 40.0;

/// A sphere of radius `r` at depth `d` on the view axis, tilted by `tilt` degrees about
/// (1, 1, 0) so that its poles and seam cross the picture, spinning by `spin` degrees about
/// its own axis over the shutter, diced at `rate` into grids of at most `grid`.
#[allow(clippy::too_many_arguments)]
fn scene(r: f32, d: f32, tilt: f32, spin: f32, rate: f32, grid: u32, crack_free: bool) -> String {
    let place = |angle: f32| {
        format!(
            "[Rotate(angle: {angle}, axis: (0.0, 0.0, 1.0)), Rotate(angle: {tilt}, axis: (1.0, 1.0, 0.0)), Translate((0.0, 0.0, {d}))]"
        )
    };
    let motion = if spin != 0.0 {
        format!(
            "motion: [(time: 0.0, transform: {}), (time: 1.0, transform: {})],",
            place(0.0),
            place(spin)
        )
    } else {
        format!("transform: {},", place(0.0))
    };
    format!(
        "Scene(image: (width: {W}, height: {H}),
           camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), up: (0.0, 1.0, 0.0), fov: {FOV},
                    hither: 0.1, yon: 100.0, shutter: (open: 0.0, close: 1.0)),
           hider: (pixel_samples: (6, 6), filter: (kind: Box, width: 1.0), seed: 5,
                   shading_rate: {rate}, max_grid_size: {grid}, crack_free: {crack_free},
                   cull_back_faces: true),
           lights: [Ambient(intensity: 1.0)],
           objects: [(shape: Sphere(radius: {r}), {motion} material: Matte(color: (0.5, 0.5, 0.5)))])"
    )
}

/// Pixels well inside the disc (every corner at least `MARGIN` inside) whose alpha is not 1.
fn uncovered(
    r: f32,
    d: f32,
    tilt: f32,
    spin: f32,
    rate: f32,
    grid: u32,
    crack_free: bool,
) -> (usize, usize) {
    let film =
        render(&parse(&scene(r, d, tilt, spin, rate, grid, crack_free)), &RenderOptions::default())
            .unwrap()
            .film;
    let k = (W.min(H) as f32 / 2.0) / (FOV.to_radians() / 2.0).tan();
    // Motion keys lerp the points the two placements give: a point spun by `spin` about the
    // sphere's axis moves along the chord, which passes within `cos(spin / 2)` of the radius
    // of the axis, so the silhouette is never smaller than the disc of that radius.
    let radius = k * r / (d * d - r * r).sqrt() * (spin.to_radians() / 2.0).cos();
    // The diced silhouette is within the flatness bound (0.05 pixel) of the true one, and
    // an edge's polyline within it too; the boundary overlap is 0.001 pixel. Half a pixel
    // leaves a wide margin for all three.
    const MARGIN: f32 = 0.5;
    let (cx, cy) = (W as f32 / 2.0, H as f32 / 2.0);
    let rgba = film.rgba();
    let (mut inside, mut bad) = (0, 0);
    for y in 0..H {
        for x in 0..W {
            let far = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .map(|(dx, dy)| (x as f32 + dx - cx).hypot(y as f32 + dy - cy))
                .fold(0.0_f32, f32::max);
            if far <= radius - MARGIN {
                inside += 1;
                if rgba[(y * W + x) as usize][3] != 1.0 {
                    bad += 1;
                }
            }
        }
    }
    (inside, bad)
}

/// Dicings of one sphere at many rates and grid sizes, still and spinning: every pixel
/// inside the silhouette is covered by every sample.
#[test]
fn front_faces_alone_cover_a_sphere_at_any_dicing() {
    let mut failures = Vec::new();
    for &(r, d, tilt, spin, rate, grid) in &[
        (1.0, 4.0, 30.0, 0.0, 1.0, 256),
        (1.0, 4.0, 55.0, 0.0, 0.5, 16),
        (1.0, 3.0, 70.0, 0.0, 2.0, 4),
        (1.0, 6.0, 10.0, 0.0, 1.0, 8),
        (1.0, 4.0, 40.0, 25.0, 1.0, 16),
        (1.0, 3.5, 80.0, 40.0, 0.7, 8),
    ] {
        let (inside, bad) = uncovered(r, d, tilt, spin, rate, grid, true);
        assert!(inside > 500, "{inside} pixels checked");
        if bad > 0 {
            failures.push(format!(
                "r {r} d {d} tilt {tilt} spin {spin} rate {rate} grid {grid}: {bad} of {inside}"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "pixels inside the silhouette not fully covered:\n{}",
        failures.join("\n")
    );
}

/// The same check fails without crack-free dicing: the test sees the cracks it is about.
#[test]
fn without_crack_free_dicing_samples_fall_through() {
    let bad: usize = [(1.0, 4.0, 55.0, 0.0, 0.5, 16), (1.0, 3.0, 70.0, 0.0, 2.0, 4)]
        .iter()
        .map(|&(r, d, tilt, spin, rate, grid)| uncovered(r, d, tilt, spin, rate, grid, false).1)
        .sum();
    assert!(bad > 0, "no crack without crack-free dicing: the check cannot fail");
}
