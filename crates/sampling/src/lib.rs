//! reyes-sampling: every source of randomness the renderer has, in one leaf crate.
//!
//! Stage: none; a leaf used by the hider (sample tables), the shading (distributed rays),
//! measurement (FIG. 23) and the sampling study. Nothing here has global state: every number
//! is a pure function of a seed and the integers that name it (bucket, pixel, sample,
//! dimension), so images are the same for any thread count and bucket order.
//!
//! - [`rng`]: the SplitMix64 mix, a hash of a seed and integers, SplitMix64 streams
//!   (Appendix A's `drand()` is one), and the conversions to uniform floats.
//! - [`permute`]: the two permutations, named by what they mean: [`permute::bit_reversal`]
//!   (Appendix A's `permute`, made a bijection for every `n`, with the original as printed
//!   beside it) and [`permute::keyed`] (a pseudo-random permutation chosen by a key).
//! - [`strata`]: stratified streams of secondary-ray choices across a set of samples.
//! - [`shutter`]: the shutter's time density and its warp of uniform times.
#![deny(missing_docs)]

pub mod permute;
pub mod rng;
pub mod shutter;
pub mod strata;

pub use rng::{Drand, SplitMix64, hash, mix64, unit, unit_f64};
pub use shutter::ShutterShape;
pub use strata::Strata;
