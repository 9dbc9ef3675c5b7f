//! Exporter noise that RenderMan renderers tolerate: each is a warning at the request (or
//! parameter) at fault naming what was done, and the model shows it done; `--strict` makes
//! each the error `file:line:col: Request: what (--strict)`.

use reyes_rib::{Loaded, RiOptions, Source, load};
use reyes_scene::{Shape, Transform};

/// Loads `text` as `test.rib`, with or without `--strict`.
fn load_as(text: &str, strict: bool) -> Result<Loaded, String> {
    let options = RiOptions { strict, ..RiOptions::default() };
    load(Source::from_bytes("test.rib", text.as_bytes().to_vec()), &options)
        .map_err(|e| e.to_string())
}

/// The warnings of `text`, which must load, as shown (`file:line:col: warning: ...`).
fn warnings(text: &str) -> (Loaded, Vec<String>) {
    let loaded = load_as(text, false).unwrap_or_else(|e| panic!("{e}"));
    let shown = loaded.warnings.iter().map(ToString::to_string).collect();
    (loaded, shown)
}

/// The one-line error `text` gives under `--strict`.
fn strict_error(text: &str) -> String {
    match load_as(text, true) {
        Ok(_) => panic!("loaded under --strict"),
        Err(e) => {
            assert_eq!(e.lines().count(), 1, "{e}");
            e
        }
    }
}

#[test]
fn options_inside_the_world_are_ignored_for_the_frame() {
    // As exporters write it: the display and an imager after WorldBegin.
    let text = "Format 32 24 1
Projection \"perspective\"
WorldBegin
Display \"+beauty.exr\" \"openexr\" \"rgba\"
Imager \"background\" \"color bgcolor\" [1 1 1]
Format 640 480 1
Translate 0 0 5
Sphere 1 -1 1 360
WorldEnd
";
    let (loaded, shown) = warnings(text);
    assert_eq!(
        shown,
        [
            "test.rib:4:1: warning: Display: options cannot change inside the world block: ignored for this frame",
            "test.rib:5:1: warning: Imager: options cannot change inside the world block: ignored for this frame",
            "test.rib:6:1: warning: Format: options cannot change inside the world block: ignored for this frame",
        ]
    );
    let frame = &loaded.frames[0];
    assert_eq!((frame.scene.image.width, frame.scene.image.height), (32, 24));
    assert!(frame.displays.is_empty(), "{:?}", frame.displays);
    assert_eq!(frame.scene.objects.len(), 1);
    assert_eq!(
        strict_error(text),
        "test.rib:4:1: Display: options cannot change inside the world block (--strict)"
    );
}

#[test]
fn matrices_with_rounding_noise_in_their_projective_terms_are_snapped() {
    // A DCC's matrices: 1e-10 and -2.5e-17 where RenderMan wants 0, and 1e-26.
    let text = "Projection \"perspective\"
WorldBegin
Transform [1 0 0 1e-10  0 1 0 -2.5e-17  0 0 1 0  0 0 5 1]
ConcatTransform [2 0 0 0  0 2 0 0  0 0 2 1e-26  0 0 0 1]
Sphere 1 -1 1 360
WorldEnd
";
    let (loaded, shown) = warnings(text);
    assert_eq!(
        shown,
        [
            "test.rib:3:1: warning: Transform: the matrix's projective terms (its numbers 4, 8, 12 and 16) are (1e-10, -2.5e-17, 0, 1), not (0, 0, 0, 1): snapped to (0, 0, 0, 1), being within 1e-6 of it relative to the matrix's scale",
            "test.rib:4:1: warning: ConcatTransform: the matrix's projective terms (its numbers 4, 8, 12 and 16) are (0, 0, 1e-26, 1), not (0, 0, 0, 1): snapped to (0, 0, 0, 1), being within 1e-6 of it relative to the matrix's scale",
        ]
    );
    // Exactly the affine matrix: a scale by 2, then 5 along z.
    let o = &loaded.frames[0].scene.objects[0];
    assert_eq!(
        o.transform,
        [Transform::Matrix([
            [2.0, 0.0, 0.0, 0.0],
            [0.0, 2.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 5.0],
            [0.0, 0.0, 0.0, 1.0]
        ])]
    );
    assert_eq!(
        strict_error(text),
        "test.rib:3:1: Transform: the matrix's projective terms (its numbers 4, 8, 12 and 16) are (1e-10, -2.5e-17, 0, 1), not (0, 0, 0, 1) (--strict)"
    );
    // A projective term of 0.5 is no noise: the matrix stays as written, and the model
    // refuses it at the primitive, as before.
    let projective = text.replace("1e-26", "0.5");
    let e = load_as(&projective, false).err().unwrap_or_else(|| panic!("loaded"));
    assert!(
        e.starts_with("test.rib:5:1: Sphere: objects[0].transform[0][3]: the last row must be"),
        "{e}"
    );
}

#[test]
fn a_primitive_under_a_singular_transformation_is_skipped() {
    let text = "Projection \"perspective\"
WorldBegin
Translate 0 0 5
AttributeBegin
Scale 0 1 1
Sphere 1 -1 1 360
AttributeEnd
Disk 0 1 360
WorldEnd
";
    let (loaded, shown) = warnings(text);
    assert_eq!(
        shown,
        [
            "test.rib:6:1: warning: Sphere: the transformation is singular (determinant 0): the primitive is skipped"
        ]
    );
    let objects = &loaded.frames[0].scene.objects;
    assert_eq!(objects.len(), 1);
    assert_eq!(objects[0].shape, Shape::Disk { height: 0.0, radius: 1.0, thetamax: 360.0 });
    assert_eq!(
        strict_error(text),
        "test.rib:6:1: Sphere: the transformation is singular (determinant 0) (--strict)"
    );
}
