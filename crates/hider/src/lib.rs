//! reyes-hider: a port of the stochastic hider of US 4,897,806, Appendix A (`ssvis.c`).
//!
//! Stage: takes one bucket's micropolygons, samples them at jittered positions, times and
//! lens positions, keeps per-sample visible-point lists, resolves them front to back, and
//! hands per-sample composites to the film stage. Single-threaded; the caller runs buckets
//! in parallel, each with its own [`Scratch`].
#![deny(missing_docs)]

pub mod frame;
pub mod lens;
pub mod mpoly;

pub use frame::{Frame, border_for_filter_width};
pub use lens::LensSetup;
pub use mpoly::{Micropolygon, flags};
