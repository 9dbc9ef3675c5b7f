//! docs/rib.md stays true: every ```rib example reads without an error or a warning, and the
//! messages it shows are the ones the reader gives for the inputs below.

use reyes_rib::{Reader, Source};

const DOC: &str = include_str!("../../../docs/rib.md");

/// The ```rib blocks of the document.
fn rib_blocks() -> Vec<String> {
    reyes_testkit::docs::fenced_blocks(DOC, "rib")
}

#[test]
fn examples_read_cleanly() {
    let blocks = rib_blocks();
    assert!(!blocks.is_empty());
    for b in blocks {
        let mut r = Reader::new(Source::from_bytes("doc.rib", b.clone()));
        let mut n = 0;
        while r.next_request().unwrap_or_else(|e| panic!("{b}\n{e}")).is_some() {
            n += 1;
        }
        assert!(n > 0);
        assert!(r.warnings().is_empty(), "{:?}", r.warnings());
    }
}

fn first_message(name: &str, bytes: Vec<u8>) -> String {
    let mut r = Reader::new(Source::from_bytes(name, bytes));
    loop {
        match r.next_request() {
            Ok(Some(_)) => {}
            Ok(None) => return r.warnings().first().map(|w| w.to_string()).unwrap_or_default(),
            Err(e) => return e.to_string(),
        }
    }
}

#[test]
fn shown_messages_are_real() {
    for (name, rib, shown) in [
        (
            "scene.rib",
            "\n\nSphere 1 -1 1 360f".as_bytes().to_vec(),
            "scene.rib:3:15: Sphere: argument thetamax: malformed number \"360f\"",
        ),
        ("scene.rib", "\n\n]".into(), "scene.rib:3:1: expected a request name, got ']'"),
        (
            "scene.rib",
            "\n\n\nSurface \"plastic\" \"Kd\" 1e39".into(),
            "scene.rib:4:24: Surface: parameter \"Kd\" (uniform float): number 1e39 is out of range (not a finite 32-bit float)",
        ),
        (
            "scene.rib",
            "\n\n\n\n\n\nTranslate 1 2 3 4".into(),
            "scene.rib:7:17: Translate: too many arguments: the number 4 after dz (Translate dx dy dz)",
        ),
        (
            "scene.rib",
            "\n\n\n\n\n\n\n\nPolygon \"P\" [0 0 0 1 0]".into(),
            "scene.rib:9:13: Polygon: parameter \"P\" (vertex point): expected a multiple of 3 values, got 5",
        ),
        (
            "scene.rib",
            "\nFrobnicate 1".into(),
            "scene.rib:2:1: warning: unknown request \"Frobnicate\" skipped",
        ),
        (
            "scene.rib.gz",
            vec![0x1f, 0x8b, 0, 0, 0, 0, 0, 0, 0, 0],
            "scene.rib.gz: cannot read: invalid gzip header",
        ),
        ("x.rib", "version 3.03\n\u{1}".into(), "x.rib:2:1: unexpected control byte 0x01"),
        (
            "x.rib",
            b"WorldBegin \xa7".to_vec(),
            "x.rib:1:12: reserved binary RIB code 0247 (byte 0xa7); the rest of the source is not read",
        ),
        (
            "x.rib",
            "Option \"user\" \"frobs\" 1".into(),
            "x.rib:1:15: warning: Option: parameter \"frobs\" is not declared; kept as written",
        ),
    ] {
        assert_eq!(first_message(name, rib), shown);
        let shown_in_doc = shown.split_once(": ").map_or(shown, |(_, m)| m);
        let shown_in_doc = shown_in_doc.trim_start_matches("warning: ");
        assert!(
            DOC.contains(shown) || DOC.contains(shown_in_doc) || name == "x.rib",
            "docs/rib.md does not show {shown:?}"
        );
    }
}
