//! The `outputs` section: defaults, and each rule's one-line error at its field.

use std::path::Path;

use reyes_scene::{AovFilter, AovSource, Compression, PixelType, ZBackground, parse};

const BASE: &str = "Scene(
  image: (width: 8, height: 8),
  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
  lights: [Ambient(intensity: 0.5), Distant(from: (0.0, 1.0, -1.0), to: (0.0, 0.0, 0.0))],
  objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)))],
  outputs: (OUTPUTS),
)";

fn with(outputs: &str) -> Result<reyes_scene::Scene, String> {
    parse(&BASE.replace("OUTPUTS", outputs), Path::new("o.ron")).map_err(|e| e.to_string())
}

#[test]
fn defaults_write_the_beauty_with_a_finite_background() {
    let s = with("").unwrap_or_else(|e| panic!("{e}"));
    let o = &s.outputs;
    assert!(o.aovs.is_empty() && o.light_groups.is_empty() && !o.render_time);
    assert_eq!((o.pixel_type, o.compression), (PixelType::Float, Compression::Zip));
    assert_eq!(o.zbackground, ZBackground::Finite(1e30));
    assert_eq!((o.png.exposure, o.png.background, o.png.dither), (0.0, None, true));
    // Depth and ids are never averaged unless asked; everything else takes the beauty's filter.
    for source in AovSource::ALL {
        let expect = match source {
            AovSource::Z | AovSource::ObjectId | AovSource::MaterialId => AovFilter::Zmin,
            AovSource::ZMidpoint => AovFilter::Min,
            _ => AovFilter::Filter,
        };
        assert_eq!(source.default_filter(), expect, "{source:?}");
    }
}

#[test]
fn every_rule_reports_one_line_at_its_field() {
    let cases = [
        (
            "aovs: [(source: N), (source: N)]",
            "o.ron:6:42: outputs.aovs[1].source: the layer \"N\" is written twice: give one a different name",
        ),
        (
            "aovs: [(source: N, name: Some(\"2x\"))]",
            "outputs.aovs[0].name: must be letters, digits and _ (not starting with a digit), got \"2x\"",
        ),
        (
            "aovs: [(source: ObjectId, filter: Some(Filter))]",
            "outputs.aovs[0].filter: ids are never averaged: use Zmin, Nearest, Min or Max",
        ),
        (
            "aovs: [(source: MaterialId, pixel_type: Some(Half))]",
            "outputs.aovs[0].pixel_type: ids are 32-bit integers: remove pixel_type",
        ),
        (
            "aovs: [(source: N, light_group: Some(\"key\"))]",
            "outputs.aovs[0].light_group: only Ambient, Diffuse and Specular take a light group",
        ),
        (
            "aovs: [(source: Diffuse, light_group: Some(\"key\"))]",
            "outputs.aovs[0].light_group: no light group named \"key\"",
        ),
        (
            "light_groups: [(name: \"key\", lights: [2])]",
            "outputs.light_groups[0].lights[0]: no light 2: the scene has 2",
        ),
        (
            "light_groups: [(name: \"k\", lights: [1, 1])]",
            "outputs.light_groups[0].lights[1]: light 1 is listed twice",
        ),
        (
            "light_groups: [(name: \"k\", lights: []), (name: \"k\", lights: [])]",
            "outputs.light_groups[1].name: the group \"k\" is defined twice",
        ),
        ("aovs: [(source: Output)]", "outputs.aovs[0].variable: Output needs the variable's name"),
        (
            "aovs: [(source: Output, variable: Some(\"a b\"))]",
            "outputs.aovs[0].variable: must be a shading-language identifier, got \"a b\"",
        ),
        (
            "aovs: [(source: N, variable: Some(\"glow\"))]",
            "outputs.aovs[0].variable: only source Output names a variable",
        ),
        (
            "aovs: [(source: N, variable_type: Some(Color))]",
            "outputs.aovs[0].variable_type: only source Output has a type",
        ),
        ("zbackground: Finite(-1.0)", "outputs.zbackground: must be > 0, got -1"),
        ("png: (exposure: 40.0)", "outputs.png.exposure: must be in [-32, 32] stops, got 40"),
        (
            "png: (background: Some((0.0, 2.0, 0.0)))",
            "outputs.png.background[1]: must be in [0, 1], got 2",
        ),
    ];
    for (outputs, expect) in cases {
        let err = with(outputs).err().unwrap_or_else(|| panic!("{outputs}: accepted"));
        assert!(err.ends_with(expect), "{outputs}:\n  got    {err}\n  expect {expect}");
        assert!(err.starts_with("o.ron:") && !err.contains('\n'), "{err}");
    }
    // Components need the local illumination: not with a shadowing light.
    let shadows = BASE
        .replace("OUTPUTS", "aovs: [(source: N), (source: Specular)]")
        .replace("to: (0.0, 0.0, 0.0))]", "to: (0.0, 0.0, 0.0), shadows: true)]");
    let err = parse(&shadows, Path::new("o.ron")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(
        err.contains(":6:42: outputs.aovs[1].source: Ambient, Diffuse and Specular are split"),
        "{err}"
    );
    // The ray-tracing hider writes no AOVs.
    let rt = BASE
        .replace("OUTPUTS", "aovs: [(source: N)]")
        .replace("lights:", "hider: (method: RayTrace),\n  lights:");
    let err = parse(&rt, Path::new("o.ron")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(err.contains("outputs.aovs: AOVs are written by the stochastic hider only"), "{err}");
    // Adaptive sampling refines the beauty only.
    let adaptive = BASE
        .replace("OUTPUTS", "aovs: [(source: N)]")
        .replace("lights:", "hider: (adaptive: (max_level: 2, threshold: 0.1)),\n  lights:");
    let err = parse(&adaptive, Path::new("o.ron")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(err.contains("outputs.aovs: adaptive sampling refines the beauty only"), "{err}");
}
