//! Local illumination (the dicer's, bit for bit), patterns, tints, compositing, mattes,
//! shadow attenuation, determinism.

use glam::Vec3;
use reyes_dice::Shader;
use reyes_sampling::Strata;
use reyes_shade::{BLACK, IVORY, Shading, SurfacePoint, Traced};
use reyes_trace::Ray;

use crate::common::{patch, scene, trace_one, tracer, white_floor};

#[test]
fn local_illumination_is_the_dicers_bit_for_bit() {
    let s = scene(
        "lights: [Ambient(intensity: 0.2), \
                  Distant(from: (1.0, 2.0, -3.0), color: (1.0, 0.9, 0.8)), \
                  Point(from: (-2.0, 3.0, -1.0), intensity: 5.0)], \
         objects: [(shape: Sphere(radius: 1.0), material: Plastic(color: (0.8, 0.3, 0.2), \
                    opacity: (0.9, 0.8, 1.0), roughness: 0.05)), \
                   (shape: Sphere(radius: 1.0), material: Matte(color: (0.2, 0.3, 0.9), ka: 0.5)), \
                   (shape: Sphere(radius: 1.0), material: Constant(color: (0.2, 0.3, 0.9)))]",
    );
    assert!(!Shading::needed(&s));
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let eye = Vec3::new(0.3, 0.5, -6.0);
    for (k, object) in s.objects.iter().enumerate() {
        let shader = Shader::new(&object.material, &s.lights, eye);
        for i in 0..50 {
            let a = i as f32 * 0.7;
            let n = Vec3::new(a.cos(), (a * 1.3).sin(), (a * 0.4).cos() - 0.5).normalize();
            let p = Vec3::new(a.sin(), 0.1 * a - 2.0, (2.0 * a).cos());
            let tint = Vec3::new(1.0, 0.5 + 0.01 * i as f32, 0.7);
            let at = SurfacePoint {
                object: k as u32,
                p_world: p,
                n_world: n,
                p_object: p,
                tint,
                from: eye,
                time: 0.5,
                looked: reyes_dice::Looked::NONE,
            };
            let got = shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1));
            assert_eq!(got, shader.shade(p, n, tint), "object {k}, point {i}");
        }
    }
}

#[test]
fn needed_detects_every_distributed_effect() {
    let base = "objects: [(shape: Sphere(radius: 1.0), material: Constant(color: (1.0, 1.0, 1.0)) ";
    for (fields, want) in [
        (format!("lights: [Point(from: (0.0, 1.0, 0.0))], {base})]"), false),
        (format!("lights: [Point(from: (0.0, 1.0, 0.0), shadows: true)], {base})]"), true),
        (format!("lights: [Distant(from: (0.0, 1.0, 0.0), shadows: true)], {base})]"), true),
        (
            format!(
                "lights: [Area(shape: Sphere(center: (0.0, 3.0, 0.0), radius: 1.0))], {base})]"
            ),
            true,
        ),
        (format!("{base}, reflect: Some((color: (1.0, 1.0, 1.0))))]"), true),
        (format!("{base}, refract: Some((ior: 1.5)))]"), true),
        (format!("{base}, pattern: Some(PoolBall(color: (1.0, 0.0, 0.0))))]"), true),
    ] {
        assert_eq!(Shading::needed(&scene(&fields)), want, "{fields}");
    }
}

/// Rays from far away at the point `p` of a sphere of radius 2 centred at the origin.
fn colour_at(shading: &Shading, p: Vec3) -> Vec3 {
    let h = trace_one(shading, &Ray::new(p * 5.0, -p, 0.0));
    assert!(h.t.is_finite(), "missed the ball at {p}");
    Vec3::new(h.rgba[0], h.rgba[1], h.rgba[2])
}

#[test]
fn pool_ball_regions_in_object_space() {
    // Two balls at the origin (only one at a time is in the scene), turned so that their
    // pole (object z) lies along world x: the pattern must follow the object.
    for striped in [true, false] {
        let s = scene(&format!(
            "objects: [(shape: Sphere(radius: 2.0), transform: [Rotate(angle: 90.0, axis: (0.0, 1.0, 0.0))], \
              material: Constant(color: (0.5, 0.5, 0.5)), \
              pattern: Some(PoolBall(color: (0.9, 0.1, 0.1), striped: {striped})))]"
        ));
        let t = tracer(&s);
        let shading = Shading::new(&s, &t);
        let red = Vec3::new(0.9, 0.1, 0.1);
        for (z, want_striped, want_solid) in [
            (0.0, red, red),
            (0.3, red, red),
            (-0.45, red, red),
            (0.5, IVORY, red),
            (-0.8, IVORY, red),
            (0.87, BLACK, IVORY),
            (-0.88, BLACK, IVORY),
            (0.93, IVORY, IVORY),
            (-0.99, IVORY, IVORY),
        ] {
            // World point with |x| / r = z (the object's pole), off the world z axis.
            let q = Vec3::new(z, (1.0 - z * z).sqrt() * 0.6, (1.0 - z * z).sqrt() * 0.8) * 2.0;
            let want = if striped { want_striped } else { want_solid };
            let got = colour_at(&shading, q);
            assert!((got - want).abs().max_element() < 1e-6, "striped {striped} z {z}: {got}");
        }
    }
}

#[test]
fn mesh_vertex_colours_tint_at_the_hit() {
    // One quad in z = 0 with a colour per corner, and a triangle beside it.
    let s = scene(
        "objects: [(shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), \
          (0.0, 1.0, 0.0), (2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (2.0, 1.0, 0.0)], \
          faces: [[0, 1, 2, 3], [4, 5, 6]], \
          colors: Some([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 1.0), \
                        (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)])), \
          material: Constant(color: (1.0, 0.5, 1.0)))]",
    );
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let at = |x: f32, y: f32| {
        let h = trace_one(&shading, &Ray::new(Vec3::new(x, y, -5.0), Vec3::Z, 0.0));
        Vec3::new(h.rgba[0], h.rgba[1], h.rgba[2])
    };
    // Quad at (u, v) = (0.25, 0.5): bilinear mix of the corner colours, times Cs.
    let (u, v) = (0.25, 0.5);
    let c = [Vec3::X, Vec3::Y, Vec3::ONE, Vec3::Z]; // corners (0,0), (1,0), (0,1), (1,1)
    let want = c[0].lerp(c[1], u).lerp(c[2].lerp(c[3], u), v) * Vec3::new(1.0, 0.5, 1.0);
    assert!((at(u, v) - want).abs().max_element() < 1e-5, "{} vs {want}", at(u, v));
    // Triangle: barycentric mix at its centroid.
    let want = (Vec3::X + Vec3::Y + Vec3::Z) / 3.0 * Vec3::new(1.0, 0.5, 1.0);
    let got = at(7.0 / 3.0, 1.0 / 3.0);
    assert!((got - want).abs().max_element() < 1e-5, "{got} vs {want}");
}

/// What the ray from the origin along +z sees through three squares facing it at z = 1, 2, 3,
/// with the given material fields.
fn through_layers(a: &str, b: &str, c: &str) -> Traced {
    let sq = |z: f32, rest: &str| {
        patch(Vec3::new(-1.0, -1.0, z), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0), rest)
    };
    let s = scene(&format!("objects: [{}, {}, {}]", sq(1.0, a), sq(2.0, b), sq(3.0, c)));
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    trace_one(&shading, &Ray::new(Vec3::ZERO, Vec3::Z, 0.0))
}

#[test]
fn transparent_surfaces_composite_front_to_back() {
    let got = through_layers(
        "material: Constant(color: (1.0, 0.0, 0.0), opacity: (0.5, 0.5, 0.5))",
        "material: Constant(color: (0.0, 1.0, 0.0), opacity: (0.5, 0.25, 1.0))",
        "material: Constant(color: (0.0, 0.0, 1.0))",
    );
    // C = Os1 C1 + (1 - Os1) Os2 C2 + (1 - Os1)(1 - Os2) C3, per channel: red 0.5 from the
    // first layer, green 0.5 * 0.25 from the second, blue 0.5 * 0 * 1 from the third (the
    // second is opaque in blue).
    let want = [0.5, 0.125, 0.0, 1.0];
    for k in 0..4 {
        assert!((got.rgba[k] - want[k]).abs() < 1e-6, "{:?} vs {want:?}", got.rgba);
    }
    assert!((got.t - 3.0).abs() < 1e-4, "t {}", got.t);
    // The composite ends at the third layer: the second is not opaque in every channel.

    // Only transparent layers: alpha is the mean coverage, t infinite.
    let got = through_layers(
        "material: Constant(color: (1.0, 1.0, 1.0), opacity: (0.5, 0.5, 0.5))",
        "material: Constant(color: (1.0, 1.0, 1.0), opacity: (0.5, 0.5, 0.5))",
        "material: Constant(color: (1.0, 1.0, 1.0), opacity: (0.0, 0.0, 0.0))",
    );
    assert!((got.rgba[3] - 0.75).abs() < 1e-6 && got.t.is_infinite(), "{got:?}");
}

#[test]
fn matte_holds_out_what_is_behind() {
    let front = "material: Constant(color: (1.0, 0.0, 0.0), opacity: (0.5, 0.5, 0.5))";
    let back = "material: Constant(color: (1.0, 1.0, 1.0))";
    let got =
        through_layers(front, "material: Constant(color: (0.0, 1.0, 0.0)), matte: true", back);
    assert_eq!(got.rgba, [0.5, 0.0, 0.0, 0.5], "only the layer in front of the matte");
    assert!((got.t - 2.0).abs() < 1e-4, "ends at the matte: {}", got.t);
    // Without the matte flag the green surface shows.
    let got = through_layers(front, "material: Constant(color: (0.0, 1.0, 0.0))", back);
    assert_eq!(got.rgba, [0.5, 0.5, 0.0, 1.0]);
}

#[test]
fn shadow_rays_are_attenuated_by_transparent_surfaces_and_blocked_by_glass() {
    // Point light at y = 4 over the floor point at the origin; a pane at y = 2.
    let floor = white_floor(5.0);
    let pane = |rest: &str| {
        patch(Vec3::new(-1.0, 2.0, -1.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 2.0), rest)
    };
    let lit = |pane_fields: &str| {
        let s = scene(&format!(
            "lights: [Point(from: (0.0, 4.0, 0.0), intensity: 16.0, shadows: true)], \
             objects: [{floor}, {}]",
            pane(pane_fields)
        ));
        let t = tracer(&s);
        let shading = Shading::new(&s, &t);
        let at = crate::common::floor_point(0, 0.0, 0.0, 0.0);
        Vec3::from(shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1)).0)
    };
    // Unshadowed: 16 / 4^2 = 1.
    let tinted = lit("material: Constant(color: (1.0, 1.0, 1.0), opacity: (0.5, 0.25, 1.0))");
    assert!((tinted - Vec3::new(0.5, 0.75, 0.0)).abs().max_element() < 1e-6, "{tinted}");
    let glass = lit("material: Constant(color: (1.0, 1.0, 1.0), opacity: (0.0, 0.0, 0.0)), \
         refract: Some((ior: 1.5))");
    assert_eq!(glass, Vec3::ZERO, "refracting objects block shadow rays");
    let opaque = lit("material: Constant(color: (1.0, 1.0, 1.0))");
    assert_eq!(opaque, Vec3::ZERO);
}

#[test]
fn same_stream_same_result() {
    let floor = patch(
        Vec3::new(-10.0, -1.0, -10.0),
        Vec3::new(20.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 20.0),
        "material: Matte(color: (1.0, 1.0, 1.0))",
    );
    let s = scene(&format!(
        "lights: [Ambient(intensity: 0.1), \
                  Area(shape: Disk(center: (0.0, 5.0, 0.0), normal: (0.0, -1.0, 0.0), radius: 1.0)), \
                  Area(shape: Sphere(center: (3.0, 4.0, 0.0), radius: 0.5), intensity: 10.0)], \
         objects: [(shape: Sphere(radius: 1.0), material: Plastic(color: (0.8, 0.3, 0.2)), \
                    reflect: Some((color: (0.5, 0.5, 0.5), gloss: 8.0)), \
                    refract: Some((ior: 1.4, color: (0.5, 0.5, 0.5), blur: 3.0))), {floor}]"
    ));
    let t = tracer(&s);
    let a = Shading::new(&s, &t);
    let b = Shading::new(&s, &t);
    let ray = Ray::new(Vec3::new(0.2, 3.0, -4.0), Vec3::new(-0.2, -3.0, 4.0), 0.3);
    let mut differ = false;
    for i in 0..16 {
        let r1 = a.trace(&ray, f32::INFINITY, &mut Strata::new(3, 11, i, 16));
        let r2 = b.trace(&ray, f32::INFINITY, &mut Strata::new(3, 11, i, 16));
        assert_eq!(r1, r2, "member {i}");
        let r0 = a.trace(&ray, f32::INFINITY, &mut Strata::new(3, 11, 0, 16));
        differ |= r1 != r0;
    }
    assert!(differ, "different members draw different rays");
}
