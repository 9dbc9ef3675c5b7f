//! The grid's globals as shaders see them: `s`, `t`, `u`, `v`, `du`, `dv`, derivatives,
//! `area` and `calculatenormal`, on a bilinear patch and on a sphere, against their exact
//! values at the samples.
//!
//! The interpolation error of a micropolygon: the hider gives a sample the colour of its
//! micropolygon's first corner (flat shading, the default), so a sample's value of a
//! quantity shaded as `f(u, v)` is `f` somewhere on that micropolygon: within `du |df/du| +
//! dv |df/dv|` of `f` at the sample. `du`, `dv` themselves are read back from a picture of
//! `Ci = color(du, dv, 0)` (the largest over the picture), so the tolerances follow the
//! grids the dicer actually made.

use super::{Files, SAMPLES, ortho, pixel, render, screen};

/// The bilinear patch `[-1, 1]^2` in the plane z = 0: `u` along x, `v` along y.
const PATCH: &str = "Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]";

const SIZE: u32 = 40;
const W: f32 = 1.25;

/// A probe surface shader setting `Ci` to `ci` (opaque).
fn probe(ci: &str) -> String {
    format!("surface probe() {{ Oi = 1; Ci = {ci}; }}")
}

/// The picture of `geometry` (after `Translate 0 0 3`) under the probe `ci`, with `extra`
/// attributes before it.
fn picture(ci: &str, extra: &str, geometry: &str) -> reyes_film::Film {
    let shader = probe(ci);
    let files = Files::new(&[("probe", &shader)]);
    let rib = format!(
        "{}WorldBegin\nTranslate 0 0 3\n{extra}\nSurface \"probe\"\n{geometry}\nWorldEnd\n",
        ortho(SIZE, W)
    );
    render(&files.scene(&rib))
}

/// Pixels whose four samples all satisfy `inside` (a screen position test).
fn pixels(inside: impl Fn(f32, f32) -> bool) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for y in 0..SIZE {
        for x in 0..SIZE {
            if SAMPLES.iter().all(|&d| {
                let (sx, sy) = screen(SIZE, W, x, y, d);
                inside(sx, sy)
            }) {
                out.push((x, y));
            }
        }
    }
    out
}

/// The largest `du` and `dv` over `px` (from a picture of `Ci = color(du, dv, 0)`), and the
/// smallest.
fn steps(extra: &str, geometry: &str, px: &[(u32, u32)]) -> ([f32; 2], [f32; 2]) {
    let f = picture("color(du, dv, 0)", extra, geometry);
    let mut max = [0.0f32; 2];
    let mut min = [f32::INFINITY; 2];
    for &(x, y) in px {
        let p = pixel(&f, x, y);
        for k in 0..2 {
            max[k] = max[k].max(p[k]);
            min[k] = min[k].min(p[k]);
        }
    }
    assert!(min[0] > 0.0 && min[1] > 0.0 && max[0] < 0.5 && max[1] < 0.5, "{min:?} {max:?}");
    (max, min)
}

fn inside_patch(x: f32, y: f32) -> bool {
    x.abs() < 1.0 && y.abs() < 1.0
}

#[test]
fn s_and_t_on_a_bilinear_patch_are_the_surface_parameters_at_the_samples() {
    let px = pixels(inside_patch);
    assert!(px.len() > 900, "{}", px.len());
    let ([du, dv], _) = steps("", PATCH, &px);
    for (ci, name) in [("color(s, t, 0)", "s t"), ("color(u, v, 0)", "u v")] {
        let f = picture(ci, "", PATCH);
        for &(x, y) in &px {
            // s = (x + 1) / 2 is linear in the screen under the orthographic camera: the
            // mean over the four symmetric samples is its value at the pixel centre.
            let (cx, cy) = screen(SIZE, W, x, y, (0.0, 0.0));
            let (s, t) = ((cx + 1.0) / 2.0, (cy + 1.0) / 2.0);
            let p = pixel(&f, x, y);
            // Within one micropolygon (s = u, t = v: one step each), and f32 rounding.
            assert!((p[0] - s).abs() <= du + 1e-5, "{name} at ({x}, {y}): {p:?} vs {s}, du {du}");
            assert!((p[1] - t).abs() <= dv + 1e-5, "{name} at ({x}, {y}): {p:?} vs {t}, dv {dv}");
            assert_eq!(p[3], 1.0);
        }
    }
}

#[test]
fn derivatives_of_s_and_t_on_a_bilinear_patch_are_one() {
    let px = pixels(inside_patch);
    let (_, [du_min, dv_min]) = steps("", PATCH, &px);
    let f = picture("color(Du(s), Dv(t), Du(u) + Dv(v))", "", PATCH);
    // s, t in [0, 1] carry a rounding of at most 6e-8 each; a difference of two over two
    // steps errs by at most 2 * 6e-8 / (2 du) relative to the exact 1.
    let tol = 6e-8 / du_min.min(dv_min) + 1e-6;
    for &(x, y) in &px {
        let p = pixel(&f, x, y);
        for (k, want) in [1.0, 1.0, 2.0].into_iter().enumerate() {
            assert!((p[k] - want).abs() <= want * tol, "({x}, {y}): {p:?}, tolerance {tol}");
        }
    }
}

#[test]
fn area_of_p_over_a_plane_sums_to_its_area() {
    let px = pixels(inside_patch);
    let (_, [du_min, dv_min]) = steps("", PATCH, &px);
    // area(P) is the area of the micropolygon at the point, du dv |dP/du x dP/dv|; the
    // patch is 2 x 2 over (u, v) in [0, 1]^2, so area(P) / (du dv) is 4 everywhere and the
    // sum of area(P) over the micropolygons is 4 du dv / (du dv) = the patch's area, 4.
    let f = picture("color(area(P) / (du * dv) / 4)", "", PATCH);
    // Camera-space P (|P| < 3.3) rounds by 2.4e-7 per coordinate: each difference across
    // two steps of length 2 * 2 du errs relatively by 2 * 2.4e-7 / (4 du), and the cross
    // product of two such by twice that.
    let tol = 2.0 * 4.8e-7 / (4.0 * du_min.min(dv_min)) + 1e-6;
    for &(x, y) in &px {
        let p = pixel(&f, x, y);
        assert!((p[0] - 1.0).abs() <= tol, "({x}, {y}): {p:?}, tolerance {tol}");
    }
}

/// The unit sphere seen along its axis from -z: object (x, y) are screen (x, y).
const SPHERE: &str = "Sphere 1 -1 1 360";

/// Screen points of the sphere at least `margin` inside its outline, away from the pole at
/// the centre and from the seam `u = 0` (the +x axis) by `margin`.
fn on_sphere(margin: f32) -> impl Fn(f32, f32) -> bool {
    move |x: f32, y: f32| {
        let r = (x * x + y * y).sqrt();
        r < 1.0 - margin && r > margin && !(x > 0.0 && y.abs() < margin)
    }
}

/// RenderMan's sphere parameters at the visible point over screen `(x, y)`: `u` the angle
/// about z from +x over 2 pi, `v` the latitude from -pi/2 over pi (the near side has z < 0).
fn sphere_uv(x: f32, y: f32) -> (f32, f32) {
    let z = -(1.0 - x * x - y * y).max(0.0).sqrt();
    let u = y.atan2(x).rem_euclid(std::f32::consts::TAU) / std::f32::consts::TAU;
    let v = (z.asin() + std::f32::consts::FRAC_PI_2) / std::f32::consts::PI;
    (u, v)
}

#[test]
fn s_and_t_on_a_sphere_are_its_parameters_at_the_samples() {
    let px_size = 2.0 * W / SIZE as f32;
    let px = pixels(on_sphere(3.0 * px_size));
    assert!(px.len() > 300, "{}", px.len());
    let ([du, dv], _) = steps("", SPHERE, &px);
    let f = picture("color(s, t, 0)", "", SPHERE);
    for &(x, y) in &px {
        // The mean of the exact values at the four samples (s, t are not linear in the
        // screen on a sphere).
        let (mut s, mut t) = (0.0, 0.0);
        for d in SAMPLES {
            let (sx, sy) = screen(SIZE, W, x, y, d);
            let (u, v) = sphere_uv(sx, sy);
            s += u / 4.0;
            t += v / 4.0;
        }
        let p = pixel(&f, x, y);
        assert!((p[0] - s).abs() <= du + 1e-5, "({x}, {y}): {p:?} vs s {s}, du {du}");
        assert!((p[1] - t).abs() <= dv + 1e-5, "({x}, {y}): {p:?} vs t {t}, dv {dv}");
    }
}

#[test]
fn calculatenormal_of_a_sphere_displaced_by_a_constant_is_the_sphere_normal() {
    let displacement = "displacement grow(float amount = 0.2) {
        P += amount * normalize(N);
        N = calculatenormal(P);
    }";
    let shader = probe("color(abs(normalize(N) . normalize(P - point \"object\" (0, 0, 0))))");
    let files = Files::new(&[("probe", &shader), ("grow", displacement)]);
    let attributes = "Attribute \"displacementbound\" \"sphere\" [0.2]\nDisplacement \"grow\"";
    let rib = |surface: &str| {
        format!(
            "{}WorldBegin\nTranslate 0 0 3\n{attributes}\nSurface \"{surface}\"\n{SPHERE}\nWorldEnd\n",
            ortho(SIZE, W)
        )
    };
    let scene = files.scene(&rib("probe"));
    assert!(scene.objects[0].shaders.as_ref().is_some_and(|s| s.displacement.is_some()));
    let f = render(&scene);
    // The sphere did grow: the ring between radius 1.05 and 1.15 is covered.
    let ring = pixels(|x, y| (1.05..1.15).contains(&(x * x + y * y).sqrt()));
    assert!(ring.len() > 20 && ring.iter().all(|&(x, y)| pixel(&f, x, y)[3] == 1.0));
    // The displaced sphere has radius 1.2; away from its outline, its pole and its seam.
    let px_size = 2.0 * W / SIZE as f32;
    let px = pixels(|x, y| {
        let r = (x * x + y * y).sqrt();
        r < 1.2 - 3.0 * px_size && r > 4.0 * px_size
    });
    assert!(px.len() > 500, "{}", px.len());
    let dsteps = Files::new(&[("probe", &probe("color(du, dv, 0)")), ("grow", displacement)]);
    let g = render(&dsteps.scene(&rib("probe")));
    let (mut du, mut dv) = (0.0f32, 0.0f32);
    for &(x, y) in &px {
        du = du.max(pixel(&g, x, y)[0]);
        dv = dv.max(pixel(&g, x, y)[1]);
    }
    // A micropolygon spans at most theta = max(2 pi du, pi dv) of arc; the normal from the
    // differences of P (chords, one-sided at a grid's edges) is within theta of the radial
    // direction, so the cosine is at least cos(theta) >= 1 - theta^2 / 2.
    let theta = f32::max(std::f32::consts::TAU * du, std::f32::consts::PI * dv);
    let tol = theta * theta / 2.0 + 1e-5;
    assert!(tol < 0.05, "{tol}");
    for &(x, y) in &px {
        let p = pixel(&f, x, y);
        assert!(p[0] >= 1.0 - tol && p[0] <= 1.0 + 1e-5, "({x}, {y}): {p:?}, tolerance {tol}");
    }
}

#[test]
fn screen_and_raster_space_positions_are_the_pixel_positions() {
    let px = pixels(inside_patch);
    let ([du, dv], _) = steps("", PATCH, &px);
    let screen_p = picture("color(transform(\"screen\", P))", "", PATCH);
    let raster_p = picture("color(transform(\"raster\", P))", "", PATCH);
    let ndc_p = picture("color(transform(\"NDC\", P))", "", PATCH);
    let pixel_size = 2.0 * W / SIZE as f32;
    for &(x, y) in &px {
        // Orthographic over the screen window [-W, W]^2: a point's screen x, y are its
        // camera x, y, linear in the screen, so the mean over the symmetric samples is the
        // value at the pixel centre; a sample's value is its micropolygon's first corner's,
        // within a micropolygon: x moves 2 per unit of u (the patch is 2 wide), y 2 per v.
        let (cx, cy) = screen(SIZE, W, x, y, (0.0, 0.0));
        let (ex, ey) = (2.0 * du + 1e-5, 2.0 * dv + 1e-5);
        let p = pixel(&screen_p, x, y);
        assert!((p[0] - cx).abs() <= ex && (p[1] - cy).abs() <= ey, "({x}, {y}): {p:?}");
        // Raster is in pixels from the top-left, NDC the same over the picture's size.
        let (rx, ry) = (x as f32 + 0.5, y as f32 + 0.5);
        let (erx, ery) = (ex / pixel_size, ey / pixel_size);
        let p = pixel(&raster_p, x, y);
        assert!((p[0] - rx).abs() <= erx && (p[1] - ry).abs() <= ery, "({x}, {y}): {p:?}");
        let p = pixel(&ndc_p, x, y);
        let n = SIZE as f32;
        assert!(
            (p[0] - rx / n).abs() <= erx / n && (p[1] - ry / n).abs() <= ery / n,
            "({x}, {y}): {p:?}"
        );
    }
}
