//! End-to-end tests of rendering, one test binary (ripgrep's habit): analytic coverage and
//! determinism through the whole pipeline, the golden images, CSG depths, the thin lens, the
//! pixel filters, both hiders against each other, the RenderMan geometry (hyperboloids, patch
//! meshes, NURBS), and RenderMan's cameras, lights and materials.

mod accuracy;
mod aovs;
mod camera;
mod cracks;
mod csg;
mod filters;
mod geometry;
mod lens;
mod lookdev;
mod meshes;
mod occlusion;
mod pipeline;
mod raytrace;
mod sampling;
mod shading;
