//! Texture lookups from shading-language shaders in a RIB render (issue #32): a prepared
//! texture read by `texture()` onto a square seen head-on, and a shadow map read by a light
//! shader's `shadow()` casting an edge onto a plane where the occluder projects, with a
//! penumbra as wide as the blur predicts.

use std::path::Path;

use reyes_render::{RenderOptions, render};
use reyes_rib::RiOptions;
use reyes_texture::make::{MakeOptions, make_texture, write_depth};
use reyes_texture::prepared::MapKind;
use reyes_texture::write::Depth;

fn ok<T, E: std::fmt::Display>(r: Result<T, E>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

/// Renders `rib` (written to `dir/scene.rib` beside `shaders`) and returns the film's RGBA.
fn render_rib(dir: &Path, rib: &str, shaders: &[(&str, &str)]) -> (usize, Vec<[f32; 4]>) {
    for (name, text) in shaders {
        ok(std::fs::write(dir.join(name), text));
    }
    let file = dir.join("scene.rib");
    ok(std::fs::write(&file, rib));
    let loaded = ok(reyes_rib::load_scene_file(&file, &RiOptions::default()));
    // The `Make*` requests before the frame run before it renders (as the CLI runs them).
    for job in &loaded.frames[0].makes {
        assert_eq!(ok(job.run()), None);
    }
    let film = ok(render(&loaded.frames[0].scene, &RenderOptions::default())).film;
    (loaded.frames[0].scene.image.width as usize, film.rgba().to_vec())
}

/// A 32 x 32 orthographic view of the square [-1, 1]^2 at z = 5, its (s, t) running with the
/// picture's x and y.
fn square_scene(surface: &str, light: &str, filter: &str) -> String {
    format!(
        "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow -1 1 -1 1\nPixelSamples 4 4\n\
         {filter}\nShadingRate 0.25\nWorldBegin\n{light}\nSurface {surface}\n\
         Patch \"bilinear\" \"P\" [-1 1 5  1 1 5  -1 -1 5  1 -1 5]\nWorldEnd\n"
    )
}

#[test]
fn texture_from_a_shader_reads_the_map_and_its_channels() {
    let dir = ok(tempfile::tempdir());
    // R = s, G = t, B = 1/4: linear in s and t, so every level of the pyramid, every
    // bilinear read and every symmetric footprint or pixel filter returns the value at the
    // centre, up to float rounding.
    let src = dir.path().join("ramp.exr");
    ok(exr::prelude::write_rgba_file(&src, 64, 64, |x, y| {
        ((x as f32 + 0.5) / 64.0, (y as f32 + 0.5) / 64.0, 0.25, 1.0)
    }));
    let map = dir.path().join("ramp.tex");
    let opts = MakeOptions {
        depth: Some(Depth::Float),
        wrap: [reyes_texture::Wrap::Clamp; 2],
        ..MakeOptions::default()
    };
    ok(make_texture(&src, &map, &opts));
    let shader = "surface maptest(string name = \"\"; float which = 0) {\n\
                  if (which == 0) Ci = color texture(name, s, t);\n\
                  else Ci = float texture(name[1], s, t);\n Oi = 1; }\n";
    for which in [0, 1] {
        let surface =
            format!("\"maptest\" \"string name\" [\"ramp.tex\"] \"float which\" [{which}]");
        let rib = square_scene(&surface, "", "PixelFilter \"box\" 1 1");
        let (w, px) = render_rib(dir.path(), &rib, &[("maptest.sl", shader)]);
        // Away from the border (where the box filter and the clamp meet the edge), pixel
        // (x, y) is the ramp at its centre: s = (x + 1/2) / 32. Micropolygons of a quarter
        // pixel interpolate the linear ramp exactly; the tolerance covers float rounding of
        // the sums (1e-4).
        for y in 2..w - 2 {
            for x in 2..w - 2 {
                let (s, t) = ((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / w as f32);
                let p = px[y * w + x];
                let want = if which == 0 { [s, t, 0.25] } else { [t, t, t] };
                for c in 0..3 {
                    assert!(
                        (p[c] - want[c]).abs() < 1e-4,
                        "which {which} ({x}, {y}): {p:?} vs {want:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_shadow_map_casts_its_edge_where_the_occluder_projects_and_blur_widens_it() {
    let dir = ok(tempfile::tempdir());
    // The light looks along +z from the origin, orthographic over x, y in [-1, 1]: its world
    // to camera and to screen are the identity. Its depth map holds an occluder at z = 2
    // over x < 1/4 (a texel boundary of the 64-texel map) and nothing elsewhere.
    let n = 64u32;
    let z: Vec<f32> = (0..n * n)
        .map(|k| if ((k % n) as f32 + 0.5) / n as f32 * 2.0 - 1.0 < 0.25 { 2.0 } else { 1e30 })
        .collect();
    let identity = [1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.];
    ok(write_depth(&dir.path().join("edge.shd"), n, n, &z, identity, identity, MapKind::Shadow));
    let light = "light shadowlight(string shadowname = \"\"; float blur = 0) {\n\
                 solar() { Cl = 1 - shadow(shadowname, Ps, \"blur\", blur, \"samples\", 1024); } }\n";
    let surface = "surface lit() { Ci = 0; illuminance(P) { Ci += Cl; } Oi = 1; }\n";
    let shaders = [("shadowlight.sl", light), ("lit.sl", surface)];
    let profile = |blur: f32| {
        let l = format!(
            "LightSource \"shadowlight\" 1 \"string shadowname\" [\"edge.shd\"] \"float blur\" [{blur}]"
        );
        let rib = square_scene("\"lit\"", &l, "PixelFilter \"box\" 1 1");
        let (w, px) = render_rib(dir.path(), &rib, &shaders);
        let row = w / 2;
        (w, (0..w).map(|x| px[row * w + x][0]).collect::<Vec<f32>>())
    };
    // Where the lit fraction crosses `v`, in pixels (linear between pixel centres).
    let crossing = |w: usize, p: &[f32], v: f32| {
        for x in 1..w {
            if p[x - 1] < v && p[x] >= v {
                return x as f32 - 0.5 + (v - p[x - 1]) / (p[x] - p[x - 1]) - 0.5;
            }
        }
        panic!("no crossing of {v} in {p:?}");
    };
    let (w, sharp) = profile(0.0);
    assert!(sharp[2] == 0.0 && sharp[w - 3] == 1.0, "{sharp:?}");
    // x = 1/4 is pixel (1/4 + 1) / 2 * 32 = 20 (an edge between pixels). Error terms, in
    // pixels: one map texel (32 / 64 = 0.5) and the quarter-pixel micropolygons'
    // interpolation of the step (half a vertex spacing, 0.125).
    let edge = crossing(w, &sharp, 0.5);
    let want = (0.25 + 1.0) / 2.0 * w as f32;
    assert!((edge - want).abs() <= 0.5 + 0.125, "edge at {edge} px, want {want}");
    // Blur b (in s, which spans the 32 pixels) spreads the edge over a linear ramp 32 b pixels
    // wide: 10% to 90% is 0.8 * 32 b. The one-pixel box filter keeps a ramp's slope where the
    // ramp is straight over a pixel (32 b >= 5 puts the 10% and 90% points half a pixel
    // inside it). 1024 stratified samples leave the fraction within 1/32, a position error of
    // 32 b / 32 at each end; plus one map texel (0.5 px) and the micropolygon spacing each end.
    for b in [0.2f32, 0.3] {
        let (_, soft) = profile(b);
        let width = crossing(w, &soft, 0.9) - crossing(w, &soft, 0.1);
        let want = 0.8 * 32.0 * b;
        let tol = 2.0 * (32.0 * b / 32.0 + 0.5 + 0.125);
        assert!((width - want).abs() <= tol, "blur {b}: penumbra {width} px, want {want} +- {tol}");
        assert!((crossing(w, &soft, 0.5) - edge).abs() <= tol, "blur {b}: the edge moved");
    }
}

#[test]
fn make_texture_requests_write_maps_the_frame_reads() {
    let dir = ok(tempfile::tempdir());
    let src = dir.path().join("ramp.exr");
    ok(exr::prelude::write_rgba_file(&src, 64, 64, |x, y| {
        ((x as f32 + 0.5) / 64.0, (y as f32 + 0.5) / 64.0, 0.25, 1.0)
    }));
    let shader =
        "surface maptest(string name = \"\") { Ci = color texture(name, s, t); Oi = 1; }\n";
    let surface = "\"maptest\" \"string name\" [\"made.tex\"]";
    let make = "MakeTexture \"ramp.exr\" \"made.tex\" \"clamp\" \"clamp\" \"gaussian\" 2 2\n";
    let rib = format!("{make}{}", square_scene(surface, "", "PixelFilter \"box\" 1 1"));
    let (w, px) = render_rib(dir.path(), &rib, &[("maptest.sl", shader)]);
    let p = ok(reyes_texture::prepared::PreparedFile::open(&dir.path().join("made.tex")));
    assert_eq!(p.header.wrap, Some([reyes_texture::Wrap::Clamp; 2]));
    assert_eq!(p.header.levels.len(), 7);
    // As in texture_from_a_shader_reads_the_map_and_its_channels: the linear ramp at each
    // pixel's centre, up to float rounding (the EXR's floats made a float map).
    for y in 2..w - 2 {
        for x in 2..w - 2 {
            let (s, t) = ((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / w as f32);
            let q = px[y * w + x];
            assert!((q[0] - s).abs() < 1e-4 && (q[1] - t).abs() < 1e-4, "({x}, {y}): {q:?}");
        }
    }
    // A picture that is not there: a one-line error naming the request when it runs (after
    // the frames before it, which may write it).
    let file = dir.path().join("bad.rib");
    let bad = "MakeTexture \"nosuch.png\" \"x.tex\" \"periodic\" \"periodic\" \"box\" 1 1\n";
    ok(std::fs::write(&file, bad));
    let loaded = ok(reyes_rib::load_scene_file(&file, &RiOptions::default()));
    let text = loaded.makes_after[0].run().err().unwrap_or_else(|| panic!("{bad}: made"));
    assert!(text.starts_with(&format!("{}:1:1: MakeTexture: ", file.display())), "{text}");
    assert!(text.contains("cannot read") && !text.contains('\n'), "{text}");
    // A filter that is no filter, a wrap mode that is none: one-line errors naming the
    // request when the file is read.
    for (bad, says) in [
        (
            "MakeTexture \"ramp.exr\" \"x.tex\" \"periodic\" \"periodic\" \"fuzzy\" 1 1",
            "unknown filter",
        ),
        (
            "MakeTexture \"ramp.exr\" \"x.tex\" \"sideways\" \"periodic\" \"box\" 1 1",
            "unknown wrap",
        ),
    ] {
        let file = dir.path().join("bad.rib");
        ok(std::fs::write(&file, format!("{bad}\n")));
        let e = reyes_rib::load_scene_file(&file, &RiOptions::default())
            .err()
            .unwrap_or_else(|| panic!("{bad}: loaded"));
        let text = e.to_string();
        assert!(text.starts_with(&format!("{}:1:1: MakeTexture: ", file.display())), "{text}");
        assert!(text.contains(says) && !text.contains('\n'), "{text}");
    }
}

/// A map that is not there: one warning when the scene loads, and the Specification's
/// fallback (0) when the shader looks it up; a map that is no shadow map read by `shadow()`:
/// unshadowed, with a warning after the render.
#[test]
fn missing_maps_warn_and_read_zero() {
    let dir = ok(tempfile::tempdir());
    let shader =
        "surface maptest(string name = \"\") { Ci = 0.5 + color texture(name, s, t); Oi = 1; }\n";
    ok(std::fs::write(dir.path().join("maptest.sl"), shader));
    let rib =
        square_scene("\"maptest\" \"string name\" [\"nosuch.tex\"]", "", "PixelFilter \"box\" 1 1");
    let file = dir.path().join("scene.rib");
    ok(std::fs::write(&file, rib));
    let loaded = ok(reyes_rib::load_scene_file(&file, &RiOptions::default()));
    let warned: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(
        warned.iter().filter(|w| w.contains("\"nosuch.tex\" is not found")).count(),
        1,
        "{warned:?}"
    );
    let film = ok(render(&loaded.frames[0].scene, &RenderOptions::default())).film;
    assert!(film.rgba().iter().all(|p| (p[0] - 0.5).abs() < 1e-6), "the lookups read 0");
}
