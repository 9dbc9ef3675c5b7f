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
mod number;
#[cfg(test)]
mod tests;

use number::{DELIM, is_number_start};
pub(crate) use number::{NumError, not_an_int, parse_number};

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

    /// Refuses a binary float array (pending after its `[`) where `want` is expected.
    fn no_binary_floats(&mut self, open: Pos, want: &str) -> Result<(), ArrayError> {
        match self.pending.take() {
            Some(_) => Err(ArrayError::Unexpected(
                open,
                format!("expected {want}, got a binary float array"),
            )),
            None => Ok(()),
        }
    }

    /// Reads the integers of an array whose `[` was consumed, through its `]`.
    pub(crate) fn ints(&mut self, open: Pos, out: &mut Vec<i32>) -> Result<(), ArrayError> {
        self.no_binary_floats(open, "integers")?;
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
        self.no_binary_floats(open, "strings")?;
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
