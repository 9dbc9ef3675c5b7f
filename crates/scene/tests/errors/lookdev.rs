//! Look development: texture maps, displacement, bump, emission, the texture cache and the
//! ray-tracing hider's refusal of them.

use std::path::Path;

use reyes_scene::parse;

use super::{BASE, Case, FILE};

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "texture map repeat zero", from: "material:", to: "maps: (color: Some((file: \"a.png\", color_space: Srgb, repeat: (0.0, 1.0)))), material:", field: "objects[0].maps.color.repeat", at: Some((7, 110)) },
    Case { name: "texture map without a colour space", from: "material:", to: "maps: (color: Some((file: \"a.png\"))), material:", field: "objects[0].maps.color.color_space", at: Some((7, 81)) },
    Case { name: "texture map empty file name", from: "material:", to: "maps: (roughness: Some((file: \"\", color_space: Linear))), material:", field: "objects[0].maps.roughness.file", at: Some((7, 78)) },
    Case { name: "texture map negative width", from: "material:", to: "maps: (specular: Some((file: \"s.png\", color_space: Linear, width: -1.0))), material:", field: "objects[0].maps.specular.width", at: Some((7, 114)) },
    Case { name: "noise with nine octaves", from: "material:", to: "displacement: Some((source: Noise(octaves: 9))), material:", field: "objects[0].displacement.source.octaves", at: Some((7, 91)) },
    Case { name: "noise frequency zero", from: "material:", to: "bump: Some((source: Noise(frequency: 0.0))), material:", field: "objects[0].bump.source.frequency", at: Some((7, 85)) },
    Case { name: "displacement bound negative", from: "material:", to: "displacement: Some((source: Constant(0.1), bound: Some(-1.0))), material:", field: "objects[0].displacement.bound", at: Some((7, 98)) },
    Case { name: "displacement amount NaN", from: "material:", to: "displacement: Some((source: Constant(0.1), amount: NaN)), material:", field: "objects[0].displacement.amount", at: Some((7, 99)) },
    Case { name: "negative emission", from: "material:", to: "emission: Some((1.0, -1.0, 0.0)), material:", field: "objects[0].emission[1]", at: Some((7, 69)) },
    Case { name: "texture cache too small", from: "  objects: [", to: "  texture_cache: (max_bytes: 1000),\n  objects: [", field: "texture_cache.max_bytes", at: Some((6, 30)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}

/// The ray-tracing hider refuses texture maps, displacement and bump (they need the REYES
/// hider's grids), at `hider.method`.
#[test]
fn the_ray_tracing_hider_refuses_look_development() {
    let text = BASE
        .replacen("pixel_samples: (4, 4),", "method: RayTrace, pixel_samples: (4, 4),", 1)
        .replacen("material:", "bump: Some((source: Constant(0.0))), material:", 1);
    let e = parse(&text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some(
            "scenes/bad.ron:4:19: hider.method: the ray-tracing hider does not read texture maps, displacement or bump (objects[0] has them: they need the REYES hider's grids); use Stochastic"
        )
    );
}
