//! Exporter noise that RenderMan renderers tolerate: each is a warning at the request (or
//! parameter) at fault naming what was done, and the model shows it done; `--strict` makes
//! each the error `file:line:col: Request: what (--strict)`.

use glam::Vec3;
use reyes_rib::{Loaded, RiOptions, Source, load};
use reyes_scene::{Light, Shape, Transform, Wrap, object_to_world};

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

const DOC: &str = include_str!("../../../../docs/rib.md");

/// Checks that docs/rib.md's table of what is tolerated shows the warning `shown` as given
/// (without its `file:line:col: warning: `), so the document cannot drift from the code.
fn documented(shown: &str) {
    let message = shown.split_once(": warning: ").map_or(shown, |(_, m)| m);
    assert!(DOC.contains(&format!("`{message}`")), "docs/rib.md does not show {message:?}");
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

/// The 1-based column of the first `needle` on line `line` (1-based) of `text`.
fn col(text: &str, line: usize, needle: &str) -> usize {
    let l = text.lines().nth(line - 1).unwrap_or_else(|| panic!("no line {line}"));
    l.find(needle).unwrap_or_else(|| panic!("no {needle:?} on line {line}")) + 1
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
    documented(&shown[0]);
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
    documented(&shown[0]);
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
    documented(&shown[0]);
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

#[test]
fn zero_normals_are_recomputed_from_the_faces_around_their_points() {
    // Two unit quads folded at x = 0: one in z = 0 (its normals +z), one in x = 0 (its
    // normals +x, against its winding, whose normal is -x). Points 1 and 4 sit on the fold
    // with a zero normal and one too short to square in single precision.
    let text = "Projection \"perspective\"
WorldBegin
Translate 0 0 5
PointsPolygons [4 4] [0 1 4 3  1 2 5 4]
  \"P\" [-1 0 0  0 0 0  0 0 1  -1 1 0  0 1 0  0 1 1]
  \"N\" [0 0 1  0 0 0  1 0 0  0 0 1  1e-30 1e-30 1e-30  1 0 0]
WorldEnd
";
    let (loaded, shown) = warnings(text);
    documented(&shown[0]);
    assert_eq!(
        shown,
        [format!(
            "test.rib:6:{}: warning: PointsPolygons: \"N\": 2 normals zero or not finite (the first at point 1): recomputed from the faces around their points",
            col(text, 6, "\"N\"")
        )]
    );
    // Each face's area-weighted normal, turned to agree with the normals it carries: +z
    // and +x, so the fold's points get their bisector.
    let h = 0.5f64.sqrt() as f32;
    match &loaded.frames[0].scene.objects[0].shape {
        Shape::Mesh { normals: Some(n), .. } => assert_eq!(
            n,
            &[
                [0.0, 0.0, 1.0],
                [h, 0.0, h],
                [1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [h, 0.0, h],
                [1.0, 0.0, 0.0]
            ]
        ),
        other => panic!("{other:?}"),
    }
    assert_eq!(
        strict_error(text),
        format!(
            "test.rib:6:{}: PointsPolygons: \"N\": 2 normals zero or not finite (the first at point 1) (--strict)",
            col(text, 6, "\"N\"")
        )
    );
}

#[test]
fn a_zero_normal_on_a_hole_is_recomputed_from_its_face() {
    // A square with a triangular hole, its normals -z (against the outline's winding, +z);
    // a point of the hole has none.
    let text = "Projection \"perspective\"
WorldBegin
Translate 0 0 5
GeneralPolygon [4 3]
  \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0  -1 -1 0  0 1 0  1 -1 0]
  \"N\" [0 0 -1  0 0 -1  0 0 -1  0 0 -1  0 0 -1  0 0 0  0 0 -1]
WorldEnd
";
    let (loaded, shown) = warnings(text);
    assert_eq!(shown.len(), 1, "{shown:?}");
    assert!(shown[0].contains("(the first at point 5): recomputed"), "{shown:?}");
    match &loaded.frames[0].scene.objects[0].shape {
        Shape::Mesh { normals: Some(n), .. } => assert_eq!(n[5], [0.0, 0.0, -1.0]),
        other => panic!("{other:?}"),
    }
}

#[test]
fn normals_that_no_face_can_replace_are_dropped_for_the_mesh() {
    // Point 3's only face, (1, 3, 4), has no area: nothing to take its normal from.
    let text = "Projection \"perspective\"
WorldBegin
Translate 0 0 5
PointsPolygons [3 3] [0 1 2  1 3 4]
  \"P\" [0 0 0  1 0 0  0 1 0  2 0 0  3 0 0]
  \"N\" [0 0 1  0 0 1  0 0 1  0 0 0  0 0 1]
WorldEnd
";
    let (loaded, shown) = warnings(text);
    documented(&shown[0]);
    assert_eq!(
        shown,
        [format!(
            "test.rib:6:{}: warning: PointsPolygons: \"N\": 1 normal zero or not finite (the first at point 3): the faces around a point have no area to take a normal from: N is dropped for this mesh, which shades by its faces' own normals",
            col(text, 6, "\"N\"")
        )]
    );
    assert!(matches!(&loaded.frames[0].scene.objects[0].shape, Shape::Mesh { normals: None, .. }));
    assert!(strict_error(text).ends_with("(the first at point 3) (--strict)"));
}

#[test]
fn lights_without_a_direction_take_the_specification_default() {
    let text = "Projection \"perspective\"
WorldBegin
LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 0] \"intensity\" [0.5]
Translate 1 2 3
LightSource \"spotlight\" 2 \"from\" [1 1 1] \"to\" [1 1 1]
Translate 0 0 5
Sphere 1 -1 1 360
WorldEnd
";
    let (loaded, shown) = warnings(text);
    documented(&shown[0]);
    assert_eq!(
        shown,
        [
            format!(
                "test.rib:3:{}: warning: LightSource: distantlight: \"from\" and \"to\" are the same point (0, 0, 0): the Specification's default direction, from (0, 0, 0) toward (0, 0, 1), is used",
                col(text, 3, "\"to\"")
            ),
            format!(
                "test.rib:5:{}: warning: LightSource: spotlight: \"from\" and \"to\" are the same point (1, 1, 1): the Specification's default direction, from (0, 0, 0) toward (0, 0, 1), is used",
                col(text, 5, "\"to\"")
            ),
        ]
    );
    let lights = &loaded.frames[0].scene.lights;
    assert_eq!(
        lights[0],
        Light::Distant {
            from: [0.0; 3],
            to: [0.0, 0.0, 1.0],
            color: [1.0; 3],
            intensity: 0.5,
            shadows: false
        }
    );
    // The spotlight keeps its place (moved by Translate 1 2 3) and shines down +z.
    match &lights[1] {
        Light::Spot { from, to, .. } => {
            assert_eq!((*from, *to), ([2.0, 3.0, 4.0], [2.0, 3.0, 5.0]))
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        strict_error(text),
        format!(
            "test.rib:3:{}: LightSource: distantlight: \"from\" and \"to\" are the same point (0, 0, 0) (--strict)",
            col(text, 3, "\"to\"")
        )
    );
}

#[test]
fn spotlight_angles_above_pi_are_read_as_degrees() {
    let text = "Projection \"perspective\"
WorldBegin
LightSource \"spotlight\" 1 \"coneangle\" [40] \"conedeltaangle\" [2]
LightSource \"spotlight\" 2 \"coneangle\" [0.5] \"conedeltaangle\" [10]
LightSource \"spotlight\" 3 \"coneangle\" [0.5] \"conedeltaangle\" [0.1]
Translate 0 0 5
Sphere 1 -1 1 360
WorldEnd
";
    let (loaded, shown) = warnings(text);
    documented(&shown[0]);
    assert_eq!(
        shown,
        [
            format!(
                "test.rib:3:{}: warning: LightSource: spotlight: \"coneangle\" 40 is more than pi radians: read as 40 degrees",
                col(text, 3, "\"coneangle\"")
            ),
            format!(
                "test.rib:3:{}: warning: LightSource: spotlight: \"conedeltaangle\" 2 comes with a cone angle in degrees: read as 2 degrees",
                col(text, 3, "\"conedeltaangle\"")
            ),
            format!(
                "test.rib:4:{}: warning: LightSource: spotlight: \"conedeltaangle\" 10 is more than pi radians: read as 10 degrees",
                col(text, 4, "\"conedeltaangle\"")
            ),
        ]
    );
    let angles: Vec<(f32, f32)> = loaded.frames[0]
        .scene
        .lights
        .iter()
        .map(|l| match l {
            Light::Spot { cone_angle, cone_delta, .. } => (*cone_angle, *cone_delta),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        angles,
        [(40.0, 2.0), (0.5f32.to_degrees(), 10.0), (0.5f32.to_degrees(), 0.1f32.to_degrees())]
    );
    assert_eq!(
        strict_error(text),
        format!(
            "test.rib:3:{}: LightSource: spotlight: \"coneangle\" 40 is more than pi radians (--strict)",
            col(text, 3, "\"coneangle\"")
        )
    );
}

#[test]
fn patch_mesh_nowrap_is_nonperiodic() {
    let text = "Projection \"perspective\"
WorldBegin
Translate 0 0 5
PatchMesh \"bilinear\" 2 \"nowrap\" 3 \"nowrap\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0  0 2 0  1 2 0]
WorldEnd
";
    let (loaded, shown) = warnings(text);
    documented(&shown[0]);
    let warning = |which: &str| {
        format!(
            "test.rib:4:1: warning: PatchMesh: {which} \"nowrap\" is not a wrap mode of the Specification: read as \"nonperiodic\""
        )
    };
    assert_eq!(shown, [warning("uwrap"), warning("vwrap")]);
    match &loaded.frames[0].scene.objects[0].shape {
        Shape::PatchMesh { nu, nv, uwrap, vwrap, .. } => {
            assert_eq!((*nu, *nv, *uwrap, *vwrap), (2, 3, Wrap::Nonperiodic, Wrap::Nonperiodic));
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        strict_error(text),
        "test.rib:4:1: PatchMesh: uwrap \"nowrap\" is not a wrap mode of the Specification (--strict)"
    );
}

#[test]
fn a_world_inside_an_attribute_block_takes_the_camera_from_its_transformation() {
    // Houdini's layout: the camera transformation and the world in one attribute block.
    let text = "FrameBegin 1
Format 32 24 1
Projection \"perspective\" \"fov\" [40]
AttributeBegin
TransformBegin
Translate 0 0 5
WorldBegin
Sphere 1 -1 1 360
WorldEnd
TransformEnd
AttributeEnd
FrameEnd
";
    let (loaded, shown) = warnings(text);
    documented(&shown[0]);
    assert_eq!(
        shown,
        [
            "test.rib:7:1: warning: WorldBegin: opened inside the AttributeBegin block of 4:1: allowed, as RenderMan renderers allow it: the transformation at WorldBegin is the camera's"
        ]
    );
    // The CTM at WorldBegin is the camera's: world to camera, 5 along z.
    let o = &loaded.frames[0].scene.objects[0];
    let p = object_to_world(&o.transform).project_point3(Vec3::ZERO);
    assert_eq!(p, Vec3::new(0.0, 0.0, 5.0));
    assert_eq!(
        strict_error(text),
        "test.rib:7:1: WorldBegin: opened inside the AttributeBegin block of 4:1 (--strict)"
    );
}

#[test]
fn a_parameter_of_an_unknown_type_is_skipped() {
    // PRMan's blobby examples declare "vertex mpoint Pref"; a typo does the same to a shader
    // parameter. The request stands without the parameter.
    let text = "Projection \"perspective\"
WorldBegin
Surface \"matte\" \"uniform flaot Kd\" 0.25 \"Ka\" 0.5
Translate 0 0 5
Sphere 1 -1 1 360 \"vertex mpoint Pref\" [1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16]
WorldEnd
";
    let (loaded, shown) = warnings(text);
    let kd = col(text, 3, "\"uniform flaot");
    let pref = col(text, 5, "\"vertex mpoint");
    assert_eq!(
        shown,
        [
            format!(
                "test.rib:3:{kd}: warning: Surface: parameter \"uniform flaot Kd\": unknown type \"flaot\": the parameter is skipped"
            ),
            format!(
                "test.rib:5:{pref}: warning: Sphere: parameter \"vertex mpoint Pref\": unknown type \"mpoint\": the parameter is skipped"
            ),
        ]
    );
    documented(&shown[1].replace("Sphere", "Blobby"));
    // The sphere is there, and its matte keeps Kd's default with the Ka given.
    let scene = &loaded.frames[0].scene;
    assert_eq!(scene.objects.len(), 1);
    let material = format!("{:?}", scene.objects[0].material);
    assert!(material.contains("ka: 0.5") && material.contains("kd: 1.0"), "{material}");
    assert_eq!(
        strict_error(text),
        format!(
            "test.rib:3:{kd}: Surface: parameter \"uniform flaot Kd\": bad inline declaration: unknown type \"flaot\" (--strict)"
        )
    );
}
