//! Requests as the state machine sees them: every argument form of the signature table
//! (alternative forms normalised to one), parameters typed by inline and table declarations,
//! positions, warnings, recovery after errors, gzip and structural comments.

mod common;

use common::{FILE, all_errors, first_error, one, read, warnings};
use reyes_rib::{
    ArgKind, Class, Data, Decl, Pos, Reader, ReaderOptions, RequestKind, Source, Type, Value,
};

#[test]
fn bare_and_array_forms_normalise_alike() {
    for (a, b) in [
        ("Color [0.1 0.2 0.3]", "Color 0.1 0.2 0.3"),
        ("Opacity [1 1 1]", "Opacity 1 1 1"),
        (
            "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
            "ConcatTransform 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1",
        ),
        (
            "Transform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]",
            "Transform 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1",
        ),
        ("Bound [-1 1 -1 1 -1 1]", "Bound -1 1 -1 1 -1 1"),
        ("Detail [-1 1 -1 1 -1 1]", "Detail -1 1 -1 1 -1 1"),
        ("MotionBegin [0 0.5 1]", "MotionBegin 0 0.5 1"),
        ("ScreenWindow [-1 1 -0.75 0.75]", "ScreenWindow -1 1 -0.75 0.75"),
        ("CropWindow [0 1 0 0.5]", "CropWindow 0 1 0 0.5"),
        ("TextureCoordinates [0 0 1 0 0 1 1 1]", "TextureCoordinates 0 0 1 0 0 1 1 1"),
        ("DetailRange [0 0 10 20]", "DetailRange 0 0 10 20"),
        ("Skew [45 0 1 0 1 0 0]", "Skew 45 0 1 0 1 0 0"),
        ("Hyperboloid [1 0 -1] [0 1 1] 360", "Hyperboloid 1 0 -1 0 1 1 360"),
        (
            "Basis [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 3 \"bezier\" 3",
            "Basis 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 3 \"bezier\" 3",
        ),
    ] {
        assert_eq!(one(a).args, one(b).args, "{a} / {b}");
    }
}

#[test]
fn normalised_values() {
    assert_eq!(one("Color [0.1 0.2 0.3]").args, vec![Value::Floats(vec![0.1, 0.2, 0.3])]);
    assert_eq!(one("MotionBegin [0 1]").floats(0), Some(&[0.0, 1.0][..]));
    let sw = one("ScreenWindow [-1 1 -0.75 0.75]");
    assert_eq!(
        sw.args,
        vec![Value::Float(-1.0), Value::Float(1.0), Value::Float(-0.75), Value::Float(0.75)]
    );
    let h = one("Hyperboloid 1 0 -1 0 1 1 270");
    assert_eq!(h.floats(0), Some(&[1.0, 0.0, -1.0][..]));
    assert_eq!(h.floats(1), Some(&[0.0, 1.0, 1.0][..]));
    assert_eq!(h.float(2), Some(270.0));
    let b = one("Basis \"bezier\" 3 \"catmull-rom\" 1");
    assert_eq!(b.string(0), Some("bezier"));
    assert_eq!(b.int(1), Some(3));
    assert_eq!(b.string(2), Some("catmull-rom"));
    assert_eq!(b.int(3), Some(1));
    let f = one("Format 640 480 1");
    assert_eq!((f.int(0), f.int(1), f.float(2)), (Some(640), Some(480), Some(1.0)));
    assert_eq!(one("SolidBegin \"difference\"").string(0), Some("difference"));
    assert_eq!(
        one("Translate -1.6 0 8").args,
        vec![Value::Float(-1.6), Value::Float(0.0), Value::Float(8.0)]
    );
    assert_eq!(one("version 3.03").float(0), Some(3.03));
}

#[test]
fn handles_are_integers_or_strings() {
    assert_eq!(one("LightSource \"spotlight\" 2").int(1), Some(2));
    assert_eq!(one("LightSource \"spotlight\" \"key\"").string(1), Some("key"));
    assert_eq!(one("Illuminate \"key\" 0").args, vec![Value::String("key".into()), Value::Int(0)]);
    assert_eq!(one("ObjectBegin 3").int(0), Some(3));
    assert_eq!(one("ObjectInstance \"tree\"").string(0), Some("tree"));
}

#[test]
fn optional_arguments() {
    assert_eq!(one("DepthOfField").args, vec![]);
    assert_eq!(one("DepthOfField 2.8 1 8").args.len(), 3);
    let s = one("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]");
    assert_eq!(s.args.len(), 3);
    assert_eq!(s.param("P").map(|p| p.data.len()), Some(12));
    let s = one(
        "SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2 1] [0 1] [2.5] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]",
    );
    assert_eq!(s.strings(3), Some(&["crease".to_string()][..]));
    assert_eq!(s.ints(4), Some(&[2, 1][..]));
    assert_eq!(s.floats(6), Some(&[2.5][..]));
}

#[test]
fn geometry_arrays() {
    let p = one("PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]");
    assert_eq!(p.ints(0), Some(&[3, 3][..]));
    assert_eq!(p.ints(1), Some(&[0, 1, 2, 0, 2, 3][..]));
    let pp = p.param("P").unwrap();
    assert_eq!(pp.decl, Some(Decl::new(Class::Vertex, Type::Point)));
    assert_eq!(pp.elements(3), Some(4));
    let n =
        one("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1 1 0 0 1 0 1 0 1 1 1 0 1]");
    assert_eq!(n.floats(2), Some(&[0.0, 0.0, 1.0, 1.0][..]));
    assert_eq!(n.int(5), Some(2));
    let t = one("TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]");
    assert_eq!(t.args.len(), 9);
    let pr = one("Procedural \"DelayedReadArchive\" [\"tree.rib\"] [-1 1 -1 1 0 2]");
    assert_eq!(pr.strings(1), Some(&["tree.rib".to_string()][..]));
    assert_eq!(pr.floats(2).map(<[f32]>::len), Some(6));
    let c = one(
        "Curves \"cubic\" [4] \"nonperiodic\" \"P\" [0 0 0 1 1 0 2 0 0 3 1 0] \"constantwidth\" 0.1",
    );
    assert_eq!(c.param("constantwidth").and_then(|p| p.floats()), Some(&[0.1][..]));
    let b = one("Blobby 1 [1001 0] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] [] ");
    assert_eq!(b.strings(3), Some(&[][..]));
}

#[test]
fn every_request_reads_with_minimal_arguments() {
    for &kind in RequestKind::ALL {
        let sig = kind.signature();
        let mut text = kind.name().to_string();
        if kind == RequestKind::Declare {
            text.push_str(" \"a\" \"float\"");
        }
        for arg in sig.args.iter().filter(|_| kind != RequestKind::Declare) {
            text.push(' ');
            text.push_str(match arg.kind {
                ArgKind::Int | ArgKind::Handle => "1",
                ArgKind::Float => "1.5",
                ArgKind::Str => "\"a\"",
                ArgKind::Ints => "[1 2]",
                ArgKind::Floats => "[1 2 3]",
                ArgKind::Strings => "[\"a\"]",
                ArgKind::Times => "[0 1]",
                ArgKind::Fixed(3) => "[0 0 0]",
                ArgKind::Fixed(6) => "[0 0 0 0 0 0]",
                ArgKind::Fixed(16) => "[1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
                ArgKind::Fixed(n) => panic!("{kind:?}: no sample for Fixed({n})"),
                ArgKind::Color => "[1 1 1]",
                ArgKind::Basis => "\"bezier\"",
            });
        }
        if sig.params {
            text.push_str(" \"Kd\" 0.5");
        }
        let r = one(&text);
        assert_eq!(r.kind, kind);
        assert_eq!(r.args.len(), sig.args.len(), "{text}");
        assert_eq!(r.params.len(), usize::from(sig.params), "{text}");
    }
}

#[test]
fn every_signature_rejects_a_missing_and_an_extra_argument() {
    for &kind in RequestKind::ALL {
        let sig = kind.signature();
        let sample = |k: ArgKind| match k {
            ArgKind::Int | ArgKind::Handle => "1",
            ArgKind::Float => "1.5",
            ArgKind::Str | ArgKind::Basis => "\"a\"",
            ArgKind::Ints => "[1 2]",
            ArgKind::Floats | ArgKind::Times => "[1 2 3]",
            ArgKind::Strings => "[\"a\"]",
            ArgKind::Fixed(3) => "[0 0 0]",
            ArgKind::Fixed(6) => "[0 0 0 0 0 0]",
            ArgKind::Fixed(_) => "[1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
            ArgKind::Color => "[1 1 1]",
        };
        if sig.required > 0 {
            let present: Vec<&str> =
                sig.args[..sig.required - 1].iter().map(|a| sample(a.kind)).collect();
            let text = format!("{} {}\nWorldBegin", kind.name(), present.join(" "));
            let last = &sig.args[sig.required - 1];
            let msg = first_error(&text);
            assert!(
                msg.starts_with(&format!(
                    "{FILE}:1:1: {}: missing argument {}",
                    kind.name(),
                    last.name
                )),
                "{text:?}: {msg}"
            );
        }
        if !sig.params {
            let all: Vec<&str> = sig.args.iter().map(|a| sample(a.kind)).collect();
            let text = format!("{} {} 7", kind.name(), all.join(" "));
            let msg = first_error(&text);
            assert!(
                msg.contains(&format!(": {}: too many arguments: the number 7 after", kind.name())),
                "{text:?}: {msg}"
            );
        }
    }
}

#[test]
fn parameters_are_typed_by_declarations() {
    let s = one(
        "Surface \"plastic\" \"Ka\" [1] \"Kd\" 0.7 \"specularcolor\" [1 0.5 0.25] \"texturename\" \"wood.tx\"",
    );
    assert_eq!(s.param("Ka").unwrap().data, Data::Floats(vec![1.0]));
    assert_eq!(s.param("Kd").unwrap().data, Data::Floats(vec![0.7]));
    assert_eq!(
        s.param("specularcolor").unwrap().decl,
        Some(Decl::new(Class::Uniform, Type::Color))
    );
    assert_eq!(s.param("texturename").unwrap().strings(), Some(&["wood.tx".to_string()][..]));
    // Inline declarations, each form.
    let s = one(concat!(
        "Surface \"x\" \"uniform float a\" 1 \"varying color b\" [1 0 0 0 1 0] ",
        "\"constant string c\" [\"s\"] \"vertex point d\" [0 0 0] \"facevarying float[2] e\" [0 1 1 0] ",
        "\"float[3] f\" [1 2 3] \"integer g\" [4 5] \"int h\" 6 \"facevertex normal i\" [0 0 1] ",
        "\"vector j\" [1 0 0] \"hpoint k\" [0 0 0 1] \"matrix l\" [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]"
    ));
    let decl = |n: &str| s.param(n).unwrap().decl.unwrap();
    assert_eq!(decl("a"), Decl::new(Class::Uniform, Type::Float));
    assert_eq!(decl("b"), Decl::new(Class::Varying, Type::Color));
    assert_eq!(s.param("b").unwrap().elements(3), Some(2));
    assert_eq!(decl("c"), Decl::new(Class::Constant, Type::String));
    assert_eq!(decl("d"), Decl::new(Class::Vertex, Type::Point));
    assert_eq!(decl("e"), Decl { class: Class::FaceVarying, ty: Type::Float, array: Some(2) });
    assert_eq!(decl("f"), Decl { class: Class::Uniform, ty: Type::Float, array: Some(3) });
    assert_eq!(s.param("g").unwrap().ints(), Some(&[4, 5][..]));
    assert_eq!(s.param("h").unwrap().ints(), Some(&[6][..]));
    assert_eq!(decl("i"), Decl::new(Class::FaceVertex, Type::Normal));
    assert_eq!(decl("l").ty, Type::Matrix);
}

#[test]
fn declare_feeds_later_parameters() {
    let all = read(
        "Declare \"direction\" \"point\"\nLightSource \"windowlight\" 0 \"direction\" [1 0 -0.1]\nDeclare \"n\" \"uniform integer\"\nAttribute \"x\" \"n\" 3",
    );
    assert_eq!(
        all[1].param("direction").unwrap().decl,
        Some(Decl::new(Class::Uniform, Type::Point))
    );
    assert_eq!(all[3].param("n").unwrap().ints(), Some(&[3][..]));
    // An inline declaration does not change the table.
    let all = read("Surface \"s\" \"string Kd\" \"x\"\nSurface \"s\" \"Kd\" 0.5");
    assert_eq!(all[1].param("Kd").unwrap().floats(), Some(&[0.5][..]));
    // A Declare may retype a predeclared name.
    let all = read("Declare \"Kd\" \"color\"\nSurface \"s\" \"Kd\" [1 0 0]");
    assert_eq!(all[1].param("Kd").unwrap().decl.unwrap().ty, Type::Color);
}

#[test]
fn undeclared_parameters_warn_and_keep_their_values() {
    let r = one("Option \"user\" \"frobs\" [1 2] \"zot\" [1 2.5] \"name\" \"x\" \"w\" \"s\"");
    assert_eq!(r.param("frobs").unwrap().data, Data::Ints(vec![1, 2]));
    assert_eq!(r.param("frobs").unwrap().decl, None);
    assert_eq!(r.param("zot").unwrap().data, Data::Floats(vec![1.0, 2.5]));
    assert_eq!(r.param("w").unwrap().data, Data::Strings(vec!["s".into()]));
    assert_eq!(
        warnings("Option \"user\" \"frobs\" [1 2]\nSurface \"s\" \"zot\" []"),
        vec![
            "test.rib:1:15: warning: Option: parameter \"frobs\" is not declared; kept as written",
            "test.rib:2:13: warning: Surface: parameter \"zot\" is not declared; kept as written",
        ]
    );
}

#[test]
fn color_samples_change_colour_sizes_until_frame_end() {
    let all = read(concat!(
        "FrameBegin 1\nColorSamples [0.5 0.5 0 0 0.5 0.5] [1 0 1 0 1 0]\nColor [0.2 0.4]\n",
        "Surface \"s\" \"specularcolor\" [1 1]\nFrameEnd\nColor 1 0 0"
    ));
    assert_eq!(all[2].floats(0), Some(&[0.2, 0.4][..]));
    assert_eq!(all[3].param("specularcolor").unwrap().elements(2), Some(1));
    assert_eq!(all[5].floats(0), Some(&[1.0, 0.0, 0.0][..]));
}

#[test]
fn positions_name_the_request_and_each_parameter() {
    let all =
        read("# header\nWorldBegin\n  Sphere 1 -1 1 360\n\tSurface \"plastic\"\n    \"Kd\" 0.5\n");
    assert_eq!(all[0].at.pos, Pos { line: 2, col: 1 });
    assert_eq!(all[1].at.pos, Pos { line: 3, col: 3 });
    assert_eq!(all[2].at.pos, Pos { line: 4, col: 2 });
    assert_eq!(all[2].params[0].at, Pos { line: 5, col: 5 });
    assert_eq!(all[2].at.to_string(), "test.rib:4:2");
}

#[test]
fn unknown_requests_are_skipped_with_a_warning() {
    let text = "WorldBegin\nFrobnicate 1 [2 3] \"x\" \"y\"\nSphere 1 -1 1 360";
    let all = read(text);
    assert_eq!(
        all.iter().map(|r| r.kind).collect::<Vec<_>>(),
        vec![RequestKind::WorldBegin, RequestKind::Sphere]
    );
    assert_eq!(
        warnings(text),
        vec!["test.rib:2:1: warning: unknown request \"Frobnicate\" skipped"]
    );
}

#[test]
fn reading_goes_on_after_an_error() {
    let (errors, requests) = all_errors(
        "] 5\nTranslate 1 2\nSphere 1 -1 \"x\" 360\nScale 1 2 3\nIdentity ] 5\nRotate 90 0 0 1",
    );
    assert_eq!(
        errors,
        vec![
            "test.rib:1:1: expected a request name, got ']'",
            "test.rib:2:1: Translate: missing argument dz (a number) in Translate dx dy dz",
            "test.rib:3:13: Sphere: argument zmax: expected a number, got the string \"x\"",
            "test.rib:5:10: Identity: too many arguments: ']' after the request name (Identity)",
        ]
    );
    assert_eq!(
        requests.iter().map(|r| r.kind).collect::<Vec<_>>(),
        vec![RequestKind::Scale, RequestKind::Rotate]
    );
}

#[test]
fn gzipped_input_is_read_transparently() {
    use std::io::Write;
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(b"WorldBegin\nSphere 1 -1 1 360\nWorldEnd\n").unwrap();
    let mut r = Reader::new(Source::from_bytes("scene.rib.gz", enc.finish().unwrap()));
    let kinds: Vec<_> = (&mut r).map(|q| q.unwrap().kind).collect();
    assert_eq!(kinds, vec![RequestKind::WorldBegin, RequestKind::Sphere, RequestKind::WorldEnd]);
    // A broken gzip stream is an I/O error naming the source, and ends the stream.
    let mut r = Reader::new(Source::from_bytes("bad.rib.gz", vec![0x1f, 0x8b, 8, 0, 1, 2, 3]));
    let e = r.next_request().unwrap_err();
    assert!(e.to_string().starts_with("bad.rib.gz: cannot read: "), "{e}");
    assert!(r.next_request().unwrap().is_none());
}

#[test]
fn structure_comments_are_kept_on_request() {
    let options = ReaderOptions { keep_structure_comments: true, ..ReaderOptions::default() };
    let mut r = Reader::with_options(
        Source::from_bytes("s.rib", "##RenderMan RIB-Structure 1.1\n# plain\nWorldBegin"),
        options,
    );
    while r.next_request().unwrap().is_some() {}
    let kept = r.take_structure_comments();
    assert_eq!(kept.len(), 1);
    assert_eq!(kept[0].0.to_string(), "s.rib:1:1");
    assert_eq!(kept[0].1, "RenderMan RIB-Structure 1.1");
}

#[test]
fn strings_keep_escapes_resolved() {
    let r = one(r#"Display "a\tb\\c\"d\101" "file" "rgba""#);
    assert_eq!(r.string(0), Some("a\tb\\c\"dA"));
    let r = one("Display \"long\\\nname\" \"file\" \"rgba\"");
    assert_eq!(r.string(0), Some("longname"));
}

#[test]
fn requests_need_no_whitespace_around_brackets_and_strings() {
    let all = read("Color[1 0 0]Surface\"plastic\"\"Kd\"[.5]Sphere 1 -1 1 360");
    assert_eq!(all.len(), 3);
    assert_eq!(all[1].param("Kd").unwrap().floats(), Some(&[0.5][..]));
}
