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
