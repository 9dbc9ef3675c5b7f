//! Message passing between an object's shaders, and what a shader can ask the renderer:
//! `displacement()` from the surface, `surface()` from the atmosphere, `attribute()`,
//! `option()`, `rendererinfo()`, and the shutter's `time` and `dtime`.

use super::{Files, ortho, pixel, render};

const SIZE: u32 = 8;
const W: f32 = 1.0;

/// A square filling the picture, `s` running across it as in `outputs.rs`.
const SQUARE: &str = "Patch \"bilinear\" \"P\" [-1.5 1.5 3  1.5 1.5 3  -1.5 -1.5 3  1.5 -1.5 3]";

/// The surface reads the displacement's output `amount` (= s, per point) after the
/// displacement ran on the same grid, and the atmosphere reads the surface's parameter `k` as
/// the surface's run left it (0.75). The picture must be, bit for bit, that of a surface
/// computing s itself and an atmosphere adding 0.75 (the same grids, samples and filter;
/// only where the values come from differs), under flat and smooth shading alike.
#[test]
fn surface_reads_the_displacement_and_atmosphere_reads_the_surface() {
    let files = Files::new(&[
        ("d", "displacement d(output varying float amount = 0) { amount = s; }"),
        (
            "m",
            "surface m(float k = 0.25) { float a = -1; displacement(\"amount\", a); \
             k = 0.75; Oi = 1; Ci = color(a, 0, 0); }",
        ),
        ("v", "volume v() { float k = -1; surface(\"k\", k); Ci += color(0, k, 0); }"),
        ("direct", "surface direct() { Oi = 1; Ci = color(s, 0, 0); }"),
        ("add", "volume add() { Ci += color(0, 0.75, 0); }"),
    ]);
    for interpolation in ["constant", "smooth"] {
        let scene = |shaders: &str| {
            format!(
                "{}WorldBegin\nShadingInterpolation \"{interpolation}\"\n{shaders}\n{SQUARE}\n\
                 WorldEnd\n",
                ortho(SIZE, W)
            )
        };
        let passed = scene("Displacement \"d\"\nSurface \"m\"\nAtmosphere \"v\"");
        let direct = scene("Displacement \"d\"\nSurface \"direct\"\nAtmosphere \"add\"");
        let (a, b) = (render(&files.scene(&passed)), render(&files.scene(&direct)));
        assert_eq!(a.rgba(), b.rgba(), "{interpolation}");
        let p = pixel(&a, SIZE / 2, SIZE / 2);
        assert!(p[0] > 0.4 && p[0] < 0.6 && p[1] == 0.75, "{interpolation}: {p:?}");
    }
}

/// `option("Format")`, `attribute("ShadingRate")`, `attribute("identifier:name")`,
/// `rendererinfo("renderer")`, `time` (shutter open) and `dtime` (its length), each to a
/// channel: every pixel is exactly the formula's.
#[test]
fn a_shader_asks_the_renderer_its_options_attributes_and_time() {
    let files = Files::new(&[(
        "q",
        "surface q() { uniform float f[3] = { 0, 0, 0 }; option(\"Format\", f);\n\
         float rate = 0; attribute(\"ShadingRate\", rate);\n\
         string nm = \"\", who = \"\"; attribute(\"identifier:name\", nm);\n\
         rendererinfo(\"renderer\", who);\n\
         float unknown = 7; attribute(\"NoSuchThing\", unknown);\n\
         Oi = 1; Ci = color(f[0] / 100 + rate, match(\"^ball$\", nm) + match(\"reyes\", who),\n\
         time + 10 * dtime + unknown); }",
    )]);
    let rib = format!(
        "{}Shutter 0.25 0.75\nWorldBegin\nAttribute \"identifier\" \"name\" [\"ball\"]\n\
         ShadingRate 0.5\nSurface \"q\"\n{SQUARE}\nWorldEnd\n",
        ortho(SIZE, W)
    );
    let film = render(&files.scene(&rib));
    // 8 / 100 + 0.5; both matches; 0.25 + 10 * 0.5 + 7 (an unknown name leaves it alone).
    let want = [0.58, 2.0, 12.25];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = pixel(&film, x, y);
            for k in 0..3 {
                assert!((p[k] - want[k]).abs() <= 1e-5, "({x}, {y}): {p:?} vs {want:?}");
            }
        }
    }
}
