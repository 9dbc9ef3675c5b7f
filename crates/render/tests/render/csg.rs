//! CSG through the whole pipeline against analytic ray-solid intersection.
//!
//! Camera at the origin looking down +z, 90 degree fov on a 64 x 64 image: the ray through
//! raster point (x, y) is d = ((x - 32)/32, (32 - y)/32, 1), and a hit at parameter t has eye
//! depth t (d.z = 1), which is what the EXR Z channel holds: the depth of the nearest opaque
//! surface, the minimum over the pixel's own samples.

use glam::DVec3;
use reyes_film::Film;
use reyes_render::{RenderOptions, render};

fn render_text(text: &str) -> Film {
    let scene = reyes_scene::parse(text, std::path::Path::new("csg.ron")).unwrap();
    render(&scene, &RenderOptions::default()).unwrap().film
}

fn scene(objects: &str, solids: &str, opacity: f32, filter: &str) -> String {
    format!(
        "Scene(image: (width: 64, height: 64),
           camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 90.0),
           hider: (pixel_samples: (4, 4), filter: {filter}, seed: 3),
           objects: [{}],
           solids: [{solids}])",
        objects.replace("OPACITY", &format!("({opacity}, {opacity}, {opacity})"))
    )
}

fn ray(x: f64, y: f64) -> DVec3 {
    DVec3::new((x - 32.0) / 32.0, (32.0 - y) / 32.0, 1.0)
}

/// Entry and exit parameters of a ray from the origin through a sphere.
fn sphere(d: DVec3, c: DVec3, r: f64) -> Option<(f64, f64)> {
    let a = d.dot(d);
    let b = -2.0 * d.dot(c);
    let k = c.dot(c) - r * r;
    let disc = b * b - 4.0 * a * k;
    (disc > 0.0).then(|| ((-b - disc.sqrt()) / (2.0 * a), (-b + disc.sqrt()) / (2.0 * a)))
}

/// Entry and exit of an infinite cylinder of radius r through c along unit axis u.
fn cylinder(d: DVec3, c: DVec3, u: DVec3, r: f64) -> Option<(f64, f64)> {
    let dp = d - u * d.dot(u);
    let cp = -c - u * (-c).dot(u);
    let a = dp.dot(dp);
    let b = 2.0 * dp.dot(cp);
    let k = cp.dot(cp) - r * r;
    let disc = b * b - 4.0 * a * k;
    (a > 0.0 && disc > 0.0)
        .then(|| ((-b - disc.sqrt()) / (2.0 * a), (-b + disc.sqrt()) / (2.0 * a)))
}

/// For every pixel whose neighbourhood gets the same kind of analytic answer (`depth`
/// returns (kind, t)), the rendered Z must lie within the analytic depth range over that
/// neighbourhood, plus the chord error.
/// Why the neighbourhood: a sample's depth is Shepard-interpolated from the vertices of the
/// micropolygon it hits, so it lies within that micropolygon's depth range (a convex
/// combination), and at shading rate 1 a micropolygon reaches at most about 1.5 pixels from
/// any sample it covers. So Z lies within the true depths over the pixel grown by 1.5 pixels,
/// sampled here on a half-pixel grid. Chord error: micropolygons are chords of the surface;
/// at depth ~4 a pixel spans 0.125 units, so on a radius >= 0.5 the sagitta is at most
/// 0.125^2 / (8 * 0.5) = 0.004 (0.005 allowed; the half-pixel grid misses at most a
/// quarter-pixel of depth change, covered by the neighbourhood's own extent).
fn check_depths(film: &Film, depth: impl Fn(DVec3) -> (u8, Option<f64>)) -> usize {
    let mut checked = 0;
    for py in 0..64u32 {
        for px in 0..64u32 {
            let pts: Vec<(u8, Option<f64>)> = (0..81)
                .map(|k| {
                    let (i, j) = ((k % 9) as f64, (k / 9) as f64);
                    depth(ray(px as f64 - 1.5 + 0.5 * i, py as f64 - 1.5 + 0.5 * j))
                })
                .collect();
            if pts.iter().any(|p| p.0 != pts[0].0) {
                continue; // near a boundary between surfaces
            }
            let z = film.depth(px, py).unwrap() as f64;
            let alpha = film.pixel(px, py).unwrap()[3];
            match pts[0].1 {
                None => {
                    assert_eq!(alpha, 0.0, "pixel ({px},{py}) must show nothing");
                    assert!(z.is_infinite());
                }
                Some(_) => {
                    let ts: Vec<f64> = pts.iter().filter_map(|p| p.1).collect();
                    let lo = ts.iter().cloned().fold(f64::INFINITY, f64::min) - 0.005;
                    let hi = ts.iter().cloned().fold(f64::NEG_INFINITY, f64::max) + 0.005;
                    assert!(z >= lo && z <= hi, "pixel ({px},{py}): z {z} not in [{lo}, {hi}]");
                }
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn difference_depth_matches_ray_solid_intersection() {
    // Sphere radius 1.5 at (0, 0, 4) minus a cylinder of radius 0.6 through its centre,
    // axis tilted 12 degrees from the view direction towards +y (RenderMan cylinders lie
    // along object z; the rotation about x by -12 degrees tilts it).
    let objects = "(name: \"ball\", shape: Sphere(radius: 1.5), transform: [Translate((0.0, 0.0, 4.0))],
                    material: Constant(color: (1.0, 0.0, 0.0))),
                   (name: \"hole\", shape: Cylinder(radius: 0.6, zmin: -3.0, zmax: 3.0),
                    transform: [Rotate(angle: -12.0, axis: (1.0, 0.0, 0.0)), Translate((0.0, 0.0, 4.0))],
                    material: Constant(color: (0.0, 1.0, 0.0)))";
    let film = render_text(&scene(
        objects,
        "(tree: Difference(Object(\"ball\"), Object(\"hole\")))",
        1.0,
        "(kind: Box, width: 1.0)",
    ));
    let c = DVec3::new(0.0, 0.0, 4.0);
    // Rotate(angle, axis) is glam's from_axis_angle: about +x by theta, +z goes to
    // (0, -sin theta, cos theta); theta = -12 degrees gives the axis (0, sin 12, cos 12).
    // (Tilted under about 22 degrees, some rays pass right through: 3 tan(theta) < 1.2.)
    let t = 12f64.to_radians();
    let u = DVec3::new(0.0, t.sin(), t.cos());
    let mut kinds = [0usize; 4];
    let checked = check_depths(&film, |d| {
        let Some((s0, s1)) = sphere(d, c, 1.5) else { return (0, None) };
        match cylinder(d, c, u, 0.6) {
            Some((c0, c1)) if s0 > c0 && s0 < c1 => {
                // The ray enters the sphere inside the hole: the first visible point is where
                // it leaves the cylinder while still inside the sphere (the hole's wall), or
                // nothing if it leaves the sphere first.
                if c1 < s1 { (2, Some(c1)) } else { (3, None) }
            }
            _ => (1, Some(s0)),
        }
    });
    for py in 0..64 {
        for px in 0..64 {
            let d = ray(px as f64 + 0.5, py as f64 + 0.5);
            let k = match sphere(d, c, 1.5) {
                None => 0,
                Some((s0, s1)) => match cylinder(d, c, u, 0.6) {
                    Some((c0, c1)) if s0 > c0 && s0 < c1 => {
                        if c1 < s1 {
                            2
                        } else {
                            3
                        }
                    }
                    _ => 1,
                },
            };
            kinds[k] += 1;
        }
    }
    assert!(checked > 1500, "only {checked} pixels checked");
    // The view must include all three cases: sphere, the hole's wall, and through the hole.
    // (The sphere's silhouette has a radius of about 32 * 1.5 / sqrt(4^2 - 1.5^2) = 13 px, some
    // 525 square pixels, of which the hole takes roughly a third.)
    assert!(kinds[1] > 250 && kinds[2] > 30 && kinds[3] > 10, "{kinds:?}");
}

/// The white spheres "a" and "b" of radius 1.2 at (-0.6, 0, 4) and (0.6, 0, 4), of opacity
/// `opacity`, combined by the solid `tree`, through a box filter a pixel wide; and their centres.
fn two_spheres(tree: &str, opacity: f32) -> (Film, DVec3, DVec3) {
    let objects = "(name: \"a\", shape: Sphere(radius: 1.2), transform: [Translate((-0.6, 0.0, 4.0))],
                    material: Constant(color: (1.0, 1.0, 1.0), opacity: OPACITY)),
                   (name: \"b\", shape: Sphere(radius: 1.2), transform: [Translate((0.6, 0.0, 4.0))],
                    material: Constant(color: (1.0, 1.0, 1.0), opacity: OPACITY))";
    let film = render_text(&scene(objects, tree, opacity, "(kind: Box, width: 1.0)"));
    (film, DVec3::new(-0.6, 0.0, 4.0), DVec3::new(0.6, 0.0, 4.0))
}

#[test]
fn intersection_depth_matches_ray_solid_intersection() {
    let (film, ca, cb) = two_spheres("(tree: Intersection([Object(\"a\"), Object(\"b\")]))", 1.0);
    let checked = check_depths(&film, |d| match (sphere(d, ca, 1.2), sphere(d, cb, 1.2)) {
        (Some((a0, a1)), Some((b0, b1))) if a0.max(b0) < a1.min(b1) => {
            (if a0 > b0 { 1 } else { 2 }, Some(a0.max(b0)))
        }
        _ => (0, None),
    });
    assert!(checked > 2000, "only {checked} pixels checked");
}

#[test]
fn a_transparent_union_shows_no_internal_surfaces() {
    // Two overlapping half-opaque spheres: every ray through the union crosses exactly two
    // boundary surfaces (in and out), so alpha = 1 - 0.5^2 = 0.75 everywhere inside the
    // silhouette, including the overlap, where the four operand surfaces would give 0.9375.
    let (film, ca, cb) = two_spheres("(tree: Union([Object(\"a\"), Object(\"b\")]))", 0.5);
    let mut overlap = 0;
    for py in 0..64u32 {
        for px in 0..64u32 {
            // Pixels entirely inside both spheres' silhouettes.
            let inside = (0..4).all(|k| {
                let d = ray(px as f64 + (k % 2) as f64, py as f64 + (k / 2) as f64);
                sphere(d, ca, 1.2).is_some() && sphere(d, cb, 1.2).is_some()
            });
            if inside {
                let a = film.pixel(px, py).unwrap()[3];
                assert!((a - 0.75).abs() < 1e-5, "pixel ({px},{py}) alpha {a}");
                overlap += 1;
            }
        }
    }
    // The two silhouettes (radius about 10 px, centres 9.6 px apart) overlap in a lens of
    // about 130 square pixels, about 90 of them whole pixels.
    assert!(overlap > 60, "{overlap}");
}

#[test]
fn nested_trees_render_like_flattened_ones() {
    // ((A - B) - C) - D and A - (B u C u D): the same solid, the same image bit for bit.
    let objects = "(name: \"a\", shape: Sphere(radius: 1.5), transform: [Translate((0.0, 0.0, 4.0))],
                    material: Constant(color: (1.0, 0.5, 0.2))),
                   (name: \"b\", shape: Sphere(radius: 0.6), transform: [Translate((-0.8, 0.0, 3.0))],
                    material: Constant(color: (0.2, 0.5, 1.0))),
                   (name: \"c\", shape: Sphere(radius: 0.6), transform: [Translate((0.8, 0.3, 3.0))],
                    material: Constant(color: (0.2, 1.0, 0.5))),
                   (name: \"d\", shape: Sphere(radius: 0.5), transform: [Translate((0.0, -0.8, 3.0))],
                    material: Constant(color: (1.0, 1.0, 0.2)))";
    let nested = "(tree: Difference(Difference(Difference(Object(\"a\"), Object(\"b\")), Object(\"c\")), Object(\"d\")))";
    let flat =
        "(tree: Difference(Object(\"a\"), Union([Object(\"b\"), Object(\"c\"), Object(\"d\")])))";
    let f = "(kind: Gaussian, width: 2.0)";
    let a = render_text(&scene(objects, nested, 1.0, f));
    let b = render_text(&scene(objects, flat, 1.0, f));
    assert_eq!(a.rgba(), b.rgba());
    assert_eq!(a.z(), b.z());
    // And the subtraction did something: some pixels show the subtracted spheres' colours.
    assert!(a.rgba().iter().any(|p| p[3] > 0.99 && p[2] > 0.9 && p[0] < 0.3));
}
