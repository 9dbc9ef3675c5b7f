//! Binary RIB (Spec 3.2 Appendix C.2) reads to the same requests as ASCII: each request of an
//! ASCII text (the peers' scenes of `tests/data/peers/` and a text touching every argument form) is re-encoded with
//! defined requests (0314/0246), defined strings (0315/0317), encoded integers, fixed-point
//! numbers, floats and float arrays (0310), mixed with ASCII brackets as the spec allows, and
//! must read back equal in everything but position.

use std::collections::HashMap;
use std::path::PathBuf;

use reyes_rib::{Data, Reader, Request, Source, Value};

/// A small binary RIB writer over parsed requests.
#[derive(Default)]
struct Encoder {
    out: Vec<u8>,
    requests: HashMap<&'static str, u8>,
    strings: HashMap<String, u16>,
}

impl Encoder {
    fn int(&mut self, i: i32) {
        // The shortest form: 0200 + w with w + 1 bytes.
        let bytes = i.to_be_bytes();
        let w = if (-128..128).contains(&i) {
            0
        } else if (-32768..32768).contains(&i) {
            1
        } else if (-8_388_608..8_388_608).contains(&i) {
            2
        } else {
            3
        };
        self.out.push(0o200 + w as u8);
        self.out.extend_from_slice(&bytes[3 - w..]);
    }

    fn float(&mut self, f: f32) {
        if f == f.trunc() && f.abs() < 100.0 && f != 0.0 {
            // Fixed point, one byte after the point: 0200 + 4 + 1 (two bytes).
            let v = (f * 256.0) as i16;
            self.out.push(0o205);
            self.out.extend_from_slice(&v.to_be_bytes());
        } else {
            self.out.push(0o244);
            self.out.extend_from_slice(&f.to_be_bytes());
        }
    }

    fn string(&mut self, s: &str) {
        let b = s.as_bytes();
        if b.len() < 16 {
            self.out.push(0o220 + b.len() as u8);
        } else {
            self.out.push(0o243);
            self.out.extend_from_slice(&(b.len() as u32).to_be_bytes());
        }
        self.out.extend_from_slice(b);
    }

    /// A string sent once through a definition (0315 + 1: a two-byte token), then by token.
    fn defined_string(&mut self, s: &str) {
        let next = self.strings.len() as u16;
        let t = *self.strings.entry(s.to_string()).or_insert_with(|| next);
        if t == next {
            self.out.push(0o316);
            self.out.extend_from_slice(&t.to_be_bytes());
            self.string(s);
        }
        self.out.push(0o320);
        self.out.extend_from_slice(&t.to_be_bytes());
    }

    fn floats(&mut self, v: &[f32]) {
        self.out.push(0o313);
        self.out.extend_from_slice(&(v.len() as u32).to_be_bytes());
        for f in v {
            self.out.extend_from_slice(&f.to_be_bytes());
        }
    }

    fn ints(&mut self, v: &[i32]) {
        self.out.push(b'[');
        for &i in v {
            self.int(i);
        }
        self.out.push(b']');
    }

    fn strings(&mut self, v: &[String]) {
        self.out.extend_from_slice(b"[ ");
        for s in v {
            self.string(s);
        }
        self.out.extend_from_slice(b" ]");
    }

    fn request(&mut self, r: &Request) {
        let next = self.requests.len() as u8;
        let code = *self.requests.entry(r.name()).or_insert(next);
        if code == next {
            self.out.extend_from_slice(&[0o314, code]);
            self.string(r.name());
        }
        self.out.extend_from_slice(&[0o246, code]);
        for a in &r.args {
            match a {
                Value::Int(i) => self.int(*i),
                Value::Float(f) => self.float(*f),
                Value::String(s) => self.string(s),
                Value::Ints(v) => self.ints(v),
                Value::Floats(v) => self.floats(v),
                Value::Strings(v) => self.strings(v),
            }
        }
        for p in &r.params {
            match p.decl {
                Some(d) => self.defined_string(&format!("{d} {}", p.name)),
                None => self.defined_string(&p.name),
            }
            match &p.data {
                Data::Floats(v) => self.floats(v),
                Data::Ints(v) => self.ints(v),
                Data::Strings(v) => self.strings(v),
            }
        }
        self.out.push(b'\n');
    }
}

fn read(source: Source) -> Vec<Request> {
    Reader::new(source).map(|r| r.unwrap_or_else(|e| panic!("{e}"))).collect()
}

/// Reads `ascii`, re-encodes it and requires the same requests back.
fn round_trip(name: &str, ascii: Vec<u8>) -> usize {
    let plain = read(Source::from_bytes(name, ascii));
    let mut enc = Encoder::default();
    for r in &plain {
        enc.request(r);
    }
    let binary = read(Source::from_bytes(name, enc.out));
    assert_eq!(plain.len(), binary.len(), "{name}");
    for (a, b) in plain.iter().zip(&binary) {
        assert_eq!((a.kind, &a.args), (b.kind, &b.args), "{name}: {}", a.at);
        assert_eq!(a.params.len(), b.params.len(), "{name}: {}", a.at);
        for (p, q) in a.params.iter().zip(&b.params) {
            assert_eq!((&p.name, p.decl, &p.data), (&q.name, q.decl, &q.data), "{name}: {}", a.at);
        }
    }
    plain.len()
}

#[test]
fn every_argument_form_round_trips() {
    let text = r#"version 3.03
Declare "dir" "uniform point"
Display "a long display name.tif" "file" "rgba" "origin" [0 0]
Format 320 240 1
ScreenWindow [-1 1 -0.75 0.75]
Projection "perspective" "fov" [45]
DepthOfField 2.8 1 8
Color [0.3 0.4 0.5]
LightSource "spotlight" "key" "from" [0 0 0] "dir" [0 0 1]
MotionBegin [0 0.25 1] Translate -4.25 -3.75 12 Translate -3.25 -3.75 1200000 Translate 0 0 -70000 MotionEnd
ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]
Basis "bezier" 3 [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 3
PointsPolygons [3 4] [0 1 2 0 2 3 40000] "P" [0 0 0 1 0 0 1 1 0 0 1 0 2 2 2] "varying color Cs" [1 0 0 0 1 0 0 0 1 1 1 1 0 0 0]
SubdivisionMesh "catmull-clark" [4] [0 1 2 3] ["crease" "hole"] [2 1 1 0] [0 1 3] [2.5] "P" [0 0 0 1 0 0 1 1 0 0 1 0]
Procedural "DelayedReadArchive" ["tree.rib"] [-1 1 -1 1 0 2]
Option "user" "frobs" [1 -2 300000] "names" ["a" "b"] "zot" 2.5
Sides 2
"#;
    assert_eq!(round_trip("forms.rib", text.as_bytes().to_vec()), 21);
}

#[test]
fn peer_scenes_round_trip() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/peers");
    for file in ["csg.rib", "a_balls.rib", "b_balls_mb.rib", "c_balls_dof.rib", "d_heavy_mb.rib"] {
        let bytes = std::fs::read(dir.join(file)).unwrap();
        assert!(round_trip(file, bytes) > 20, "{file}");
    }
}
