//! The errors of rendering a valid scene, each with its source.

impl RenderError {
    /// The process exit code: 2 for a frame refused up front (the scene asks for more than
    /// the limit, like any other out-of-range setting), 1 for everything else.
    pub fn exit_code(&self) -> u8 {
        match self {
            RenderError::WontFit { .. } => 2,
            RenderError::Dice(reyes_dice::DiceError::Texture { code, .. }) => *code,
            _ => 1,
        }
    }
}

/// Errors while rendering a valid scene.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The dicer failed.
    #[error("dicing failed: {0}")]
    Dice(#[from] reyes_dice::DiceError),
    /// The film stage failed (e.g. a degenerate filter).
    #[error("{0}")]
    Film(#[from] reyes_film::FilmError),
    /// The frame cannot fit in the memory limit (known before anything is allocated).
    #[error(
        "the frame needs at least {need} MB (film {film} MB, bucket samples {buckets} MB) and the memory limit is {limit} MB; lower the resolution, pixel samples or bucket size, or raise --memory-limit"
    )]
    WontFit {
        /// The whole estimate, in MB.
        need: u64,
        /// The film and its encoded copy, in MB.
        film: u64,
        /// The workers' bucket arrays, in MB.
        buckets: u64,
        /// The limit, in MB.
        limit: u64,
    },
    /// A bucket needed more visible points than the memory budget's share.
    #[error(
        "memory limit reached: a bucket needs more than {limit} visible points (overlapping transparent layers); raise --memory-limit, or lower the pixel samples or bucket size"
    )]
    VisiblePointBudget {
        /// The most visible points one bucket may keep.
        limit: u64,
    },
    /// The thread pool could not be built.
    #[error("cannot start render threads: {0}")]
    Threads(#[from] rayon::ThreadPoolBuildError),
    /// A texture tile could not be read back from the cache's temporary file.
    #[error("texture cache: a tile could not be read back from its temporary file")]
    TextureRead,
    /// [`crate::cancel::request`] was called: the render stopped before its last bucket.
    #[error("the render was cancelled")]
    Cancelled,
}
