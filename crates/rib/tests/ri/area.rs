//! `AreaLightSource`: geometry that emits. The illumination straight below a rectangle
//! against the analytic point-to-parallel-rectangle form factor, the penumbra of an edge
//! against the width the light's size predicts, a Cornell-style box lit by its ceiling lamp,
//! and what cannot emit.
//!
//! Sampling: the stochastic hider shades each grid vertex with one point of the light
//! (stratified), so a pixel's value is a Monte Carlo estimate; tolerances are a number of
//! standard errors of the mean of the pixels averaged (measured from those pixels), plus
//! the small bias the test names where one exists.

use reyes_render::{RenderOptions, render};
use reyes_scene::{AreaShape, Light};

use super::{rib, scene};

/// The floor frame seen from a tilted orthographic camera: floor point `(x, 0, z)` is at
/// camera `(x, -z/sqrt 2, 10 + z/sqrt 2)`, so screen x is the floor's x and screen y is
/// `-z/sqrt 2`; the floor's normal leans 45 degrees toward the camera.
const TILT: &str =
    "ConcatTransform [1 0 0 0  0 0.70710678 -0.70710678 0  0 0.70710678 0.70710678 0  0 0 10 1]";

/// A 2 x 2 `arealight` of radiance 1 at height 4 over a matte floor, in the tilted view
/// (the lamp is far above the screen), with `extra` in the floor frame.
fn floor_scene(size: u32, extra: &str) -> String {
    let lamp = "Polygon \"P\" [-1 4 -1  1 4 -1  1 4 1  -1 4 1]";
    lamp_scene(size, lamp, extra)
}

/// [`floor_scene`] with the lamp's geometry `lamp`.
fn lamp_scene(size: u32, lamp: &str, extra: &str) -> String {
    format!(
        "Format {size} {size} 1
Projection \"orthographic\"
PixelSamples 4 4
ShadingRate 0.25
WorldBegin
{TILT}
AttributeBegin
  AreaLightSource \"arealight\" 1 \"intensity\" [1]
  {lamp}
AttributeEnd
Illuminate 1 1
Surface \"matte\"
Polygon \"P\" [-3 0 -3  -3 0 3  3 0 3  3 0 -3]
{extra}
WorldEnd
"
    )
}

/// Red channel of a render, row by row from the top.
fn red(text: &str) -> Vec<f32> {
    let film = render(&scene(text), &RenderOptions::default()).unwrap().film;
    film.rgba().iter().map(|p| p[0]).collect()
}

/// Form factor from a point to a parallel `a x b` rectangle at distance `h` whose corner is
/// straight above it (the standard closed form).
fn corner_form_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
}

/// Mean and standard error of the mean.
fn mean_and_error(v: &[f32]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().map(|&x| f64::from(x)).sum::<f64>() / n;
    let var = v.iter().map(|&x| (f64::from(x) - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

#[test]
fn a_rectangle_lights_the_point_below_it_by_its_form_factor() {
    let scene = scene(&floor_scene(64, ""));
    // One area light over the quad, intensity = radiance x area, and the quad links to it.
    let area = scene.lights.iter().position(|l| matches!(l, Light::Area { .. })).unwrap();
    let Light::Area { shape: AreaShape::Rectangle { .. }, intensity, .. } = &scene.lights[area]
    else {
        panic!("{:?}", scene.lights)
    };
    assert!((intensity - 4.0).abs() < 1e-5);
    let lamp = scene.objects.iter().find(|o| o.area_light.is_some()).unwrap();
    assert_eq!(lamp.area_light, Some(area as u32));
    assert_eq!(lamp.emission, Some([1.0; 3]));

    let image = red(&floor_scene(64, ""));
    // The central 8 x 8 pixels: floor |x| <= 1/8, |z| <= 0.18 around the point below the
    // lamp's centre. Over that patch the form factor changes by under 0.1% (second order
    // in offset / height = 0.045), which is the bias allowed besides the noise.
    let centre: Vec<f32> = (28..36)
        .flat_map(|y| (28..36).map(move |x| (x, y)))
        .map(|(x, y)| image[y * 64 + x])
        .collect();
    let (mean, error) = mean_and_error(&centre);
    // matte, Kd = 1, no ambient light: Ci = irradiance = pi * radiance * F, F four times the
    // corner form factor of a 1 x 1 quarter at height 4.
    let want = std::f64::consts::PI * 4.0 * corner_form_factor(1.0, 1.0, 4.0);
    let tolerance = 5.0 * error + 1e-3 * want;
    assert!((mean - want).abs() <= tolerance, "mean {mean} want {want} (+- {tolerance})");
}

/// The mean of the central 8 x 8 pixels of a 64 x 64 render of `text`, and its standard
/// error.
fn centre(text: &str) -> (f64, f64) {
    let image = red(text);
    let centre: Vec<f32> = (28..36)
        .flat_map(|y| (28..36).map(move |x| (x, y)))
        .map(|(x, y)| image[y * 64 + x])
        .collect();
    mean_and_error(&centre)
}

#[test]
fn a_disk_and_a_ball_light_the_point_below_them_as_their_radiance_predicts() {
    // A disk of radius r = 1/2 at height h = 4 facing down (its +z turned to -y): the
    // irradiance on its axis is pi L r^2 / (h^2 + r^2), exactly (a Lambertian disk).
    let down = "ConcatTransform [1 0 0 0  0 0 1 0  0 -1 0 0  0 4 0 1]";
    let (r, h) = (0.5f64, 4.0f64);
    let (mean, error) = centre(&lamp_scene(64, &format!("{down} Disk 0 0.5 360"), ""));
    let want = std::f64::consts::PI * r * r / (h * h + r * r);
    let tolerance = 5.0 * error + 1e-3 * want;
    assert!((mean - want).abs() <= tolerance, "disk: {mean} want {want} (+- {tolerance})");
    // A ball of radius 1/2 centred at height 4: pi L (r / h)^2 exactly. The model draws a
    // ball's points on the disk through its centre facing the shaded point (lights.rs), which
    // gives 2 pi L (1 - h / sqrt(h^2 + r^2)) on the axis, 1.2% less here: that bias is allowed.
    let (mean, error) = centre(&lamp_scene(64, "Translate 0 4 0 Sphere 0.5 -0.5 0.5 360", ""));
    let exact = std::f64::consts::PI * (r / h).powi(2);
    let model = 2.0 * std::f64::consts::PI * (1.0 - h / (h * h + r * r).sqrt());
    let tolerance = 5.0 * error + (exact - model).abs() + 1e-3 * exact;
    assert!((mean - exact).abs() <= tolerance, "ball: {mean} want {exact} (+- {tolerance})");
}

#[test]
fn an_edge_under_the_lamp_casts_the_penumbra_its_size_predicts() {
    // A card at height 1 over x < 0, long enough in z to be an endless edge for the rows
    // measured (floor |z| <= 0.28; a ray to the lamp crosses height 1 within 0.25 of its
    // floor point's z). The lamp is 2 wide at height 4: floor points with x > 1/3 see all of
    // it, x < -1/3 none, and between, the part beyond the line through the card's edge; the
    // penumbra is 2 * 1 / (4 - 1) = 2/3 wide, centred on x = 0, where half the lamp shows
    // (exactly half of the light by symmetry).
    let card = "Polygon \"P\" [-5 1 -0.6  0 1 -0.6  0 1 0.6  -5 1 0.6]";
    let n = 128;
    let (lit, shadowed) = (red(&floor_scene(n, "")), red(&floor_scene(n, card)));
    // Rows at screen |y| <= 0.2 (floor |z| <= 0.28).
    let rows: Vec<usize> = (0..n as usize)
        .filter(|&y| (1.0 - (y as f64 + 0.5) * 2.0 / n as f64).abs() <= 0.2)
        .collect();
    let column = |x: usize, img: &[f32]| -> Vec<f32> {
        rows.iter().map(|&y| img[y * n as usize + x]).collect()
    };
    let pixel = 2.0 / n as f64;
    for x in 0..n as usize {
        let floor_x = -1.0 + (x as f64 + 0.5) * pixel;
        let (on, _) = mean_and_error(&column(x, &lit));
        let (off, error) = mean_and_error(&column(x, &shadowed));
        let ratio = off / on;
        // A pixel's filter reaches about a pixel beyond it: that much slack at each edge.
        if floor_x < -1.0 / 3.0 - 2.0 * pixel {
            assert!(off <= 5.0 * error + 1e-6, "umbra at x {floor_x}: {ratio}");
        } else if floor_x > 1.0 / 3.0 + 2.0 * pixel {
            assert!((ratio - 1.0).abs() <= 5.0 * error / on + 1e-3, "lit at x {floor_x}: {ratio}");
        } else if floor_x.abs() < 1.0 / 3.0 - 2.0 * pixel {
            // Inside the penumbra: partly lit, neither umbra nor full light.
            assert!(ratio > 0.0 && ratio < 1.0, "penumbra at x {floor_x}: {ratio}");
        }
    }
    let middle: Vec<f32> = [n as usize / 2 - 1, n as usize / 2]
        .iter()
        .flat_map(|&x| column(x, &shadowed).into_iter().zip(column(x, &lit)))
        .map(|(off, on)| off / on.max(1e-6))
        .collect();
    let (half, error) = mean_and_error(&middle);
    // The two columns sit 1/2 pixel either side of x = 0, where the visible fraction moves by
    // about 3/4 of a pixel's width per unit x (of 2/3): +- 0.035, averaging out to first
    // order; 5 standard errors besides.
    assert!((half - 0.5).abs() <= 5.0 * error + 0.01, "{half} +- {error}");
}

#[test]
fn a_cornell_box_is_lit_by_its_ceiling_lamp() {
    // Camera space: the box spans x, y in [-1, 1], z in [2, 4], open toward the camera; the
    // lamp is a 0.5 x 0.5 quad just under the ceiling, facing down.
    let text = "Format 48 48 1
Projection \"perspective\" \"fov\" [60]
PixelSamples 2 2
WorldBegin
AttributeBegin
  AreaLightSource \"arealight\" \"lamp\" \"intensity\" [8] \"lightcolor\" [1 0.9 0.8]
  Surface \"constant\"
  Color [0 0 0]
  Polygon \"P\" [-0.25 0.99 2.75  0.25 0.99 2.75  0.25 0.99 3.25  -0.25 0.99 3.25]
AttributeEnd
Illuminate \"lamp\" 1
Surface \"matte\"
AttributeBegin
  Color [0.8 0.8 0.8]
  Polygon \"P\" [-1 -1 2  1 -1 2  1 -1 4  -1 -1 4]
  Polygon \"P\" [-1 1 2  -1 1 4  1 1 4  1 1 2]
  Polygon \"P\" [-1 -1 4  1 -1 4  1 1 4  -1 1 4]
AttributeEnd
AttributeBegin
  Color [0.8 0.1 0.1]
  Polygon \"P\" [-1 -1 2  -1 -1 4  -1 1 4  -1 1 2]
AttributeEnd
AttributeBegin
  Color [0.1 0.8 0.1]
  Polygon \"P\" [1 -1 2  1 1 2  1 1 4  1 -1 4]
AttributeEnd
WorldEnd
";
    let s = scene(text);
    assert_eq!(s.lights.len(), 1);
    // Every wall is lit by the lamp (the light set is every light), the lamp glows.
    let film = render(&s, &RenderOptions::default()).unwrap().film;
    let at = |x: u32, y: u32| film.pixel(x, y).unwrap();
    // Floor below the lamp (screen y well below the centre), the back wall, both side walls.
    let floor = at(24, 40);
    let back = at(24, 24);
    let (left, right) = (at(3, 24), at(44, 24));
    assert!(floor[0] > 0.1 && back[0] > 0.05, "floor {floor:?} back {back:?}");
    assert!(left[0] > 2.0 * left[1] && right[1] > 2.0 * right[0], "{left:?} {right:?}");
    // The lamp seen from below shows its radiance: 8 * lightcolor (its constant shader black).
    let lamp = (0..48).flat_map(|y| (0..48).map(move |x| (x, y))).map(|(x, y)| at(x, y)[0]);
    let brightest = lamp.fold(0.0, f32::max);
    assert!(brightest > 5.0, "{brightest}");
}

#[test]
fn geometry_that_cannot_emit_is_drawn_with_a_warning() {
    let text = super::world(
        "AttributeBegin
  AreaLightSource \"arealight\" 2
  Translate 0 0 5
  Cylinder 1 -1 1 360
AttributeEnd
Illuminate 2 1
Sphere 1 -1 1 360",
    );
    let loaded = rib(&text).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert!(w.iter().any(|w| w.contains("cannot emit from a Cylinder")), "{w:?}");
    assert!(loaded.frames[0].scene.lights.is_empty());
    assert_eq!(loaded.frames[0].scene.objects.len(), 2);
}

#[test]
fn another_area_light_shader_stands_in_as_arealight_and_strict_refuses_it() {
    let text = super::world(
        "AttributeBegin
  AreaLightSource \"glow\" 3 \"intensity\" [2]
  Polygon \"P\" [-1 1 5  1 1 5  1 1 6  -1 1 6]
AttributeEnd",
    );
    let loaded = rib(&text).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert!(w.iter().any(|w| w.contains("unknown area light shader \"glow\"")), "{w:?}");
    let Light::Area { intensity, .. } = &loaded.frames[0].scene.lights[0] else { panic!() };
    // Radiance 2 over the 2 x 1 quad.
    assert!((intensity - 4.0).abs() < 1e-5);
    let strict = reyes_rib::RiOptions { strict: true, ..Default::default() };
    let e = reyes_rib::load(reyes_rib::Source::from_bytes("test.rib", text.into_bytes()), &strict)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "test.rib:5:3: AreaLightSource: unknown area light shader \"glow\" (--strict)");
}
