//! `cargo xtask rate [SCENE...]`: how the dicer's micropolygons compare with the shading
//! rate (issue #13). RenderMan's `ShadingRate` is the target area of a micropolygon in
//! raster pixels; this measures, over every grid the dicer makes (before any micropolygon
//! is culled, back faces included), each micropolygon's raster area at shutter open divided
//! by its object's shading rate, and prints the mean, quantiles and a histogram in powers
//! of two, per micropolygon and per grid (a grid's mean area over the rate, the quantity
//! the dicing rule aims at).
//!
//! How: the scene is diced with a vertex shader hooked in (`DiceOptions::vertex_shader`),
//! which the dicer calls once for every vertex of every grid at shutter open, with the
//! grid's place and size; the shader records the vertex's world position and shades
//! nothing. The grids are then rebuilt and projected through the camera at shutter open.
//! A boundary vertex is recorded at its surface point, not at the crack-free polyline
//! point its micropolygon corner uses (at most the edge tolerance, 0.05 pixel, apart).
//! The rate divided by is the object's `shading_rate` or `hider.shading_rate`, not grown
//! by the motion and focus factors (`scenes/bench/*-factor.ron` would read low).

use std::path::Path;
use std::sync::Mutex;

use reyes_dice::{CameraSetup, DiceOptions, VertexContext, VertexShader};
use reyes_scene::Scene;

/// One recorded vertex: grid key (object, surface, patch rectangle's bits), grid size,
/// vertex index and world position.
type Record = ((usize, usize, [u32; 4]), (u32, u32), (u32, u32), [f32; 3]);

/// The vertex shader that records positions.
struct Recorder(Mutex<Vec<Record>>);

impl VertexShader for Recorder {
    fn shade(&self, v: &VertexContext) -> ([f32; 3], [f32; 3]) {
        let key = (
            v.object,
            v.surface,
            [
                v.patch_u[0].to_bits(),
                v.patch_u[1].to_bits(),
                v.patch_v[0].to_bits(),
                v.patch_v[1].to_bits(),
            ],
        );
        let r = (key, (v.nu, v.nv), (v.i, v.j), v.p_world.to_array());
        self.0.lock().unwrap_or_else(|e| e.into_inner()).push(r);
        ([0.0; 3], [1.0; 3])
    }
}

/// The measured distribution of one scene.
#[derive(Debug, Clone, Default)]
pub struct Distribution {
    /// Micropolygon area over rate, one per micropolygon with all corners in front of the eye.
    pub mpolys: Vec<f64>,
    /// Grid mean area over rate, one per grid.
    pub grids: Vec<f64>,
    /// Of `mpolys`, those whose raster bound overlaps the image (what the picture shows;
    /// a grid that reaches far off screen, or near the eye, has huge micropolygons there).
    pub on_screen: Vec<f64>,
    /// Per object (scene order): its micropolygons' summed area over rate, and their count.
    pub objects: Vec<(f64, u64)>,
    /// Micropolygons skipped (a corner at or behind the eye).
    pub skipped: u64,
}

/// Dice `scene` and measure its micropolygons' areas against the shading rate.
pub fn measure(scene: &Scene) -> Result<Distribution, String> {
    let frame = reyes_render::settings::frame_for(scene);
    let camera = CameraSetup::new(scene);
    let recorder = Recorder(Mutex::new(Vec::new()));
    let options = DiceOptions { vertex_shader: Some(&recorder), ..Default::default() };
    reyes_dice::dice_scene_with(scene, &frame, &options).map_err(|e| e.to_string())?;
    let mut records = recorder.0.into_inner().unwrap_or_else(|e| e.into_inner());
    records.sort_by_key(|a| (a.0, a.2.1, a.2.0));
    let to_camera = camera.world_to_camera();
    let mut out =
        Distribution { objects: vec![(0.0, 0); scene.objects.len()], ..Default::default() };
    let (width, height) = (f64::from(scene.image.width), f64::from(scene.image.height));
    let mut start = 0;
    while start < records.len() {
        let key = records[start].0;
        let end = start + records[start..].iter().take_while(|r| r.0 == key).count();
        let (nu, nv) = records[start].1;
        let (nu, nv) = (nu as usize, nv as usize);
        let grid = &records[start..end];
        start = end;
        if grid.len() != (nu + 1) * (nv + 1) {
            return Err(format!(
                "grid {key:?}: {} vertices recorded for {nu} x {nv} (two grids with one key?)",
                grid.len()
            ));
        }
        let object = &scene.objects[key.0];
        let rate = f64::from(object.shading_rate.unwrap_or(scene.hider.shading_rate));
        let raster: Vec<Option<[f64; 2]>> = grid
            .iter()
            .map(|r| {
                let p = to_camera.project_point3(glam::Vec3::from_array(r.3));
                (p.is_finite() && p.z > 0.0).then(|| {
                    let q = camera.eye_to_raster(p);
                    [f64::from(q.x), f64::from(q.y)]
                })
            })
            .collect();
        let (mut sum, mut n) = (0.0, 0usize);
        for j in 0..nv {
            for i in 0..nu {
                let at = |i: usize, j: usize| raster[j * (nu + 1) + i];
                let corners = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                let Some(c) = corners.into_iter().collect::<Option<Vec<_>>>() else {
                    out.skipped += 1;
                    continue;
                };
                // Shoelace area of the quad (a bow tie's lobes cancel, as its coverage does
                // not; micropolygons are small and nearly planar, so bow ties are rare).
                let twice: f64 =
                    (0..4).map(|k| c[k][0] * c[(k + 1) % 4][1] - c[(k + 1) % 4][0] * c[k][1]).sum();
                let a = 0.5 * twice.abs() / rate;
                out.mpolys.push(a);
                let (x0, x1) = c.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[0]), hi.max(p[0]))
                });
                let (y0, y1) = c.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[1]), hi.max(p[1]))
                });
                if x1 >= 0.0 && x0 <= width && y1 >= 0.0 && y0 <= height {
                    out.on_screen.push(a);
                    out.objects[key.0].0 += a;
                    out.objects[key.0].1 += 1;
                }
                sum += a;
                n += 1;
            }
        }
        if n > 0 {
            out.grids.push(sum / n as f64);
        }
    }
    Ok(out)
}

/// Mean, quantiles and power-of-two histogram of `xs`, as text.
pub fn summary(xs: &mut [f64]) -> String {
    use std::fmt::Write;
    if xs.is_empty() {
        return "none".to_string();
    }
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    let mean = xs.iter().sum::<f64>() / n as f64;
    let q = |p: f64| xs[((p * (n - 1) as f64).round() as usize).min(n - 1)];
    let mut s = String::new();
    let _ = write!(
        s,
        "n {n}, mean {mean:.3}, quantiles 5% {:.3} 25% {:.3} 50% {:.3} 75% {:.3} 95% {:.3}, \
         max {:.3}\n    histogram (area / rate):",
        q(0.05),
        q(0.25),
        q(0.5),
        q(0.75),
        q(0.95),
        xs[n - 1]
    );
    // Bins [2^k, 2^(k+1)) for k in -5..=2, below 1/32 and from 8 up.
    let bins: Vec<(String, f64, f64)> = std::iter::once(("<1/32".to_string(), 0.0, 1.0 / 32.0))
        .chain((-5..=2).map(|k: i32| {
            let lo = 2f64.powi(k);
            let name = if k < 0 { format!("1/{}", 1 << -k) } else { format!("{}", 1 << k) };
            (name, lo, 2.0 * lo)
        }))
        .chain(std::iter::once((">=8".to_string(), 8.0, f64::INFINITY)))
        .collect();
    for (name, lo, hi) in bins {
        let c = xs.iter().filter(|&&x| x >= lo && x < hi).count();
        let _ = write!(s, " {name}: {:.1}%", 100.0 * c as f64 / n as f64);
    }
    s
}

/// `cargo xtask rate [SCENE...]` (default: the three bench balls scenes).
pub fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let defaults =
        ["scenes/bench/balls.ron", "scenes/bench/balls-motion.ron", "scenes/bench/balls-dof.ron"];
    let scenes: Vec<String> = if args.is_empty() {
        defaults.iter().map(|s| s.to_string()).collect()
    } else {
        args.to_vec()
    };
    for name in scenes {
        let path = root.join(&name);
        let scene = reyes_scene::load(&path).map_err(|e| format!("{name}: {e}"))?;
        let mut d = measure(&scene).map_err(|e| format!("{name}: {e}"))?;
        println!("{name}:");
        println!("  micropolygons: {}", summary(&mut d.mpolys));
        println!("  on screen:     {}", summary(&mut d.on_screen));
        println!("  grid means:    {}", summary(&mut d.grids));
        let by_object: Vec<String> = scene
            .objects
            .iter()
            .zip(&d.objects)
            .filter(|(_, (_, n))| *n > 0)
            .map(|(o, (sum, n))| format!("{} {:.3} ({n})", o.name, sum / *n as f64))
            .collect();
        println!("  on-screen mean by object: {}", by_object.join(", "));
        if d.skipped > 0 {
            println!("  ({} micropolygons with a corner at or behind the eye skipped)", d.skipped);
        }
    }
    Ok(())
}
