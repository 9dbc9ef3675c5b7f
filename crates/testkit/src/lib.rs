//! reyes-testkit: what the tests of several crates share, so that none of them keeps a copy.
//! A dev-dependency only (and of xtask): no shipping crate depends on it.
//!
//! - [`coverage`]: fields of small shapes, for coverage against exact projected areas;
//! - [`docs`]: the fenced examples of the Markdown documents;
//! - [`golden`]: the golden-image harness (`golden/manifest.ron`, tolerances, bless);
//! - [`geometry`]: exact areas of clipped polygons, the analytic truth of coverage tests;
//! - [`image`]: comparing films (PSNR);
//! - [`random`]: pseudo-random test inputs, the same on every run;
//! - [`shading`]: closed forms of the Shading Language (smoothstep) for shading tests;
//! - [`textures`]: the texture maps of the look-development scenes and tests, made by code;
//! - [`fixtures`]: scenes and objects built in code, and the frame a scene lays out.
#![deny(missing_docs)]

pub mod coverage;
pub mod docs;
pub mod files;
pub mod fixtures;
pub mod geometry;
pub mod golden;
pub mod image;
pub mod random;
pub mod shading;
pub mod textures;
