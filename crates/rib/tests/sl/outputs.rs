//! A shader's output variables written as AOVs (`Display "+name" "file" "variable"`): each
//! pixel of the layer is the filtered value the shader left at the samples.
//!
//! The square fills the picture under the orthographic camera and `s` runs linearly across
//! it, so the output `ramp = s` is linear on every micropolygon; the micropolygons carry it
//! by bilinear interpolation of their corners, which reproduces a linear function to float
//! rounding, and the box filter over the four stratum-centred samples of a pixel averages
//! them to the value at the pixel's centre. So each pixel equals s at its centre, but for
//! the crack-free overlap: a grid's boundary vertices are pushed out by `OVERLAP` (0.001 px,
//! docs/geometry.md) with their values, which shifts the value at a sample by at most
//! 0.001 px times the gradient, here ds/dx = (2/3) / 16 per px, about 4.2e-5; plus a few
//! ulps of the interpolation and the filter's sum: 5e-5.

use reyes_render::RenderOptions;

use super::{Files, ortho, screen};

const SIZE: u32 = 16;
const W: f32 = 1.0;

const SHADER: &str = "surface ramp(output varying float ramp = 0; \
                      output varying color tint = 0; output varying float unused = 0) {\n\
                      ramp = s; tint = color(s, t, 0.25); Oi = 1; Ci = 0.5; }";

#[test]
fn output_variables_are_written_as_aov_layers() {
    let files = Files::new(&[("ramp", SHADER)]);
    // The square spans [-1.5, 1.5]^2 on the screen with s = (x + 1.5) / 3, t from the top.
    let rib = format!(
        "Display \"+ramp\" \"file\" \"ramp\"\nDisplay \"+tint\" \"file\" \"varying color tint\"\n\
         Display \"+missing\" \"file\" \"float missing\"\n{}WorldBegin\nSurface \"ramp\"\n\
         Patch \"bilinear\" \"P\" [-1.5 1.5 3  1.5 1.5 3  -1.5 -1.5 3  1.5 -1.5 3]\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let loaded = files.load(&rib).unwrap_or_else(|e| panic!("{e}"));
    let warned: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        warned.iter().any(|w| w.contains("\"missing\"")),
        "a variable no shader writes is warned about: {warned:?}"
    );
    let scene = &loaded.frames[0].scene;
    let r = reyes_render::render(scene, &RenderOptions::default()).unwrap();
    let a = r.aovs.as_ref().expect("the frame writes AOVs");
    let names: Vec<(&str, Vec<&str>)> =
        a.layers.iter().map(|l| (l.name.as_str(), l.channels.clone())).collect();
    assert_eq!(names, [("ramp", vec!["Y"]), ("tint", vec!["R", "G", "B"]), ("missing", vec!["Y"])]);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (sx, sy) = screen(SIZE, W, x, y, (0.0, 0.0));
            let (s, t) = ((sx + 1.5) / 3.0, (1.5 - sy) / 3.0);
            let at = |c: usize| a.film.value(x, y, c);
            let (ramp, tint, missing) = (at(0), [at(1), at(2), at(3)], at(4));
            const TOL: f32 = 5e-5;
            assert!((ramp - s).abs() <= TOL, "({x}, {y}): ramp {ramp} vs s {s}");
            assert!((tint[0] - s).abs() <= TOL && (tint[1] - t).abs() <= TOL, "{tint:?}");
            assert!((tint[2] - 0.25).abs() <= 1e-6, "{tint:?}");
            assert_eq!(missing, 0.0);
        }
    }
}
