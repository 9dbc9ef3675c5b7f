//! The malformed-RIB catalogue: each case is a small RIB text and the exact one-line message of
//! its first error (`file:line:col: Request: message`, or `file:line:col: message` at the
//! lexical level). The whole catalogue is also an insta snapshot, so no message drifts unseen.

mod common;

use common::{FILE, first_error, first_error_bytes};

/// One bad input and its exact first error.
struct Case {
    name: &'static str,
    rib: &'static str,
    error: &'static str,
}

#[rustfmt::skip]
const CASES: &[Case] = &[
    // Lexical level.
    Case { name: "unterminated string", rib: "Display \"out.tif", error: "test.rib:1:9: Display: argument name: unterminated string" },
    Case { name: "unterminated string across lines", rib: "WorldBegin\nDisplay \"out.tif\nWorldEnd\n", error: "test.rib:2:9: Display: argument name: unterminated string" },
    Case { name: "malformed number: trailing letter", rib: "Sphere 1 -1 1 360f", error: "test.rib:1:15: Sphere: argument thetamax: malformed number \"360f\"" },
    Case { name: "malformed number: two periods", rib: "Translate 1.2.3 0 0", error: "test.rib:1:11: Translate: argument dx: malformed number \"1.2.3\"" },
    Case { name: "malformed number: lone minus", rib: "Translate - 0 0", error: "test.rib:1:11: Translate: argument dx: malformed number \"-\"" },
    Case { name: "malformed number: exponent without digits", rib: "Scale 1e 1 1", error: "test.rib:1:7: Scale: argument sx: malformed number \"1e\"" },
    Case { name: "non-finite number", rib: "Sphere 1e39 -1 1 360", error: "test.rib:1:8: Sphere: argument radius: number 1e39 is out of range (not a finite 32-bit float)" },
    Case { name: "non-finite number in an array", rib: "Color [1 -1e40 0]", error: "test.rib:1:10: Color: argument color: number -1e40 is out of range (not a finite 32-bit float)" },
    Case { name: "NaN written as a word", rib: "Rotate NaN 0 1 0", error: "test.rib:1:8: Rotate: argument angle: expected a number, got \"NaN\": RIB numbers are finite (NaN and infinity cannot be written)" },
    Case { name: "infinity written as a word", rib: "Translate 0 Infinity 0", error: "test.rib:1:13: Translate: argument dy: expected a number, got \"Infinity\": RIB numbers are finite (NaN and infinity cannot be written)" },
    Case { name: "octal escape above 255", rib: "Display \"a\\400\" \"file\" \"rgb\"", error: "test.rib:1:11: Display: argument name: octal escape \\400 is above \\377" },
    Case { name: "control byte", rib: "WorldBegin\n\u{1}", error: "test.rib:2:1: unexpected control byte 0x01" },
    Case { name: "stray closing bracket", rib: "]", error: "test.rib:1:1: expected a request name, got ']'" },
    Case { name: "number outside a request", rib: "# c\n 42 WorldBegin", error: "test.rib:2:2: expected a request name, got the number 42" },
    Case { name: "unterminated array", rib: "PointsPolygons [3 [0 1 2]", error: "test.rib:1:19: PointsPolygons: argument nvertices: arrays cannot nest" },
    Case { name: "unterminated array at end", rib: "Color [1 0", error: "test.rib:1:7: Color: argument color: unterminated array: '[' without ']'" },
    Case { name: "non-finite number in a parameter", rib: "Surface \"plastic\" \"Kd\" [1e39]", error: "test.rib:1:25: Surface: parameter \"Kd\" (uniform float): number 1e39 is out of range (not a finite 32-bit float)" },
    Case { name: "malformed number in a parameter array", rib: "PointsPolygons [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0.0.0]", error: "test.rib:1:49: PointsPolygons: parameter \"P\" (vertex point): malformed number \"0.0.0\"" },
    Case { name: "malformed number after a parameter", rib: "Surface \"plastic\" \"Kd\" 1 2x", error: "test.rib:1:26: malformed number \"2x\"" },
    Case { name: "nested array", rib: "Color [[1 0 0]]", error: "test.rib:1:8: Color: argument color: arrays cannot nest" },
    // Signatures: arity.
    Case { name: "missing argument", rib: "Sphere 1 -1 1\nWorldEnd", error: "test.rib:1:1: Sphere: missing argument thetamax (a number) in Sphere radius zmin zmax thetamax ..." },
    Case { name: "missing all arguments", rib: "Translate", error: "test.rib:1:1: Translate: missing argument dx (a number) in Translate dx dy dz" },
    Case { name: "extra argument", rib: "Translate 1 2 3 4", error: "test.rib:1:17: Translate: too many arguments: the number 4 after dz (Translate dx dy dz)" },
    Case { name: "parameter list where none is taken", rib: "Translate 1 2 3 \"Kd\" 1", error: "test.rib:1:17: Translate: takes no parameter list, got the string \"Kd\" (Translate dx dy dz)" },
    Case { name: "extra number before parameters", rib: "Sphere 1 -1 1 360 5 \"Kd\" 1", error: "test.rib:1:19: Sphere: too many arguments: the number 5 after thetamax (Sphere radius zmin zmax thetamax ...)" },
    Case { name: "matrix too short", rib: "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0]", error: "test.rib:1:17: ConcatTransform: argument transform: expected 16 numbers, got 12" },
    Case { name: "bare matrix too short", rib: "Transform 1 0 0 0\nWorldBegin", error: "test.rib:2:1: Transform: argument transform: expected 16 numbers, got 4 then the request name WorldBegin" },
    Case { name: "colour of four", rib: "Color [1 0 0 1]", error: "test.rib:1:7: Color: argument color: expected 3 numbers, got 4" },
    Case { name: "bound of five", rib: "Bound [0 1 0 1 0]", error: "test.rib:1:7: Bound: argument bound: expected 6 numbers, got 5" },
    Case { name: "array form of the wrong size", rib: "ScreenWindow [-1 1 -1]", error: "test.rib:1:14: ScreenWindow: expected an array of 4 numbers, got 3" },
    Case { name: "basis matrix short", rib: "Basis [1 0 0 0] 3 \"bezier\" 3", error: "test.rib:1:7: Basis: argument ubasis: expected 16 numbers, got 4" },
    Case { name: "optional group half present", rib: "DepthOfField 2.8 1", error: "test.rib:1:1: DepthOfField: missing argument focaldistance (a number) in DepthOfField [fstop focallength focaldistance]" },
    // Signatures: types.
    Case { name: "string for a number", rib: "Translate \"x\" 0 0", error: "test.rib:1:11: Translate: argument dx: expected a number, got the string \"x\"" },
    Case { name: "float for an integer", rib: "Format 640.5 480 1", error: "test.rib:1:8: Format: argument xresolution: expected an integer, got 640.5" },
    Case { name: "integer out of range", rib: "Sides 3000000000", error: "test.rib:1:7: Sides: argument nsides: integer 3000000000 is out of range" },
    Case { name: "number for a string", rib: "Surface 3", error: "test.rib:1:9: Surface: argument name: expected a string, got the number 3" },
    Case { name: "array for a number", rib: "Sphere [1] -1 1 360", error: "test.rib:1:8: Sphere: argument radius: expected a number, got '['" },
    Case { name: "bare number for an array", rib: "PointsPolygons 3 [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]", error: "test.rib:1:16: PointsPolygons: argument nvertices: expected an array of integers, got the number 3" },
    Case { name: "float in an integer array", rib: "PointsPolygons [3] [0 1.5 2] \"P\" [0 0 0 1 0 0 1 1 0]", error: "test.rib:1:23: PointsPolygons: argument vertices: expected an integer, got 1.5" },
    Case { name: "string in a number array", rib: "ColorSamples [1 \"x\"] [1]", error: "test.rib:1:17: ColorSamples: argument nRGB: expected numbers, got a string" },
    Case { name: "number in a string array", rib: "Procedural \"RunProgram\" [\"a\" 2] [0 1 0 1 0 1]", error: "test.rib:1:30: Procedural: argument args: expected strings, got the number 2" },
    Case { name: "bad handle", rib: "LightSource \"spotlight\" 1.5", error: "test.rib:1:25: LightSource: argument handle: expected an integer, got 1.5" },
    Case { name: "ColorSamples sizes", rib: "ColorSamples [1 0] [1 0]", error: "test.rib:1:1: ColorSamples: nRGB and RGBn must both hold 3*N numbers (N >= 1), got 2 and 2" },
    // Parameters.
    Case { name: "parameter without value", rib: "Surface \"plastic\" \"Kd\"\nWorldEnd", error: "test.rib:2:1: Surface: parameter \"Kd\" (uniform float): expected a value, got the request name WorldEnd" },
    Case { name: "parameter without value at end", rib: "Surface \"plastic\" \"Kd\"", error: "test.rib:1:23: Surface: parameter \"Kd\" (uniform float): expected a value, got the end of the input" },
    Case { name: "number where a parameter name belongs", rib: "Surface \"plastic\" \"Kd\" 1 2", error: "test.rib:1:26: Surface: expected a parameter name (a string), got the number 2" },
    Case { name: "string for a float parameter", rib: "Surface \"plastic\" \"Kd\" \"high\"", error: "test.rib:1:24: Surface: parameter \"Kd\" (uniform float): expected numbers, got the string \"high\"" },
    Case { name: "numbers for a string parameter", rib: "Surface \"paintedplastic\" \"texturename\" [1 2]", error: "test.rib:1:41: Surface: parameter \"texturename\" (uniform string): expected strings, got the number 1" },
    Case { name: "float for an integer parameter", rib: "Option \"statistics\" \"endofframe\" [1.5]", error: "test.rib:1:35: Option: parameter \"endofframe\" (uniform integer): expected an integer, got 1.5" },
    Case { name: "point parameter not a multiple of 3", rib: "Polygon \"P\" [0 0 0 1 0]", error: "test.rib:1:13: Polygon: parameter \"P\" (vertex point): expected a multiple of 3 values, got 5" },
    Case { name: "constant parameter with two values", rib: "Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0] \"constantwidth\" [1 2]", error: "test.rib:1:69: Curves: parameter \"constantwidth\" (constant float): expected 1 value, got 2" },
    Case { name: "inline declaration without name", rib: "Surface \"s\" \"uniform float\" 1", error: "test.rib:1:13: Surface: parameter \"uniform float\": bad inline declaration: no name after the declaration" },
    Case { name: "inline declaration with bad array size", rib: "Surface \"s\" \"float[0] v\" 1", error: "test.rib:1:13: Surface: parameter \"float[0] v\": bad inline declaration: array size must be a positive integer, got \"0\"" },
    Case { name: "inline array size not a multiple", rib: "Surface \"s\" \"float[2] v\" [1 2 3]", error: "test.rib:1:26: Surface: parameter \"v\" (uniform float[2]): expected a multiple of 2 values, got 3" },
    Case { name: "Declare with unknown type", rib: "Declare \"foo\" \"colour\"", error: "test.rib:1:1: Declare: bad declaration \"colour\" for \"foo\": unknown type \"colour\"" },
    Case { name: "Declare with a name of two words", rib: "Declare \"my var\" \"float\"", error: "test.rib:1:1: Declare: bad name \"my var\": one word expected" },
    Case { name: "string array in a float parameter", rib: "Attribute \"user\" \"float f\" [\"a\"]", error: "test.rib:1:29: Attribute: parameter \"f\" (uniform float): expected numbers, got a string" },
];

/// Cases of the binary encoding, as bytes (each `\xNN` is one raw byte).
#[rustfmt::skip]
const BINARY: &[(&str, &[u8], &str)] = &[
    ("binary: reserved code", b"version 3.03\n\xa7 WorldBegin", "test.rib:2:1: reserved binary RIB code 0247 (byte 0xa7); the rest of the source is not read"),
    ("binary: undefined request code", b"WorldBegin \xa6\x07", "test.rib:1:12: binary request code 7 is not defined"),
    ("binary: undefined string token", b"Surface \xcf\x01", "test.rib:1:9: Surface: argument name: binary string token 1 is not defined"),
    ("binary: truncated integer", b"Sides \x81", "test.rib:1:7: Sides: argument nsides: truncated binary token"),
    ("binary: truncated string", b"Surface \xa0\x20abc", "test.rib:1:9: Surface: argument name: truncated binary token"),
    ("binary: float array for integers", b"PointsPolygons \xc8\x00 [] \"P\" []", "test.rib:1:16: PointsPolygons: argument nvertices: expected integers, got a binary float array"),
    ("binary: non-finite float", b"Sphere \xa4\x7f\x80\x00\x00 -1 1 360", "test.rib:1:8: Sphere: argument radius: binary float is not a finite 32-bit float"),
    ("binary: string for a number", b"Translate \x91x 0 0", "test.rib:1:11: Translate: argument dx: expected a number, got the string \"x\""),
];

#[test]
fn each_binary_case_gives_its_exact_message() {
    let mut wrong = Vec::new();
    for &(name, rib, error) in BINARY {
        let got = first_error_bytes(rib);
        assert!(!got.contains('\n'), "{name}: not one line: {got}");
        if got != error {
            wrong.push(format!("{name}: expected\n  {error}\ngot\n  {got}"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn each_case_gives_its_exact_message() {
    assert!(CASES.len() + BINARY.len() >= 30);
    let mut wrong = Vec::new();
    for c in CASES {
        let got = first_error(c.rib);
        assert!(!got.contains('\n'), "{}: not one line: {got}", c.name);
        assert!(got.starts_with(&format!("{FILE}:")), "{}: no file: {got}", c.name);
        if got != c.error {
            wrong.push(format!("{}: expected\n  {}\ngot\n  {}", c.name, c.error, got));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn catalogue_snapshot() {
    let text: String = CASES
        .iter()
        .map(|c| format!("{}\n  {:?}\n  {}\n", c.name, c.rib, first_error(c.rib)))
        .chain(BINARY.iter().map(|&(name, rib, _)| {
            format!("{name}\n  {:?}\n  {}\n", String::from_utf8_lossy(rib), first_error_bytes(rib))
        }))
        .collect();
    insta::assert_snapshot!("catalogue", text);
}
