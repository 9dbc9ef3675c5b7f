//! Positions, warnings and [`RibError`], the one error type of the RIB reader.
//!
//! Invariant: `Display` of every error and warning is exactly one line, `FILE:LINE:COL: REQUEST:
//! MESSAGE` (or `FILE:LINE:COL: MESSAGE` at the lexical level, `FILE: MESSAGE` when no position
//! applies); control characters coming from the input (names, strings) are written escaped.

use std::fmt;
use std::io;
use std::sync::Arc;

/// A 1-based line and column inside one source.
///
/// Columns count bytes, not characters: a tab counts 1, a UTF-8 character inside a string counts
/// its byte length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Pos {
    /// 1-based line; lines end at `\n`.
    pub line: u32,
    /// 1-based byte column within the line.
    pub col: u32,
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// A position in a named source: what every request, error and warning carries.
///
/// `file` is the source's display name (the path as given, an archive's resolved path, or
/// `<stdin>`), shared by every location in that source.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Location {
    /// Display name of the source.
    pub file: Arc<str>,
    /// Line and column in it.
    pub pos: Pos,
}

impl Location {
    /// The same file at another position.
    pub fn at(&self, pos: Pos) -> Location {
        Location { file: self.file.clone(), pos }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", OneLine(&self.file), self.pos)
    }
}

/// Something the reader accepted but that the author probably did not mean: an unknown request
/// (skipped), an undeclared parameter (kept as written), an unknown string escape.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// Where.
    pub at: Location,
    /// What, e.g. `unknown request "Foo" skipped`; starts with the request's name when one applies.
    pub message: String,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: warning: {}", self.at, OneLine(&self.message))
    }
}

/// Why the reader could not deliver a request.
///
/// Calling [`crate::Reader::next_request`] again after any error is safe and always ends:
/// after a [`RibError::Syntax`] or [`RibError::Request`] error the same source goes on at the
/// next request name; after [`RibError::Archive`] the including source goes on; after
/// [`RibError::Io`] or [`RibError::Binary`] that source is finished (an archive's includer then
/// goes on).
#[derive(Debug, thiserror::Error)]
pub enum RibError {
    /// Bad bytes at the lexical level: an unterminated string, a malformed number, a stray `]`.
    #[error("{at}: {}", OneLine(message))]
    Syntax {
        /// Where the offending text starts.
        at: Location,
        /// What is wrong.
        message: String,
    },
    /// A request whose arguments or parameters do not fit its signature or declarations.
    #[error("{at}: {request}: {}", OneLine(message))]
    Request {
        /// Where the offending token starts (the request name when no token applies).
        at: Location,
        /// The request's RIB name, e.g. `Sphere`.
        request: &'static str,
        /// What is wrong, naming the argument or parameter.
        message: String,
    },
    /// A reserved code of the binary encoding (Spec 3.2 Appendix C.2: 0247-0307 and
    /// 0321-0377); its length is unknown, so the source ends there.
    #[error(
        "{at}: reserved binary RIB code 0{byte:o} (byte 0x{byte:02x}); the rest of the source is not read"
    )]
    Binary {
        /// The byte.
        at: Location,
        /// Its value.
        byte: u8,
    },
    /// The source could not be read (or decompressed); the stream ends.
    #[error("{}: cannot read: {}", OneLine(file), OneLine(&source.to_string()))]
    Io {
        /// Display name of the source.
        file: Arc<str>,
        /// The underlying failure.
        source: io::Error,
    },
    /// A shading-language shader that does not compile (or cannot be read): the compiler's
    /// one line, `file:line:col: message`.
    #[error("{}", OneLine(message))]
    Shader {
        /// The request naming the shader.
        at: Location,
        /// The compiler's message.
        message: String,
    },
    /// A `ReadArchive` whose file cannot be opened; the including stream goes on.
    #[error("{at}: ReadArchive: cannot read \"{}\": {}", OneLine(file), OneLine(&source.to_string()))]
    Archive {
        /// The including request.
        at: Location,
        /// The archive's resolved path.
        file: String,
        /// The underlying failure.
        source: io::Error,
    },
}

impl RibError {
    /// The location the error names, if it has one.
    pub fn location(&self) -> Option<&Location> {
        match self {
            RibError::Syntax { at, .. }
            | RibError::Request { at, .. }
            | RibError::Binary { at, .. }
            | RibError::Archive { at, .. }
            | RibError::Shader { at, .. } => Some(at),
            RibError::Io { .. } => None,
        }
    }

    /// True if the source that reported the error goes on (it resynchronises at the next
    /// request name, or, for [`RibError::Archive`], the including source was never left).
    pub fn is_recoverable(&self) -> bool {
        matches!(
            self,
            RibError::Syntax { .. } | RibError::Request { .. } | RibError::Archive { .. }
        )
    }
}

/// Writes a string on one line: control characters (and the Unicode line separators) escaped.
pub(crate) struct OneLine<'a>(pub(crate) &'a str);

impl fmt::Display for OneLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            if c.is_control() || c == '\u{2028}' || c == '\u{2029}' {
                write!(f, "{}", c.escape_default())?;
            } else {
                write!(f, "{c}")?;
            }
        }
        Ok(())
    }
}

/// Quotes and escapes input text for a message: `"Kd"`, `"a\nb"`; long text is cut at 40
/// characters with `...`.
pub(crate) fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len().min(48) + 2);
    out.push('"');
    for (n, c) in s.chars().enumerate() {
        if n == 40 {
            out.push_str("...");
            break;
        }
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() || c == '\u{2028}' || c == '\u{2029}' => {
                out.extend(c.escape_default())
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_stay_on_one_line() {
        let at = Location { file: Arc::from("a\nb.rib"), pos: Pos { line: 3, col: 7 } };
        let e = RibError::Syntax { at, message: "bad\rthing".into() };
        assert_eq!(e.to_string(), "a\\nb.rib:3:7: bad\\rthing");
    }

    #[test]
    fn quote_escapes_and_cuts() {
        assert_eq!(quote("K\"d\n"), "\"K\\\"d\\n\"");
        assert_eq!(quote(&"x".repeat(50)), format!("\"{}...\"", "x".repeat(40)));
    }
}
