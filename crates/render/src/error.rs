//! The errors of rendering a valid scene, each with its source.

/// Errors while rendering a valid scene.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The dicer failed.
    #[error("dicing failed: {0}")]
    Dice(#[from] reyes_dice::DiceError),
    /// The film stage failed (e.g. a degenerate filter).
    #[error("{0}")]
    Film(#[from] reyes_film::FilmError),
    /// The thread pool could not be built.
    #[error("cannot start render threads: {0}")]
    Threads(#[from] rayon::ThreadPoolBuildError),
    /// [`crate::cancel::request`] was called: the render stopped before its last bucket.
    #[error("the render was cancelled")]
    Cancelled,
}
