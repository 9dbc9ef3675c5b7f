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

use reyes_scene::Scene;
use reyes_testkit::golden;

/// A scene file of `scenes/` at 120 pixels wide (its aspect kept), edited by `edit`: the
/// scenes the culling and shading-order tests render both ways.
fn scene_file(name: &str, edit: impl Fn(&mut Scene)) -> Scene {
    let root = golden::workspace_root();
    let mut scene = reyes_scene::load(&root.join(format!("scenes/{name}.ron"))).unwrap();
    let (w, h) = (scene.image.width, scene.image.height);
    scene.image.width = 120;
    scene.image.height = (120 * h / w).max(1);
    edit(&mut scene);
    scene
}
