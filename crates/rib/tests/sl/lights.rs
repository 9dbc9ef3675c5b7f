//! Lights as shaders see them: the scene's native lights and light shaders through
//! `illuminance`, `illuminate` cones, `solar`, and messages from lights.

use super::{Files, SAMPLES, ortho, pixel, render, screen};

const SIZE: u32 = 32;
const W: f32 = 1.25;

/// A surface summing `Cl` times the cosine over the lights (a matte of colour 1).
const DIFFUSE: &str = "surface lambert() {
    normal Nn = faceforward(normalize(N), I);
    Oi = 1;
    Ci = 0;
    illuminance(P, Nn, PI / 2) {
        Ci += Cl * (normalize(L) . Nn);
    }
}";

/// A spot without fall-off: `intensity` inside the cone of half-angle `angle` about the
/// axis from `from` to `to`.
const CONE: &str = "light cone(float intensity = 1; point from = point \"shader\" (0, 0, 0);
        point to = point \"shader\" (0, 0, 1); float angle = radians(30);
        output float __tag = 0.25) {
    illuminate(from, normalize(to - from), angle) {
        Cl = intensity;
    }
}";

/// A distant light along `to - from` at `intensity`.
const SUN: &str = "light sun(float intensity = 1; point from = point \"shader\" (0, 0, 0);
        point to = point \"shader\" (0, 0, 1)) {
    solar(to - from, 0) {
        Cl = intensity;
    }
}";

/// The square `[-1, 1]^2` facing the camera at z = 3 (its normal toward the camera).
const QUAD: &str = "Patch \"bilinear\" \"P\" [-1 -1 3  1 -1 3  -1 1 3  1 1 3]";

fn picture(files: &Files, lights: &str, surface: &str) -> reyes_film::Film {
    let rib = format!(
        "{}WorldBegin\n{lights}\nSurface \"{surface}\"\n{QUAD}\nWorldEnd\n",
        ortho(SIZE, W)
    );
    render(&files.scene(&rib))
}

#[test]
fn illuminance_with_two_lights_is_the_sum_of_the_single_light_renders() {
    let files = Files::new(&[("lambert", DIFFUSE), ("cone", CONE)]);
    // One native light and one light shader, each lighting part of the square.
    let native = "LightSource \"pointlight\" 1 \"intensity\" 4 \"from\" [-0.5 0.3 1]";
    let shader = "LightSource \"cone\" 2 \"intensity\" 0.7 \"from\" [0.4 0 0] \"to\" [0.4 0 3]";
    let a = picture(&files, native, "lambert");
    let b = picture(&files, shader, "lambert");
    let both = picture(&files, &format!("{native}\n{shader}"), "lambert");
    let (mut lit_a, mut lit_b) = (0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (pa, pb, p) = (pixel(&a, x, y), pixel(&b, x, y), pixel(&both, x, y));
            lit_a += usize::from(pa[0] > 0.0);
            lit_b += usize::from(pb[0] > 0.0);
            for k in 0..3 {
                // The same products summed in one order per sample, then the same filter:
                // only the rounding of one addition per sample (relative 2^-24, twice).
                let tol = 2.0 * f32::EPSILON * (pa[k] + pb[k]) + 1e-7;
                assert!((p[k] - pa[k] - pb[k]).abs() <= tol, "({x}, {y}): {p:?} {pa:?} {pb:?}");
            }
        }
    }
    assert!(lit_a > 100 && lit_b > 100, "{lit_a} {lit_b}");
}

#[test]
fn illuminate_lights_only_its_cone() {
    let files = Files::new(&[("lambert", DIFFUSE), ("cone", CONE)]);
    // From the origin along +z with a half-angle of 10 degrees: the disc of radius
    // 3 tan(10 deg) = 0.529 on the square at z = 3.
    let light = "LightSource \"cone\" 1 \"from\" [0 0 0] \"to\" [0 0 1] \"angle\" [0.17453293]";
    let f = picture(&files, light, "lambert");
    let radius = 3.0 * 0.17453293f32.tan();
    // A sample takes the colour of its micropolygon's first corner, which is within a
    // micropolygon of it; the grids of this square are finer than a pixel (shading rate 1
    // on a square 26 pixels across is diced into cells of at most a pixel), so a pixel
    // whose samples all lie more than 1.5 pixels inside (outside) the disc is wholly lit
    // (dark).
    let margin = 1.5 * 2.0 * W / SIZE as f32;
    let (mut lit, mut dark) = (0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let r = |d| {
                let (sx, sy) = screen(SIZE, W, x, y, d);
                (sx * sx + sy * sy).sqrt()
            };
            let p = pixel(&f, x, y);
            if SAMPLES.iter().all(|&d| r(d) < radius - margin) {
                // Cl = 1 times the cosine of L with the normal, 3 / sqrt(r^2 + 9) at radius r,
                // whose slope is at most 3 r / (r^2 + 9)^1.5 <= 3 radius / 9^1.5 inside the
                // disc; a sample's value is taken within a micropolygon (at most a pixel) of
                // it and a sample is half a pixel from the centre: within 2 pixels.
                let (cx, cy) = screen(SIZE, W, x, y, (0.0, 0.0));
                let cos = 3.0 / (cx * cx + cy * cy + 9.0).sqrt();
                let tol = 3.0 * radius / 27.0 * 2.0 * (2.0 * W / SIZE as f32) + 1e-6;
                assert!(p[0] >= cos - tol && p[0] <= 1.0 + 1e-6, "({x}, {y}) inside: {p:?}");
                lit += 1;
            } else if SAMPLES.iter().all(|&d| r(d) > radius + margin) {
                assert_eq!(p[0], 0.0, "({x}, {y}) outside: {p:?}");
                dark += 1;
            }
        }
    }
    assert!(lit > 20 && dark > 300, "{lit} {dark}");
}

#[test]
fn solar_lights_along_its_axis_by_the_cosine() {
    let files = Files::new(&[("lambert", DIFFUSE), ("sun", SUN)]);
    // Light travelling along (0, -sin a, cos a) onto a square whose normal is -z: the
    // cosine is cos a everywhere, exactly, in every sample.
    let a = 0.6f32;
    let light = format!(
        "LightSource \"sun\" 1 \"intensity\" 2 \"from\" [0 0 0] \"to\" [0 {} {}]",
        -a.sin(),
        a.cos()
    );
    let f = picture(&files, &light, "lambert");
    let want = 2.0 * a.cos();
    let mut n = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = pixel(&f, x, y);
            if p[3] == 1.0 {
                // The direction goes through float rounding (sin, cos, normalise: a few ulps).
                assert!((p[0] - want).abs() <= 1e-5, "({x}, {y}): {p:?} vs {want}");
                n += 1;
            }
        }
    }
    assert!(n > 400, "{n}");
}

#[test]
fn a_surface_reads_a_lights_output_parameter_through_lightsource() {
    let reader = "surface reader() {
        Oi = 1;
        Ci = 0;
        illuminance(P) {
            float tag = -1;
            if (lightsource(\"__tag\", tag) != 0)
                Ci += color(tag, 0, 0);
        }
    }";
    let files = Files::new(&[("reader", reader), ("cone", CONE)]);
    let light =
        "LightSource \"cone\" 1 \"from\" [0 0 0] \"to\" [0 0 1] \"angle\" [1.2] \"__tag\" [0.375]";
    let f = picture(&files, light, "reader");
    // Every sample of the square is within the cone (1.2 radians > atan(sqrt 2 / 3)).
    let mut n = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = pixel(&f, x, y);
            if p[3] == 1.0 {
                assert_eq!(p[0], 0.375, "({x}, {y}): {p:?}");
                n += 1;
            }
        }
    }
    assert!(n > 400, "{n}");
}

#[test]
fn shaded_pictures_do_not_depend_on_the_thread_count() {
    let noisy = "surface noisy() {
        normal Nn = faceforward(normalize(N), I);
        Oi = 1;
        Ci = color noise(P * 7) * diffuse(Nn) + 0.1 * cellnoise(s * 20, t * 20);
    }";
    let files = Files::new(&[("noisy", noisy), ("cone", CONE)]);
    let rib = format!(
        "{}WorldBegin\nLightSource \"cone\" 1 \"intensity\" [0.8] \"angle\" [0.5]\n\
         LightSource \"pointlight\" 2 \"from\" [1 1 0] \"intensity\" [3]\n\
         Surface \"noisy\"\n{QUAD}\nTranslate 0 0 3\nSphere 0.6 -0.6 0.6 360\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let scene = files.scene(&rib);
    let bits = |threads: usize| {
        let opts = reyes_render::RenderOptions { threads: Some(threads), ..Default::default() };
        let film = reyes_render::render(&scene, &opts).unwrap().film;
        film.rgba().iter().flatten().map(|v| v.to_bits()).collect::<Vec<u32>>()
    };
    let one = bits(1);
    assert!(one.iter().any(|&b| f32::from_bits(b) > 0.05));
    assert_eq!(one, bits(2));
    assert_eq!(one, bits(3));
}

/// A light shader lights the standard surfaces too: under `sun` (a distant light written as a
/// shader), `matte` and `plastic` run as their built-in shading-language copies and the
/// picture equals, to float rounding, the one under the same light given as the standard
/// `distantlight` (shaded natively: the same formulas in another order). Before, the native
/// models saw only native lights, and the light shader left them black.
#[test]
fn a_light_shader_lights_the_standard_surfaces() {
    let files = Files::new(&[("sun", SUN)]);
    for surface in ["Surface \"matte\"", "Surface \"plastic\" \"roughness\" [0.2]"] {
        let body =
            format!("Color [0.8 0.6 0.4]\n{surface}\nTranslate 0 0 4\nSphere 1.2 -1.2 1.2 360");
        let light = "\"intensity\" [0.9] \"from\" [0 0 0] \"to\" [0.4 -0.5 1]";
        let scene = |l: &str| {
            let rib = format!(
                "{}WorldBegin\nLightSource \"{l}\" 1 {light}\n{body}\nWorldEnd\n",
                ortho(SIZE, W)
            );
            render(&files.scene(&rib))
        };
        let (by_shader, native) = (scene("sun"), scene("distantlight"));
        let mut lit = 0;
        for y in 0..SIZE {
            for x in 0..SIZE {
                let (p, q) = (pixel(&by_shader, x, y), pixel(&native, x, y));
                for k in 0..4 {
                    assert!((p[k] - q[k]).abs() <= 2e-6, "{surface} ({x}, {y}): {p:?} vs {q:?}");
                }
                lit += usize::from(p[0] > 0.2);
            }
        }
        assert!(lit > 50, "{surface}: the sphere is lit: {lit} pixels");
    }
}

/// A `NAME.sl` on the shader search path comes before the built-in shader of that name, for
/// surfaces and lights alike, as a RenderMan renderer's search finds it first.
#[test]
fn a_standard_name_on_the_search_path_runs_the_users_shader() {
    let files = Files::new(&[
        ("matte", "surface matte() { Oi = 1; Ci = color(0.25, 0.5, 0.75); }"),
        ("pointlight", "light pointlight() { solar() { Cl = 0; } }"),
    ]);
    let rib = format!(
        "{}WorldBegin\nLightSource \"pointlight\" 1\nSurface \"matte\"\n{QUAD}\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let scene = files.scene(&rib);
    assert_eq!(scene.shaders.lights.len(), 1, "the light is the file's shader");
    let f = render(&scene);
    assert_eq!(pixel(&f, SIZE / 2, SIZE / 2), [0.25, 0.5, 0.75, 1.0]);
}
