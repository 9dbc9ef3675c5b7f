//! The state machine's malformed-RIB catalogue: each case gives exactly one error, one line,
//! `file:line:col: Request: message`, at the request at fault (a value that fails the scene's
//! validation is reported at the request that made it). The whole catalogue is a snapshot.

use super::{rib, world};

/// Cases: a name and RIB text that must fail.
fn cases() -> Vec<(&'static str, String)> {
    let w = world;
    vec![
        ("geometry outside the world", "Sphere 1 -1 1 360".into()),
        ("AttributeEnd without AttributeBegin", w("AttributeEnd")),
        ("TransformEnd closing an attribute block", w("AttributeBegin TransformEnd")),
        ("WorldEnd without WorldBegin", "WorldEnd".into()),
        ("unclosed AttributeBegin", "WorldBegin AttributeBegin Sphere 1 -1 1 360".into()),
        ("unclosed MotionBegin", w("MotionBegin [0 1] Translate 0 0 1")),
        ("motion times not increasing", w("MotionBegin [1 0] Translate 0 0 1 Translate 0 0 2 MotionEnd")),
        ("motion with too few transformations", w("MotionBegin [0 0.5 1] Translate 0 0 1 Translate 0 0 2 MotionEnd")),
        ("nested MotionBegin", w("MotionBegin [0 1] MotionBegin [0 1]")),
        ("motion of two kinds", w("MotionBegin [0 1] Translate 0 0 1 Rotate 3 0 0 1 MotionEnd")),
        ("motion of a changing polygon", w("MotionBegin [0 1] Polygon \"P\" [0 0 0 1 0 0 1 1 0] Polygon \"P\" [0 0 0 1 0 0 1 1 0 0 1 0] MotionEnd")),
        ("unknown solid operation", w("SolidBegin \"xor\"")),
        ("SolidEnd without SolidBegin", w("SolidEnd")),
        ("empty solid", w("SolidBegin \"union\" SolidEnd")),
        ("unknown object handle", w("ObjectInstance 7")),
        ("ObjectEnd without ObjectBegin", w("ObjectEnd")),
        ("Illuminate of an unknown light", w("Illuminate 3 1")),
        ("unknown projection", "Projection \"fisheye\"".into()),
        ("empty format", "Format 0 0 1".into()),
        ("no pixel samples", "PixelSamples 0 2".into()),
        ("unknown pixel filter", "PixelFilter \"lanczos3\" 2 2".into()),
        ("unknown hider", "Hider \"zbuffer\"".into()),
        ("bad bucket size", "Option \"limits\" \"bucketsize\" [0 16]".into()),
        ("unknown basis", w("Basis \"nurbs\" 1 \"bezier\" 3")),
        ("bad patch type", w("Patch \"trilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]")),
        ("polygon of two points", w("Polygon \"P\" [0 0 0 1 0 0]")),
        ("a face of two vertices", w("PointsPolygons [2] [0 1] \"P\" [0 0 0 1 0 0]")),
        ("vertex count mismatch", w("PointsPolygons [3 3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]")),
        ("negative vertex index", w("PointsPolygons [3] [0 -1 2] \"P\" [0 0 0 1 0 0 1 1 0]")),
        ("too few points for the indices", w("PointsPolygons [3] [0 1 5] \"P\" [0 0 0 1 0 0 1 1 0]")),
        ("varying colours of the wrong count", w("Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"varying color Cs\" [1 0 0]")),
        ("normals of the wrong count", w("PointsPolygons [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0] \"N\" [0 0 1 0 0 1]")),
        ("face-varying st of the wrong count", w("PointsPolygons [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0] \"facevarying float[2] st\" [0 0 1 0]")),
        ("grid size zero", "Option \"limits\" \"gridsize\" [0]".into()),
        ("sphere of radius zero", w("Sphere 0 -1 1 360")),
        ("torus with a zero tube", w("Torus 1 0 0 360 360")),
        ("far clipping before near", "Clipping 10 1 Projection \"perspective\" WorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("shutter closing before it opens", "Shutter 1 0 Projection \"perspective\" WorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("focal distance behind the lens", "DepthOfField 2.8 1 -3 Projection \"perspective\" WorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("shading rate zero", w("ShadingRate 0")),
        ("negative flatness", w("GeometricApproximation \"flatness\" -1")),
        ("negative motion factor", w("GeometricApproximation \"motionfactor\" -1")),
        ("negative focus factor", w("GeometricApproximation \"focusfactor\" -0.5")),
        ("motion factor not a number", w("GeometricApproximation \"motionfactor\" \"fast\"")),
        ("three sides", w("Sides 3")),
        ("shading interpolation", w("ShadingInterpolation \"phong\"")),
        ("unknown orientation", w("Orientation \"sideways\"")),
        ("skew of parallel vectors", w("Skew 30 1 0 0 2 0 0")),
        ("perspective of 200 degrees", w("Perspective 200")),
        ("unknown coordinate system", w("CoordSysTransform \"lamp\"")),
        ("an open CSG operand", w("SolidBegin \"union\" SolidBegin \"primitive\" Disk 0 1 360 SolidEnd SolidBegin \"primitive\" Sphere 1 -1 1 360 SolidEnd SolidEnd")),
        ("FrameBegin inside the world", w("FrameBegin 1")),
        ("WorldBegin twice", "WorldBegin WorldBegin".into()),
        ("a degenerate polygon", w("Polygon \"P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]")),
        ("geometry in an object definition left open", w("ObjectBegin 1 AttributeBegin Sphere 1 -1 1 360 ObjectEnd ObjectInstance 1")),
        // Options the renderer could not set up: reported at the request by validation.
        ("a filter narrower than the sample strata", "PixelSamples 2 2\nPixelFilter \"gaussian\" 0.01 0.01\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("a box filter of 1e-20 pixels", "PixelFilter \"box\" 1e-20 1e-20\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("a field of view too narrow for single precision", "Projection \"perspective\" \"fov\" [1e-44]\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("a screen window too small for single precision", "ScreenWindow 0 1e-40 0 1e-40\nProjection \"perspective\"\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("an orthographic screen window too small for single precision", "Projection \"orthographic\"\nScreenWindow 0 1e-40 0 1e-40\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("a lens too large for single precision", "DepthOfField 1e-38 3e38 5\nProjection \"perspective\"\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("a shutter too long for single precision", "Shutter -3e38 3e38\nProjection \"perspective\"\nWorldBegin Sphere 1 -1 1 360 WorldEnd".into()),
        ("subdivision nargs of the wrong length", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2] [0 1] [] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision crease of one point", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [1 1] [0] [2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision crease asking past intargs", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [3 1] [0 1] [2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision negative sharpness", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2 1] [0 1] [-2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision crease not along an edge", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2 1] [0 2] [2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision hole of a missing face", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"hole\"] [1 0] [4] [] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision negative corner point", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"corner\"] [1 1] [-1] [3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision interpolateboundary 3", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"interpolateboundary\"] [1 0] [3] [] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]")),
        ("subdivision face used backwards", w("SubdivisionMesh \"catmull-clark\" [3 3] [0 1 2 0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]")),
        ("subdivision facevarying st of the wrong count", w("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0] \"facevarying float[2] st\" [0 0 1 0]")),
        ("an object that instances itself", w("ObjectBegin \"a\" Sphere 1 -1 1 360 ObjectEnd ObjectBegin \"a\" ObjectInstance \"a\" ObjectEnd ObjectInstance \"a\"")),
    ]
}

#[test]
fn every_malformed_case_gives_its_one_line_error() {
    let mut snapshot = String::new();
    for (name, text) in cases() {
        let err = match rib(&text) {
            Ok(_) => panic!("{name}: loaded without an error"),
            Err(e) => e.to_string(),
        };
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.starts_with("test.rib:"), "{name}: {err}");
        snapshot.push_str(&format!("{name}\n  {err}\n"));
    }
    assert!(cases().len() >= 30);
    insta::assert_snapshot!("state_machine_catalogue", snapshot);
}

/// Loads `text` as the file `test.rib` in a temporary folder, through the CLI's entry.
fn load_file(text: &str) -> Result<reyes_rib::Loaded, reyes_rib::Refusal> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.rib");
    std::fs::write(&path, text).unwrap();
    reyes_rib::load_scene_file(&path, &reyes_rib::RiOptions::default())
}

/// Each warning's `line:col` and the start of its message.
fn places(warnings: &[reyes_rib::Warning]) -> Vec<String> {
    warnings.iter().map(|w| format!("{}: {}", w.at.pos, &w.message[..12])).collect()
}

#[test]
fn a_refused_scene_keeps_the_warnings_raised_before_its_error() {
    // An unknown request and an unused parameter are tolerated; then the file is refused.
    let text = "Projection \"perspective\"\nWorldBegin\nFrobnicate 1\n\
                Sphere 1 -1 1 360 \"bogus\" [1]\nIlluminate 3 1\nWorldEnd\n";
    let refused = load_file(text).expect_err("refused");
    assert!(refused.to_string().contains("Illuminate"), "{refused}");
    assert_eq!(refused.exit_code(), 2);
    assert_eq!(refused.warnings.len(), 2, "{:?}", refused.warnings);
    assert_eq!(refused.warnings[0].at.pos.line, 3, "{:?}", refused.warnings);
    assert_eq!(refused.warnings[1].at.pos.line, 4, "{:?}", refused.warnings);
    assert!(refused.warnings.iter().all(|w| w.at.file.ends_with("test.rib")));
}

#[test]
fn warnings_come_in_file_order() {
    // The orthographic camera's depth-of-field warning is raised when the frame is built, at
    // WorldEnd, but belongs to WorldBegin (line 3): it comes before the unknown request of
    // line 4 and the unused parameter of line 5.
    let text = "DepthOfField 2.8 1 5\nProjection \"orthographic\"\nWorldBegin\nFrobnicate 1\n\
                Sphere 1 -1 1 360 \"bogus\" [1]\nWorldEnd\n";
    let loaded = load_file(text).unwrap();
    let lines: Vec<u32> = loaded.warnings.iter().map(|w| w.at.pos.line).collect();
    assert_eq!(lines, [3, 4, 5], "{:?}", places(&loaded.warnings));
}

#[test]
fn an_unused_normal_on_a_patch_is_not_called_a_polygon_mesh() {
    let text = "Projection \"perspective\"\nWorldBegin\nPatch \"bilinear\" \"P\" [0 0 5 1 0 5 0 1 5 1 1 5] \
                \"N\" [0 0 -1 0 0 -1 0 0 -1 0 0 -1]\nWorldEnd\n";
    let loaded = load_file(text).unwrap();
    let shown: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(shown.len(), 1, "{shown:?}");
    assert!(shown[0].contains("Patch: \"N\": not used on this primitive"), "{shown:?}");
    assert!(!shown[0].contains("polygon"), "{shown:?}");
}
