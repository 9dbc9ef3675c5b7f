//! Atmosphere and imager shaders against their formulas: the standard `fog` (compiled from
//! the built-in copy, no file needed) on a surface, and the standard `background` imager on
//! the finished pixels.

use super::{Files, ortho, pixel, render};

const SIZE: u32 = 24;
const W: f32 = 1.25;

/// A constant white surface.
const WHITE: &str = "surface white() { Oi = 1; Ci = 1; }";

#[test]
fn fog_blends_toward_its_background_by_the_length_of_i() {
    let files = Files::new(&[("white", WHITE)]);
    // Under the orthographic camera I runs along z to the point: on the square at z = 4 its
    // length is 4 at every sample, so every covered pixel is exactly
    // mix(1, background, 1 - exp(-4 / distance)) (up to the rounding of exp and mix).
    let rib = format!(
        "{}WorldBegin\nAtmosphere \"fog\" \"distance\" [5] \"background\" [0 0.5 1]\n\
         Surface \"white\"\nPatch \"bilinear\" \"P\" [-2 -2 4  2 -2 4  -2 2 4  2 2 4]\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let scene = files.scene(&rib);
    assert!(scene.objects[0].shaders.as_ref().is_some_and(|s| s.atmosphere.is_some()));
    let f = render(&scene);
    let d = 1.0 - (-4.0f32 / 5.0).exp();
    let want = [1.0 - d, 1.0 + (0.5 - 1.0) * d, 1.0];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = pixel(&f, x, y);
            for k in 0..3 {
                assert!((p[k] - want[k]).abs() <= 1e-6, "({x}, {y}): {p:?} vs {want:?}");
            }
            assert_eq!(p[3], 1.0);
        }
    }
}

/// A native surface under a shading-language atmosphere: the atmosphere sees the native
/// shading as it is without one. An atmosphere that passes Ci and Oi on unchanged leaves the
/// picture identical to no atmosphere at all, for a coloured matte (Cs is the material
/// colour, and the native material must not take it a second time).
#[test]
fn an_atmosphere_over_a_native_surface_sees_its_shading_unchanged() {
    let files = Files::new(&[("still", "volume still() { Ci = Ci; Oi = Oi; }")]);
    let body = "LightSource \"ambientlight\" 1 \"intensity\" [0.3]\n\
                LightSource \"distantlight\" 2 \"from\" [0 0 0] \"to\" [0.3 -0.2 1]\n\
                Color [0.6 0.7 0.8]\nSurface \"matte\"\nSphere 1.5 -1.5 1.5 360\nWorldEnd\n";
    let plain = format!("{}WorldBegin\nTranslate 0 0 4\n{body}", ortho(SIZE, W));
    let fogged = plain.replace("Translate 0 0 4\n", "Translate 0 0 4\nAtmosphere \"still\"\n");
    let (a, b) = (render(&files.scene(&plain)), render(&files.scene(&fogged)));
    let mut lit = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (p, q) = (pixel(&a, x, y), pixel(&b, x, y));
            for k in 0..4 {
                // The same shading, once per vertex on either path: equal to rounding.
                assert!((p[k] - q[k]).abs() <= 1e-6, "({x}, {y}): {p:?} vs {q:?}");
            }
            lit += usize::from(p[3] == 1.0 && p[0] > 0.1);
        }
    }
    assert!(lit > 100, "the sphere covers the middle of the picture: {lit} lit pixels");
}

#[test]
fn the_background_imager_fills_what_the_scene_leaves_uncovered() {
    let files = Files::new(&[("white", WHITE)]);
    // An opaque white square over the left half of the picture: the imager adds
    // (1 - alpha) * background to the premultiplied colour and makes alpha 1, so covered
    // pixels stay white and uncovered ones become the background.
    let rib = format!(
        "{}Imager \"background\" \"background\" [0.25 0.5 0.75]\nWorldBegin\n\
         Surface \"white\"\nPatch \"bilinear\" \"P\" [-2 -2 4  0 -2 4  -2 2 4  0 2 4]\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let scene = files.scene(&rib);
    assert!(scene.shaders.imager.is_some());
    let f = render(&scene);
    let bg = [0.25f32, 0.5, 0.75];
    let (mut empty, mut covered) = (0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = pixel(&f, x, y);
            assert_eq!(p[3], 1.0, "({x}, {y}): {p:?}");
            // Pixels on the square's edge (columns 11 and 12) are mixed: not checked.
            let want = if x < SIZE / 2 - 1 {
                covered += 1;
                [1.0; 3]
            } else if x > SIZE / 2 {
                empty += 1;
                bg
            } else {
                continue;
            };
            for k in 0..3 {
                assert!((p[k] - want[k]).abs() <= 1e-6, "({x}, {y}): {p:?} vs {want:?}");
            }
        }
    }
    assert!(covered > 100 && empty > 100, "{covered} {empty}");
}

#[test]
fn the_ray_tracing_hider_refuses_shading_language_shaders_in_one_line() {
    let files = Files::new(&[("white", WHITE)]);
    let rib = format!(
        "{}Hider \"raytrace\"\nWorldBegin\nSurface \"white\"\nTranslate 0 0 3\nSphere 1 -1 1 360\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let scene = files.scene(&rib);
    let e = reyes_render::render(&scene, &reyes_render::RenderOptions::default())
        .err()
        .map(|e| (e.to_string(), e.exit_code()));
    let (message, code) = e.expect("refused");
    assert_eq!(code, 1);
    assert_eq!(message.lines().count(), 1);
    assert!(message.contains("ray-tracing hider"), "{message}");
}

/// An imager's parameters given on the `Imager` line reach it (inline-declared or declared
/// by the shader alone), as for the other shader types.
#[test]
fn an_imager_takes_its_parameters() {
    let shader = "imager background(color bgcolor = 1, background = 1) {\n\
                  Ci += (1 - alpha) * (bgcolor * background); Oi = 1; alpha = 1; }";
    let files = Files::new(&[("background", shader), ("white", WHITE)]);
    for decl in ["\"uniform color bgcolor\"", "\"bgcolor\""] {
        let rib = format!(
            "{}Imager \"background\" {decl} [0.2 0.3 0.5]\nWorldBegin\n\
             Surface \"white\"\nPatch \"bilinear\" \"P\" [-2 -2 4  0 -2 4  -2 2 4  0 2 4]\n\
             WorldEnd\n",
            ortho(SIZE, W)
        );
        let f = render(&files.scene(&rib));
        assert_eq!(pixel(&f, SIZE - 1, 0), [0.2, 0.3, 0.5, 1.0], "{decl}");
    }
}

/// An imager asks the renderer's options as the other shaders do: `option("Format")` gives
/// the picture's size in every pixel.
#[test]
fn an_imager_reads_the_options() {
    let shader = "imager res() { float r[3]; option(\"Format\", r); \
                  Ci = color(r[0] / 100, r[1] / 100, r[2]); alpha = 1; }";
    let files = Files::new(&[("res", shader)]);
    let rib = format!("{}Imager \"res\"\nWorldBegin\nWorldEnd\n", ortho(SIZE, W));
    let f = render(&files.scene(&rib));
    let s = SIZE as f32 / 100.0;
    assert_eq!(pixel(&f, 3, 5), [s, s, 1.0, 1.0]);
}
