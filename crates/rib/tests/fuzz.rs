//! Robustness law: no input makes the reader panic or loop. Random bytes, random mutations of
//! valid RIB and random gzip streams are read to the end (reading on after every error); every
//! error and warning displays as one line naming the source.

use std::io::Write;

use proptest::prelude::*;
use reyes_rib::{Reader, Source};

/// A valid RIB touching most token kinds and argument forms.
const VALID: &str = r#"##RenderMan RIB
version 3.03
Declare "dir" "uniform point"
Option "searchpath" "shader" ["@:."]
Display "out.tif" "file" "rgba" "origin" [0 0]
Format 320 240 1
ScreenWindow [-1 1 -0.75 0.75]
Projection "perspective" "fov" [45]
DepthOfField 2.8 1 8
Shutter 0 1
ColorSamples [1 0 0 0 1 0 0 0 1] [1 0 0 0 1 0 0 0 1]
FrameBegin 1
WorldBegin
LightSource "distantlight" 1 "intensity" [1.0] "from" [-1 1 -1] "to" [0 0 0]
Surface "plastic" "Ka" 1 "Kd" [.7] "Ks" [5.] "roughness" [-.1e-1] "texturename" "a\tb\\c\"d\101"
AttributeBegin
  Color [0.3 0.4 0.5]
  MotionBegin [0 1] Translate -4.25 -3.75 12 Translate -3.25 -3.75 12 MotionEnd
  ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]
  Basis "bezier" 3 [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 3
  SolidBegin "difference" SolidBegin "primitive" Sphere 1.4 -1.4 1.4 360 SolidEnd SolidEnd
  PointsPolygons [3 4] [0 1 2 0 2 3 4] "P" [0 0 0 1 0 0 1 1 0 0 1 0 2 2 2] "varying color Cs" [1 0 0 0 1 0 0 0 1 1 1 1 0 0 0]
  SubdivisionMesh "catmull-clark" [4] [0 1 2 3] ["crease"] [2 1] [0 1] [2.5] "P" [0 0 0 1 0 0 1 1 0 0 1 0]
  Procedural "DelayedReadArchive" ["tree.rib"] [-1 1 -1 1 0 2]
  Unknown 1 2 [3] "x"
AttributeEnd
WorldEnd
FrameEnd
"#;

/// Snippets that upset a RIB reader.
const SNIPPETS: &[&str] = &[
    "[",
    "]",
    "\"",
    "\\",
    "#",
    "##",
    "\n",
    "-",
    ".",
    "e",
    "1e99",
    "1e",
    "+.",
    "\\777",
    "\\\n",
    "[[",
    "\u{80}",
    "\u{1}",
    "\"uniform float[\"",
    "\"float[0] x\"",
    "Sphere",
    "ReadArchive \"x.rib\"",
    "Declare \"x\" \"y\"",
    "ColorSamples [1] [1]",
    "99999999999999999999",
    "\"P\"",
    "Color",
    "MotionBegin",
    "\u{ff}",
];

/// Binary-encoding snippets (raw bytes): lying lengths, definitions, references.
const BINARY: &[&[u8]] = &[
    b"\xcb\xff\xff\xff\xff",
    b"\xa3\xff\xff\xff\xff",
    b"\xcc\x01\x96Sphere",
    b"\xa6\x01",
    b"\xcd\x01\x91x",
    b"\xcf\x01",
    b"\x83\x7f",
    b"\x8f\x01\x02\x03\x04",
    b"\xa4\x7f\xc0\x00\x00",
    b"\xc8\x02\x3f\x80\x00\x00",
    b"\xa7",
    b"\xff",
];

/// Reads `bytes` to the end, reading on after errors; checks the one-line law.
fn read_all(bytes: Vec<u8>) {
    let mut r = Reader::new(Source::from_bytes("fuzz.rib", bytes));
    for _ in 0..100_000 {
        match r.next_request() {
            Ok(Some(_)) => {}
            Ok(None) => {
                for w in r.warnings() {
                    let s = w.to_string();
                    assert!(!s.contains('\n') && s.starts_with("fuzz.rib:"), "{s}");
                }
                return;
            }
            Err(e) => {
                let s = e.to_string();
                assert!(!s.contains('\n') && s.starts_with("fuzz.rib:"), "{s}");
            }
        }
    }
    panic!("the reader did not finish");
}

#[test]
fn the_valid_base_reads() {
    let mut r = Reader::new(Source::from_bytes("fuzz.rib", VALID));
    let mut n = 0;
    while r.next_request().unwrap_or_else(|e| panic!("{e}")).is_some() {
        n += 1;
    }
    assert_eq!(n, 33);
    assert_eq!(r.warnings().len(), 1, "{:?}", r.warnings());
}

/// One edit of the valid text.
#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, usize),
    InsertBinary(usize, usize),
    Delete(usize, usize),
    Byte(usize, u8),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0..SNIPPETS.len()).prop_map(|(at, s)| Edit::Insert(at, s)),
        (any::<usize>(), 0..BINARY.len()).prop_map(|(at, s)| Edit::InsertBinary(at, s)),
        (any::<usize>(), 1usize..40).prop_map(|(at, n)| Edit::Delete(at, n)),
        (any::<usize>(), any::<u8>()).prop_map(|(at, b)| Edit::Byte(at, b)),
    ]
}

fn apply(edits: &[Edit]) -> Vec<u8> {
    let mut v = VALID.as_bytes().to_vec();
    for e in edits {
        let len = v.len().max(1);
        match *e {
            Edit::Insert(at, s) => {
                let at = at % len;
                v.splice(at..at, SNIPPETS[s].bytes());
            }
            Edit::InsertBinary(at, s) => {
                let at = at % len;
                v.splice(at..at, BINARY[s].iter().copied());
            }
            Edit::Delete(at, n) => {
                let at = at % len;
                let end = (at + n).min(v.len());
                v.drain(at.min(end)..end);
            }
            Edit::Byte(at, b) => {
                if let Some(x) = v.get_mut(at % len) {
                    *x = b;
                }
            }
        }
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        read_all(bytes);
    }

    #[test]
    fn random_ascii_never_panics(text in "[ -~\n\t]{0,400}") {
        read_all(text.into_bytes());
    }

    #[test]
    fn mutated_valid_rib_never_panics(edits in proptest::collection::vec(edit(), 1..8)) {
        read_all(apply(&edits));
    }

    #[test]
    fn mutated_gzip_never_panics(edits in proptest::collection::vec(edit(), 0..3), cut in any::<usize>(), flip in any::<(usize, u8)>()) {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&apply(&edits)).unwrap();
        let mut gz = enc.finish().unwrap();
        let len = gz.len();
        if flip.0 % 3 == 0 {
            gz[2 + flip.0 % (len - 2)] ^= flip.1 | 1;
        } else if flip.0 % 3 == 1 {
            gz.truncate(2 + cut % (len - 2));
        }
        read_all(gz);
    }
}
