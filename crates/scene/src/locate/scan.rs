//! The tokenizer under the source map: splits RON text into the few kinds of token the path
//! builder needs, each with the position of its first and last character.
//!
//! Invariants: total on any input (never panics, never recurses; unclosed strings, comments
//! and raw literals run to the end of input); positions are 1-based lines split on `'\n'` and
//! 1-based columns counted in `char`s, exactly as ron counts them.

/// A position in the source: 1-based line and 1-based column in `char`s.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Pos {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub col: usize,
}

impl Pos {
    const START: Pos = Pos { line: 1, col: 1 };
    /// After any position in any text.
    pub(crate) const MAX: Pos = Pos { line: usize::MAX, col: usize::MAX };
}

/// What a token is; only what the path builder needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Tok<'a> {
    /// `(`, `[` or `{`, holding the matching closer.
    Open(char),
    /// `)`, `]` or `}`.
    Close(char),
    /// `:`.
    Colon,
    /// `,`.
    Comma,
    /// An identifier (raw identifiers without their `r#`).
    Ident(&'a str),
    /// A string, character or byte literal.
    Atom,
    /// A number as written (sign, digits, point, exponent and any letters run into it).
    Number(&'a str),
    /// Anything else (`#`, `!`, stray punctuation).
    Other(char),
}

/// A token with the position of its first and last character.
#[derive(Debug, Clone, Copy)]
pub(super) struct Token<'a> {
    pub tok: Tok<'a>,
    pub start: Pos,
    pub end: Pos,
}

/// A character cursor that tracks line and column.
struct Cursor<'a> {
    src: &'a str,
    at: usize,
    pos: Pos,
    last: Pos,
}

impl<'a> Cursor<'a> {
    fn new(src: &'a str) -> Self {
        Cursor { src, at: 0, pos: Pos::START, last: Pos::START }
    }

    fn rest(&self) -> &'a str {
        self.src.get(self.at..).unwrap_or("")
    }

    fn peek(&self) -> Option<char> {
        self.rest().chars().next()
    }

    fn peek_nth(&self, n: usize) -> Option<char> {
        self.rest().chars().nth(n)
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.at += c.len_utf8();
        self.last = self.pos;
        if c == '\n' {
            self.pos = Pos { line: self.pos.line.saturating_add(1), col: 1 };
        } else {
            self.pos.col = self.pos.col.saturating_add(1);
        }
        Some(c)
    }

    fn bump_while(&mut self, keep: impl Fn(char) -> bool) {
        while let Some(c) = self.peek() {
            if !keep(c) {
                break;
            }
            self.bump();
        }
    }

    /// Skips a (nested) block comment; the cursor is on its `/*`. Stops at end of input.
    /// Returns false if the comment is not closed.
    fn block_comment(&mut self) -> bool {
        self.bump();
        self.bump();
        let mut level = 1usize;
        while level > 0 {
            match self.bump() {
                None => return false,
                Some('/') if self.peek() == Some('*') => {
                    self.bump();
                    level += 1;
                }
                Some('*') if self.peek() == Some('/') => {
                    self.bump();
                    level -= 1;
                }
                Some(_) => {}
            }
        }
        true
    }

    /// Skips a quoted string body with backslash escapes; the cursor is past the opening quote.
    fn quoted(&mut self, quote: char) {
        while let Some(c) = self.bump() {
            if c == '\\' {
                self.bump();
            } else if c == quote {
                return;
            } else if quote == '\'' && c == '\n' {
                // A character literal never spans lines: stop so one stray quote
                // does not swallow the rest of the file.
                return;
            }
        }
    }

    /// Skips a raw string; the cursor is on the `#`s (if any) before the opening quote.
    fn raw_string(&mut self, hashes: usize) {
        for _ in 0..hashes {
            self.bump();
        }
        self.bump(); // opening quote
        let closer: String = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
        match self.rest().find(closer.as_str()) {
            Some(len) => {
                let stop = self.at + len + closer.len();
                while self.at < stop && self.bump().is_some() {}
            }
            None => while self.bump().is_some() {},
        }
    }

    /// Number of `#` at character offset `from` of the rest.
    fn hashes_from(&self, from: usize) -> usize {
        self.rest().chars().skip(from).take_while(|&c| c == '#').count()
    }
}

fn is_ident_start(c: char) -> bool {
    c == '_' || c.is_alphabetic()
}

fn is_ident_continue(c: char) -> bool {
    c == '_' || c.is_alphanumeric()
}

/// The tokens of a text, with where it ends and where an unclosed block comment starts.
pub(super) struct Tokens<'a> {
    pub tokens: Vec<Token<'a>>,
    pub eof: Pos,
    pub unclosed_comment: Option<Pos>,
}

/// Splits `src` into tokens, skipping whitespace and comments. Total on any input.
pub(super) fn tokenize(src: &str) -> Tokens<'_> {
    let mut cur = Cursor::new(src);
    let mut out = Vec::new();
    let mut unclosed_comment = None;
    while let Some(c) = cur.peek() {
        if c.is_whitespace() {
            cur.bump();
            continue;
        }
        let start = cur.pos;
        let at = cur.at;
        let tok = match c {
            '/' if cur.peek_nth(1) == Some('/') => {
                cur.bump_while(|c| c != '\n');
                continue;
            }
            '/' if cur.peek_nth(1) == Some('*') => {
                if !cur.block_comment() {
                    unclosed_comment = Some(start);
                }
                continue;
            }
            '(' | '[' | '{' => {
                cur.bump();
                Tok::Open(match c {
                    '(' => ')',
                    '[' => ']',
                    _ => '}',
                })
            }
            ')' | ']' | '}' => {
                cur.bump();
                Tok::Close(c)
            }
            ':' => {
                cur.bump();
                Tok::Colon
            }
            ',' => {
                cur.bump();
                Tok::Comma
            }
            '"' | '\'' => {
                cur.bump();
                cur.quoted(c);
                Tok::Atom
            }
            'b' if matches!(cur.peek_nth(1), Some('"' | '\'')) => {
                cur.bump();
                if let Some(q) = cur.bump() {
                    cur.quoted(q);
                }
                Tok::Atom
            }
            'b' if cur.peek_nth(1) == Some('r')
                && cur.peek_nth(2 + cur.hashes_from(2)) == Some('"') =>
            {
                let hashes = cur.hashes_from(2);
                cur.bump();
                cur.bump();
                cur.raw_string(hashes);
                Tok::Atom
            }
            'r' if cur.peek_nth(1 + cur.hashes_from(1)) == Some('"') => {
                let hashes = cur.hashes_from(1);
                cur.bump();
                cur.raw_string(hashes);
                Tok::Atom
            }
            'r' if cur.peek_nth(1) == Some('#')
                && cur
                    .peek_nth(2)
                    .is_some_and(|c| is_ident_continue(c) || matches!(c, '.' | '+' | '-')) =>
            {
                cur.bump();
                cur.bump();
                let from = cur.at;
                cur.bump_while(|c| is_ident_continue(c) || matches!(c, '.' | '+' | '-'));
                Tok::Ident(src.get(from..cur.at).unwrap_or(""))
            }
            c if c.is_ascii_digit() || matches!(c, '+' | '-' | '.') => {
                let mut prev = c;
                cur.bump();
                while let Some(n) = cur.peek() {
                    let exponent_sign = matches!(n, '+' | '-') && matches!(prev, 'e' | 'E');
                    if !(is_ident_continue(n) || n == '.' || exponent_sign) {
                        break;
                    }
                    prev = n;
                    cur.bump();
                }
                Tok::Number(src.get(at..cur.at).unwrap_or(""))
            }
            c if is_ident_start(c) => {
                cur.bump_while(is_ident_continue);
                Tok::Ident(src.get(at..cur.at).unwrap_or(""))
            }
            other => {
                cur.bump();
                Tok::Other(other)
            }
        };
        out.push(Token { tok, start, end: cur.last });
    }
    Tokens { tokens: out, eof: cur.pos, unclosed_comment }
}
