//! The fields of distributed ray tracing (lights with shadows and extent, reflection,
//! refraction, patterns, rolling, the ray-tracing hider and its limits) and their defaults.

use crate::{FULL, ok};

/// Every new field of distributed ray tracing, with defaults left out where they exist.
pub(crate) const TRACED: &str = r#"
Scene(
  image: (width: 64, height: 48),
  camera: (eye: (0.0, 2.0, -10.0), look_at: (0.0, 1.0, 0.0)),
  lights: [
    Point(from: (0.0, 5.0, 0.0), shadows: true),
    Distant(from: (1.0, 1.0, -1.0), shadows: true),
    Area(shape: Sphere(center: (0.0, 8.0, 0.0), radius: 1.0)),
    Area(shape: Disk(center: (2.0, 8.0, 0.0), normal: (0.0, -1.0, 0.0), radius: 0.5),
         color: (1.0, 0.9, 0.8), intensity: 30.0),
    Area(shape: Rectangle(corner: (-1.0, 9.0, -1.0), edge_u: (2.0, 0.0, 0.0), edge_v: (0.0, 0.0, 2.0)),
         motion: [(time: 0.0), (time: 1.0, offset: (1.0, 0.0, 0.0), intensity: 0.5)]),
  ],
  objects: [
    (name: "mirror", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
     reflect: Some((color: (0.9, 0.9, 0.9)))),
    (name: "glass", shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5)),
     refract: Some((ior: 1.5))),
    (name: "ball", shape: Sphere(radius: 0.5), material: Plastic(color: (1.0, 1.0, 1.0)),
     pattern: Some(PoolBall(color: (0.9, 0.7, 0.1))),
     roll: Some((radius: 0.5, path: [(time: 0.0, position: (-1.0, 0.5, 0.0)), (time: 1.0, position: (1.0, 0.5, 0.0))]))),
  ],
)
"#;

#[test]
fn ray_tracing_fields_take_their_defaults() {
    use reyes_scene::{
        AreaShape, HiderMethod, Light, LightKey, Pattern, RayTrace, Reflect, Refract,
    };
    let scene = ok(TRACED);
    assert_eq!(scene.hider.method, HiderMethod::Stochastic);
    assert_eq!(scene.raytrace, RayTrace { max_depth: 4, min_weight: 0.01, vertex_rays: 1 });
    assert_eq!(scene.raytrace, RayTrace::default());
    let plain = ok(FULL);
    assert!(plain.lights.iter().all(|l| match l {
        Light::Distant { shadows, .. } | Light::Point { shadows, .. } => !shadows,
        _ => true,
    }));
    assert!(matches!(scene.lights[0], Light::Point { shadows: true, .. }));
    assert_eq!(
        scene.lights[2],
        Light::Area {
            shape: AreaShape::Sphere { center: [0.0, 8.0, 0.0], radius: 1.0 },
            color: [1.0, 1.0, 1.0],
            intensity: 1.0,
            motion: vec![],
            one_sided: false,
        }
    );
    let Light::Area { motion, .. } = &scene.lights[4] else { panic!("not an area light") };
    assert_eq!(
        motion,
        &[
            LightKey { time: 0.0, offset: [0.0, 0.0, 0.0], intensity: 1.0 },
            LightKey { time: 1.0, offset: [1.0, 0.0, 0.0], intensity: 0.5 },
        ]
    );
    assert_eq!(scene.objects[0].reflect, Some(Reflect { color: [0.9, 0.9, 0.9], gloss: 0.0 }));
    assert_eq!(
        scene.objects[1].refract,
        Some(Refract { ior: 1.5, color: [1.0, 1.0, 1.0], blur: 0.0 })
    );
    assert_eq!(
        scene.objects[2].pattern,
        Some(Pattern::PoolBall { color: [0.9, 0.7, 0.1], striped: false })
    );
    let roll = scene.objects[2].roll.as_ref().unwrap_or_else(|| panic!("no roll"));
    assert_eq!((roll.up, roll.steps), ([0.0, 1.0, 0.0], 8));
    // Nothing of it is in the plain scene.
    assert!(plain.objects.iter().all(|o| o.reflect.is_none()
        && o.refract.is_none()
        && o.pattern.is_none()
        && o.roll.is_none()));
}

#[test]
fn limits_at_their_ends_are_accepted() {
    let with = |hider: &str, raytrace: &str, mirror: &str| {
        TRACED
            .replacen(
                "  lights: [",
                &format!("  hider: ({hider}),\n  raytrace: ({raytrace}),\n  lights: ["),
                1,
            )
            .replacen("reflect: Some((color: (0.9, 0.9, 0.9)))", mirror, 1)
    };
    let scene = ok(&with(
        "method: RayTrace",
        "max_depth: 64, min_weight: 0.0, vertex_rays: 4096",
        "reflect: Some((color: (1.0, 0.0, 1.0), gloss: 89.9))",
    ));
    assert_eq!(scene.hider.method, reyes_scene::HiderMethod::RayTrace);
    assert_eq!(scene.raytrace.vertex_rays, 4096);
    // A depth limit of zero is fine when no object asks for reflection or refraction rays.
    let text = with("", "max_depth: 0, min_weight: 0.999", "matte: false").replacen(
        ",\n     refract: Some((ior: 1.5))",
        "",
        1,
    );
    assert_eq!(ok(&text).raytrace.max_depth, 0);
}
