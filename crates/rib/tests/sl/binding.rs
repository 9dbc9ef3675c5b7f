//! How a RIB request's values reach a shader: by the shader's declared types, from the
//! request's parameters and the primitive's variables, with warnings for what does not fit;
//! how a shader is found along the search path; and what a compile error looks like.

use super::{Files, SAMPLES, ortho, pixel, render, screen};

const SIZE: u32 = 24;
const W: f32 = 1.25;
const PATCH: &str = "Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]";

fn rib(surface: &str, geometry: &str) -> String {
    format!("{}WorldBegin\nTranslate 0 0 3\n{surface}\n{geometry}\nWorldEnd\n", ortho(SIZE, W))
}

#[test]
fn parameters_bind_by_the_shaders_declared_types() {
    let shader = "surface typed(float k = 0; color c = 0; point p = 0; string name = \"\";
                                float arr[2] = {0, 0}) {
        Oi = 1;
        Ci = k * c + (name == \"yes\" ? 1 : 0) * color(arr[1], 0, 0) + color(0, 0, zcomp(p));
    }";
    let files = Files::new(&[("typed", shader)]);
    let loaded = files
        .load(&rib(
            "Surface \"typed\" \"k\" [0.5] \"c\" [0.2 0.4 0.6] \"p\" [0 0 -2.75] \"name\" \"yes\" \"arr\" [0 0.25] \"nothere\" [1]",
            PATCH,
        ))
        .unwrap();
    // The parameter the shader lacks is named in a warning; none about undeclared names.
    let shown: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(shown.iter().filter(|w| w.contains("\"nothere\"")).count(), 1, "{shown:?}");
    assert!(!shown.iter().any(|w| w.contains("\"k\"") || w.contains("\"arr\"")), "{shown:?}");
    let f = render(&loaded.frames[0].scene);
    // The point is given in shader space, which is the object's (translated by 3 in z):
    // in camera space its z is 3 - 2.75 = 0.25.
    let want = [0.5 * 0.2 + 0.25, 0.5 * 0.4, 0.5 * 0.6 + 0.25];
    let p = pixel(&f, SIZE / 2, SIZE / 2);
    for k in 0..3 {
        assert!((p[k] - want[k]).abs() <= 1e-6, "{p:?} vs {want:?}");
    }
}

#[test]
fn a_value_that_does_not_fit_keeps_the_default_with_a_warning() {
    let shader = "surface one(float k = 0.125) { Oi = 1; Ci = k; }";
    let files = Files::new(&[("one", shader)]);
    let loaded = files.load(&rib("Surface \"one\" \"k\" [1 2 3]", PATCH)).unwrap();
    let shown: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert!(shown.iter().any(|w| w.contains("\"k\"") && w.contains("default")), "{shown:?}");
    let f = render(&loaded.frames[0].scene);
    assert_eq!(pixel(&f, SIZE / 2, SIZE / 2)[0], 0.125);
}

#[test]
fn primitive_variables_bind_to_parameters_of_the_same_name() {
    let shader = "surface pv(varying float k = 0; uniform float g = 0) {
        Oi = 1;
        Ci = color(k, g, du);
    }";
    let files = Files::new(&[("pv", shader)]);
    // k at the corners (u, v) = (0,0), (1,0), (0,1), (1,1): 0, 1, 0, 1, so k = u; g constant.
    let geometry = format!("{PATCH} \"varying float k\" [0 1 0 1] \"constant float g\" [0.75]");
    let f = render(&files.scene(&rib("Surface \"pv\"", &geometry)));
    let mut n = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let inside = SAMPLES.iter().all(|&d| {
                let (sx, sy) = screen(SIZE, W, x, y, d);
                sx.abs() < 1.0 && sy.abs() < 1.0
            });
            if !inside {
                continue;
            }
            // Each sample's k is its micropolygon's first corner's, within that grid's du of
            // u at the sample; the pixel is the mean of the four, so within the mean du,
            // which is the pixel's blue. The mean of u at the symmetric samples is u at the
            // centre, (x + 1) / 2.
            let (cx, _) = screen(SIZE, W, x, y, (0.0, 0.0));
            let p = pixel(&f, x, y);
            assert!(p[2] > 0.0 && p[2] < 0.25, "({x}, {y}): {p:?}");
            assert!((p[0] - (cx + 1.0) / 2.0).abs() <= p[2] + 1e-6, "({x}, {y}): {p:?}");
            assert_eq!(p[1], 0.75);
            n += 1;
        }
    }
    assert!(n > 200, "{n}");
}

#[test]
fn shaders_are_found_along_the_shader_search_path() {
    let files = Files::new(&[]);
    let dir = files.0.path().join("lib");
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("far.sl"), "surface far() { Oi = 1; Ci = color(0, 1, 0); }").unwrap();
    let body = rib("Surface \"far\"", PATCH);
    // Not next to the RIB file: a stand-in plastic with a warning.
    let loaded = files.load(&body).unwrap();
    assert!(loaded.frames[0].scene.objects[0].shaders.is_none());
    assert!(loaded.warnings.iter().any(|w| w.to_string().contains("unknown shader \"far\"")));
    // Along the path ("&" the previous path, "@" the RIB file's folder).
    let loaded =
        files.load(&format!("Option \"searchpath\" \"shader\" [\"lib:&\"]\n{body}")).unwrap();
    let shaders = loaded.frames[0].scene.objects[0].shaders.clone().expect("bound");
    assert_eq!(shaders.surface.as_ref().map(|s| s.name()), Some("far"));
    let f = render(&loaded.frames[0].scene);
    assert_eq!(pixel(&f, SIZE / 2, SIZE / 2), [0.0, 1.0, 0.0, 1.0]);
}

/// Real shaders: a Latin-1 comment (not UTF-8) reads, and an `#include` is found in the
/// shader's folder or along the shader search path.
#[test]
fn latin1_comments_read_and_includes_follow_the_search_path() {
    let files = Files::new(&[]);
    let (lib, inc) = (files.0.path().join("lib"), files.0.path().join("inc"));
    std::fs::create_dir(&lib).unwrap();
    std::fs::create_dir(&inc).unwrap();
    std::fs::write(inc.join("green.h"), "#define GREEN color(0, 1, 0)\n").unwrap();
    let mut source = b"/* (c) 1999 Andr\xe9 */\n#include \"green.h\"\n".to_vec();
    source.extend_from_slice(b"surface lat() { Oi = 1; Ci = GREEN; }\n");
    std::fs::write(lib.join("lat.sl"), source).unwrap();
    let body = rib("Surface \"lat\"", PATCH);
    let loaded =
        files.load(&format!("Option \"searchpath\" \"shader\" [\"lib:inc:&\"]\n{body}")).unwrap();
    let f = render(&loaded.frames[0].scene);
    assert_eq!(pixel(&f, SIZE / 2, SIZE / 2), [0.0, 1.0, 0.0, 1.0]);
}

#[test]
fn one_source_is_compiled_once_per_load() {
    let files = Files::new(&[("flat", "surface flat(float k = 1) { Oi = 1; Ci = k; }")]);
    let geometry = format!("{PATCH}\nSurface \"flat\" \"k\" [0.5]\n{PATCH}");
    let scene = files.scene(&rib("Surface \"flat\"", &geometry));
    let shader = |i: usize| {
        scene.objects[i].shaders.as_ref().and_then(|s| s.surface.clone()).expect("bound").shader
    };
    assert!(std::sync::Arc::ptr_eq(&shader(0), &shader(1)));
}

#[test]
fn a_compile_error_is_the_compilers_one_line() {
    let files = Files::new(&[("bad", "surface bad() {\n  Ci = 1 +;\n}\n")]);
    let e = files.load(&rib("Surface \"bad\"", PATCH)).expect_err("an error").to_string();
    let file = files.0.path().join("bad.sl");
    assert!(e.starts_with(&format!("{}:2:", file.display())), "{e}");
    assert_eq!(e.lines().count(), 1, "{e}");
}

#[test]
fn a_standard_shader_of_another_type_names_no_shader() {
    // fog is a volume shader: as a surface it is unknown, with the stand-in and its warning.
    let loaded = Files::new(&[]).load(&rib("Surface \"fog\"", PATCH)).unwrap();
    assert!(loaded.frames[0].scene.objects[0].shaders.is_none());
    assert!(loaded.warnings.iter().any(|w| w.to_string().contains("unknown shader \"fog\"")));
}

#[test]
fn objects_shaded_by_shaders_write_the_geometric_aovs() {
    let files = Files::new(&[("flat", "surface flat() { Oi = 1; Ci = color(0.5); }")]);
    let text = rib("Surface \"flat\"", PATCH).replacen(
        "WorldBegin",
        "Display \"+n\" \"file\" \"N\"\nDisplay \"+st\" \"file\" \"s\"\nWorldBegin",
        1,
    );
    let scene = files.scene(&text);
    assert_eq!(scene.outputs.aovs.len(), 2);
    let rendered = reyes_render::render(&scene, &reyes_render::RenderOptions::default()).unwrap();
    let aovs = rendered.aovs.expect("AOVs");
    // The patch faces the camera: N is (0, 0, -1) or (0, 0, 1) (its z within rounding of
    // a unit vector's), and s at the centre is within a micropolygon (at most half the patch)
    // of 0.5.
    let layer = |name: &str| aovs.layers.iter().find(|l| l.name == name).expect(name).start;
    let (n, st) = (layer("N"), layer("s"));
    let (x, y) = (SIZE / 2, SIZE / 2);
    let nz = aovs.film.value(x, y, n + 2);
    assert!((nz.abs() - 1.0).abs() < 1e-5, "{nz}");
    let s = aovs.film.value(x, y, st);
    assert!(s > 0.0 && s < 1.0, "{s}");
    assert_eq!(pixel(&rendered.film, SIZE / 2, SIZE / 2)[0], 0.5);
}

#[test]
fn a_displacement_without_a_bound_is_named_in_a_warning() {
    let d = "displacement push() { P += 0.01 * normalize(N); }";
    let files = Files::new(&[("push", d)]);
    let loaded = files.load(&rib("Displacement \"push\"", PATCH)).unwrap();
    let shown: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        shown.iter().any(|w| w.contains("\"push\"") && w.contains("displacementbound")),
        "{shown:?}"
    );
    let bounded =
        rib("Attribute \"displacementbound\" \"sphere\" [0.01]\nDisplacement \"push\"", PATCH);
    let loaded = files.load(&bounded).unwrap();
    assert!(!loaded.warnings.iter().any(|w| w.to_string().contains("displacementbound")));
}
