//! Measures single-thread primary-ray throughput of `reyes-trace`.
//!
//! Two scenes of at least 10,000 primitives: a 100 x 100 grid of small spheres (each one
//! quadric under a transform) and a height-field mesh of 20,000 triangles. For each,
//! 1000 x 1000 pinhole primary rays (or `N x N` with the argument `N`) are traced on one thread with `intersect`, then the
//! same rays with `occluded`; the rate is printed. Run with
//! `cargo run --release -p reyes-trace --example rays_per_second`.

use std::path::Path;
use std::time::Instant;

use glam::Vec3;
use reyes_scene::{Faces, Object, Scene, Shape, Transform};
use reyes_trace::{Ray, Tracer};

const BASE: &str = "Scene(image: (width: 64, height: 64), \
    camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0)), \
    objects: [(shape: Sphere(radius: 1.0), material: Constant(color: (1.0, 1.0, 1.0)))])";

/// The parsed base scene (one template object) or an explanation.
fn base() -> Result<Scene, String> {
    reyes_scene::parse(BASE, Path::new("base.ron")).map_err(|e| e.to_string())
}

fn with_objects(objects: Vec<Object>) -> Result<Scene, String> {
    let mut scene = base()?;
    scene.objects = objects;
    Ok(scene)
}

fn spheres(template: &Object) -> Vec<Object> {
    let mut out = Vec::with_capacity(10_000);
    for j in 0..100 {
        for i in 0..100 {
            let mut o = template.clone();
            o.shape = Shape::Sphere { radius: 0.07, zmin: None, zmax: None, thetamax: 360.0 };
            let (x, y) = ((i as f32 - 49.5) * 0.2, (j as f32 - 49.5) * 0.2);
            let z = 0.3 * (x * 0.7).sin() * (y * 0.5).cos();
            o.transform = vec![Transform::Translate([x, y, z])];
            out.push(o);
        }
    }
    out
}

fn mesh(template: &Object) -> Vec<Object> {
    let n = 101u32;
    let mut points = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = ((i as f32 - 50.0) * 0.2, (j as f32 - 50.0) * 0.2);
            points.push([x, y, 0.3 * (x * 0.7).sin() * (y * 0.5).cos()]);
        }
    }
    let mut faces = Faces::with_capacity(20_000, 60_000);
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let at = |i: u32, j: u32| j * n + i;
            faces.push(&[at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            faces.push(&[at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let mut o = template.clone();
    o.shape = Shape::Mesh { points, faces, colors: None, normals: None, st: None };
    o.transform = vec![];
    vec![o]
}

/// Pinhole primary rays from (0, 0, -25) over a `res` x `res` image covering the grid.
fn primary(res: u32) -> impl Iterator<Item = Ray> {
    let eye = Vec3::new(0.0, 0.0, -25.0);
    let half = (22.0_f32.to_radians() * 0.5).tan();
    (0..res * res).map(move |k| {
        let (px, py) = (k % res, k / res);
        let sx = ((px as f32 + 0.5) / res as f32 * 2.0 - 1.0) * half;
        let sy = ((py as f32 + 0.5) / res as f32 * 2.0 - 1.0) * half;
        Ray::new(eye, Vec3::new(sx, sy, 1.0), (k % 17) as f32 / 16.0)
    })
}

fn measure(name: &str, scene: &Scene, res: u32) {
    let start = Instant::now();
    let tracer = Tracer::new(scene);
    let build = start.elapsed().as_secs_f64();
    let count = f64::from(res * res);
    let start = Instant::now();
    let mut hits = 0u64;
    let mut depth = 0.0f64;
    for ray in primary(res) {
        if let Some(h) = tracer.intersect(&ray, f32::INFINITY) {
            hits += 1;
            depth += f64::from(h.t);
        }
    }
    let closest = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let mut blocked = 0u64;
    for ray in primary(res) {
        blocked += u64::from(tracer.occluded(&ray, f32::INFINITY));
    }
    let any = start.elapsed().as_secs_f64();
    println!(
        "{name}: {} primitives, {} nodes, build {:.3} s; intersect {:.2} Mrays/s ({hits} hits, mean t {:.3}); occluded {:.2} Mrays/s ({blocked} blocked)",
        tracer.primitive_count(),
        tracer.node_count(),
        build,
        count / closest / 1e6,
        depth / hits.max(1) as f64,
        count / any / 1e6,
    );
}

fn main() -> Result<(), String> {
    let template = base()?.objects.into_iter().next().ok_or("the base scene has an object")?;
    let res = match std::env::args().nth(1) {
        Some(arg) => arg.parse().map_err(|e| format!("resolution {arg:?}: {e}"))?,
        None => 1000,
    };
    measure("100x100 spheres", &with_objects(spheres(&template))?, res);
    measure("20,000-triangle mesh", &with_objects(mesh(&template))?, res);
    Ok(())
}
