//! Reference figures (printed with `--nocapture`) with loose sanity bounds.

mod common;

use common::*;
use reyes_dice::CameraSetup;
use reyes_scene::Transform;

#[test]
fn unit_sphere_at_ten_units() {
    let s = scene_ahead(
        640,
        480,
        35.0,
        vec![object(sphere(1.0), vec![Transform::Translate([0.0, 0.0, 10.0])])],
    );
    let start = std::time::Instant::now();
    let (d, _) = dice(&s);
    let elapsed = start.elapsed();
    let k = f64::from(CameraSetup::new(&s).pixels_per_unit());
    let radius = k / 99.0_f64.sqrt();
    let disk = std::f64::consts::PI * radius * radius;
    let front: f64 = d.mpolys.iter().map(signed_area).filter(|a| *a > 0.0).sum();
    let total: f64 = d.mpolys.iter().map(|m| signed_area(m).abs()).sum();
    println!("unit sphere at 10, fov 35, 640x480, shading rate 1: {:?} in {elapsed:?}", d.stats);
    println!(
        "  disk {disk:.1} px^2, front-facing area {front:.1} ({:+.3}%), mean |area| {:.3} px^2",
        100.0 * (front - disk) / disk,
        total / d.mpolys.len() as f64
    );
    // Front and back halves each cover the disk at about one pixel per micropolygon.
    assert!(
        d.stats.micropolygons as f64 > 1.5 * disk && (d.stats.micropolygons as f64) < 4.0 * disk
    );
}
