//! The errors of the farm layer, and [`one_line`], which keeps a message on one line.
//!
//! Invariant: every [`FarmError`] displays as one line: the paths and names in its own
//! messages are written through [`one_line`].

use std::fmt::Display;
use std::path::Path;

use reyes_film::FilmError;
use reyes_render::RenderError;

/// Everything the farm layer can report.
#[derive(Debug, thiserror::Error)]
pub enum FarmError {
    /// The scene file could not be loaded (the warnings raised before the error are in it,
    /// to be shown first).
    #[error(transparent)]
    Load(#[from] reyes_rib::Refusal),
    /// A request that cannot be met: an output that is not an image, a frame the scene does
    /// not have, more tiles than buckets, pieces that do not belong together (exit code 2).
    #[error("{0}")]
    Invalid(String),
    /// A file or a command that failed (exit code 1).
    #[error("{0}")]
    Failed(String),
    /// Rendering the frame failed or was cancelled.
    #[error("{}: {source}", one_line(scene))]
    Render {
        /// The scene file, as the front end named it.
        scene: String,
        /// Why.
        #[source]
        source: RenderError,
    },
    /// Reading or writing an image file failed (or a write was interrupted:
    /// [`FilmError::Interrupted`]) (exit code 1).
    #[error(transparent)]
    Film(#[from] FilmError),
    /// A file is not a piece of a render (exit code 2): not an OpenEXR file, or not one of
    /// ours.
    #[error(transparent)]
    NotAPiece(FilmError),
}

impl FarmError {
    /// The process exit code: 2 for bad input (a bad scene, request or piece), 1 for failed
    /// I/O, commands and renders.
    pub fn exit_code(&self) -> u8 {
        match self {
            FarmError::Load(e) => e.exit_code(),
            FarmError::Invalid(_) | FarmError::NotAPiece(_) => 2,
            FarmError::Failed(_) | FarmError::Film(_) => 1,
            FarmError::Render { source, .. } => source.exit_code(),
        }
    }

    /// The file a cancel request ([`reyes_render::cancel`]) stopped, if that is what this
    /// is: `rendering` for a cancelled render, the file itself for an interrupted write.
    pub fn cancelled<'a>(&'a self, rendering: &'a Path) -> Option<&'a Path> {
        match self {
            FarmError::Render { source: RenderError::Cancelled, .. } => Some(rendering),
            FarmError::Film(FilmError::Interrupted { path }) => Some(path),
            _ => None,
        }
    }

    /// A [`FarmError::Invalid`] of the message `args`.
    pub(crate) fn invalid(args: std::fmt::Arguments) -> FarmError {
        FarmError::Invalid(args.to_string())
    }

    /// A [`FarmError::Failed`] of the message `args`.
    pub(crate) fn failed(args: std::fmt::Arguments) -> FarmError {
        FarmError::Failed(args.to_string())
    }
}

/// `text` on one line: control characters (a newline, a tab, an escape) and the Unicode line
/// and paragraph separators written escaped as Rust writes them (`\n`, `\u{1b}`), everything
/// else as it is. Paths in messages go through here (`one_line(path.display())`), and a front
/// end may pass every line it prints.
pub fn one_line(text: impl Display) -> String {
    let text = text.to_string();
    if !text.chars().any(breaks_line) {
        return text;
    }
    text.chars()
        .map(|c| if breaks_line(c) { c.escape_default().to_string() } else { c.to_string() })
        .collect()
}

fn breaks_line(c: char) -> bool {
    c.is_control() || matches!(c, '\u{2028}' | '\u{2029}')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_line_escapes_what_would_break_the_line() {
        assert_eq!(one_line("tiles/a.exr"), "tiles/a.exr");
        assert_eq!(one_line("a\nb\tc\u{1b}[1m\u{2028}é"), "a\\nb\\tc\\u{1b}[1m\\u{2028}é");
        assert_eq!(one_line(one_line("x\ry")), "x\\ry", "idempotent");
        let e = FarmError::Render { scene: "s\n.ron".into(), source: RenderError::Cancelled };
        assert_eq!(e.to_string().lines().count(), 1);
        assert_eq!(e.cancelled(Path::new("out.exr")), Some(Path::new("out.exr")));
        let e = FarmError::Film(FilmError::Interrupted { path: "x.png".into() });
        assert_eq!(e.cancelled(Path::new("out.exr")), Some(Path::new("x.png")));
        assert_eq!(FarmError::Failed("disk".into()).cancelled(Path::new("out.exr")), None);
    }
}
