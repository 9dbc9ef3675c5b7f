//! End-to-end tests of rendering, one test binary (ripgrep's habit): analytic coverage and
//! determinism through the whole pipeline, the golden images, CSG depths, the thin lens, both
//! hiders against each other, and RenderMan's cameras, lights and materials.

mod camera;
mod csg;
mod lens;
mod pipeline;
mod raytrace;
