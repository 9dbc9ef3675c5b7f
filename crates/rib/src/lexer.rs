//! Lexical stage: ASCII RIB bytes (Spec 3.2 Appendix C.2) to positioned tokens.
//!
//! Invariants: the input is read through one bounded buffer that grows only to hold the longest
//! single name or number (capped at [`MAX_TOKEN`]), so memory does not grow with the file; every
//! call that returns an error has consumed at least one byte or reached the end, so a caller
//! that keeps calling always terminates; numbers are converted without allocating.
//!
//! Rules implemented (Spec 3.2 Appendix C.2, "ASCII encoding"):
//! - whitespace is space, tab, CR, LF, VT and FF; `#` starts a comment to the end of the line
//!   (`##` structural comments are skipped too, or collected when asked);
//! - `[` and `]` are self-delimiting;
//! - a string is `"..."` with the escapes `\n \r \t \b \f \\ \"`, `\ddd` (one to three octal
//!   digits) and backslash-newline (a line continuation: both are dropped); raw newlines may
//!   appear inside; an unknown escape `\q` is kept as written, with a warning;
//! - a number is `[+-]? digits [. digits] [(e|E) [+-] digits]` with at least one mantissa digit
//!   (`1`, `-2`, `1e-3`, `.5`, `-.5`, `5.`); integers are the forms without `.` or exponent;
//! - anything else up to a delimiter (whitespace, `[`, `]`, `"`, `#`) is a name (a request);
//! - a byte with the top bit set outside a string starts an encoded token of the binary
//!   encoding (decoded in `binary.rs`); a reserved code is [`LexError::Binary`].

use std::collections::HashMap;
use std::io::{self, Read};

use crate::error::{Pos, quote};
use crate::signature::RequestKind;

mod binary;

/// Longest name or number accepted, in bytes (strings are not limited).
pub(crate) const MAX_TOKEN: usize = 1 << 16;

/// Size of the read buffer.
const CHUNK: usize = 1 << 16;

/// A number token: its `f32` value, and its `i32` value when it was written as an integer that
/// fits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Num {
    /// The value as a float (integers convert exactly up to 2^24, rounded beyond).
    pub(crate) f: f32,
    /// The value, if written without `.` or exponent and within `i32`.
    pub(crate) i: Option<i32>,
    /// True if written without `.` or exponent (even if out of `i32` range).
    pub(crate) int_form: bool,
}

/// A token.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Tok {
    /// A known request name.
    Request(RequestKind),
    /// A name that is no request of the table.
    Unknown(String),
    /// A string, escapes resolved.
    Str(String),
    /// A number.
    Num(Num),
    /// `[`
    Open,
    /// `]`
    Close,
    /// End of input.
    Eof,
}

impl Tok {
    /// A few words naming the token's kind, for messages.
    pub(crate) fn describe(&self) -> String {
        match self {
            Tok::Request(k) => format!("the request name {}", k.name()),
            Tok::Unknown(n) => format!("the name {}", quote(n)),
            Tok::Str(s) => format!("the string {}", quote(s)),
            Tok::Num(n) => format!("the number {}", n.f),
            Tok::Open => "'['".into(),
            Tok::Close => "']'".into(),
            Tok::Eof => "the end of the input".into(),
        }
    }
}

/// Why a token could not be read.
#[derive(Debug)]
pub(crate) enum LexError {
    /// Malformed text at `pos`.
    Syntax(Pos, String),
    /// A reserved binary code (Spec C.2 assigns no meaning to it): the source cannot go on.
    Binary(Pos, u8),
    /// The underlying reader failed.
    Io(io::Error),
}

impl From<io::Error> for LexError {
    fn from(e: io::Error) -> Self {
        LexError::Io(e)
    }
}

/// Why a typed array could not be read (after its `[`).
#[derive(Debug)]
pub(crate) enum ArrayError {
    /// A lexical error inside the array.
    Lex(LexError),
    /// A token that does not belong in this array, e.g. a string among numbers, or a number
    /// that is not an integer in an integer array.
    Unexpected(Pos, String),
}

impl From<LexError> for ArrayError {
    fn from(e: LexError) -> Self {
        ArrayError::Lex(e)
    }
}

impl From<io::Error> for ArrayError {
    fn from(e: io::Error) -> Self {
        ArrayError::Lex(LexError::Io(e))
    }
}

/// One item inside an array.
#[derive(Debug)]
enum Item {
    /// A number (ASCII or encoded).
    Num(Pos, Num),
    /// A string (ASCII or encoded).
    Str(Pos, String),
    /// `]`.
    Close,
    /// The end of input.
    Eof,
    /// Any other token.
    Other(Pos, Tok),
}

/// A binary float array (0310) being handed out as `[`, numbers, `]` to a caller that reads
/// token by token (the array readers take it whole).
#[derive(Debug)]
pub(crate) struct Pending {
    at: Pos,
    values: Vec<f32>,
    next: usize,
}

/// The values of an array read without a declared type (Spec: an array with any float is all
/// floats).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum AnyArray {
    /// `[]`
    Empty,
    /// Only integer literals within `i32`.
    Ints(Vec<i32>),
    /// Numbers, at least one not an `i32` literal.
    Floats(Vec<f32>),
    /// Strings.
    Strings(Vec<String>),
}

/// Byte classes: delimiters end names and numbers.
const fn delimiters() -> [bool; 256] {
    let mut t = [false; 256];
    let mut b = 0;
    while b < 256 {
        t[b] = matches!(
            b as u8,
            b' ' | b'\t' | b'\r' | b'\n' | 0x0b | 0x0c | b'[' | b']' | b'"' | b'#'
        ) || b >= 0x80
            || b < 0x20
            || b == 0x7f;
        b += 1;
    }
    t
}
static DELIM: [bool; 256] = delimiters();

fn is_number_start(b: u8) -> bool {
    b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.')
}

/// The RIB tokenizer over one source.
pub(crate) struct Lexer {
    read: Box<dyn Read>,
    buf: Vec<u8>,
    pos: usize,
    end: usize,
    eof: bool,
    line: u32,
    col: u32,
    /// Warnings not yet collected by the reader.
    pub(crate) warnings: Vec<(Pos, String)>,
    /// `##` comments (text after `##`), if they are kept.
    pub(crate) structure: Option<Vec<(Pos, String)>>,
    /// A binary float array being handed out token by token.
    pending: Option<Pending>,
    /// Binary RIB: request names bound to codes (0314).
    requests: Vec<Option<Tok>>,
    /// Binary RIB: strings bound to tokens (0315, 0316).
    strings: HashMap<u16, String>,
}

impl Lexer {
    /// A lexer over a plain (already decompressed) byte stream.
    pub(crate) fn new(read: Box<dyn Read>, keep_structure: bool) -> Lexer {
        Lexer {
            read,
            buf: vec![0; CHUNK],
            pos: 0,
            end: 0,
            eof: false,
            line: 1,
            col: 1,
            warnings: Vec::new(),
            structure: keep_structure.then(Vec::new),
            pending: None,
            requests: vec![None; 256],
            strings: HashMap::new(),
        }
    }

    /// Position of the next unread byte.
    pub(crate) fn here(&self) -> Pos {
        Pos { line: self.line, col: self.col }
    }

    /// Reads more input, keeping `buf[pos..end]`. Returns false at the end of input.
    #[cold]
    fn refill(&mut self) -> io::Result<bool> {
        if self.eof {
            return Ok(false);
        }
        if self.pos > 0 {
            self.buf.copy_within(self.pos..self.end, 0);
            self.end -= self.pos;
            self.pos = 0;
        }
        if self.end == self.buf.len() {
            let len = self.buf.len() * 2;
            self.buf.resize(len, 0);
        }
        loop {
            match self.read.read(&mut self.buf[self.end..]) {
                Ok(0) => {
                    self.eof = true;
                    return Ok(false);
                }
                Ok(n) => {
                    self.end += n;
                    return Ok(true);
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => {
                    // The stream is over: report once, then behave as at its end.
                    self.eof = true;
                    return Err(e);
                }
            }
        }
    }

    /// The next byte, without consuming it.
    #[inline]
    fn peek(&mut self) -> io::Result<Option<u8>> {
        if self.pos < self.end {
            return Ok(Some(self.buf[self.pos]));
        }
        if self.refill()? { Ok(Some(self.buf[self.pos])) } else { Ok(None) }
    }

    /// Consumes one byte known not to be a newline.
    #[inline]
    fn bump(&mut self) {
        self.pos += 1;
        self.col = self.col.saturating_add(1);
    }

    /// Skips whitespace and comments.
    #[inline]
    fn skip_blank(&mut self) -> io::Result<()> {
        loop {
            while self.pos < self.end {
                match self.buf[self.pos] {
                    b'\n' => {
                        self.line = self.line.saturating_add(1);
                        self.col = 1;
                    }
                    b' ' | b'\t' | b'\r' | 0x0b | 0x0c => self.col = self.col.saturating_add(1),
                    b'#' => {
                        self.comment()?;
                        continue;
                    }
                    _ => return Ok(()),
                }
                self.pos += 1;
            }
            if !self.refill()? {
                return Ok(());
            }
        }
    }

    /// Consumes a comment from its `#` up to (not including) the newline.
    #[cold]
    fn comment(&mut self) -> io::Result<()> {
        let at = self.here();
        self.bump();
        let structural = self.peek()? == Some(b'#');
        let mut text = Vec::new();
        if structural {
            self.bump();
        }
        let keep = structural && self.structure.is_some();
        loop {
            let start = self.pos;
            while self.pos < self.end && self.buf[self.pos] != b'\n' {
                self.pos += 1;
            }
            self.col = self.col.saturating_add((self.pos - start) as u32);
            if keep && text.len() < MAX_TOKEN {
                text.extend_from_slice(&self.buf[start..self.pos]);
            }
            if self.pos < self.end || !self.refill()? {
                break;
            }
        }
        if keep && let Some(list) = self.structure.as_mut() {
            list.push((at, String::from_utf8_lossy(&text).into_owned()));
        }
        Ok(())
    }

    /// Length of the run of non-delimiter bytes at `pos`, made contiguous in the buffer.
    fn run(&mut self) -> io::Result<usize> {
        let mut i = self.pos;
        loop {
            while i < self.end {
                if DELIM[self.buf[i] as usize] {
                    return Ok(i - self.pos);
                }
                i += 1;
            }
            let len = i - self.pos;
            if len >= MAX_TOKEN || !self.refill()? {
                return Ok(len);
            }
            i = self.pos + len;
        }
    }

    /// Consumes `len` bytes of a run (no newlines in it).
    fn take(&mut self, len: usize) {
        self.pos += len;
        self.col = self.col.saturating_add(len as u32);
    }

    /// The next token and where it starts.
    pub(crate) fn next(&mut self) -> Result<(Pos, Tok), LexError> {
        if let Some(p) = self.pending.as_mut() {
            let at = p.at;
            let tok = match p.values.get(p.next) {
                Some(&f) => {
                    p.next += 1;
                    Tok::Num(Num { f, i: None, int_form: false })
                }
                None => {
                    self.pending = None;
                    Tok::Close
                }
            };
            return Ok((at, tok));
        }
        loop {
            self.skip_blank()?;
            let at = self.here();
            let Some(b) = self.peek()? else { return Ok((at, Tok::Eof)) };
            let tok = match b {
                b'[' => {
                    self.bump();
                    Tok::Open
                }
                b']' => {
                    self.bump();
                    Tok::Close
                }
                b'"' => Tok::Str(self.string()?),
                b if is_number_start(b) => Tok::Num(self.number()?),
                b if b >= 0x80 => match self.binary(at)? {
                    Some(t) => t,
                    // A definition: no token; go on to the next.
                    None => continue,
                },
                b if DELIM[b as usize] => {
                    self.bump();
                    return Err(LexError::Syntax(at, format!("unexpected control byte 0x{b:02x}")));
                }
                _ => {
                    let len = self.run()?;
                    if len >= MAX_TOKEN {
                        self.take(len);
                        return Err(LexError::Syntax(
                            at,
                            format!("name longer than {MAX_TOKEN} bytes"),
                        ));
                    }
                    let name = &self.buf[self.pos..self.pos + len];
                    let tok = match RequestKind::from_name(name) {
                        Some(k) => Tok::Request(k),
                        None => Tok::Unknown(String::from_utf8_lossy(name).into_owned()),
                    };
                    self.take(len);
                    tok
                }
            };
            return Ok((at, tok));
        }
    }

    /// Reads a number at `pos`.
    #[inline]
    fn number(&mut self) -> Result<Num, LexError> {
        let at = self.here();
        let len = self.run()?;
        let text = &self.buf[self.pos..self.pos + len];
        let parsed = parse_number(text);
        let result = match parsed {
            Ok(n) => Ok(n),
            Err(NumError::Malformed) => Err(LexError::Syntax(
                at,
                format!("malformed number {}", quote(&String::from_utf8_lossy(text))),
            )),
            Err(NumError::OutOfRange) => Err(LexError::Syntax(
                at,
                format!(
                    "number {} is out of range (not a finite 32-bit float)",
                    String::from_utf8_lossy(text)
                ),
            )),
        };
        // Consume the run even on error so the caller makes progress.
        self.take(len.max(1));
        result
    }

    /// Reads a string from its opening quote; escapes resolved. Errors inside are reported at
    /// the closing quote's end, so the whole string is consumed either way.
    fn string(&mut self) -> Result<String, LexError> {
        let at = self.here();
        self.bump();
        let mut out: Vec<u8> = Vec::new();
        let mut error: Option<(Pos, String)> = None;
        loop {
            // Plain run.
            let start = self.pos;
            while self.pos < self.end && !matches!(self.buf[self.pos], b'"' | b'\\' | b'\n') {
                self.pos += 1;
            }
            out.extend_from_slice(&self.buf[start..self.pos]);
            self.col = self.col.saturating_add((self.pos - start) as u32);
            let Some(b) = self.peek()? else {
                return Err(LexError::Syntax(at, "unterminated string".into()));
            };
            match b {
                b'"' => {
                    self.bump();
                    break;
                }
                b'\n' => {
                    out.push(b'\n');
                    self.pos += 1;
                    self.line = self.line.saturating_add(1);
                    self.col = 1;
                }
                b'\\' => {
                    let esc_at = self.here();
                    self.bump();
                    let Some(e) = self.peek()? else {
                        return Err(LexError::Syntax(at, "unterminated string".into()));
                    };
                    match e {
                        b'n' | b'r' | b't' | b'b' | b'f' | b'\\' | b'"' => {
                            out.push(match e {
                                b'n' => b'\n',
                                b'r' => b'\r',
                                b't' => b'\t',
                                b'b' => 0x08,
                                b'f' => 0x0c,
                                other => other,
                            });
                            self.bump();
                        }
                        b'\n' => {
                            self.pos += 1;
                            self.line = self.line.saturating_add(1);
                            self.col = 1;
                        }
                        b'\r' => {
                            self.bump();
                            if self.peek()? == Some(b'\n') {
                                self.pos += 1;
                                self.line = self.line.saturating_add(1);
                                self.col = 1;
                            }
                        }
                        b'0'..=b'7' => {
                            let mut v: u32 = 0;
                            let mut n = 0;
                            while n < 3 {
                                match self.peek()? {
                                    Some(d @ b'0'..=b'7') => {
                                        v = v * 8 + u32::from(d - b'0');
                                        self.bump();
                                        n += 1;
                                    }
                                    _ => break,
                                }
                            }
                            if v > 0xff {
                                error.get_or_insert((
                                    esc_at,
                                    format!("octal escape \\{v:o} is above \\377"),
                                ));
                            } else {
                                out.push(v as u8);
                            }
                        }
                        other => {
                            // Kept as written: the backslash and the byte (the byte is consumed by
                            // the next plain run).
                            out.push(b'\\');
                            let shown = if other.is_ascii_graphic() {
                                format!("\\{}", other as char)
                            } else {
                                format!("\\ followed by byte 0x{other:02x}")
                            };
                            self.warnings.push((
                                esc_at,
                                format!("unknown string escape {shown} kept as written"),
                            ));
                        }
                    }
                }
                // The plain run stopped at the buffer's end: go on with the refilled bytes.
                _ => {}
            }
        }
        if let Some((pos, message)) = error {
            return Err(LexError::Syntax(pos, message));
        }
        Ok(self.utf8(at, out))
    }

    /// A string's bytes as UTF-8; invalid bytes are replaced, with a warning.
    fn utf8(&mut self, at: Pos, bytes: Vec<u8>) -> String {
        match String::from_utf8(bytes) {
            Ok(s) => s,
            Err(e) => {
                self.warnings.push((
                    at,
                    "string is not valid UTF-8; invalid bytes replaced by U+FFFD".into(),
                ));
                String::from_utf8_lossy(e.as_bytes()).into_owned()
            }
        }
    }

    /// The next item inside an array: a number, a string, `]`, the end of input, or any other
    /// token (binary tokens included).
    #[inline]
    fn item(&mut self) -> Result<Item, LexError> {
        loop {
            self.skip_blank()?;
            let at = self.here();
            return Ok(match self.peek()? {
                Some(b) if is_number_start(b) => Item::Num(at, self.number()?),
                Some(b']') => {
                    self.bump();
                    Item::Close
                }
                Some(b'"') => Item::Str(at, self.string()?),
                None => Item::Eof,
                Some(b) if b >= 0x80 => match self.binary(at)? {
                    Some(Tok::Num(n)) => Item::Num(at, n),
                    Some(Tok::Str(s)) => Item::Str(at, s),
                    Some(t) => Item::Other(at, t),
                    None => continue,
                },
                Some(_) => {
                    let (p, t) = self.next()?;
                    Item::Other(p, t)
                }
            });
        }
    }

    /// The error for an array item that does not belong, or for the end of input.
    fn bad_item(item: Item, open: Pos, want: &str) -> ArrayError {
        match item {
            Item::Eof => ArrayError::Lex(LexError::Syntax(
                open,
                "unterminated array: '[' without ']'".into(),
            )),
            Item::Str(at, _) => {
                ArrayError::Unexpected(at, format!("expected {want}, got a string"))
            }
            Item::Num(at, n) => {
                ArrayError::Unexpected(at, format!("expected {want}, got the number {}", n.f))
            }
            Item::Other(at, Tok::Open) => ArrayError::Unexpected(at, "arrays cannot nest".into()),
            Item::Other(at, t) => {
                ArrayError::Unexpected(at, format!("expected {want} or ']', got {}", t.describe()))
            }
            Item::Close => ArrayError::Unexpected(open, format!("expected {want}")),
        }
    }

    /// Reads the floats of an array whose `[` (at `open`) was consumed, through its `]`,
    /// appending to `out`. Integers convert to floats.
    pub(crate) fn floats(&mut self, open: Pos, out: &mut Vec<f32>) -> Result<(), ArrayError> {
        if let Some(p) = self.pending.take() {
            out.extend_from_slice(&p.values[p.next..]);
            return Ok(());
        }
        loop {
            match self.item()? {
                Item::Num(_, n) => out.push(n.f),
                Item::Close => return Ok(()),
                other => return Err(Self::bad_item(other, open, "numbers")),
            }
        }
    }

    /// Reads the integers of an array whose `[` was consumed, through its `]`.
    pub(crate) fn ints(&mut self, open: Pos, out: &mut Vec<i32>) -> Result<(), ArrayError> {
        if self.pending.take().is_some() {
            return Err(ArrayError::Unexpected(
                open,
                "expected integers, got a binary float array".into(),
            ));
        }
        loop {
            match self.item()? {
                Item::Num(_, Num { i: Some(i), .. }) => out.push(i),
                Item::Num(at, n) => return Err(ArrayError::Unexpected(at, not_an_int(n))),
                Item::Close => return Ok(()),
                other => return Err(Self::bad_item(other, open, "integers")),
            }
        }
    }

    /// Reads the strings of an array whose `[` was consumed, through its `]`.
    pub(crate) fn strings(&mut self, open: Pos, out: &mut Vec<String>) -> Result<(), ArrayError> {
        if self.pending.take().is_some() {
            return Err(ArrayError::Unexpected(
                open,
                "expected strings, got a binary float array".into(),
            ));
        }
        loop {
            match self.item()? {
                Item::Str(_, s) => out.push(s),
                Item::Close => return Ok(()),
                other => return Err(Self::bad_item(other, open, "strings")),
            }
        }
    }

    /// Reads an array whose `[` was consumed without knowing its type: all strings, or all
    /// numbers (integers if every one is an `i32` literal).
    pub(crate) fn any(&mut self, open: Pos) -> Result<AnyArray, ArrayError> {
        if let Some(p) = self.pending.take() {
            return Ok(AnyArray::Floats(p.values[p.next..].to_vec()));
        }
        match self.item()? {
            Item::Close => Ok(AnyArray::Empty),
            Item::Str(_, s) => {
                let mut v = vec![s];
                self.strings(open, &mut v)?;
                Ok(AnyArray::Strings(v))
            }
            Item::Num(_, first) => {
                let mut ints = Vec::new();
                let mut n = first;
                loop {
                    match n.i {
                        Some(i) => ints.push(i),
                        None => {
                            let mut floats: Vec<f32> = ints.iter().map(|&i| i as f32).collect();
                            floats.push(n.f);
                            self.floats(open, &mut floats)?;
                            return Ok(AnyArray::Floats(floats));
                        }
                    }
                    match self.item()? {
                        Item::Num(_, next) => n = next,
                        Item::Close => return Ok(AnyArray::Ints(ints)),
                        other => return Err(Self::bad_item(other, open, "numbers")),
                    }
                }
            }
            other => Err(Self::bad_item(other, open, "numbers or strings")),
        }
    }
}

/// Message for a number where an integer was required.
pub(crate) fn not_an_int(n: Num) -> String {
    if n.int_form {
        format!("integer {} is out of range", n.f)
    } else {
        format!("expected an integer, got {}", n.f)
    }
}

/// Why a number's text was rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NumError {
    /// Not of the RIB number form.
    Malformed,
    /// Of the form, but not a finite `f32`.
    OutOfRange,
}

/// Exact powers of ten in `f32` (10^10 = 2^10 · 5^10 and 5^10 < 2^24).
const POW10: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// Converts a RIB number's text (Spec C.2: optional sign, digits with an embedded period, a
/// trailing exponent, or both) without allocating.
///
/// Correctly rounded: when the decimal mantissa fits in 24 bits and the power of ten is at most
/// 10^10 both are exact `f32`s and one multiply or divide rounds once (Clinger's fast path);
/// otherwise the already validated text goes to `core`'s `f32` parser (Eisel-Lemire, also
/// allocation-free).
pub(crate) fn parse_number(text: &[u8]) -> Result<Num, NumError> {
    let mut i = 0;
    let neg = match text.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    let mut mant: u64 = 0;
    let mut truncated = false;
    let mut exp10: i32 = 0;
    let int_start = i;
    while i < text.len() && text[i].is_ascii_digit() {
        if mant < 100_000_000_000_000_000 {
            mant = mant * 10 + u64::from(text[i] - b'0');
        } else {
            truncated = true;
        }
        i += 1;
    }
    let mut digits = i - int_start;
    let mut int_form = true;
    if i < text.len() && text[i] == b'.' {
        int_form = false;
        i += 1;
        let frac_start = i;
        while i < text.len() && text[i].is_ascii_digit() {
            if mant < 100_000_000_000_000_000 {
                mant = mant * 10 + u64::from(text[i] - b'0');
                exp10 -= 1;
            } else {
                truncated = true;
            }
            i += 1;
        }
        digits += i - frac_start;
    }
    if digits == 0 {
        return Err(NumError::Malformed);
    }
    if i < text.len() && (text[i] == b'e' || text[i] == b'E') {
        int_form = false;
        i += 1;
        let eneg = match text.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let exp_start = i;
        let mut e: i32 = 0;
        while i < text.len() && text[i].is_ascii_digit() {
            e = (e * 10 + i32::from(text[i] - b'0')).min(100_000);
            i += 1;
        }
        if i == exp_start {
            return Err(NumError::Malformed);
        }
        exp10 += if eneg { -e } else { e };
    }
    if i != text.len() {
        return Err(NumError::Malformed);
    }
    if int_form && !truncated {
        let limit = if neg { 1u64 << 31 } else { (1u64 << 31) - 1 };
        let f = if neg { -(mant as f32) } else { mant as f32 };
        let i = (mant <= limit)
            .then(|| if neg { (mant as i64).wrapping_neg() as i32 } else { mant as i32 });
        return Ok(Num { f, i, int_form: true });
    }
    let f = if !truncated && mant <= 1 << 24 && (-10..=10).contains(&exp10) {
        let m = mant as f32;
        let v = if exp10 >= 0 { m * POW10[exp10 as usize] } else { m / POW10[(-exp10) as usize] };
        if neg { -v } else { v }
    } else {
        let s = std::str::from_utf8(text).map_err(|_| NumError::Malformed)?;
        s.parse::<f32>().map_err(|_| NumError::Malformed)?
    };
    if !f.is_finite() {
        return Err(NumError::OutOfRange);
    }
    Ok(Num { f, i: None, int_form })
}

#[cfg(test)]
mod tests {
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
            Box::new(io::Cursor::new(
                b"##RenderMan RIB\n# plain\n WorldBegin ##Shaders x".to_vec(),
            )),
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
        assert_eq!(
            lex_err("1 1.0f"),
            (Pos { line: 1, col: 3 }, "malformed number \"1.0f\"".into())
        );
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
            (
                Pos { line: 1, col: 1 },
                "number 1e40 is out of range (not a finite 32-bit float)".into()
            )
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
}
