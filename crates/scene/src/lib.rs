//! reyes-scene: the scene model, RON parsing and validation.
//!
//! Stage: first in the pipeline. Produces an immutable, validated [`Scene`] that every later
//! stage borrows.
#![deny(missing_docs)]

pub mod model;

pub use model::*;
