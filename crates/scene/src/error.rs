//! Error types of scene loading: [`SceneError`] (bad scene text) and [`LoadError`].
//!
//! Invariant: `Display` of either type is exactly one line, whatever the fields hold: control
//! characters and line separators in the path, field or message are written escaped.

use std::fmt;
use std::path::{Path, PathBuf};

/// A scene file that cannot be used: a RON syntax or type error, or a value out of range.
///
/// Displays as one line, `FILE:LINE:COL: FIELD: MESSAGE`, with `:LINE:COL` left out when the
/// position is unknown and `FIELD: ` left out when no field applies (pure syntax errors).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file, as given by the caller (used only in messages).
    pub file: PathBuf,
    /// 1-based line of the offending text, if known.
    pub line: Option<usize>,
    /// 1-based column, counted in characters, if known.
    pub col: Option<usize>,
    /// Path of the offending value, e.g. `objects[0].shape.radius`; empty if none applies.
    pub field: String,
    /// What is wrong, in a few words, e.g. `must be > 0, got -1`.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_one_line(f, &self.file.display().to_string())?;
        match (self.line, self.col) {
            (Some(line), Some(col)) => write!(f, ":{line}:{col}")?,
            (Some(line), None) => write!(f, ":{line}")?,
            _ => {}
        }
        f.write_str(": ")?;
        if !self.field.is_empty() {
            write_one_line(f, &self.field)?;
            f.write_str(": ")?;
        }
        write_one_line(f, &self.message)
    }
}

impl std::error::Error for SceneError {}

/// Why [`crate::load`] failed.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("{}: cannot read the scene file: {}", OneLine(&path.display().to_string()), OneLine(&source.to_string()))]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying failure.
        source: std::io::Error,
    },
    /// The file was read but is not a valid scene.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A mesh file the scene names (`MeshFile`) could not be read; the error is at the
    /// shape's `path` field.
    #[error(transparent)]
    MeshIo(SceneError),
}

impl LoadError {
    /// Process exit status for this error: 1 for an unreadable file, 2 for a bad scene.
    pub fn exit_code(&self) -> u8 {
        match self {
            LoadError::Io { .. } | LoadError::MeshIo(_) => 1,
            LoadError::Scene(_) => 2,
        }
    }

    /// The scene file concerned.
    pub fn path(&self) -> &Path {
        match self {
            LoadError::Io { path, .. } => path,
            LoadError::Scene(e) | LoadError::MeshIo(e) => &e.file,
        }
    }
}

/// Displays a string on one line (see [`write_one_line`]).
struct OneLine<'a>(&'a str);

impl fmt::Display for OneLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_one_line(f, self.0)
    }
}

/// Writes `s` with control characters and Unicode line/paragraph separators escaped.
fn write_one_line(f: &mut fmt::Formatter<'_>, s: &str) -> fmt::Result {
    for c in s.chars() {
        if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') {
            write!(f, "{}", c.escape_default())?;
        } else {
            fmt::Write::write_char(f, c)?;
        }
    }
    Ok(())
}

/// Shortens `s` to at most `max` characters, marking the cut with `…`.
pub(crate) fn clip(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_string()
    } else {
        let mut out: String = s.chars().take(max.saturating_sub(1)).collect();
        out.push('…');
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(line: Option<usize>, col: Option<usize>, field: &str, message: &str) -> SceneError {
        SceneError {
            file: PathBuf::from("scenes/x.ron"),
            line,
            col,
            field: field.into(),
            message: message.into(),
        }
    }

    #[test]
    fn display_forms() {
        let e = err(Some(12), Some(30), "objects[0].shape.radius", "must be > 0, got -1");
        assert_eq!(
            e.to_string(),
            "scenes/x.ron:12:30: objects[0].shape.radius: must be > 0, got -1"
        );
        assert_eq!(err(None, None, "a", "b").to_string(), "scenes/x.ron: a: b");
        assert_eq!(err(Some(1), Some(2), "", "b").to_string(), "scenes/x.ron:1:2: b");
        assert_eq!(err(Some(1), None, "", "b").to_string(), "scenes/x.ron:1: b");
    }

    #[test]
    fn display_is_one_line() {
        let mut e = err(Some(1), Some(1), "a\nb", "c\r\nd\u{2028}");
        e.file = PathBuf::from("x\ny.ron");
        let s = e.to_string();
        assert!(!s.contains('\n') && !s.contains('\r') && !s.contains('\u{2028}'), "{s}");
        assert_eq!(s, "x\\ny.ron:1:1: a\\nb: c\\r\\nd\\u{2028}");
    }

    #[test]
    fn exit_codes() {
        let io = LoadError::Io {
            path: PathBuf::from("nope.ron"),
            source: std::io::Error::new(std::io::ErrorKind::NotFound, "gone"),
        };
        assert_eq!(io.exit_code(), 1);
        assert_eq!(io.to_string(), "nope.ron: cannot read the scene file: gone");
        let scene = LoadError::from(err(None, None, "", "bad"));
        assert_eq!(scene.exit_code(), 2);
        assert_eq!(scene.to_string(), "scenes/x.ron: bad");
    }

    #[test]
    fn clipping() {
        assert_eq!(clip("abc", 3), "abc");
        assert_eq!(clip("abcd", 3), "ab…");
    }
}
