//! Look development from RIB (docs/rib.md, docs/lookdev.md): `paintedplastic`'s texture,
//! the standard `bumpy` displacement with `displacementbound`, `TextureCoordinates` as a
//! repeat, a `constant` surface above 1, and scenes/lookdev.rib, the twin of lookdev.ron.

use std::path::Path;

use reyes_rib::{RiOptions, Source, load};
use reyes_scene::{ColorSpace, Material, Scalar};

use crate::{rib, scene, world};

#[test]
fn paintedplastic_bumpy_and_texture_coordinates_map_onto_the_model() {
    let s = scene(&world(
        "Surface \"paintedplastic\" \"texturename\" [\"wood.png\"] \"Ks\" [0.3]
         Displacement \"bumpy\" \"Km\" [0.25] \"texturename\" \"height.png\"
         Attribute \"displacementbound\" \"sphere\" [0.25] \"coordinatesystem\" [\"object\"]
         TextureCoordinates 0 0 4 0 0 2 4 2
         Sphere 1 -1 1 360",
    ));
    let o = &s.objects[0];
    let color = o.maps.color.as_ref().unwrap_or_else(|| panic!("a colour map"));
    assert_eq!(
        (color.file.as_str(), color.color_space, color.repeat),
        ("wood.png", ColorSpace::Srgb, (4.0, 2.0))
    );
    let d = o.displacement.as_ref().unwrap_or_else(|| panic!("displaced"));
    assert_eq!((d.amount, d.bound, d.center), (0.25, Some(0.25), 0.0));
    match &d.source {
        Scalar::Texture(m) => {
            assert_eq!((m.file.as_str(), m.color_space), ("height.png", ColorSpace::Linear))
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(o.material, Material::Plastic { ks: 0.3, .. }), "{:?}", o.material);
}

#[test]
fn unknown_displacement_shaders_and_other_texture_coordinates_warn() {
    let l = rib(&world(
        "Displacement \"dented\" \"Km\" [1]\nTextureCoordinates 0 0 1 0 0 1 1 0.5\nSphere 1 -1 1 360",
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    let messages: Vec<String> = l.warnings.iter().map(|w| w.to_string()).collect();
    assert!(messages.iter().any(|m| m.contains("unknown shader \"dented\"")), "{messages:?}");
    assert!(
        messages.iter().any(|m| m.contains("only a scale of the surface parameters")),
        "{messages:?}"
    );
    assert!(l.frames[0].scene.objects[0].displacement.is_none());
    let strict = RiOptions { strict: true, ..RiOptions::default() };
    let e = load(
        Source::from_bytes(
            "test.rib",
            world("Displacement \"dented\"\nSphere 1 -1 1 360").into_bytes(),
        ),
        &strict,
    );
    assert!(e.is_err_and(|e| e.to_string().contains("unknown displacement shader \"dented\"")));
    let bad = rib(&world("Attribute \"displacementbound\" \"sphere\" [-1]\nSphere 1 -1 1 360"));
    assert!(bad.is_err_and(|e| e.to_string().contains("\"sphere\" must be one number >= 0")));
}

/// scenes/lookdev.rib loads without a warning, its textures resolved beside it, the lamp
/// card a constant surface above 1.
#[test]
fn the_lookdev_twin_loads_cleanly() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/lookdev.rib");
    let l = load(Source::open(&path).unwrap_or_else(|e| panic!("{e}")), &RiOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let s = &l.frames[0].scene;
    let by = |name: &str| {
        s.objects.iter().find(|o| o.name == name).unwrap_or_else(|| panic!("no {name}"))
    };
    let wood = by("table").maps.color.as_ref().unwrap_or_else(|| panic!("wood"));
    assert!(Path::new(&wood.file).is_file(), "{}", wood.file);
    assert!(by("tiled ball").displacement.is_some());
    assert!(matches!(by("lamp card").material, Material::Constant { color: [4.0, 3.4, 2.4], .. }));
}
