//! End-to-end tests of rendering, one test binary (ripgrep's habit): analytic coverage and
//! determinism through the whole pipeline, the golden images, CSG depths, the thin lens, the
//! pixel filters, and both hiders against each other.

mod csg;
mod filters;
mod lens;
mod pipeline;
mod raytrace;
