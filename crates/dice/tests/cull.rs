//! Back-face culling (`hider.cull_back_faces`): only micropolygons that face away from the
//! eye over their whole segment are dropped, about half of a ball's, and only where the
//! switch and the object allow it.

mod common;

use common::*;
use glam::Vec3;
use reyes_hider::Micropolygon;
use reyes_scene::{Material, Scene, Transform, TransformKey};

const W: u32 = 160;
const H: u32 = 120;
const FOV: f32 = 40.0;

/// Eye-space point of raster vertex `v` for the pinhole camera at the origin looking down +z.
fn eye_point(v: [f32; 3]) -> Vec3 {
    let k = 0.5 * W.min(H) as f32 / (0.5 * FOV.to_radians()).tan();
    Vec3::new((v[0] - 0.5 * W as f32) * v[2] / k, -(v[1] - 0.5 * H as f32) * v[2] / k, v[2])
}

/// How much the ball (centre `c`) faces the eye at the micropolygon's centroid: the cosine
/// between the outward normal and the direction to the eye (negative: facing away).
fn facing(mp: &Micropolygon, c: Vec3, t: f32) -> f32 {
    let p =
        mp.v.iter()
            .zip(&mp.speed)
            .map(|(v, s)| eye_point([v[0] + t * s[0], v[1] + t * s[1], v[2] + t * s[2]]))
            .sum::<Vec3>()
            / 4.0;
    (p - c).normalize().dot(-p.normalize())
}

fn ball_scene(cull: bool, moving: bool) -> Scene {
    let mut ball = object(sphere(1.0), vec![Transform::Translate([0.3, -0.2, 5.0])]);
    if moving {
        ball.motion = vec![
            TransformKey { time: 0.0, transform: vec![Transform::Translate([-0.6, -0.2, 5.0])] },
            TransformKey {
                time: 1.0,
                transform: vec![
                    Transform::Rotate { angle: 50.0, axis: [0.0, 1.0, 0.0] },
                    Transform::Translate([0.8, 0.1, 5.5]),
                ],
            },
        ];
    }
    let mut s = scene_ahead(W, H, FOV, vec![ball]);
    s.hider.cull_back_faces = cull;
    s
}

fn key(mp: &Micropolygon) -> Vec<u32> {
    bytemuck::cast_slice::<Micropolygon, u32>(std::slice::from_ref(mp)).to_vec()
}

#[test]
fn culled_micropolygons_face_away_and_are_about_half() {
    for moving in [false, true] {
        let (all, _) = dice(&ball_scene(false, moving));
        let (kept, _) = dice(&ball_scene(true, moving));
        assert_eq!(all.stats.backfacing, 0);
        let n = all.mpolys.len() as f64;
        let culled = kept.stats.backfacing as f64;
        // A ball seen from 5 radii shows 1/2 - 1/(2*5) of its surface... as area on the
        // sphere: the cap facing the eye is (1 - 1/d)/2 = 0.4 of it, so 0.6 faces away;
        // the margin of the winding test keeps the rim. Parametrisation is not uniform in
        // area, so allow a broad band around it.
        assert!((0.35..0.7).contains(&(culled / n)), "moving {moving}: {culled} of {n} culled");
        // Every culled micropolygon is one of the uncut set, and faces away (at both ends
        // of its segment when it moves); every kept one is in the uncut set too.
        let kept_keys: std::collections::HashSet<Vec<u32>> = kept.mpolys.iter().map(key).collect();
        assert_eq!(kept.mpolys.len() as f64 + culled, n);
        let mut dropped = 0;
        for mp in &all.mpolys {
            if kept_keys.contains(&key(mp)) {
                continue;
            }
            dropped += 1;
            // Centre of the ball at the micropolygon's segment ends (in eye space).
            let centre = |t: f32| {
                if moving {
                    let a = Vec3::new(-0.6, -0.2, 5.0);
                    let b = Vec3::new(0.8, 0.1, 5.5);
                    a.lerp(b, mp.time[0] + t * (mp.time[1] - mp.time[0]))
                } else {
                    Vec3::new(0.3, -0.2, 5.0)
                }
            };
            for t in [0.0, 1.0] {
                // Micropolygons are ~1 pixel; their centroid's normal is within a few
                // degrees of the flat quad's, so a small slack on the cosine.
                let f = facing(mp, centre(t), t);
                assert!(
                    f < 0.05,
                    "moving {moving}: a culled micropolygon faces the eye at t {t}: {f}, {:?} {:?} {:?}",
                    mp.v,
                    mp.speed,
                    mp.time
                );
            }
        }
        assert_eq!(dropped as f64, culled);
    }
}

#[test]
fn only_closed_opaque_plain_objects_under_a_pinhole_are_culled() {
    let count = |edit: &dyn Fn(&mut Scene)| {
        let mut s = ball_scene(true, false);
        edit(&mut s);
        dice(&s).0.stats.backfacing
    };
    assert!(count(&|_| {}) > 0);
    assert_eq!(count(&|s| s.hider.cull_back_faces = false), 0, "switch off");
    assert_eq!(
        count(&|s| s.objects[0].material =
            Material::Matte { color: [1.0; 3], opacity: [0.5; 3], ka: 1.0, kd: 1.0 }),
        0,
        "transparent"
    );
    assert_eq!(count(&|s| s.objects[0].matte = true), 0, "matte");
    assert_eq!(count(&|s| s.objects[0].glass = Some(0.5)), 0, "glass");
    assert_eq!(
        count(&|s| s.objects[0].shape = reyes_scene::Shape::Sphere {
            radius: 1.0,
            zmin: Some(-0.5),
            zmax: None,
            thetamax: 360.0
        }),
        0,
        "open (cut) sphere"
    );
    // Cylinders, cones and paraboloids are closed only by a solid's end caps: alone, their
    // insides show through their open ends.
    for shape in [
        reyes_scene::Shape::Cylinder { radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 360.0 },
        reyes_scene::Shape::Cone { height: 1.0, radius: 1.0, thetamax: 360.0 },
        reyes_scene::Shape::Paraboloid { rmax: 1.0, zmin: 0.0, zmax: 1.0, thetamax: 360.0 },
    ] {
        let name = shape.name();
        assert_eq!(count(&|s| s.objects[0].shape = shape.clone()), 0, "open {name}");
    }
    assert_eq!(
        count(&|s| s.camera.lens =
            Some(reyes_scene::Lens { focal_length: 1.0, f_stop: 2.8, focal_distance: 5.0 })),
        0,
        "lens"
    );
    // A mirroring transform flips the winding; the calibration against the normal keeps
    // culling the far side.
    assert!(count(&|s| s.objects[0].transform.insert(0, Transform::Scale([-1.0, 1.0, 1.0]))) > 0);
}

/// Culling before shading: a vertex is shaded only if a kept micropolygon uses it, so a
/// ball whose back faces are culled shades about half of its grid vertices plus a band,
/// and the same ball drawn two-sided shades all of them.
///
/// The bound, per grid of `nu x nv` cells (one micropolygon per kept cell, the ball being
/// still): give each shaded vertex `(i, j)` the cell `(i, j)` it is corner 0 of. Where that
/// cell is kept, this is one-to-one into the `K` kept cells. Where it is not, either the cell
/// does not exist (`i = nu` or `j = nv`: `nu + nv + 1` vertices per grid, `V - C` over the
/// scene, `V` the vertices diced and `C` the cells), or it is a culled cell sharing the
/// vertex with a kept one (the vertex is shaded for a kept cell it is a corner of), again
/// one-to-one. So `shaded <= K + (V - C) + R`, `R` the culled cells that share a vertex
/// with a kept cell: the band along the silhouette. `R` is counted here from the two-sided
/// dicing (the same grids): a culled micropolygon with a corner bit for bit at a kept one's
/// (corners of different grids or at a pole that happen to coincide only make `R` larger).
#[test]
fn a_ball_shades_about_half_its_vertices() {
    let (all, _) = dice(&ball_scene(false, false));
    let (kept, _) = dice(&ball_scene(true, false));
    // Two-sided: every diced vertex is used, and shaded.
    assert_eq!(all.stats.shaded, all.stats.vertices);
    assert_eq!(all.stats.culled, 0, "the ball is on screen and in front of the eye");
    assert_eq!(kept.stats.vertices, all.stats.vertices, "the same grids");
    let v = all.stats.vertices;
    let c = all.mpolys.len() as u64;
    let k = kept.mpolys.len() as u64;
    assert_eq!(k + kept.stats.backfacing, c);
    let kept_keys: std::collections::HashSet<Vec<u32>> = kept.mpolys.iter().map(key).collect();
    let corner_bits = |mp: &Micropolygon| mp.v.map(|p| p.map(f32::to_bits));
    let kept_corners: std::collections::HashSet<[u32; 3]> =
        kept.mpolys.iter().flat_map(corner_bits).collect();
    let band = all
        .mpolys
        .iter()
        .filter(|mp| !kept_keys.contains(&key(mp)))
        .filter(|mp| corner_bits(mp).iter().any(|p| kept_corners.contains(p)))
        .count() as u64;
    let bound = k + (v - c) + band;
    let shaded = kept.stats.shaded;
    assert!(shaded <= bound, "{shaded} vertices shaded, bound {bound} = {k} + {} + {band}", v - c);
    // Not vacuous: the bound is well below shading every vertex, and so is the count: the
    // cap facing the eye from 5 radii is 0.4 of the sphere.
    assert!(bound < v * 7 / 10, "bound {bound} of {v} vertices");
    assert!(shaded < v * 6 / 10, "{shaded} of {v} vertices shaded");
}
