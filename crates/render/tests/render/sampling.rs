//! The samplers and sampling modes of issue #14 through the whole pipeline: the joint sampler,
//! adaptive sampling and perspective-correct motion give byte-identical images for any thread
//! count, and adaptive sampling reports what it did.

use reyes_render::{RenderOptions, render};
use reyes_scene::{Scene, SpatialPattern};
use reyes_testkit::golden;

/// `scenes/motion-dof.ron` (moving and out of focus, so every path runs) at a small size,
/// with 4 x 4 samples (its own 5 x 5 would make the joint sampler fall back to FIG. 6).
fn scene(edit: impl Fn(&mut Scene)) -> Scene {
    let root = golden::workspace_root();
    let mut scene = reyes_scene::load(&root.join("scenes/motion-dof.ron")).unwrap();
    scene.image.width = 96;
    scene.image.height = 64;
    scene.hider.pixel_samples = (4, 4);
    edit(&mut scene);
    scene
}

/// The EXR file of `scene` rendered with `threads` threads.
pub(crate) fn exr_bytes(scene: &Scene, threads: usize) -> Vec<u8> {
    let film = render(scene, &RenderOptions { threads: Some(threads), ..Default::default() })
        .unwrap()
        .film;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.exr");
    reyes_film::write(&path, &film).unwrap();
    std::fs::read(&path).unwrap()
}

#[test]
fn new_sampling_options_are_byte_identical_for_any_thread_count() {
    type Edit = fn(&mut Scene);
    let cases: [(&str, Edit); 4] = [
        ("SobolJoint", |s| s.hider.pattern = SpatialPattern::SobolJoint),
        ("adaptive", |s| {
            s.hider.adaptive.max_level = 2;
            s.hider.adaptive.threshold = 0.05;
        }),
        ("SobolJoint + adaptive", |s| {
            s.hider.pattern = SpatialPattern::SobolJoint;
            s.hider.adaptive.max_level = 3;
        }),
        ("straight motion", |s| s.hider.original.linear_motion = true),
    ];
    for (name, edit) in cases {
        let s = scene(edit);
        let one = exr_bytes(&s, 1);
        assert_eq!(one, exr_bytes(&s, 2), "{name}: 2 threads");
        assert_eq!(one, exr_bytes(&s, 8), "{name}: 8 threads");
    }
}

#[test]
fn adaptive_sampling_refines_edges_and_counts_its_samples() {
    let plain = scene(|s| s.hider.pattern = SpatialPattern::SobolJoint);
    let adaptive = scene(|s| {
        s.hider.pattern = SpatialPattern::SobolJoint;
        s.hider.adaptive.max_level = 2;
    });
    let opts = RenderOptions { threads: Some(2), ..Default::default() };
    let a = render(&plain, &opts).unwrap();
    let b = render(&adaptive, &opts).unwrap();
    let (ha, hb) = (a.stats.hider, b.stats.hider);
    assert_eq!((ha.refined_pixels, ha.extra_samples), (0, 0));
    let pixels = 96 * 64;
    assert!(hb.refined_pixels > 0 && hb.refined_pixels < pixels, "{hb:?}");
    // Each refined pixel gets 4 NS samples at level 1, and at most 4 NS more per leaf split.
    let ns = (adaptive.hider.pixel_samples.0 * adaptive.hider.pixel_samples.1) as u64;
    assert!(hb.extra_samples >= 4 * ns * hb.refined_pixels, "{hb:?}");
    assert!(hb.extra_samples <= (4 + 16) * ns * hb.refined_pixels, "{hb:?}");
    assert!(b.stats.counts().contains(&format!(
        " Adaptive sampling: {} pixels refined, {} extra samples",
        hb.refined_pixels, hb.extra_samples
    )));
    assert!(!a.stats.counts().contains("Adaptive"));
    // Unrefined pixels keep their own samples: only refined pixels and the neighbours their
    // filter footprint reaches (3 x 3 for this scene's width-2 Gaussian) change.
    let changed = (0..64)
        .flat_map(|y| (0..96).map(move |x| (x, y)))
        .filter(|&(x, y)| a.film.pixel(x, y) != b.film.pixel(x, y))
        .count() as u64;
    assert!(changed > 0 && changed <= hb.refined_pixels * 9, "{changed} pixels changed");
}
