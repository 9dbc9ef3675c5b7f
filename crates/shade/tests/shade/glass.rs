//! Refraction through a glass slab (FIG. 21): the lateral displacement of a ray.
//!
//! A closed box mesh `|x|, |y| <= 50`, `0 <= z <= D` of index `N`, black and opaque but
//! fully transmitting; behind it, at z = 5, a white wall covering x < 0 (nothing for x > 0).
//! A ray leaving (x0, 0, -1) at incidence theta in the xz plane crosses the slab and comes
//! out parallel to itself, displaced sideways by
//! `delta = D sin(theta) (1 - cos(theta) / sqrt(N^2 - sin^2 theta))`, i.e. by
//! `delta / cos(theta)` along x on the wall: the wall's edge x = 0 is seen from the ray
//! start x0* = delta / cos(theta) - tan(theta) (5 + 1).

use glam::Vec3;
use reyes_shade::Shading;
use reyes_trace::Ray;

use crate::common::{patch, scene, trace_one, tracer};

const D: f32 = 1.0;
const N: f32 = 1.5;
const WALL_Z: f32 = 5.0;

/// A RON mesh of the box `lo..hi` with every face wound so that the tracer's normal points
/// out of the box when `outward`, into it otherwise.
fn box_mesh(lo: Vec3, hi: Vec3, outward: bool) -> String {
    let corner = |i: usize| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    let pts: Vec<String> =
        (0..8).map(corner).map(|p| format!("({:?}, {:?}, {:?})", p.x, p.y, p.z)).collect();
    // Each face: the four corners with bit `axis` equal to `side`, in order around it.
    let mut faces = Vec::new();
    for axis in 0..3 {
        for side in 0..2 {
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let bit = |k: usize, v: usize| v << k;
            let base = bit(axis, side);
            let mut f = [base, base | bit(a, 1), base | bit(a, 1) | bit(b, 1), base | bit(b, 1)];
            // (P1 - P0) x (P3 - P0) along the side's outward direction, then as asked.
            let n = (corner(f[1]) - corner(f[0])).cross(corner(f[3]) - corner(f[0]));
            let mut out = Vec3::ZERO;
            out[axis] = if side == 1 { 1.0 } else { -1.0 };
            if (n.dot(out) > 0.0) != outward {
                f.reverse();
            }
            faces.push(format!("[{}, {}, {}, {}]", f[0], f[1], f[2], f[3]));
        }
    }
    format!("Mesh(points: [{}], faces: [{}])", pts.join(", "), faces.join(", "))
}

fn setup(outward: bool) -> reyes_scene::Scene {
    let slab = format!(
        "(shape: {}, material: Constant(color: (0.0, 0.0, 0.0)), \
          refract: Some((ior: {N:?}, color: (1.0, 1.0, 1.0))))",
        box_mesh(Vec3::new(-50.0, -50.0, 0.0), Vec3::new(50.0, 50.0, D), outward)
    );
    let wall = patch(
        Vec3::new(-100.0, -100.0, WALL_Z),
        Vec3::new(100.0, 0.0, 0.0),
        Vec3::new(0.0, 200.0, 0.0),
        "material: Constant(color: (1.0, 1.0, 1.0))",
    );
    scene(&format!("objects: [{slab}, {wall}], raytrace: (max_depth: 4)"))
}

#[test]
fn slab_displaces_the_edge_by_the_textbook_amount() {
    // Find the winding whose normals the tracer reports pointing out of the box (the
    // refraction's entering / leaving test relies on outward normals).
    let s = [setup(true), setup(false)]
        .into_iter()
        .find(|s| {
            let t = tracer(s);
            let hit =
                t.intersect(&Ray::new(Vec3::new(0.0, 0.0, -1.0), Vec3::Z, 0.0), f32::INFINITY);
            hit.is_some_and(|h| h.object == 0 && h.n_world.z < -0.99)
        })
        .expect("one winding faces out");
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    for theta_deg in [0.0f32, 15.0, 30.0, 45.0, 60.0] {
        let theta = theta_deg.to_radians();
        let dir = Vec3::new(theta.sin(), 0.0, theta.cos());
        let delta = D * theta.sin() * (1.0 - theta.cos() / (N * N - theta.sin().powi(2)).sqrt());
        let want = delta / theta.cos() - theta.tan() * (WALL_Z + 1.0);
        // Scan K rays across [want - 0.5, want + 0.5]: the edge lies between the last ray
        // that sees white and the first that sees black, so their midpoint is within half
        // a step (0.5e-3) of it; the spawn nudges (1e-5 (1 + |p|) ~ 2e-5 along z at each
        // face, moving the ray by tan(theta) times that along x) add under 1e-4.
        let k = 1001;
        let step = 1.0 / (k - 1) as f32;
        let mut edge = None;
        let mut prev_white = true;
        for i in 0..k {
            // A quarter step off the grid, so that no ray sits exactly on the edge.
            let x0 = want - 0.5 + (i as f32 + 0.25) * step;
            let white =
                trace_one(&shading, &Ray::new(Vec3::new(x0, 0.0, -1.0), dir, 0.0)).rgba[0] > 0.5;
            if i == 0 {
                assert!(white, "theta {theta_deg}: the scan must start on the white side");
            }
            if prev_white && !white && edge.is_none() {
                edge = Some(x0 - 0.5 * step);
            }
            prev_white = white;
        }
        let edge = edge.unwrap_or(f32::NAN);
        let tol = 0.5 * step + 1e-4;
        eprintln!("slab theta {theta_deg}: edge from x0 = {edge:.5}, expected {want:.5}");
        assert!((edge - want).abs() <= tol, "theta {theta_deg}: edge {edge} vs {want}");
    }
}
