//! The errors of rendering a valid scene, each with its source.

impl RenderError {
    /// The process exit code: 2 for a frame refused up front (the scene asks for more than
    /// the limit, like any other out-of-range setting), 1 for everything else.
    pub fn exit_code(&self) -> u8 {
        match self {
            RenderError::WontFit { .. } => 2,
            RenderError::Texture { code, .. } => *code,
            _ => 1,
        }
    }
}

/// Errors while rendering a valid scene.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The dicer failed.
    #[error("dicing failed: {0}")]
    Dice(reyes_dice::DiceError),
    /// A texture map could not be loaded: found when the maps load, before any bucket is
    /// diced, so it is not called a dicing failure. The message names the file.
    #[error("{message}")]
    Texture {
        /// The loader's message.
        message: String,
        /// Its exit code: 1 for I/O, 2 for a file that is not a usable image.
        code: u8,
    },
    /// A shading-language shader failed (its instruction budget spent, most likely), or a
    /// scene with such shaders asked for a hider that cannot run them; one line naming the
    /// shader and the object.
    #[error("{message}")]
    Shader {
        /// The message.
        message: String,
    },
    /// The film stage failed (e.g. a degenerate filter).
    #[error("{0}")]
    Film(#[from] reyes_film::FilmError),
    /// The frame cannot fit in the memory limit (known before anything is allocated).
    #[error(
        "the frame needs at least {need} MB (film {film} MB, bucket samples {buckets} MB, program and scene {base} MB) and the memory limit is {limit} MB; lower the resolution, pixel samples or bucket size, or raise --memory-limit"
    )]
    WontFit {
        /// The whole estimate, in MB: the sum of the three parts below as shown.
        need: u64,
        /// The film and its encoded copy, in MB.
        film: u64,
        /// The workers' bucket arrays, in MB.
        buckets: u64,
        /// The program, its threads and the scene, in MB.
        base: u64,
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

impl From<reyes_dice::DiceError> for RenderError {
    fn from(e: reyes_dice::DiceError) -> RenderError {
        match e {
            reyes_dice::DiceError::Texture { message, code } => {
                RenderError::Texture { message, code }
            }
            reyes_dice::DiceError::Shader { message } => RenderError::Shader { message },
            e => RenderError::Dice(e),
        }
    }
}
