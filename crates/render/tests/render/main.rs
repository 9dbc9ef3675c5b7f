//! End-to-end tests of rendering, one test binary (ripgrep's habit): analytic coverage and
//! determinism through the whole pipeline, the golden images, CSG depths, the thin lens, the
//! pixel filters, both hiders against each other, the RenderMan geometry (hyperboloids, patch
//! meshes, NURBS), and RenderMan's cameras, lights and materials.

mod accuracy;
mod aovs;
mod blobby;
mod camera;
mod cracks;
mod csg;
mod csg_coverage;
mod filters;
mod geometry;
mod hair;
mod lens;
mod lookdev;
mod meshes;
mod occlusion;
mod pipeline;
mod raytrace;
mod rsl;
mod sampling;
mod shading;
mod silhouette;

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

/// `scene` rendered with `opts`, and its EXR file's bytes.
fn rendered_exr(
    scene: &Scene,
    opts: &reyes_render::RenderOptions,
) -> (reyes_render::Rendered, Vec<u8>) {
    let r = reyes_render::render(scene, opts).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.exr");
    reyes_film::write(&path, &r.film).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    (r, bytes)
}

/// The bits of `v`.
fn bits(v: impl IntoIterator<Item = f32>) -> Vec<u32> {
    v.into_iter().map(f32::to_bits).collect()
}

/// Two renders of one scene gave the same file, colours, depths and AOVs, bit for bit.
fn assert_same_output(
    name: &str,
    (a, a_exr): &(reyes_render::Rendered, Vec<u8>),
    (b, b_exr): &(reyes_render::Rendered, Vec<u8>),
) {
    assert!(a_exr == b_exr, "{name}: the EXRs differ");
    let rgba = |r: &reyes_render::Rendered| bits(r.film.rgba().iter().flatten().copied());
    assert_eq!(rgba(a), rgba(b), "{name}: colours");
    assert_eq!(
        bits(a.film.z().iter().copied()),
        bits(b.film.z().iter().copied()),
        "{name}: depths"
    );
    match (&a.aovs, &b.aovs) {
        (Some(x), Some(y)) => assert_eq!(
            bits(x.film.data().iter().copied()),
            bits(y.film.data().iter().copied()),
            "{name}: AOVs"
        ),
        (None, None) => {}
        _ => panic!("{name}: AOVs in one render only"),
    }
}
