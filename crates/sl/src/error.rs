//! Positions, the file table and [`SlError`], the one error type of the front end.
//!
//! Invariant: `Display` of every error is exactly one line, `FILE:LINE:COL: MESSAGE` (or
//! `FILE: MESSAGE` for an I/O error without position); control characters from the source are
//! written escaped.

use std::fmt;

/// A position in a source file the user wrote: file index, 1-based line, 1-based byte column.
///
/// Tokens made by macro expansion carry the position of the expansion site (the macro's name
/// where it was used), so every position is a place in a file the user can open.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Pos {
    /// Index into [`SourceMap::files`].
    pub file: u32,
    /// 1-based line (after any `#line`).
    pub line: u32,
    /// 1-based byte column within the line.
    pub col: u32,
}

/// The display names of the files a compilation read, indexed by [`Pos::file`].
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SourceMap {
    /// Display names (the path as found, or the name given to in-memory text, or a `#line`
    /// file name).
    pub files: Vec<String>,
}

impl SourceMap {
    /// The index of `name`, added when new.
    pub fn intern(&mut self, name: &str) -> u32 {
        if let Some(i) = self.files.iter().position(|f| f == name) {
            return i as u32;
        }
        self.files.push(name.to_string());
        (self.files.len() - 1) as u32
    }

    /// The display name of file `i` (`?` when out of range, which no position made here is).
    pub fn name(&self, i: u32) -> &str {
        self.files.get(i as usize).map(String::as_str).unwrap_or("?")
    }

    /// `file:line:col` of a position.
    pub fn show(&self, pos: Pos) -> String {
        format!("{}:{}:{}", OneLine(self.name(pos.file)), pos.line, pos.col)
    }
}

/// An error of the front end: bad source (exit code 2) or an unreadable file (exit code 1).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SlError {
    /// A lexical, preprocessor, syntax or type error at a position of the source.
    #[error("{}:{line}:{col}: {}", OneLine(file), OneLine(message))]
    Source {
        /// Display name of the file.
        file: String,
        /// 1-based line.
        line: u32,
        /// 1-based byte column.
        col: u32,
        /// What is wrong, naming the construct.
        message: String,
    },
    /// A file could not be read (the shader itself, or an `#include`d file that exists).
    #[error("{}: {}", OneLine(path), OneLine(message))]
    Io {
        /// `file:line:col` of the `#include`, or the path of the shader file.
        path: String,
        /// The operating system's message, with what was being read.
        message: String,
    },
}

impl SlError {
    /// The process exit code a command-line compiler returns for this error: 2 for bad source,
    /// 1 for I/O.
    pub fn exit_code(&self) -> i32 {
        match self {
            SlError::Source { .. } => 2,
            SlError::Io { .. } => 1,
        }
    }

    /// The message without its position.
    pub fn message(&self) -> &str {
        match self {
            SlError::Source { message, .. } | SlError::Io { message, .. } => message,
        }
    }
}

/// An error before file names are attached: position and message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Diag {
    pub pos: Pos,
    pub message: String,
    /// A file that exists could not be read (exit code 1, not 2).
    pub io: bool,
}

impl Diag {
    pub fn new(pos: Pos, message: impl Into<String>) -> Diag {
        Diag { pos, message: message.into(), io: false }
    }

    pub fn into_error(self, map: &SourceMap) -> SlError {
        if self.io {
            // Line 0: the shader file itself, which has no position to show.
            let path = if self.pos.line == 0 {
                map.name(self.pos.file).to_string()
            } else {
                map.show(self.pos)
            };
            return SlError::Io { path, message: self.message };
        }
        SlError::Source {
            file: map.name(self.pos.file).to_string(),
            line: self.pos.line,
            col: self.pos.col,
            message: self.message,
        }
    }
}

/// Shorthand for results carrying a [`Diag`].
pub(crate) type DResult<T> = Result<T, Diag>;

/// Writes text on one line: control characters escaped.
pub(crate) struct OneLine<'a>(pub &'a str);

impl fmt::Display for OneLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            match c {
                '\n' => f.write_str("\\n")?,
                '\r' => f.write_str("\\r")?,
                '\t' => f.write_str("\\t")?,
                c if c.is_control() => write!(f, "\\x{:02x}", c as u32)?,
                c => write!(f, "{c}")?,
            }
        }
        Ok(())
    }
}
