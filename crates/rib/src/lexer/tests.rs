//! Unit tests of the lexer: every token kind, escape and number form, positions, recovery.

use super::*;

fn lex(text: &str) -> Vec<Tok> {
    let mut l = Lexer::new(Box::new(io::Cursor::new(text.as_bytes().to_vec())), false);
    let mut out = Vec::new();
    loop {
        match l.next() {
            Ok((_, Tok::Eof)) => return out,
            Ok((_, t)) => out.push(t),
            Err(e) => panic!("{text:?}: {e:?}"),
        }
    }
}

fn lex_err(text: &str) -> (Pos, String) {
    let mut l = Lexer::new(Box::new(io::Cursor::new(text.as_bytes().to_vec())), false);
    loop {
        match l.next() {
            Ok((_, Tok::Eof)) => panic!("{text:?}: no error"),
            Ok(_) => {}
            Err(LexError::Syntax(p, m)) => return (p, m),
            Err(e) => return (Pos::default(), format!("{e:?}")),
        }
    }
}

fn num(text: &str) -> Num {
    parse_number(text.as_bytes()).unwrap_or_else(|e| panic!("{text}: {e:?}"))
}

fn s(text: &str) -> String {
    match lex(text).as_slice() {
        [Tok::Str(s)] => s.clone(),
        other => panic!("{other:?}"),
    }
}

#[test]
fn integers() {
    assert_eq!(num("0"), Num { f: 0.0, i: Some(0), int_form: true });
    assert_eq!(num("42"), Num { f: 42.0, i: Some(42), int_form: true });
    assert_eq!(num("-7"), Num { f: -7.0, i: Some(-7), int_form: true });
    assert_eq!(num("+7").i, Some(7));
    assert_eq!(num("2147483647").i, Some(i32::MAX));
    assert_eq!(num("-2147483648").i, Some(i32::MIN));
    assert_eq!(num("2147483648").i, None);
    assert_eq!(num("2147483648").f, 2147483648.0);
    assert_eq!(num("123456789012345678901234567890").i, None);
    assert!(num("123456789012345678901234567890").int_form);
}

#[test]
fn float_forms() {
    for (t, v) in [
        ("1.5", 1.5f32),
        ("-1.5", -1.5),
        (".5", 0.5),
        ("-.5", -0.5),
        ("+.5", 0.5),
        ("5.", 5.0),
        ("1e-3", 1e-3),
        ("1E3", 1e3),
        ("1e+3", 1e3),
        ("2.5e2", 250.0),
        ("0.1", 0.1),
        ("0.300", 0.3),
        ("60.235", 60.235),
        ("3.14159265358979", std::f32::consts::PI),
        ("1e-45", 1e-45),
        ("1e-50", 0.0),
        ("3.4028234e38", f32::MAX),
        ("0.000000000000000000000000000001", 1e-30),
    ] {
        let n = num(t);
        assert_eq!(n.f, v, "{t}");
        assert_eq!(n.i, None, "{t}");
    }
}

#[test]
fn floats_are_correctly_rounded() {
    // Against core's parser on a spread of forms, fast and slow paths alike.
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for _ in 0..20_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let mant = x % 100_000_000_000;
        let digits = (x >> 40) % 12;
        let exp = ((x >> 50) % 40) as i32 - 20;
        let text = format!(
            "{}.{:0w$}e{exp}",
            mant / 10u64.pow(digits as u32),
            mant % 10u64.pow(digits as u32),
            w = digits as usize
        );
        let want: f32 = text.parse().unwrap();
        assert_eq!(num(&text).f, want, "{text}");
    }
}

#[test]
fn malformed_numbers() {
    for t in ["-", "+", ".", "1e", "1e+", "1.2.3", "1-2", "--1", "1x", "e5", ".e5", "1e5.0"] {
        assert_eq!(parse_number(t.as_bytes()), Err(NumError::Malformed), "{t}");
    }
    assert_eq!(parse_number(b"1e39"), Err(NumError::OutOfRange));
    assert_eq!(parse_number(b"-1e39"), Err(NumError::OutOfRange));
    assert_eq!(parse_number(b"1e100000000"), Err(NumError::OutOfRange));
}

#[test]
fn token_kinds() {
    assert_eq!(
        lex("Sphere 1 [ 2.5 \"a\" ] Frob"),
        vec![
            Tok::Request(RequestKind::Sphere),
            Tok::Num(num("1")),
            Tok::Open,
            Tok::Num(num("2.5")),
            Tok::Str("a".into()),
            Tok::Close,
            Tok::Unknown("Frob".into()),
        ]
    );
    assert_eq!(lex("[1]"), vec![Tok::Open, Tok::Num(num("1")), Tok::Close]);
    assert_eq!(lex("version 3.03")[0], Tok::Request(RequestKind::Version));
    assert_eq!(lex(""), vec![]);
}

#[test]
fn comments_are_blank() {
    assert_eq!(lex("# only a comment"), vec![]);
    assert_eq!(lex("1 # c \"not a string\n2"), vec![Tok::Num(num("1")), Tok::Num(num("2"))]);
    assert_eq!(lex("1#c\n2"), vec![Tok::Num(num("1")), Tok::Num(num("2"))]);
    assert_eq!(lex("##RenderMan RIB\nWorldBegin"), vec![Tok::Request(RequestKind::WorldBegin)]);
}

#[test]
fn structure_comments_can_be_kept() {
    let mut l = Lexer::new(
        Box::new(io::Cursor::new(b"##RenderMan RIB\n# plain\n WorldBegin ##Shaders x".to_vec())),
        true,
    );
    while !matches!(l.next().unwrap().1, Tok::Eof) {}
    let kept = l.structure.unwrap();
    assert_eq!(
        kept,
        vec![
            (Pos { line: 1, col: 1 }, "RenderMan RIB".into()),
            (Pos { line: 3, col: 13 }, "Shaders x".into())
        ]
    );
}

#[test]
fn escapes() {
    assert_eq!(s(r#""a\nb""#), "a\nb");
    assert_eq!(s(r#""\r\t\b\f""#), "\r\t\u{8}\u{c}");
    assert_eq!(s(r#""\\ \"""#), "\\ \"");
    assert_eq!(s(r#""\101\0\12x""#), "A\0\nx");
    assert_eq!(s(r#""\1014""#), "A4");
    assert_eq!(s("\"ab\\\ncd\""), "abcd");
    assert_eq!(s("\"ab\\\r\ncd\""), "abcd");
    assert_eq!(s("\"raw\nnewline\""), "raw\nnewline");
    assert_eq!(s(r#""""#), "");
    assert_eq!(s("\"caf\u{e9}\""), "caf\u{e9}");
}

#[test]
fn unknown_escape_is_kept_with_a_warning() {
    let mut l = Lexer::new(Box::new(io::Cursor::new(br#""C:\q""#.to_vec())), false);
    assert_eq!(l.next().unwrap().1, Tok::Str("C:\\q".into()));
    assert_eq!(
        l.warnings,
        vec![(Pos { line: 1, col: 4 }, "unknown string escape \\q kept as written".into())]
    );
}

#[test]
fn positions_count_bytes_and_lines() {
    let mut l = Lexer::new(Box::new(io::Cursor::new(b"A\n\tB \"x\ny\" C".to_vec())), false);
    let mut at = Vec::new();
    loop {
        let (p, t) = l.next().unwrap();
        if t == Tok::Eof {
            break;
        }
        at.push((p.line, p.col));
    }
    assert_eq!(at, vec![(1, 1), (2, 2), (2, 4), (3, 4)]);
}

#[test]
fn lexical_errors() {
    assert_eq!(lex_err("\"abc"), (Pos { line: 1, col: 1 }, "unterminated string".into()));
    assert_eq!(lex_err("1 1.0f"), (Pos { line: 1, col: 3 }, "malformed number \"1.0f\"".into()));
    assert_eq!(
        lex_err("x \u{1}"),
        (Pos { line: 1, col: 3 }, "unexpected control byte 0x01".into())
    );
    assert_eq!(
        lex_err(r#""\400""#),
        (Pos { line: 1, col: 2 }, "octal escape \\400 is above \\377".into())
    );
    assert_eq!(
        lex_err("1e40"),
        (Pos { line: 1, col: 1 }, "number 1e40 is out of range (not a finite 32-bit float)".into())
    );
}

#[test]
fn binary_byte_is_reported() {
    // A reserved binary code (0247) cannot be skipped over: the source ends there.
    let mut l = Lexer::new(Box::new(io::Cursor::new(b"Sphere \xa7".to_vec())), false);
    l.next().unwrap();
    assert!(matches!(l.next(), Err(LexError::Binary(Pos { line: 1, col: 8 }, 0xa7))));
    // but not inside strings
    let mut l = Lexer::new(Box::new(io::Cursor::new(b"\"\xc3\xa9\"".to_vec())), false);
    assert_eq!(l.next().unwrap().1, Tok::Str("\u{e9}".into()));
}

#[test]
fn tokens_straddling_refills() {
    // A reader that hands out one byte at a time exercises every refill path.
    struct Trickle(Vec<u8>, usize);
    impl Read for Trickle {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            if self.1 >= self.0.len() || buf.is_empty() {
                return Ok(0);
            }
            buf[0] = self.0[self.1];
            self.1 += 1;
            Ok(1)
        }
    }
    let text = "Sphere -12.5e-1 \"a\\nb\" # c\n [1 2] ";
    let mut l = Lexer::new(Box::new(Trickle(text.as_bytes().to_vec(), 0)), false);
    let mut toks = Vec::new();
    loop {
        let (_, t) = l.next().unwrap();
        if t == Tok::Eof {
            break;
        }
        toks.push(t);
    }
    assert_eq!(toks, lex(text));
}

#[test]
fn long_arrays_cross_the_buffer() {
    let text: String = (0..50_000).map(|i| format!("{}.25 ", i)).collect();
    let mut l = Lexer::new(Box::new(io::Cursor::new(format!("[{text}]").into_bytes())), false);
    assert_eq!(l.next().unwrap().1, Tok::Open);
    let mut v = Vec::new();
    l.floats(Pos::default(), &mut v).unwrap();
    assert_eq!(v.len(), 50_000);
    assert_eq!(v[49_999], 49_999.25);
}

#[test]
fn untyped_arrays() {
    let any = |t: &str| {
        let mut l = Lexer::new(Box::new(io::Cursor::new(t.as_bytes().to_vec())), false);
        l.next().unwrap();
        l.any(Pos::default()).unwrap()
    };
    assert_eq!(any("[]"), AnyArray::Empty);
    assert_eq!(any("[1 2]"), AnyArray::Ints(vec![1, 2]));
    assert_eq!(any("[1 2.5 3]"), AnyArray::Floats(vec![1.0, 2.5, 3.0]));
    assert_eq!(any("[\"a\" \"b\"]"), AnyArray::Strings(vec!["a".into(), "b".into()]));
}
