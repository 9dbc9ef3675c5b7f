//! Frames in pieces, for any front end (the `reyes-render` command, a language binding, a
//! render server): the farm contract of docs/farm.md on top of the render library.
//!
//! - [`job`]: one run as a front end asks for it: a scene file's frames with the overrides
//!   applied ([`plan`]), and each frame rendered and written, whole, as a tile, or resumed
//!   from a checkpoint ([`FrameJob`]).
//! - [`fingerprint()`]: which render a piece belongs to.
//! - [`tile`]: which buckets a tile renders; [`piece`]: the tile file and its header;
//!   [`merge()`]: tiles reassembled into the whole render's file, byte for byte.
//! - [`checkpoint`]: every finished bucket written as it completes, and read back to resume.
//! - [`progress`]: the plain progress line and the time-left estimate.
//! - [`output`]: output names (frame numbers, extra outputs), their checks, and writing a
//!   frame's file as the scene asks.
//! - [`slurm`]: job scripts for a Slurm array job and its merge job, their submission, and
//!   their state read back.
//! - [`testing`]: the test hooks of docs/reliability.md, which pause a run at a known point.
//!
//! Invariant: nothing here prints. Warnings go to the caller's `warn` callback, one line
//! each; errors are [`FarmError`]s whose messages are one line, with control characters in
//! paths and names escaped ([`one_line`]).

pub mod checkpoint;
pub mod depth;
pub mod error;
pub mod fingerprint;
pub mod frames;
pub mod job;
pub mod merge;
pub mod output;
pub mod piece;
pub mod progress;
pub mod slurm;
pub mod testing;
pub mod tile;

pub use checkpoint::Checkpoint;
pub use error::{FarmError, one_line};
pub use fingerprint::fingerprint;
pub use frames::FrameList;
pub use job::{
    FrameJob, FramePlan, Overrides, RenderedFrame, Request, WriteHooks, load_one_frame, plan,
};
pub use merge::merge;
pub use piece::{Header, Piece};
pub use progress::{Estimator, ProgressLines};
pub use tile::Tile;

/// The renderer's version, which every piece records: pieces of different versions are never
/// mixed.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// A small valid scene (a sphere, 32 x 24 pixels, 2 x 2 buckets of 16) for the unit tests.
#[cfg(test)]
pub(crate) fn test_scene() -> reyes_scene::Scene {
    let text = "Scene(
  image: (width: 32, height: 24),
  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 40.0, hither: 0.1, yon: 100.0),
  hider: (pixel_samples: (2, 2), filter: (kind: Gaussian, width: 2.0)),
  lights: [Ambient(intensity: 1.0)],
  objects: [(name: \"ball\", shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 0.5, 0.2)))],
)";
    reyes_scene::parse(text, std::path::Path::new("t.ron")).expect("the test scene")
}
