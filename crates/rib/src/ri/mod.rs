//! The RI state machine: RIB requests to validated scenes of the scene model, one per frame.
//!
//! World space of the model is RenderMan's camera space at shutter open (+x right, +y up, +z
//! into the screen, the model's canonical camera at the origin looking down +z): every object
//! carries its object-to-camera transformation, lights are placed in camera space, and a
//! moving camera becomes the model's camera motion keys relative to its pose at shutter open.
//!
//! Invariants: the graphics state is a stack of value types, so `AttributeEnd` restores
//! exactly what `AttributeBegin` saw; blocks must balance and nest as the Specification says
//! (a mismatch is an error at the offending request); every scene handed out has passed
//! [`reyes_scene::validate`], and a validation failure is reported at the RIB request that
//! produced the offending value.

mod archives;
mod area;
mod attributes;
mod build;
mod detail;
mod frame;
pub(crate) mod geometry;
mod hair;
mod make;
mod options;
mod primitives;
mod program;
mod rsl;
mod search;
mod shaders;
mod solids;
mod spaces;
pub(crate) mod state;
mod subdivision;
pub mod teapot;
mod triangulate;
mod trim;
pub(crate) mod xform;

use reyes_scene::Scene;

pub use make::{MakeJob, is_depth_driver};
pub use state::Display;

use crate::{Reader, RibError, Source, Warning};

/// How to read a RIB file.
#[derive(Debug, Clone, Default)]
pub struct RiOptions {
    /// Unknown shaders are errors instead of warnings.
    pub strict: bool,
    /// Build only the frames whose `FrameBegin` number is in one of these inclusive ranges
    /// (None: every frame). A file without frames is frame 1 for this purpose.
    pub frames: Option<Vec<(i32, i32)>>,
}

/// What reading a scene may do beyond reading files: running programs the scene names is a
/// security decision for the person rendering it, off by default. (Kept apart from
/// [`RiOptions`], which callers build field by field, so that adding a permission breaks no
/// caller.)
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Permissions {
    /// `Procedural "RunProgram"` may run the programs the scene names (off: refused with an
    /// error; the CLI's `--allow-run-program`).
    pub run_program: bool,
}

impl RiOptions {
    /// True if frame `n` is to be built.
    pub fn wants(&self, n: i32) -> bool {
        self.frames.as_ref().is_none_or(|r| r.iter().any(|&(a, b)| a <= n && n <= b))
    }
}

/// One frame of a RIB file.
#[derive(Debug, Clone)]
pub struct Frame {
    /// The `FrameBegin` number (None: the file has no frame block).
    pub number: Option<i32>,
    /// The scene, validated.
    pub scene: Scene,
    /// Its `Display` requests, main output first.
    pub displays: Vec<Display>,
    /// The `Make*` requests read since the frame before it was built: run before it
    /// renders, after the frames before it (a multipass file's maps).
    pub makes: Vec<make::MakeJob>,
}

/// What a RIB file holds.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The frames built, in file order.
    pub frames: Vec<Frame>,
    /// The `Make*` requests after the last frame built: run after the frames.
    pub makes_after: Vec<make::MakeJob>,
    /// Everything accepted but worth telling: unknown requests and parameters, features we
    /// do not support, stand-in shaders.
    pub warnings: Vec<Warning>,
    /// The file has more than one frame (RIB world blocks, whether `--frames` built them or
    /// not; an animated RON scene): its output names are numbered.
    pub several_frames: bool,
    /// Two world blocks have the same main `Display` name: without `-o`, the frames'
    /// names are numbered so that they do not overwrite each other.
    pub display_repeats: bool,
}

/// Reads RIB from `source` into validated scenes, one per frame (archives are read relative
/// to the including file).
///
/// # Errors
///
/// The first malformed request, unbalanced block or invalid value, as one line
/// `file:line:col: Request: message`; [`RibError::Io`] if the source cannot be read.
pub fn load(source: Source, options: &RiOptions) -> Result<Loaded, RibError> {
    load_with(source, options, Permissions::default())
}

/// [`load`] with `permissions` (running `RunProgram` procedurals).
///
/// # Errors
///
/// As [`load`].
pub fn load_with(
    source: Source,
    options: &RiOptions,
    permissions: Permissions,
) -> Result<Loaded, RibError> {
    load_reporting(source, options, permissions).map_err(|(e, _)| e)
}

/// [`load`], keeping on an error the warnings gathered before it (in file order).
pub(crate) fn load_reporting(
    source: Source,
    options: &RiOptions,
    permissions: Permissions,
) -> Result<Loaded, (RibError, Vec<Warning>)> {
    // The machine follows ReadArchive itself: an inline archive (ArchiveBegin) is replayed,
    // a file is looked up along the archive search path and read in place.
    let reader_options =
        crate::ReaderOptions { strict: options.strict, ..crate::ReaderOptions::default() };
    let reader = Reader::with_options(source, reader_options);
    frame::Machine::new(reader, options.clone(), permissions).run()
}
