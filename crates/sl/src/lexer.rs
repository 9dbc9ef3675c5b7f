//! The lexer: one file's bytes to tokens with 1-based line:column positions.
//!
//! Backslash-newline is spliced away before anything else (C translation phase 2), comments
//! become whitespace, and each token records whether it starts a logical line (where a `#`
//! introduces a directive) and whether whitespace came before it (for `#` stringizing).
//! Lexical errors become [`Tok::Bad`] tokens: the preprocessor reports one only if the token is
//! used, so text inside `#if 0` may hold anything but an unterminated comment.

use crate::error::Pos;

/// Punctuators of RSL, plus those the preprocessor's `#if` expressions need.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(missing_docs)]
pub enum P {
    LParen,
    RParen,
    LBrace,
    RBrace,
    LBracket,
    RBracket,
    Semi,
    Comma,
    Dot,
    Question,
    Colon,
    Assign,
    AddAssign,
    SubAssign,
    MulAssign,
    DivAssign,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    AndAnd,
    OrOr,
    Not,
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    Hash,
    HashHash,
    Amp,
    Pipe,
    Tilde,
    Percent,
    Shl,
    Shr,
    PlusPlus,
    MinusMinus,
}

impl P {
    /// The punctuator as written.
    pub fn as_str(self) -> &'static str {
        use P::*;
        match self {
            LParen => "(",
            RParen => ")",
            LBrace => "{",
            RBrace => "}",
            LBracket => "[",
            RBracket => "]",
            Semi => ";",
            Comma => ",",
            Dot => ".",
            Question => "?",
            Colon => ":",
            Assign => "=",
            AddAssign => "+=",
            SubAssign => "-=",
            MulAssign => "*=",
            DivAssign => "/=",
            Eq => "==",
            Ne => "!=",
            Lt => "<",
            Le => "<=",
            Gt => ">",
            Ge => ">=",
            AndAnd => "&&",
            OrOr => "||",
            Not => "!",
            Plus => "+",
            Minus => "-",
            Star => "*",
            Slash => "/",
            Caret => "^",
            Hash => "#",
            HashHash => "##",
            Amp => "&",
            Pipe => "|",
            Tilde => "~",
            Percent => "%",
            Shl => "<<",
            Shr => ">>",
            PlusPlus => "++",
            MinusMinus => "--",
        }
    }
}

/// What a token is.
#[derive(Debug, Clone, PartialEq)]
pub enum Tok {
    /// A name (keywords are names here; the parser tells them apart).
    Ident(String),
    /// A number: its value and its spelling.
    Num(f64, String),
    /// A string literal, escapes resolved.
    Str(String),
    /// A punctuator.
    Punct(P),
    /// A lexical error, reported if the token is used.
    Bad(String),
}

impl Tok {
    /// The token as it would be written in source.
    pub fn spelling(&self) -> String {
        match self {
            Tok::Ident(s) => s.clone(),
            Tok::Num(_, s) => s.clone(),
            Tok::Str(s) => quote(s),
            Tok::Punct(p) => p.as_str().to_string(),
            Tok::Bad(_) => String::new(),
        }
    }

    /// How "unexpected ..." messages name this token: `"x"`, `2`, `"a"` (a string), `'('`.
    pub fn shown(&self) -> String {
        match self {
            Tok::Ident(s) => format!("\"{s}\""),
            Tok::Num(_, s) => s.clone(),
            Tok::Str(s) => format!("string {}", quote(s)),
            Tok::Punct(p) => format!("'{}'", p.as_str()),
            Tok::Bad(m) => m.clone(),
        }
    }

    /// How messages name this token: `'('`, `the name "x"`, `the number 1.5`, `the string "a"`.
    pub fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("\"{s}\""),
            Tok::Num(_, s) => format!("the number {s}"),
            Tok::Str(s) => format!("the string {}", quote(s)),
            Tok::Punct(p) => format!("'{}'", p.as_str()),
            Tok::Bad(m) => m.clone(),
        }
    }
}

/// A string as a literal, with escapes.
pub fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A token and where it was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where (for tokens out of a macro: where the macro was used).
    pub pos: Pos,
    /// First token of a logical line.
    pub line_start: bool,
    /// Whitespace (or a comment) before it.
    pub space_before: bool,
}

/// The bytes of a file with splices removed, each with its physical position.
struct Chars {
    bytes: Vec<(u8, u32, u32)>,
    end: (u32, u32),
}

fn splice(text: &[u8]) -> Chars {
    let mut bytes = Vec::with_capacity(text.len());
    let (mut line, mut col) = (1u32, 1u32);
    let mut i = 0;
    while i < text.len() {
        let b = text[i];
        if b == b'\\' {
            // Backslash, optional carriage return, newline: a splice.
            let mut j = i + 1;
            if j < text.len() && text[j] == b'\r' {
                j += 1;
            }
            if j < text.len() && text[j] == b'\n' {
                i = j + 1;
                line += 1;
                col = 1;
                continue;
            }
        }
        bytes.push((b, line, col));
        if b == b'\n' {
            line += 1;
            col = 1;
        } else {
            col += 1;
        }
        i += 1;
    }
    Chars { bytes, end: (line, col) }
}

/// Tokens of one file (`file` is its index for positions).
pub fn lex(text: &[u8], file: u32) -> Vec<Token> {
    // A UTF-8 byte-order mark is not part of the source.
    let text = text.strip_prefix(b"\xef\xbb\xbf").unwrap_or(text);
    let chars = splice(text);
    let c = &chars.bytes;
    let at = |i: usize| c.get(i).map(|x| x.0).unwrap_or(0);
    let pos_of = |i: usize| match c.get(i) {
        Some(&(_, line, col)) => Pos { file, line, col },
        None => Pos { file, line: chars.end.0, col: chars.end.1 },
    };
    let mut out = Vec::new();
    let mut i = 0;
    let mut line_start = true;
    let mut space = false;
    while i < c.len() {
        let b = c[i].0;
        match b {
            b'\n' => {
                line_start = true;
                space = true;
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' | 0x0b | 0x0c => {
                space = true;
                i += 1;
                continue;
            }
            b'/' if at(i + 1) == b'/' => {
                while i < c.len() && c[i].0 != b'\n' {
                    i += 1;
                }
                space = true;
                continue;
            }
            b'/' if at(i + 1) == b'*' => {
                let start = i;
                i += 2;
                loop {
                    if i >= c.len() {
                        out.push(Token {
                            tok: Tok::Bad("unterminated comment: '/*' without '*/'".into()),
                            pos: pos_of(start),
                            line_start,
                            space_before: space,
                        });
                        return out;
                    }
                    if c[i].0 == b'*' && at(i + 1) == b'/' {
                        i += 2;
                        break;
                    }
                    i += 1;
                }
                space = true;
                continue;
            }
            _ => {}
        }
        let start = i;
        let pos = pos_of(start);
        let tok = if b.is_ascii_alphabetic() || b == b'_' {
            while at(i).is_ascii_alphanumeric() || at(i) == b'_' {
                i += 1;
            }
            Tok::Ident(c[start..i].iter().map(|x| x.0 as char).collect())
        } else if b.is_ascii_digit() || (b == b'.' && at(i + 1).is_ascii_digit()) {
            lex_number(c, &mut i)
        } else if b == b'"' {
            lex_string(c, &mut i)
        } else if let Some((p, n)) = punct(b, at(i + 1)) {
            i += n;
            Tok::Punct(p)
        } else {
            // One character, whole if UTF-8.
            let len = utf8_len(b);
            let bytes: Vec<u8> = c[i..(i + len).min(c.len())].iter().map(|x| x.0).collect();
            i += len.max(1);
            let shown = match std::str::from_utf8(&bytes) {
                Ok(s) if !s.chars().any(char::is_control) => format!("character '{s}'"),
                _ if b < 0x20 || b == 0x7f => format!("control byte 0x{b:02x}"),
                _ => format!("byte 0x{b:02x}"),
            };
            Tok::Bad(format!("unexpected {shown}"))
        };
        out.push(Token { tok, pos, line_start, space_before: space });
        line_start = false;
        space = false;
    }
    out
}

fn utf8_len(b: u8) -> usize {
    match b {
        0xc0..=0xdf => 2,
        0xe0..=0xef => 3,
        0xf0..=0xf7 => 4,
        _ => 1,
    }
}

fn punct(a: u8, b: u8) -> Option<(P, usize)> {
    use P::*;
    let two = match (a, b) {
        (b'+', b'=') => Some(AddAssign),
        (b'-', b'=') => Some(SubAssign),
        (b'*', b'=') => Some(MulAssign),
        (b'/', b'=') => Some(DivAssign),
        (b'=', b'=') => Some(Eq),
        (b'!', b'=') => Some(Ne),
        (b'<', b'=') => Some(Le),
        (b'>', b'=') => Some(Ge),
        (b'&', b'&') => Some(AndAnd),
        (b'|', b'|') => Some(OrOr),
        (b'#', b'#') => Some(HashHash),
        (b'<', b'<') => Some(Shl),
        (b'>', b'>') => Some(Shr),
        (b'+', b'+') => Some(PlusPlus),
        (b'-', b'-') => Some(MinusMinus),
        _ => None,
    };
    if let Some(p) = two {
        return Some((p, 2));
    }
    let one = match a {
        b'(' => LParen,
        b')' => RParen,
        b'{' => LBrace,
        b'}' => RBrace,
        b'[' => LBracket,
        b']' => RBracket,
        b';' => Semi,
        b',' => Comma,
        b'.' => Dot,
        b'?' => Question,
        b':' => Colon,
        b'=' => Assign,
        b'<' => Lt,
        b'>' => Gt,
        b'!' => Not,
        b'+' => Plus,
        b'-' => Minus,
        b'*' => Star,
        b'/' => Slash,
        b'^' => Caret,
        b'#' => Hash,
        b'&' => Amp,
        b'|' => Pipe,
        b'~' => Tilde,
        b'%' => Percent,
        _ => return None,
    };
    Some((one, 1))
}

fn lex_number(c: &[(u8, u32, u32)], i: &mut usize) -> Tok {
    let at = |k: usize| c.get(k).map(|x| x.0).unwrap_or(0);
    let start = *i;
    let mut ok = true;
    while at(*i).is_ascii_digit() {
        *i += 1;
    }
    if at(*i) == b'.' {
        *i += 1;
        while at(*i).is_ascii_digit() {
            *i += 1;
        }
    }
    if at(*i) == b'e' || at(*i) == b'E' {
        let save = *i;
        *i += 1;
        if at(*i) == b'+' || at(*i) == b'-' {
            *i += 1;
        }
        if at(*i).is_ascii_digit() {
            while at(*i).is_ascii_digit() {
                *i += 1;
            }
        } else {
            // "1e" or "1e+": malformed, unless the letter starts a name (never in RSL).
            ok = false;
            *i = save + 1;
        }
    }
    // C's float suffix (1.0f), which Aqsis's compiler accepts and public shaders write.
    if (at(*i) == b'f' || at(*i) == b'F')
        && !(at(*i + 1).is_ascii_alphanumeric() || at(*i + 1) == b'_')
    {
        let text: String = c[start..*i].iter().map(|x| x.0 as char).collect();
        *i += 1;
        return match text.parse::<f64>() {
            Ok(v) if ok && v.is_finite() && (v as f32).is_finite() => Tok::Num(v, text),
            _ => Tok::Bad(format!("malformed number \"{text}f\"")),
        };
    }
    // A number runs into letters, digits, periods: "1x", "1.2.3" are one malformed number.
    while at(*i).is_ascii_alphanumeric() || at(*i) == b'_' || at(*i) == b'.' {
        ok = false;
        *i += 1;
    }
    let text: String = c[start..*i].iter().map(|x| x.0 as char).collect();
    if !ok {
        return Tok::Bad(format!("malformed number \"{text}\""));
    }
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && (v == 0.0 || (v as f32).is_finite()) => Tok::Num(v, text),
        _ => Tok::Bad(format!("number {text} is out of range (not a finite 32-bit float)")),
    }
}

fn lex_string(c: &[(u8, u32, u32)], i: &mut usize) -> Tok {
    let at = |k: usize| c.get(k).map(|x| x.0);
    *i += 1;
    let mut bytes = Vec::new();
    loop {
        match at(*i) {
            None | Some(b'\n') => return Tok::Bad("unterminated string".into()),
            Some(b'"') => {
                *i += 1;
                break;
            }
            Some(b'\\') => {
                *i += 1;
                let e = at(*i);
                *i += 1;
                let v = match e {
                    Some(b'n') => b'\n',
                    Some(b't') => b'\t',
                    Some(b'r') => b'\r',
                    Some(b'b') => 8,
                    Some(b'f') => 12,
                    Some(b'v') => 11,
                    Some(b'a') => 7,
                    Some(b'\\') => b'\\',
                    Some(b'"') => b'"',
                    Some(b'\'') => b'\'',
                    Some(d @ b'0'..=b'7') => {
                        let mut v = u32::from(d - b'0');
                        for _ in 0..2 {
                            match at(*i) {
                                Some(d @ b'0'..=b'7') => {
                                    v = v * 8 + u32::from(d - b'0');
                                    *i += 1;
                                }
                                _ => break,
                            }
                        }
                        if v > 255 {
                            return Tok::Bad(format!("octal escape \\{v:o} is above \\377"));
                        }
                        v as u8
                    }
                    None | Some(b'\n') => return Tok::Bad("unterminated string".into()),
                    Some(other) => {
                        return Tok::Bad(format!(
                            "unknown escape \\{} in a string",
                            if other.is_ascii_graphic() {
                                (other as char).to_string()
                            } else {
                                format!("x{other:02x}")
                            }
                        ));
                    }
                };
                bytes.push(v);
            }
            Some(b) => {
                bytes.push(b);
                *i += 1;
            }
        }
    }
    Tok::Str(String::from_utf8_lossy(&bytes).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok> {
        lex(s.as_bytes(), 0).into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn numbers_names_strings_puncts() {
        assert_eq!(
            toks("a1 _b 1 .5 2. 1e3 1.5e-2 \"x\\ty\" += ^ . ##"),
            vec![
                Tok::Ident("a1".into()),
                Tok::Ident("_b".into()),
                Tok::Num(1.0, "1".into()),
                Tok::Num(0.5, ".5".into()),
                Tok::Num(2.0, "2.".into()),
                Tok::Num(1000.0, "1e3".into()),
                Tok::Num(0.015, "1.5e-2".into()),
                Tok::Str("x\ty".into()),
                Tok::Punct(P::AddAssign),
                Tok::Punct(P::Caret),
                Tok::Punct(P::Dot),
                Tok::Punct(P::HashHash),
            ]
        );
    }

    #[test]
    fn dot_product_is_not_a_number() {
        assert_eq!(
            toks("N.I"),
            vec![Tok::Ident("N".into()), Tok::Punct(P::Dot), Tok::Ident("I".into())]
        );
    }

    #[test]
    fn positions_splices_and_line_starts() {
        let t = lex(b"a /* x\n y */ b\n  c \\\n d\n\"s\\\nt\"", 3);
        let got: Vec<(u32, u32, bool)> =
            t.iter().map(|t| (t.pos.line, t.pos.col, t.line_start)).collect();
        assert_eq!(
            got,
            vec![(1, 1, true), (2, 7, false), (3, 3, true), (4, 2, false), (5, 1, true)]
        );
        assert_eq!(t[4].tok, Tok::Str("st".into()));
        assert_eq!(t[0].pos.file, 3);
    }

    #[test]
    fn byte_order_mark_is_skipped() {
        let t = lex(b"\xef\xbb\xbfa", 0);
        assert_eq!((t[0].tok.clone(), t[0].pos.col), (Tok::Ident("a".into()), 1));
    }

    #[test]
    fn errors_are_tokens() {
        assert_eq!(toks("1x"), vec![Tok::Bad("malformed number \"1x\"".into())]);
        assert_eq!(toks("1.5f"), vec![Tok::Num(1.5, "1.5".into())]);
        assert_eq!(toks("1fx"), vec![Tok::Bad("malformed number \"1fx\"".into())]);
        assert_eq!(toks("1.2.3"), vec![Tok::Bad("malformed number \"1.2.3\"".into())]);
        assert_eq!(toks("1e"), vec![Tok::Bad("malformed number \"1e\"".into())]);
        assert_eq!(toks("\"ab"), vec![Tok::Bad("unterminated string".into())]);
        assert_eq!(toks("@"), vec![Tok::Bad("unexpected character '@'".into())]);
        assert_eq!(toks("/* x"), vec![Tok::Bad("unterminated comment: '/*' without '*/'".into())]);
        assert_eq!(
            toks("1e39"),
            vec![Tok::Bad("number 1e39 is out of range (not a finite 32-bit float)".into())]
        );
    }
}
