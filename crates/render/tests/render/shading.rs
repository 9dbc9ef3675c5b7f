//! Culling before shading (issue #13): the dicer shades only the grid vertices that kept
//! micropolygons use, and that never changes the picture. Every scene here renders to the
//! same EXR bytes, depths and AOVs bit for bit as with every vertex shaded
//! (`RenderOptions::shade_every_vertex`), while fewer vertices are shaded (so the comparison
//! is not vacuous). The scenes cover what shading a subset could get wrong: back faces and
//! off-screen cells dropped, crack-free boundaries (corners on a polyline, shading at the
//! surface point), displacement, texture maps, bump and emission, the ray-traced vertex
//! shader (whose rays are drawn per vertex from its tile of the grid), AOVs, CSG, motion
//! blur (cells kept over part of the shutter) and depth of field.

use reyes_render::{RenderOptions, Rendered};
use reyes_scene::Scene;

use crate::{assert_same_output, rendered_exr, scene_file};

fn render_with(scene: &Scene, shade_every_vertex: bool) -> (Rendered, Vec<u8>) {
    rendered_exr(
        scene,
        &RenderOptions { threads: Some(2), shade_every_vertex, ..Default::default() },
    )
}

/// Render `scene` shading every vertex and shading only the used ones; require identical
/// output and counts but for the vertices shaded. Returns (vertices shaded, diced, whether
/// the ray-traced vertex shader shaded them).
fn same_either_way(name: &str, scene: &Scene) -> (u64, u64, bool) {
    let (u, a) = (render_with(scene, false), render_with(scene, true));
    assert_same_output(name, &u, &a);
    let (used, all) = (u.0, a.0);
    let (u, a) = (&used.stats, &all.stats);
    // The same dicing and hiding: only the vertices shaded differ.
    assert_eq!(u.micropolygons, a.micropolygons, "{name}");
    assert_eq!((u.dice.grids, u.dice.culled), (a.dice.grids, a.dice.culled), "{name}");
    assert_eq!(u.hider.hits + u.hider.misses, a.hider.hits + a.hider.misses, "{name}");
    assert_eq!(u.dice.vertices, a.dice.vertices, "{name}");
    assert_eq!(a.dice.shaded, a.dice.vertices, "{name}: shading every vertex");
    assert!(u.dice.shaded <= u.dice.vertices, "{name}");
    // The ray-traced vertex shader counts what it was asked to shade.
    if let (Some(ru), Some(ra)) = (&u.rays, &a.rays) {
        assert_eq!(ru.vertices, u.dice.shaded, "{name}: ray-traced vertices");
        assert_eq!(ra.vertices, a.dice.vertices, "{name}: ray-traced vertices, all shaded");
    }
    (u.dice.shaded, u.dice.vertices, u.rays.is_some())
}

#[test]
fn the_scenes_render_the_same_shading_only_the_vertices_used() {
    type Edit = fn(&mut Scene);
    let none: Edit = |_| {};
    let cases: [(&str, &str, Edit); 13] = [
        ("spheres", "spheres", none),
        ("pool balls: ray-traced vertex shading", "pool-balls", none),
        ("transparency", "transparency", none),
        ("CSG and glass", "csg", none),
        ("motion blur", "motion-blur", none),
        ("depth of field", "depth-of-field", none),
        ("motion and depth of field", "motion-dof", none),
        ("AOVs", "aovs", none),
        ("look development: displacement, maps, bump, emission", "lookdev", none),
        ("RenderMan geometry", "ri-geometry", none),
        ("subdivision surfaces", "subdivision", none),
        ("without crack-free dicing", "spheres", |s| s.hider.crack_free = false),
        ("a narrower view", "pool-balls", |s| {
            // Cells off screen are dropped too.
            s.camera.fov *= 0.4;
        }),
    ];
    let (mut shaded, mut diced, mut traced) = (0, 0, false);
    for (name, file, edit) in cases {
        let (s, d, rays) = same_either_way(name, &scene_file(file, edit));
        shaded += s;
        diced += d;
        traced |= rays && s < d;
    }
    assert!(shaded < diced, "no vertex went unshaded: {shaded} of {diced}");
    assert!(traced, "no ray-traced vertex shading left vertices unshaded");
}
