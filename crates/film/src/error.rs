//! Errors of the film stage (filter tables and image output).
//!
//! Invariant: every variant's `Display` is a single line; variants about a file name its path.

use std::path::PathBuf;

use reyes_scene::FilterKind;

/// Everything the film stage can report.
#[derive(Debug, thiserror::Error)]
pub enum FilmError {
    /// Reading or writing `path` failed at the operating-system level (missing or unwritable
    /// directory, disk full, rename failure, ...).
    #[error("{}: {source}", path.display())]
    Io {
        /// The file being written or read.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Writing `path` was cancelled ([`crate::WriteOptions::cancel`]) before the file was
    /// complete; nothing was written.
    #[error("{}: the write was interrupted", path.display())]
    Interrupted {
        /// The file that was being written.
        path: PathBuf,
    },
    /// The output path's extension is neither `.exr` nor `.png` (case-insensitive).
    #[error("{}: unknown image format (expected a .exr or .png extension)", path.display())]
    UnknownFormat {
        /// The requested output file.
        path: PathBuf,
    },
    /// The OpenEXR encoder or decoder rejected the image or the file.
    #[error("{}: OpenEXR error: {source}", path.display())]
    Exr {
        /// The file being written or read.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: exr::error::Error,
    },
    /// An EXR file read back lacks a required channel or has inconsistent channel sizes.
    #[error("{}: unexpected OpenEXR contents: {reason}", path.display())]
    BadExr {
        /// The file being read.
        path: PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// The PNG encoder rejected the image.
    #[error("{}: PNG error: {source}", path.display())]
    Png {
        /// The file being written.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: image::ImageError,
    },
    /// The filter table cannot be built: its weights sum to zero or a non-finite value, or the
    /// table parameters are invalid (width not finite and positive, empty sample grid, wrong
    /// number of stratum locations).
    #[error("degenerate {kind:?} filter of width {}: {reason}", widths(*width, *height))]
    DegenerateFilter {
        /// The kernel.
        kind: FilterKind,
        /// Its full width in x, in pixels.
        width: f32,
        /// Its full width in y, in pixels.
        height: f32,
        /// Why the table is unusable.
        reason: String,
    },
}

/// `2` for a filter as tall as it is wide, `4 x 1` otherwise.
fn widths(width: f32, height: f32) -> String {
    if height == width { format!("{width}") } else { format!("{width} x {height}") }
}
