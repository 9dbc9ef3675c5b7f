//! docs/scene-format.md stays true: every complete example (a ```ron block starting with
//! `Scene(`) parses and validates, and every fragment is valid in some place of a scene.

use std::path::Path;

use reyes_scene::parse;

const DOC: &str = include_str!("../../../docs/scene-format.md");

/// The ```ron blocks of the document, in order.
fn ron_blocks() -> Vec<String> {
    reyes_testkit::docs::fenced_blocks(DOC, "ron")
}

fn is_complete(block: &str) -> bool {
    block.trim_start().starts_with("Scene(")
}

#[test]
fn every_complete_example_parses() {
    let complete: Vec<String> = ron_blocks().into_iter().filter(|b| is_complete(b)).collect();
    assert!(complete.len() >= 5, "only {} complete examples", complete.len());
    for (i, block) in complete.iter().enumerate() {
        if let Err(e) = parse(block, Path::new("docs/scene-format.md")) {
            panic!("complete example {i} does not parse: {e}\n{block}");
        }
    }
}

/// Places in a scene where a fragment may belong; `@` stands for the fragment.
const CONTEXTS: &[&str] = &[
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), @)",
    "Scene(image: (width: 8, height: 8), @)",
    "Scene(camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), @)",
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), lights: [@])",
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), objects: [@])",
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), objects: [(shape: @, material: Matte(color: (0.5, 0.5, 0.5)))])",
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), objects: [(shape: Sphere(radius: 1.0), material: @)])",
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)), @)])",
    // A CSG tree over five closed objects.
    "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
     objects: [(name: \"ball\", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5))),
               (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),
               (name: \"left\", shape: Sphere(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),
               (name: \"right\", shape: Sphere(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),
               (name: \"cap\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5)))],
     solids: [(tree: @)])",
];

#[test]
fn every_fragment_fits_somewhere() {
    let fragments: Vec<String> = ron_blocks().into_iter().filter(|b| !is_complete(b)).collect();
    assert!(fragments.len() >= 15, "only {} fragments", fragments.len());
    for fragment in &fragments {
        let errors: Vec<String> = CONTEXTS
            .iter()
            .map(|c| parse(&c.replace('@', fragment.trim()), Path::new("fragment.ron")))
            .filter_map(|r| r.err().map(|e| e.to_string()))
            .collect();
        assert!(errors.len() < CONTEXTS.len(), "fragment fits nowhere:\n{fragment}\n{errors:#?}");
    }
}

#[test]
fn the_document_covers_every_variant() {
    for name in [
        "Sphere(",
        "Cylinder(",
        "Cone(",
        "Disk(",
        "Torus(",
        "BilinearPatch(",
        "Mesh(",
        "SubdivisionMesh(",
        "Crease(vertices",
        "Corner(vertices",
        "Hyperboloid(",
        "PatchMesh(kind: Bicubic",
        "PatchMesh(kind: Bilinear",
        "uwrap: Periodic",
        "ubasis: BSpline",
        "ubasis: CatmullRom",
        "ubasis: Matrix(",
        "vbasis: Power",
        "NuPatch(",
        "Ambient(",
        "Distant(",
        "Point(",
        "Constant(",
        "Matte(",
        "Plastic(",
        "Translate(",
        "Rotate(",
        "Scale(",
        "Matrix(",
        "matte: true",
        "pattern:",
        "original:",
        "lens: Some(",
        "Gradual(",
        "camera: (eye",
        "motion: [",
        "deform: [",
        "time_pairing:",
        "moving_clip:",
        "solids: [",
        "Object(",
        "Union([",
        "Intersection([",
        "Difference(",
        "interpolation: Gouraud",
        "glass: Some(",
        "csg_order:",
        "method: RayTrace",
        "raytrace: (",
        "shadows: true",
        "Area(",
        "Sphere(center:",
        "Disk(center:",
        "Rectangle(",
        "offset:",
        "reflect: Some(",
        "gloss:",
        "refract: Some(",
        "blur:",
        "PoolBall(",
        "striped: true",
        "roll: Some(",
        "steps:",
        "height: Some(",
        "kind: RiGaussian",
        "projection: Orthographic",
        "screen_window: Some(",
        "Spot(",
        "cone_delta:",
        "beam_distribution:",
        "Metal(",
        "DefaultSurface(",
        "shading_rate: Some(",
        "lights: Some([",
    ] {
        assert!(ron_blocks().iter().any(|b| b.contains(name)), "no ```ron example uses {name}");
    }
}

/// docs/outputs.md stays true: its example scene parses and validates, and the error it
/// shows is the one validation gives.
#[test]
fn the_outputs_example_parses_and_its_error_is_shown() {
    const OUTPUTS: &str = include_str!("../../../docs/outputs.md");
    let blocks = reyes_testkit::docs::fenced_blocks(OUTPUTS, "ron");
    assert_eq!(blocks.len(), 1, "one example in docs/outputs.md");
    let scene = parse(&blocks[0], Path::new("outputs.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.outputs.aovs.len(), 5);
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/aovs.ron"))
            .unwrap_or_else(|e| panic!("{e}"));
    let bad = text.replace("(source: ObjectId),", "(source: ObjectId, filter: Some(Filter)),");
    let err = parse(&bad, Path::new("aovs.ron")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(OUTPUTS.contains(&format!("`{err}`")), "docs/outputs.md should show {err}");
}

/// The animated examples (```text blocks starting with `Scene(` that hold a `${`): every
/// frame of them substitutes, parses and validates, and the frames differ.
#[test]
fn every_animated_example_renders_its_frames() {
    let animated: Vec<String> = reyes_testkit::docs::fenced_blocks(DOC, "text")
        .into_iter()
        .filter(|b| is_complete(b) && reyes_scene::animate::is_animated(b))
        .collect();
    assert!(!animated.is_empty(), "no animated example");
    for block in &animated {
        let frame = |f| {
            let text = reyes_scene::animate::substitute(block, f, Path::new("doc"))
                .unwrap_or_else(|e| panic!("frame {f}: {e}\n{block}"));
            parse(&text, Path::new("doc")).unwrap_or_else(|e| panic!("frame {f}: {e}\n{text}"))
        };
        let scenes: Vec<_> = [1, 12, 24, 30].into_iter().map(frame).collect();
        assert_ne!(scenes[0], scenes[1]);
        assert_eq!(scenes[2].objects, scenes[3].objects, "held after the last key");
    }
}
