//! RenderMan's standard spot light and metal, per-object light sets and orthographic viewing
//! in the ray-traced shading, against closed forms and against the dicer's local
//! illumination (both shading paths must agree).

use glam::Vec3;
use reyes_dice::{Shader, VertexShader, Viewer, smoothstep};
use reyes_sampling::{ShutterShape, Strata};
use reyes_scene::Scene;
use reyes_shade::{RayVertexShader, Shading, SurfacePoint};
use reyes_trace::Ray;

use crate::common::{floor_point, patch, scene, shade_mean, trace_one, tracer, white_floor};

/// A white matte floor `y = 0` (ka 0) lit by a spot light 6 units above the origin aimed
/// straight down (cone 30, penumbra 8 degrees, beam 2), with a shadow ray when `shadows`,
/// and `extra` more objects.
fn spot_floor(shadows: bool, extra: &str) -> Scene {
    let floor = white_floor(20.0);
    scene(&format!(
        "lights: [Spot(from: (0.0, 6.0, 0.0), to: (0.0, 0.0, 0.0), intensity: 36.0, \
                       cone_angle: 30.0, cone_delta: 8.0, beam_distribution: 2.0, shadows: {shadows})], \
         objects: [{floor}{extra}]"
    ))
}

/// The Specification's spotlight on the floor at radial distance `r`, times Lambert's
/// cosine: `36 cos^2 / d^2 * smoothstep(cos 30, cos 22, cos) * cos`, with `cos = 6 / d`.
fn spot_closed_form(r: f64) -> f64 {
    let d2 = 36.0 + r * r;
    let cos = 6.0 / d2.sqrt();
    let (e0, e1) = (30f64.to_radians().cos(), 22f64.to_radians().cos());
    let step = reyes_testkit::shading::smoothstep(e0, e1, cos);
    36.0 * cos * cos / d2 * step * cos
}

/// Radial distances across the beam: inside the inner cone (r < 6 tan 22 = 2.42), across the
/// penumbra (to 6 tan 30 = 3.46) and past the edge.
fn radii() -> impl Iterator<Item = f32> {
    (0..=90).map(|k| k as f32 * 0.05)
}

#[test]
fn the_spot_lights_falloff_across_its_penumbra_is_the_closed_form() {
    for shadows in [false, true] {
        let s = spot_floor(shadows, "");
        assert_eq!(Shading::needed(&s), shadows);
        let t = tracer(&s);
        let shading = Shading::new(&s, &t);
        let eye = Vec3::new(0.0, 20.0, -20.0);
        let dicer = Shader::new(&s.objects[0].material, &s.lights, eye);
        for r in radii() {
            for angle in [0.0f32, 1.3, 2.9] {
                let at = floor_point(0, r * angle.cos(), r * angle.sin(), 0.0);
                let got = shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1));
                let want = spot_closed_form(f64::from(r));
                // f32 arithmetic against f64: a few ulps of values below 1.
                assert!((f64::from(got.0[0]) - want).abs() < 2e-6, "r {r}: {:?} vs {want}", got.0);
                // The dicer lights the point bit for bit alike (the shadow ray is clear).
                assert_eq!(got, dicer.shade(at.p_world, at.n_world, at.tint), "r {r}");
            }
        }
    }
    // The cone's edge and the penumbra's inner edge, where the closed form is 0 and 1.
    let (cos_outer, cos_inner) = (30f32.to_radians().cos(), 22f32.to_radians().cos());
    assert_eq!(smoothstep(cos_outer, cos_inner, cos_outer - 1e-6), 0.0);
    assert_eq!(smoothstep(cos_outer, cos_inner, cos_inner), 1.0);
}

#[test]
fn a_shadowing_spot_light_casts_a_hard_shadow() {
    // An opaque plate at height 3 over x in [-1, 1]: its shadow on the floor spans
    // x in [-2, 2] (the light is at height 6), inside the beam.
    let plate = patch(
        Vec3::new(-1.0, 3.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        "material: Matte(color: (1.0, 1.0, 1.0))",
    );
    for shadows in [true, false] {
        let s = spot_floor(shadows, &format!(", {plate}"));
        let t = tracer(&s);
        let shading = Shading::new(&s, &t);
        for x in [0.0f32, 1.5, 1.9, 2.1, 2.4] {
            let at = floor_point(0, x, 0.0, 0.0);
            let got = f64::from(shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1)).0[0]);
            let want = if shadows && x < 2.0 { 0.0 } else { spot_closed_form(f64::from(x)) };
            assert!((got - want).abs() < 2e-6, "shadows {shadows}, x {x}: {got} vs {want}");
        }
    }
}

#[test]
fn metal_shades_as_the_dicers_metal_and_its_formula() {
    let s = scene(
        "lights: [Ambient(intensity: 0.2), Distant(from: (1.0, 2.0, -3.0), color: (1.0, 0.9, 0.8)), \
                  Point(from: (-2.0, 3.0, -1.0), intensity: 5.0), \
                  Spot(from: (0.0, 4.0, -4.0), to: (0.0, 0.0, 0.0), intensity: 20.0, cone_angle: 60.0)], \
         objects: [(shape: Sphere(radius: 1.0), material: Metal(color: (0.9, 0.6, 0.3), \
                    opacity: (0.9, 0.8, 1.0), ka: 0.7, ks: 0.9, roughness: 0.15))]",
    );
    assert!(!Shading::needed(&s));
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let eye = Vec3::new(0.3, 0.5, -6.0);
    let shader = Shader::new(&s.objects[0].material, &s.lights, eye);
    for i in 0..50 {
        let a = i as f32 * 0.7;
        let n = Vec3::new(a.cos(), (a * 1.3).sin(), (a * 0.4).cos() - 0.5).normalize();
        let p = Vec3::new(a.sin(), 0.1 * a - 2.0, (2.0 * a).cos());
        let at = SurfacePoint {
            object: 0,
            p_world: p,
            n_world: n,
            p_object: p,
            tint: Vec3::ONE,
            from: eye,
            time: 0.5,
            looked: reyes_dice::Looked::NONE,
        };
        let got = shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1));
        assert_eq!(got, shader.shade(p, n, Vec3::ONE), "point {i}");
    }
    // The formula at one point: light and eye straight along -z, normal -z; N.H = 1.
    let s = scene(
        "lights: [Ambient(intensity: 0.5), Distant(from: (0.0, 0.0, -1.0), intensity: 0.8)], \
         objects: [(shape: Sphere(radius: 1.0), material: Metal(color: (0.9, 0.6, 0.3), \
                    opacity: (0.5, 1.0, 1.0), ka: 0.4, ks: 0.9))]",
    );
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let p = Vec3::new(0.0, 0.0, -1.0);
    let at = SurfacePoint {
        object: 0,
        p_world: p,
        n_world: Vec3::NEG_Z,
        p_object: p,
        tint: Vec3::ONE,
        from: Vec3::new(0.0, 0.0, -10.0),
        time: 0.0,
        looked: reyes_dice::Looked::NONE,
    };
    let (c, trans) = shading.shade_surface(&at, &mut Strata::new(0, 0, 0, 1));
    // Ci = Os * Cs * (Ka * ambient + Ks * Cl * 1^(8/roughness)).
    let ci = Vec3::new(0.9, 0.6, 0.3) * (0.4 * 0.5 + 0.9 * 0.8);
    let want = Vec3::new(0.5, 1.0, 1.0) * ci;
    assert!((Vec3::from(c) - want).abs().max_element() < 1e-6, "{c:?} vs {want}");
    assert_eq!(trans, [0.5, 0.0, 0.0]);
}

/// Two floors side by side under an ambient light, a spot light and a shadowing area light;
/// the right one (object 1) has the light set `set`.
fn two_floors(set: &str) -> Scene {
    let left = patch(
        Vec3::new(-8.0, 0.0, -4.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 8.0),
        "material: Matte(color: (1.0, 1.0, 1.0))",
    );
    let right = patch(
        Vec3::new(0.0, 0.0, -4.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 8.0),
        &format!("material: Matte(color: (1.0, 1.0, 1.0)), lights: {set}"),
    );
    scene(&format!(
        "lights: [Ambient(intensity: 0.1), \
                  Spot(from: (0.0, 5.0, 0.0), to: (0.0, 0.0, 0.0), intensity: 25.0, cone_angle: 70.0, shadows: true), \
                  Area(shape: Disk(center: (0.0, 6.0, 0.0), normal: (0.0, -1.0, 0.0), radius: 0.5), intensity: 36.0)], \
         objects: [{left}, {right}]"
    ))
}

#[test]
fn an_object_outside_a_lights_set_is_not_lit_by_it() {
    let all = two_floors("None");
    let t_all = tracer(&all);
    let shading_all = Shading::new(&all, &t_all);
    let mean = |shading: &Shading, object: u32, x: f32| {
        shade_mean(shading, &floor_point(object, x, 0.5, 0.0), 64, 3)
    };
    // The right floor lit by the spot light only, by the area light only, by nothing.
    for (set, lit_by) in [("Some([1])", "spot"), ("Some([2])", "area"), ("Some([])", "nothing")] {
        let s = two_floors(set);
        let t = tracer(&s);
        let shading = Shading::new(&s, &t);
        // The left floor, lit by everything, is unchanged, member for member: an excluded area
        // light keeps its stratum dimension.
        for x in [-0.5f32, -2.0, -3.0] {
            let at = floor_point(0, x, 0.5, 0.0);
            for m in 0..8 {
                let a = shading_all.shade_surface(&at, &mut Strata::new(7, 3, m, 8));
                let b = shading.shade_surface(&at, &mut Strata::new(7, 3, m, 8));
                assert_eq!(a, b, "{set}: the left floor at {x}");
            }
        }
        // The right floor gets exactly the lights of its set. A scene holding only them
        // shades it identically: each excluded light adds nothing, shadow rays included.
        let only = |keep: &[&str]| {
            let lights = [
                "Ambient(intensity: 0.1)",
                "Spot(from: (0.0, 5.0, 0.0), to: (0.0, 0.0, 0.0), intensity: 25.0, cone_angle: 70.0, shadows: true)",
                "Area(shape: Disk(center: (0.0, 6.0, 0.0), normal: (0.0, -1.0, 0.0), radius: 0.5), intensity: 36.0)",
            ];
            let kept: Vec<&str> =
                lights.iter().copied().filter(|l| keep.iter().any(|k| l.starts_with(k))).collect();
            let floor = patch(
                Vec3::new(0.0, 0.0, -4.0),
                Vec3::new(8.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 8.0),
                "material: Matte(color: (1.0, 1.0, 1.0))",
            );
            scene(&format!("lights: [{}], objects: [{floor}]", kept.join(", ")))
        };
        let reference = match lit_by {
            "spot" => only(&["Spot"]),
            "area" => only(&["Area"]),
            _ => only(&[]),
        };
        let t_ref = tracer(&reference);
        let shading_ref = Shading::new(&reference, &t_ref);
        for x in [0.5f32, 2.0, 3.5] {
            let got = mean(&shading, 1, x);
            let want = mean(&shading_ref, 0, x);
            assert!((got - want).abs().max_element() < 1e-6, "{set} at {x}: {got} vs {want}");
            if lit_by == "nothing" {
                assert_eq!(got, Vec3::ZERO, "an empty light set leaves a matte surface black");
            }
        }
        // The dicer's local illumination honours the set too (no shadows, no area lights).
        let eye = Vec3::new(0.0, 20.0, -20.0);
        let dicer = Shader::for_object(&s.objects[1], &s.lights, Viewer::Eye(eye));
        let dicer_all = Shader::for_object(&all.objects[1], &all.lights, Viewer::Eye(eye));
        let p = Vec3::new(2.0, 0.0, 0.5);
        let (c, _) = dicer.shade(p, Vec3::Y, Vec3::ONE);
        let (c_all, _) = dicer_all.shade(p, Vec3::Y, Vec3::ONE);
        match lit_by {
            // The spot light's contribution alone: everything minus the ambient 0.1.
            "spot" => assert!((c[0] - (c_all[0] - 0.1)).abs() < 1e-6, "{c:?} vs {c_all:?}"),
            // Area lights are the ray-traced shading's; the dicer has nothing left.
            _ => assert_eq!(c, [0.0; 3], "{set}"),
        }
    }
}

#[test]
fn ray_traced_vertices_under_an_orthographic_camera_are_seen_along_the_view() {
    // A glossy plate facing the camera (camera looks down +z): with light and view along -z,
    // the highlight covers the whole plate under an orthographic camera; every vertex shades
    // as the dicer's orthographic shader does, bit for bit.
    let text = "Scene(image: (width: 8, height: 8), \
        camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0), projection: Orthographic), \
        lights: [Distant(from: (0.0, 0.0, -1.0), shadows: true)], \
        objects: [(shape: Disk(radius: 5.0), transform: [Rotate(angle: 180.0, axis: (0.0, 1.0, 0.0))], \
                   material: Plastic(color: (0.0, 0.0, 0.0), kd: 0.0, ks: 1.0))])";
    let s = reyes_scene::parse(text, std::path::Path::new("ortho.ron")).expect("parses");
    let t = tracer(&s);
    let shading = Shading::new(&s, &t);
    let vertex = RayVertexShader::new(&s, &shading, ShutterShape::Uniform);
    let camera = reyes_dice::CameraSetup::new(&s);
    let dicer = Shader::for_object(&s.objects[0], &s.lights, camera.viewer());
    for (x, y) in [(0.0f32, 0.0f32), (3.0, 1.0), (-4.0, -2.5)] {
        let p = Vec3::new(x, y, 0.0);
        let ctx = reyes_dice::VertexContext {
            object: 0,
            surface: 0,
            patch_u: [0.0, 1.0],
            patch_v: [0.0, 1.0],
            i: 0,
            j: 0,
            nu: 1,
            nv: 1,
            p_world: p,
            n_world: Vec3::NEG_Z,
            p_object: p,
            tint: Vec3::ONE,
            looked: reyes_dice::Looked::NONE,
        };
        let (c, _) = VertexShader::shade(&vertex, &ctx);
        assert!((c[0] - 1.0).abs() < 1e-5, "({x}, {y}): the peak of the highlight, {c:?}");
        assert_eq!((c, [0.0; 3]), dicer.shade(p, Vec3::NEG_Z, Vec3::ONE), "({x}, {y})");
        // The ray-tracing hider's ray along the view sees the same highlight.
        let h = trace_one(&shading, &Ray::new(Vec3::new(x, y, -9.0), Vec3::Z, 0.0));
        assert!((h.rgba[0] - 1.0).abs() < 1e-5, "({x}, {y}): {h:?}");
    }
}
