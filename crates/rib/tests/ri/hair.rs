//! `Curves`, `Points` and `Blobby` (issue #34): each maps onto its model shape with every
//! storage class of its primitive variables, and each malformed case is one error of one
//! line, `test.rib:line:col: Request: message`, at the argument or parameter at fault.

use reyes_scene::{CurveType, Primvar, Shape, Wrap};

use super::{rib, scene, world};

#[test]
fn curves_points_and_blobbies_map_onto_their_shapes() {
    let s = scene(&world(
        "Basis \"bezier\" 3 \"b-spline\" 1
         Curves \"cubic\" [5 4] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 1 0 3 0 0 4 0 0  0 1 0 1 1 0 2 1 0 3 1 0]
           \"width\" [0.1 0.2 0.3 0.1 0.2] \"vertex color Cs\" [1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 0 1 0 0 1 0 0 1 0 0 1 0]
           \"uniform color Os\" [0.5 0.5 0.5 1 1 1]
         Curves \"linear\" [3] \"periodic\" \"P\" [0 0 0 1 0 0 0 1 0] \"constantwidth\" 0.05 \"N\" [0 0 1 0 0 1 0 0 1]
         Points \"P\" [0 0 0 1 1 1] \"width\" [0.5 0.25]
         Blobby 2 [1001 0 1001 16 0 2 0 1] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1  1 0 0 0 0 1 0 0 0 0 1 0 0.5 0 0 1] [\"\"]
           \"varying color Cs\" [1 0 0 0 0 1]",
    ));
    let Shape::Curves { kind, wrap, nvertices, basis, step, width, colors, opacities, .. } =
        &s.objects[0].shape
    else {
        panic!("{:?}", s.objects[0].shape)
    };
    assert_eq!(
        (*kind, *wrap, nvertices.clone()),
        (CurveType::Cubic, Wrap::Nonperiodic, vec![5, 4])
    );
    // The v basis and step.
    assert_eq!((*basis, *step), (reyes_scene::Basis::BSpline, Some(1)));
    // Varying: segments + 1 per curve (2 + 1 and 1 + 1).
    assert!(matches!(width, Primvar::Varying(w) if w.len() == 5));
    assert!(matches!(colors, Some(Primvar::Vertex(c)) if c.len() == 9));
    assert!(matches!(opacities, Some(Primvar::Uniform(o)) if o.len() == 2));
    let Shape::Curves { wrap, width, normals, .. } = &s.objects[1].shape else { panic!() };
    assert_eq!(*wrap, Wrap::Periodic);
    assert_eq!(width, &Primvar::Constant(0.05));
    // N is declared varying: one per segment end, 3 on a periodic curve of 3 segments.
    assert!(matches!(normals, Some(Primvar::Varying(n)) if n.len() == 3));
    let Shape::Points { points, width, .. } = &s.objects[2].shape else { panic!() };
    assert_eq!(points.len(), 2);
    // width is declared varying.
    assert_eq!(width, &Primvar::Varying(vec![0.5, 0.25]));
    let Shape::Blobby { code, colors, .. } = &s.objects[3].shape else { panic!() };
    assert_eq!(code.len(), 8);
    assert!(matches!(colors, Some(Primvar::Varying(c)) if c.len() == 2));
}

/// Each case: a name, a body, and what the one-line error must hold.
#[test]
fn malformed_hair_gives_one_line_errors_at_the_fault() {
    let cases = [
        (
            "curve of the wrong point count",
            "Curves \"cubic\" [4] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0]",
            "parameter \"P\"",
        ),
        (
            "cubic curve of 6 points in steps of 3",
            "Curves \"cubic\" [6] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0 5 0 0]",
            "nvertices[0]",
        ),
        (
            "widths of the wrong count",
            "Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0] \"width\" [1 2 3]",
            "\"width\"",
        ),
        (
            "unknown curve type",
            "Curves \"quadratic\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0]",
            "type must be",
        ),
        ("unknown wrap", "Curves \"linear\" [2] \"wrapped\" \"P\" [0 0 0 1 0 0]", "wrap must be"),
        (
            "negative width",
            "Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0] \"constantwidth\" -1",
            "width",
        ),
        (
            "point colours of the wrong count",
            "Points \"P\" [0 0 0 1 1 1] \"varying color Cs\" [1 0 0]",
            "\"Cs\"",
        ),
        (
            "unknown blobby opcode",
            "Blobby 1 [1001 0 1010 0] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] [\"\"]",
            "code[2]: unknown blobby opcode 1010",
        ),
        (
            "blobby float index out of range",
            "Blobby 1 [1001 4] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] [\"\"]",
            "code[1]: float index 4",
        ),
        (
            "blobby operand naming a later instruction",
            "Blobby 1 [1001 0 0 2 0 1] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] [\"\"]",
            "code[5]",
        ),
        (
            "blobby string index out of range",
            "Blobby 1 [1003 2 0] [1 1 1 1] [\"\"]",
            "string index 2",
        ),
    ];
    for (name, body, holds) in cases {
        let err = match rib(&world(body)) {
            Ok(_) => panic!("{name}: loaded without an error"),
            Err(e) => e.to_string(),
        };
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
        assert!(err.starts_with("test.rib:4:"), "{name}: {err}");
        assert!(err.contains(holds), "{name}: {err}");
    }
}
