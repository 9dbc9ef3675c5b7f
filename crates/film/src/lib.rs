//! reyes-film: reconstruction filtering and image output.
//!
//! Stage: after the hider. Per frame, [`FilterTable::new`] builds the normalised filter table
//! from the kernels and weights of [`reyes_scene::filter`]
//! (Appendix A `tablesinit`); per bucket, [`splat`] filters the per-sample composites into a
//! bordered [`Window`] (Appendix A `filter` / `applyboxfilter`); [`Film::add`] sums the
//! overlapping windows into the image in a fixed bucket order (3.17); [`write()`] stores the
//! image atomically as OpenEXR or PNG, through an unnamed temporary
//! file where the system allows ([`atomic`]).
//!
//! Invariants: colour is premultiplied linear light throughout; filter tables sum to 1, so a
//! fully covered interior pixel has unit gain; our kernel fixes are the default and the
//! original 1985 shapes are behind [`reyes_scene::Original`].
#![deny(missing_docs)]

pub mod aov;
pub mod atomic;
pub mod early;
pub mod error;
pub mod image;
pub mod layers;
pub mod output;
pub mod points;
pub mod table;
pub mod tiles;
pub mod window;

/// The kernels live in the scene crate, whose validation evaluates the same filter sums as
/// [`FilterTable`]; they are re-exported here where the film stage always had them.
pub use reyes_scene::filter::{kernel, renderman};

pub use self::image::Film;
pub use aov::{AovChannels, AovFilm, AovSamples, AovWindow, splat_aovs};
pub use atomic::{WriteOptions, remove_stale_temporaries};
pub use early::EarlyBlocks;
pub use error::FilmError;
pub use kernel::{bessel_j1, weight};
pub use layers::{
    AovLayer, Metadata, Picture, Placement, ReadChannel, as_stored, bayer8, read_layers,
    view_pixel, write_picture,
};
pub use output::{read_exr, srgb_decode, srgb_encode, write, write_with};
pub use points::splat_points;
pub use table::{FilterTable, border_for_width};
pub use tiles::{BucketFile, StoredBucket, read_buckets, write_buckets};
pub use window::{Window, splat};
