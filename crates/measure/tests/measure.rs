//! FIG. 23 through the library: volumes and centres of mass of closed objects and CSG
//! solids against their closed forms, within the estimator's own standard errors; errors.

use std::f64::consts::PI;
use std::path::Path;

use glam::{DVec3, Mat4, Vec3};
use reyes_measure::{MeasureError, MeasureOptions, Measurement, measure};
use reyes_testkit::fixtures::measure_scene as scene_text;

fn parse(text: &str) -> reyes_scene::Scene {
    reyes_scene::parse(text, Path::new("measure.ron")).unwrap()
}

fn run(scene: &reyes_scene::Scene, name: &str, samples: u64, seed: u64) -> Measurement {
    measure(scene, Path::new("measure.ron"), name, &MeasureOptions { samples, seed })
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A closed cube mesh of side 1 centred on the origin, quads wound outward.
const CUBE: &str = "shape: Mesh(
      points: [(-0.5, -0.5, -0.5), (0.5, -0.5, -0.5), (0.5, 0.5, -0.5), (-0.5, 0.5, -0.5),
               (-0.5, -0.5, 0.5), (0.5, -0.5, 0.5), (0.5, 0.5, 0.5), (-0.5, 0.5, 0.5)],
      faces: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]])";

/// `m`'s volume and centre within three standard errors of `volume` and `centre`, and its
/// errors small enough for that to mean something.
#[track_caller]
fn check(m: &Measurement, volume: f64, centre: DVec3) {
    eprintln!("{m}");
    let k = 3.0;
    assert!(
        (m.volume - volume).abs() <= k * m.volume_se,
        "{}: volume {} ± {} vs {volume}",
        m.name,
        m.volume,
        m.volume_se
    );
    assert!(m.volume_se < 2e-3 * volume, "{}: volume s.e. {} too large", m.name, m.volume_se);
    let c = m.centre.unwrap_or_else(|| panic!("{}: no centre", m.name));
    for a in 0..3 {
        assert!(
            (c.at[a] - centre[a]).abs() <= k * c.se[a],
            "{}: centre[{a}] {} ± {} vs {}",
            m.name,
            c.at[a],
            c.se[a],
            centre[a]
        );
        assert!(c.se[a] < 2e-3 * volume.cbrt(), "{}: centre s.e. {} too large", m.name, c.se[a]);
    }
}

#[test]
fn box_mesh_scaled_and_moved() {
    let scene = parse(&scene_text(
        &[
            &format!(
                "name: \"box\", {CUBE}, transform: [Scale((2.0, 3.0, 4.0)), Translate((-1.0, 0.5, 2.0))]"
            ),
            &format!(
                "name: \"tilted\", {CUBE}, transform: [Scale((2.0, 3.0, 4.0)), \
                 Rotate(angle: 30.0, axis: (1.0, 1.0, 0.0)), Translate((4.0, -2.0, 1.0))]"
            ),
        ],
        "",
    ));
    check(&run(&scene, "box", 1_000_000, 1), 24.0, DVec3::new(-1.0, 0.5, 2.0));
    // Tilted, the box fills about a third of its bounding box.
    check(&run(&scene, "tilted", 1_000_000, 2), 24.0, DVec3::new(4.0, -2.0, 1.0));
}

/// The Catmull-Clark cube (half-side 1), moved: its volume is that of the ray engine's
/// tessellation of the limit surface, whose vertices are on the surface and which is within
/// `1e-3` of each patch's box diagonal of it, so within `area x that` of the limit surface's
/// volume; the reference is the divergence theorem on the limit patches, `V = 1/3 sum of
/// the integral of p . (p_u x p_v)`, by 4-point Gauss-Legendre on 8 x 8 cells per patch (a
/// smooth integrand: far below the tolerances here). The centre is the translation.
#[test]
fn a_subdivision_cube_has_its_limit_surface_volume() {
    let cube = "shape: SubdivisionMesh(points: [(-1.0, -1.0, -1.0), (1.0, -1.0, -1.0), \
        (-1.0, 1.0, -1.0), (1.0, 1.0, -1.0), (-1.0, -1.0, 1.0), (1.0, -1.0, 1.0), \
        (-1.0, 1.0, 1.0), (1.0, 1.0, 1.0)], faces: [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], \
        [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]])";
    let scene = parse(&scene_text(
        &[&format!("name: \"cc\", {cube}, transform: [Translate((0.5, -1.0, 2.0))]")],
        "",
    ));
    let mesh = reyes_scene::subdiv::control_mesh(&scene.objects[0].shape, |_, own| own)
        .expect("a subdivision mesh");
    let patches = reyes_subdiv::limit_patches(&mesh).expect("a valid mesh");
    let gauss = [
        (0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.861_136_311_594_053, 0.347_854_845_137_454),
    ];
    let nodes: Vec<(f64, f64)> = gauss
        .iter()
        .flat_map(|&(x, w)| [(0.5 - 0.5 * x, 0.5 * w), (0.5 + 0.5 * x, 0.5 * w)])
        .collect();
    let (mut volume, mut area, mut size) = (0.0_f64, 0.0_f64, 0.0_f64);
    for patch in &patches {
        let (lo, hi) = patch.bound();
        size = size.max(f64::from((hi - lo).length()));
        for cell in 0..64 {
            let (ci, cj) = (f64::from(cell % 8), f64::from(cell / 8));
            for &(x, wx) in &nodes {
                for &(y, wy) in &nodes {
                    let (u, v) = ((ci + x) / 8.0, (cj + y) / 8.0);
                    let (p, du, dv) = patch.eval(u as f32, v as f32);
                    let n = du.as_dvec3().cross(dv.as_dvec3());
                    let w = wx * wy / 64.0;
                    volume += w * p.as_dvec3().dot(n) / 3.0;
                    area += w * n.length();
                }
            }
        }
    }
    // Between the spheres of the face-centre and corner limit radii.
    let ball = |r: f64| 4.0 / 3.0 * PI * r.powi(3);
    assert!((ball(68.0 / 81.0)..ball(0.75_f64.sqrt())).contains(&volume), "reference {volume}");
    let m = run(&scene, "cc", 400_000, 3);
    eprintln!("{m} (reference {volume}, area {area})");
    let bias = area * 1e-3 * size;
    assert!(
        (m.volume - volume).abs() <= 3.0 * m.volume_se + bias,
        "volume {} ± {} vs {volume} (tessellation within {bias})",
        m.volume,
        m.volume_se
    );
    assert!(m.volume_se < 5e-3 * volume, "volume s.e. {} too large", m.volume_se);
    // The missing sliver (volume at most `bias`) lies within 1 of the centre (the corner
    // radius is 0.87), so it moves the centre by at most bias / volume.
    let c = m.centre.expect("a centre");
    for (a, want) in [0.5, -1.0, 2.0].into_iter().enumerate() {
        assert!((c.at[a] - want).abs() <= 3.0 * c.se[a] + bias / volume, "centre {:?}", c.at);
    }
}

/// Volume of the lens where spheres of radii `big` and `small` with centres `d` apart overlap,
/// and the distance of its centroid from the big sphere's centre, towards the small one.
fn lens(big: f64, small: f64, d: f64) -> (f64, f64) {
    // The spheres meet in the plane at distance a from the big one's centre; the lens is the
    // big sphere's cap beyond it plus the small sphere's cap before it.
    let a = (d * d + big * big - small * small) / (2.0 * d);
    let cap = |r: f64, h: f64| PI * h * h * (3.0 * r - h) / 3.0;
    // Centroid of a cap of height h from its sphere's centre.
    let cap_centroid = |r: f64, h: f64| 3.0 * (2.0 * r - h).powi(2) / (4.0 * (3.0 * r - h));
    let (h1, h2) = (big - a, a - (d - small));
    let (v1, v2) = (cap(big, h1), cap(small, h2));
    let (x1, x2) = (cap_centroid(big, h1), d - cap_centroid(small, h2));
    (v1 + v2, (v1 * x1 + v2 * x2) / (v1 + v2))
}

#[test]
fn lens_formula_is_right() {
    // Equal spheres one radius apart: the lens is two caps of height r/2, 5 pi r^3 / 12.
    let (v, x) = lens(1.0, 1.0, 1.0);
    assert!((v - 5.0 * PI / 12.0).abs() < 1e-12 && (x - 0.5).abs() < 1e-12, "{v} {x}");
}

#[test]
fn sphere_minus_an_off_centre_sphere() {
    let (big, small) = (1.5f64, 1.0f64);
    let at = DVec3::new(0.5, -1.0, 2.0);
    let offset = DVec3::new(0.72, 0.0, 0.96); // length 1.2
    let text = scene_text(
        &[
            "name: \"big\", shape: Sphere(radius: 1.5), transform: [Translate((0.5, -1.0, 2.0))]",
            "name: \"small\", shape: Sphere(radius: 1.0), transform: [Translate((1.22, -1.0, 2.96))]",
            "name: \"a\", shape: Sphere(radius: 1.5), transform: [Translate((0.5, -1.0, 2.0))]",
            "name: \"b\", shape: Sphere(radius: 1.0), transform: [Translate((1.22, -1.0, 2.96))]",
            "name: \"c\", shape: Sphere(radius: 1.5), transform: [Translate((0.5, -1.0, 2.0))]",
            "name: \"d\", shape: Sphere(radius: 1.0), transform: [Translate((1.22, -1.0, 2.96))]",
        ],
        "(name: \"bitten\", tree: Difference(Object(\"big\"), Object(\"small\"))),
         (name: \"lens\", tree: Intersection([Object(\"a\"), Object(\"b\")])),
         (name: \"both\", tree: Union([Object(\"c\"), Object(\"d\")]))",
    );
    let scene = parse(&text);
    let u = offset.normalize();
    let (v_lens, x_lens) = lens(big, small, offset.length());
    let v_big = 4.0 / 3.0 * PI * big.powi(3);
    let v_small = 4.0 / 3.0 * PI * small.powi(3);
    // Difference: the big sphere (centroid at its centre) less the lens.
    let x_bitten = -v_lens * x_lens / (v_big - v_lens);
    check(&run(&scene, "bitten", 1_000_000, 3), v_big - v_lens, at + u * x_bitten);
    check(&run(&scene, "lens", 1_000_000, 4), v_lens, at + u * x_lens);
    let v_both = v_big + v_small - v_lens;
    let x_both = (v_small * offset.length() - v_lens * x_lens) / v_both;
    check(&run(&scene, "both", 1_000_000, 5), v_both, at + u * x_both);
    // The operands on their own.
    check(&run(&scene, "small", 1_000_000, 6), v_small, at + offset);
}

#[test]
fn other_quadrics_closed_by_their_caps() {
    // Scale, then rotate 90 degrees about x ((x, y, z) -> (x, -z, y)), then translate.
    let place = "transform: [Scale((1.0, 2.0, 0.5)), Rotate(angle: 90.0, axis: (1.0, 0.0, 0.0)), \
                 Translate((1.0, -2.0, 3.0))]";
    let scene = parse(&scene_text(
        &[
            &format!("name: \"cyl\", shape: Cylinder(radius: 0.8, zmin: -1.0, zmax: 2.0), {place}"),
            &format!("name: \"cone\", shape: Cone(height: -2.0, radius: 1.2), {place}"),
            &format!("name: \"bowl\", shape: Paraboloid(rmax: 1.0, zmin: 0.5, zmax: 2.0), {place}"),
            &format!("name: \"ring\", shape: Torus(major_radius: 2.0, minor_radius: 0.5), {place}"),
        ],
        "",
    ));
    let m = Mat4::from_translation(Vec3::new(1.0, -2.0, 3.0))
        * Mat4::from_axis_angle(Vec3::X, 90f32.to_radians())
        * Mat4::from_scale(Vec3::new(1.0, 2.0, 0.5));
    let world = |z: f64| m.as_dmat4().transform_point3(DVec3::new(0.0, 0.0, z));
    let det = 1.0 * 2.0 * 0.5;
    // Cylinder: pi r^2 h, centroid mid-height.
    check(&run(&scene, "cyl", 1_000_000, 1), det * PI * 0.64 * 3.0, world(0.5));
    // Cone: pi r^2 h / 3, centroid a quarter of the way from the base to the apex.
    check(&run(&scene, "cone", 1_000_000, 2), det * PI * 1.44 * 2.0 / 3.0, world(-0.5));
    // Paraboloid x^2 + y^2 = k z (k = rmax^2 / zmax): pi k (z1^2 - z0^2) / 2, centroid at
    // 2 (z1^3 - z0^3) / (3 (z1^2 - z0^2)).
    let (k, z0, z1) = (0.5f64, 0.5f64, 2.0f64);
    let v = PI * k * (z1 * z1 - z0 * z0) / 2.0;
    let zc = 2.0 * (z1.powi(3) - z0.powi(3)) / (3.0 * (z1 * z1 - z0 * z0));
    check(&run(&scene, "bowl", 1_000_000, 3), det * v, world(zc));
    // Torus: 2 pi^2 R r^2, centroid at its centre.
    check(&run(&scene, "ring", 1_000_000, 4), det * 2.0 * PI * PI * 2.0 * 0.25, world(0.0));
}

#[test]
fn mesh_and_quadric_in_one_solid_and_motion_at_shutter_open() {
    let scene = parse(&scene_text(
        &[
            &format!("name: \"cube\", {CUBE}, transform: [Scale((2.0, 2.0, 2.0))]"),
            "name: \"core\", shape: Sphere(radius: 0.6), transform: [Translate((0.2, 0.0, 0.0))]",
            // Moving: measured at its first key.
            "name: \"mover\", shape: Sphere(radius: 1.0), \
             motion: [(time: 0.0, transform: [Translate((5.0, 0.0, 0.0))]), \
                      (time: 1.0, transform: [Translate((9.0, 0.0, 0.0))])]",
        ],
        "(name: \"hollow\", tree: Difference(Object(\"cube\"), Object(\"core\")))",
    ));
    let v_core = 4.0 / 3.0 * PI * 0.216;
    let x = -v_core * 0.2 / (8.0 - v_core);
    check(&run(&scene, "hollow", 1_000_000, 1), 8.0 - v_core, DVec3::new(x, 0.0, 0.0));
    check(&run(&scene, "mover", 1_000_000, 2), 4.0 / 3.0 * PI, DVec3::new(5.0, 0.0, 0.0));
    // Few samples still give an answer (at least a 2 x 2 x 2 grid).
    let tiny = run(&scene, "mover", 1, 0);
    assert_eq!(tiny.points(), 8);
}

#[test]
fn library_errors() {
    let scene = parse(&scene_text(
        &[
            "name: \"ball\", shape: Sphere(radius: 1.0)",
            "name: \"ball\", shape: Sphere(radius: 2.0)",
            "name: \"flat\", shape: Sphere(radius: 1.0), \
             transform: [Scale((1.0, 1e-30, 1.0)), Scale((1.0, 1e-30, 1.0))]",
        ],
        "",
    ));
    let err = |name: &str, samples: u64| {
        measure(&scene, Path::new("m.ron"), name, &MeasureOptions { samples, seed: 0 }).unwrap_err()
    };
    assert!(matches!(err("ball", 1000), MeasureError::Ambiguous { .. }));
    assert_eq!(
        err("ball", 1000).to_string(),
        "--object: the name \"ball\" is ambiguous: objects[0] and objects[1] both have it"
    );
    assert_eq!(
        err("flat", 1000).to_string(),
        "--object: object \"flat\" cannot be measured: its transform at shutter open is singular"
    );
    assert!(matches!(err("", 1000), MeasureError::NotFound { .. }));
    assert_eq!(err("x", 0).to_string(), "--samples: must be from 1 to 100000000000, got 0");
}

#[test]
fn disjoint_intersection_is_empty() {
    let scene = parse(&scene_text(
        &[
            "name: \"a\", shape: Sphere(radius: 1.0)",
            "name: \"b\", shape: Sphere(radius: 1.0), transform: [Translate((3.0, 0.0, 0.0))]",
            "name: \"c\", shape: Sphere(radius: 1.0)",
            "name: \"d\", shape: Sphere(radius: 1.0), transform: [Translate((1.9, 1.9, 0.0))]",
        ],
        "(name: \"none\", tree: Intersection([Object(\"a\"), Object(\"b\")])),
         (name: \"corner\", tree: Intersection([Object(\"c\"), Object(\"d\")]))",
    ));
    // Boxes apart: nothing is sampled.
    let m = run(&scene, "none", 1000, 0);
    assert_eq!((m.points(), m.inside, m.volume, m.centre), (0, 0, 0.0, None));
    assert!(m.to_string().contains("box      empty"), "{m}");
    // Boxes overlap in a corner the spheres do not reach: sampled, nothing inside.
    let m = run(&scene, "corner", 1000, 0);
    assert!(m.points() >= 1000 && m.inside == 0 && m.volume == 0.0 && m.centre.is_none());
    assert!(m.to_string().contains("centre   none"), "{m}");
}

#[test]
fn the_renderman_surfaces_are_open() {
    // Hyperboloids, patch meshes (even wrapped into a tube) and NURBS bound no volume by the
    // scene's closure rule: measuring one is the "not closed" error naming the shape.
    let scene = parse(&scene_text(
        &[
            "name: \"hyp\", shape: Hyperboloid(point1: (1.0, 0.0, -1.0), point2: (1.0, 0.0, 1.0))",
            "name: \"tube\", shape: PatchMesh(kind: Bilinear, nu: 3, nv: 2, uwrap: Periodic, \
             points: [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), \
                      (1.0, 0.0, 1.0), (0.0, 1.0, 1.0), (-1.0, 0.0, 1.0)])",
            "name: \"nurbs\", shape: NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], \
             umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, \
             vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), \
             (1.0, 1.0, 0.0, 1.0)])",
        ],
        "",
    ));
    for (name, shape) in [("hyp", "Hyperboloid"), ("tube", "PatchMesh"), ("nurbs", "NuPatch")] {
        let err =
            measure(&scene, Path::new("m.ron"), name, &MeasureOptions { samples: 1000, seed: 0 })
                .unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("--object: object \"{name}\" is not closed ({shape}), so it bounds no volume")
        );
    }
}
