//! The standard shaders (crates/sl/shaders, written for this project from the Specification's
//! formulas) all compile, with the types and details the Specification gives their parameters.

use reyes_sl::shaders::STANDARD;
use reyes_sl::{Detail, ShaderKind, Type, compile_str};

#[test]
fn every_standard_shader_compiles() {
    assert_eq!(STANDARD.len(), 15);
    for (name, src) in STANDARD {
        let s =
            compile_str(&format!("{name}.sl"), src, &[]).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(&s.name, name);
    }
}

#[test]
fn kinds_and_parameters() {
    let kind = |n: &str| compile_str(n, reyes_sl::shaders::standard(n).unwrap(), &[]).unwrap();
    assert_eq!(kind("plastic").kind, ShaderKind::Surface);
    assert_eq!(kind("spotlight").kind, ShaderKind::Light);
    assert_eq!(kind("bumpy").kind, ShaderKind::Displacement);
    assert_eq!(kind("fog").kind, ShaderKind::Volume);
    assert_eq!(kind("background").kind, ShaderKind::Imager);
    let p = kind("plastic");
    let names: Vec<&str> = p.params.iter().map(|&i| p.vars[i].name.as_str()).collect();
    assert_eq!(names, ["Ks", "Kd", "Ka", "roughness", "specularcolor"]);
    let sc = p.param("specularcolor").unwrap();
    assert_eq!((sc.ty, sc.detail), (Type::COLOR, Detail::Uniform));
    let spot = kind("spotlight");
    assert_eq!(spot.param("from").unwrap().ty, Type::POINT);
    assert!(spot.globals_written.contains(&"Cl"));
}

#[test]
fn standard_shaders_ir_snapshot() {
    let text: String = STANDARD
        .iter()
        .map(|(name, src)| compile_str(&format!("{name}.sl"), src, &[]).unwrap().dump())
        .collect::<Vec<_>>()
        .join("\n");
    insta::assert_snapshot!("standard_ir", text);
}

/// `shader info` of a built-in: every parameter with its storage, type and evaluated default
/// (spotlight's are expressions: `radians(30)`, `point "shader" (0, 0, 0)`).
#[test]
fn info_lists_parameters_with_their_evaluated_defaults() {
    let args = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let out = reyes_sl::tool::run(&args(&["info", "plastic"]));
    assert_eq!((out.code, out.errors.len()), (0, 0), "{out:?}");
    assert_eq!(
        out.stdout,
        "surface \"plastic\"
    \"Ks\" \"uniform float\"
        default 0.5
    \"Kd\" \"uniform float\"
        default 0.5
    \"Ka\" \"uniform float\"
        default 1
    \"roughness\" \"uniform float\"
        default 0.1
    \"specularcolor\" \"uniform color\"
        default [1 1 1]
"
    );
    let spot = reyes_sl::tool::run(&args(&["info", "spotlight"])).stdout;
    let cone = (30f32).to_radians();
    assert!(
        spot.contains(&format!("\"coneangle\" \"uniform float\"\n        default {cone}")),
        "{spot}"
    );
    assert!(spot.contains("\"to\" \"uniform point\"\n        default [0 0 1]"), "{spot}");
}

#[test]
fn check_and_info_read_files_and_report_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("stripes.sl");
    std::fs::write(
        &good,
        "surface stripes(float freq = 4; output varying float band = 0; string names[2] = {\"a\", \"b\"}) {\n  band = mod(floor(s * freq), 2);\n  Ci = band;\n}\n",
    )
    .unwrap();
    let bad = dir.path().join("bad.sl");
    std::fs::write(&bad, "surface bad() {\n  Ci = undefined_thing;\n}\n").unwrap();
    let s = |p: &std::path::Path| p.to_str().unwrap().to_string();
    let out = reyes_sl::tool::run(&["check".into(), s(&good), s(&bad)]);
    assert_eq!(out.code, 2, "{out:?}");
    assert_eq!(out.stdout, format!("{}: ok: surface \"stripes\", 3 parameters\n", s(&good)));
    assert_eq!(out.errors.len(), 1, "{out:?}");
    assert!(out.errors[0].starts_with(&format!("error: {}:2:8: ", s(&bad))), "{out:?}");
    // A file that is not there is an I/O error: exit 1.
    let out = reyes_sl::tool::run(&["check".into(), s(&dir.path().join("none.sl"))]);
    assert_eq!(out.code, 1, "{out:?}");
    // info finds NAME.sl in a -I folder; outputs and arrays are listed as such.
    let out = reyes_sl::tool::run(&["info".into(), "-I".into(), s(dir.path()), "stripes".into()]);
    assert_eq!(
        out.stdout,
        "surface \"stripes\"
    \"freq\" \"uniform float\"
        default 4
    \"band\" \"output varying float\"
        default 0
    \"names\" \"uniform string[2]\"
        default {\"a\", \"b\"}
",
        "{out:?}"
    );
    let out = reyes_sl::tool::run(&["info".into(), "nosuch".into()]);
    assert_eq!(out.code, 2);
    assert!(
        out.errors[0].contains("nosuch: no shader of that name: nosuch.sl is in none of ."),
        "{out:?}"
    );
    assert_eq!(reyes_sl::tool::run(&["frobnicate".into()]).code, 2);
}
