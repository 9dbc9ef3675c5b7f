//! Occlusion culling (`hider.occlusion_cull`, issue #13) never changes the picture: every
//! scene here renders to the same EXR bytes, depths and AOVs bit for bit with culling on and
//! off, while culling does cull (so the comparison is not vacuous). The scenes cover what could
//! make the bits differ (`crates/hider/src/bucket/occlusion.rs`): opaque, transparent, glass,
//! matte (both rules), CSG, motion blur, depth of field and both together, the `original`
//! switches, adaptive refinement, AOVs, and coincident surfaces whose depths tie, where the
//! order of a sample's visible points decides which is seen.

use reyes_render::{RenderOptions, Rendered};
use reyes_scene::Scene;

use crate::{assert_same_output, rendered_exr, scene_file};
use reyes_testkit::fixtures;

fn render_with(scene: &Scene, cull: bool) -> (Rendered, Vec<u8>) {
    let mut scene = scene.clone();
    scene.hider.occlusion_cull = cull;
    rendered_exr(&scene, &RenderOptions { threads: Some(2), ..Default::default() })
}

/// Render `scene` both ways and require identical output; returns the micropolygons culled
/// whole and the sample tests skipped with culling on.
fn same_with_and_without(name: &str, scene: &Scene) -> (u64, u64) {
    let (a, b) = (render_with(scene, true), render_with(scene, false));
    assert_same_output(name, &a, &b);
    let (on, off) = (a.0, b.0);
    let (h_on, h_off) = (&on.stats.hider, &off.stats.hider);
    assert_eq!((h_off.occlusion_culled, h_off.occluded_tests), (0, 0), "{name}: culling off");
    // Culling only removes work: never more tests, and the same visits of micropolygons.
    assert_eq!(h_on.micropolygons, h_off.micropolygons, "{name}");
    assert!(h_on.hits + h_on.misses <= h_off.hits + h_off.misses, "{name}");
    (h_on.occlusion_culled, h_on.occluded_tests)
}

#[test]
fn the_scenes_render_the_same_with_and_without_culling() {
    type Edit = fn(&mut Scene);
    let none: Edit = |_| {};
    let cases: [(&str, &str, Edit); 13] = [
        ("spheres", "spheres", none),
        ("pool balls", "pool-balls", none),
        ("transparency", "transparency", none),
        ("CSG and glass", "csg", none),
        ("motion blur", "motion-blur", none),
        ("depth of field", "depth-of-field", none),
        ("motion and depth of field", "motion-dof", none),
        ("AOVs", "aovs", none),
        ("look development", "lookdev", none),
        ("RenderMan geometry", "ri-geometry", none),
        ("every original switch, motion and lens", "motion-dof", |s| {
            let o = &mut s.hider.original;
            (o.permute, o.jitter_tables, o.time_pairing, o.lens) = (true, true, true, true);
            (o.moving_clip, o.matte, o.csg_order, o.linear_motion) = (true, true, true, true);
        }),
        ("every original switch, CSG", "csg", |s| {
            let o = &mut s.hider.original;
            (o.matte, o.csg_order, o.moving_clip) = (true, true, true);
        }),
        ("adaptive sampling", "motion-dof", |s| {
            s.hider.pixel_samples = (4, 4);
            s.hider.adaptive.max_level = 2;
            s.hider.adaptive.threshold = 0.05;
        }),
    ];
    let mut culled = 0;
    for (name, file, edit) in cases {
        let (c, _) = same_with_and_without(name, &scene_file(file, edit));
        culled += c;
    }
    assert!(culled > 0, "nothing was culled");
}

/// Coincident spheres of different colours, opaque and transparent, matte (under both rules)
/// and moving, in front of a wall: their depths tie exactly, so which is seen depends on the
/// order of the sample's visible points, which culling must keep.
#[test]
fn ties_matte_and_transparency_are_kept() {
    let text = |original_matte: bool, lens: &str| {
        format!(
            r#"Scene(
  image: (width: 64, height: 48),
  camera: (eye: (0.0, 0.0, -6.0), look_at: (0.0, 0.0, 0.0), fov: 40.0, lens: {lens}),
  hider: (pixel_samples: (4, 4), seed: 3, original: (matte: {original_matte})),
  lights: [Ambient(intensity: 0.3), Distant(from: (1.0, 1.0, -1.0))],
  objects: [
    (name: "red", shape: Sphere(radius: 1.0), material: Matte(color: (0.9, 0.1, 0.1))),
    (name: "green", shape: Sphere(radius: 1.0), material: Matte(color: (0.1, 0.9, 0.1))),
    (name: "blue", shape: Sphere(radius: 1.0), transform: [Translate((0.6, 0.0, 0.0))],
     material: Matte(color: (0.1, 0.1, 0.9))),
    (name: "veil", shape: Sphere(radius: 1.0), transform: [Translate((0.6, 0.0, 0.0))],
     material: Matte(color: (0.9, 0.9, 0.9), opacity: (0.5, 0.5, 0.5))),
    (name: "hole", shape: Disk(radius: 0.6), transform: [Translate((-0.8, 0.3, -1.5))],
     material: Constant(color: (0.0, 0.0, 0.0)), matte: true),
    (name: "hole behind", shape: Disk(radius: 0.6), transform: [Translate((0.9, -0.3, 0.5))],
     material: Constant(color: (0.0, 0.0, 0.0)), matte: true),
    (name: "mover", shape: Sphere(radius: 0.5), material: Matte(color: (0.9, 0.9, 0.1)),
     motion: [(time: 0.0, transform: [Translate((0.0, -0.6, -0.4))]),
              (time: 1.0, transform: [Translate((1.0, -0.6, 0.6))])]),
    (name: "wall", shape: Disk(radius: 8.0), transform: [Translate((0.0, 0.0, 3.0))],
     material: Matte(color: (0.5, 0.5, 0.5))),
  ],
)"#
        )
    };
    let mut culled = 0;
    for original_matte in [false, true] {
        for lens in ["None", "Some((focal_length: 0.2, f_stop: 2.0, focal_distance: 6.0))"] {
            let scene = fixtures::parse(&text(original_matte, lens));
            let name = format!("ties, original matte {original_matte}, lens {lens}");
            culled += same_with_and_without(&name, &scene).0;
        }
    }
    assert!(culled > 0, "nothing was culled");
}
