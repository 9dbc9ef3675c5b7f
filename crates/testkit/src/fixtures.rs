//! Scenes and objects built in code for tests, and the frame a scene lays out.
//!
//! Invariant: a fixture is the same scene every time (no randomness, no environment).

use std::path::Path;

pub use reyes_render::frame_for;
use reyes_scene::{
    Basis, Camera, Hider, Image, Lens, Light, Material, Object, PatchType, Projection, Scene,
    Shape, Shutter, Transform, Wrap,
};

/// Parse and validate RON scene text, panicking with the error (tests only).
pub fn parse(text: &str) -> Scene {
    match reyes_scene::parse(text, Path::new("test.ron")) {
        Ok(scene) => scene,
        Err(e) => panic!("{e}"),
    }
}

/// A perspective camera at `eye` looking at `look_at` with +y up (default screen window).
pub fn camera(eye: [f32; 3], look_at: [f32; 3], fov: f32, lens: Option<Lens>) -> Camera {
    Camera {
        eye,
        look_at,
        up: [0.0, 1.0, 0.0],
        projection: Projection::Perspective,
        fov,
        screen_window: None,
        hither: 0.1,
        yon: 1000.0,
        shutter: Shutter::default(),
        lens,
        motion: Vec::new(),
    }
}

/// A scene of `objects` seen by `camera`, default hider, one ambient and one distant light.
pub fn scene(width: u32, height: u32, camera: Camera, objects: Vec<Object>) -> Scene {
    Scene {
        image: Image::new(width, height),
        camera,
        hider: Hider::default(),
        lights: vec![
            Light::Ambient { color: [1.0; 3], intensity: 0.2 },
            Light::Distant {
                from: [1.0, 1.0, -1.0],
                to: [0.0; 3],
                color: [1.0; 3],
                intensity: 1.0,
                shadows: false,
            },
        ],
        objects,
        solids: Vec::new(),
        raytrace: Default::default(),
        outputs: Default::default(),
        texture_cache: Default::default(),
        shader_path: Vec::new(),
        shaders: Default::default(),
    }
}

/// White matte (`ka = kd = 1`).
pub fn white_matte() -> Material {
    Material::Matte { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, kd: 1.0 }
}

/// A white matte object.
pub fn object(shape: Shape, transform: Vec<Transform>) -> Object {
    Object::new(shape, white_matte()).with_transform(transform)
}

/// A whole sphere of radius `r`.
pub fn sphere(r: f32) -> Shape {
    Shape::Sphere { radius: r, zmin: None, zmax: None, thetamax: 360.0 }
}

/// Five distinct vertex colours, a mesh's `colors` for its five points: red, green, blue,
/// yellow and cyan.
pub fn five_colors() -> Vec<[f32; 3]> {
    vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.0], [0.0, 1.0, 1.0]]
}

/// A nonperiodic patch mesh of `kind` with `nu` x `nv` `points` (bicubic: in the Bezier basis).
pub fn patch_mesh(kind: PatchType, nu: u32, nv: u32, points: Vec<[f32; 3]>) -> Shape {
    let bezier = (Basis::Bezier, Basis::Bezier);
    patch_mesh_with(kind, nu, nv, (Wrap::Nonperiodic, Wrap::Nonperiodic), bezier, points)
}

/// A patch mesh of `kind` with `nu` x `nv` `points`, the `(u, v)` wraps and bases and the
/// bases' standard steps.
pub fn patch_mesh_with(
    kind: PatchType,
    nu: u32,
    nv: u32,
    wrap: (Wrap, Wrap),
    basis: (Basis, Basis),
    points: Vec<[f32; 3]>,
) -> Shape {
    Shape::PatchMesh {
        kind,
        nu,
        nv,
        uwrap: wrap.0,
        vwrap: wrap.1,
        points,
        ubasis: basis.0,
        ustep: None,
        vbasis: basis.1,
        vstep: None,
    }
}

/// The nine control points of the unit circle around z as a rational quadratic (corners of
/// weight 1/sqrt(2), from (1, 0) round to (1, 0) again), a row at each of the two `heights`,
/// in homogeneous form `[x w, y w, z w, w]`.
pub fn nurbs_circle_points(heights: [f32; 2]) -> Vec<[f32; 4]> {
    let w = std::f32::consts::FRAC_1_SQRT_2;
    let ring = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    let mut points = Vec::new();
    for z in heights {
        for (k, (x, y)) in ring.iter().enumerate() {
            let wk = if k % 2 == 1 { w } else { 1.0 };
            points.push([x * wk, y * wk, z * wk, wk]);
        }
    }
    points
}

/// The knots of [`nurbs_circle_points`] along u: four quadratic spans, one a quarter circle.
pub const NURBS_CIRCLE_KNOTS: [f32; 12] =
    [0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0];

/// A NURBS of `nu` points along u, of order `uorder` on `uknot`, ruled linearly in v between
/// two rows (order 2 on `[0, 0, 1, 1]`): `points` holds both rows, `[x w, y w, z w, w]`.
pub fn nurbs_ruled(nu: u32, uorder: u32, uknot: Vec<f32>, points: Vec<[f32; 4]>) -> Shape {
    Shape::NuPatch {
        nu,
        uorder,
        uknot,
        umin: 0.0,
        umax: 1.0,
        nv: 2,
        vorder: 2,
        vknot: vec![0.0, 0.0, 1.0, 1.0],
        vmin: 0.0,
        vmax: 1.0,
        points,
        trim: Vec::new(),
        trim_outside: false,
    }
}

/// The unit cylinder around z from z = -1 to 1 as a NURBS: the nine-point circle ruled
/// between the two heights.
pub fn nurbs_cylinder() -> Shape {
    nurbs_ruled(9, 3, NURBS_CIRCLE_KNOTS.to_vec(), nurbs_circle_points([-1.0, 1.0]))
}

/// The RON text of a scene for measurement (FIG. 23): these objects (each given a grey
/// matte material) and solids, seed 7.
pub fn measure_scene(objects: &[&str], solids: &str) -> String {
    let objects: Vec<String> =
        objects.iter().map(|o| format!("({o}, material: Matte(color: (0.8, 0.8, 0.8)))")).collect();
    format!(
        "Scene(
  image: (width: 32, height: 24),
  camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0)),
  hider: (seed: 7),
  objects: [{}],
  solids: [{solids}],
)
",
        objects.join(",\n    ")
    )
}

/// The control cube of half-side 1: point `i` at `(+-1, +-1, +-1)` by its bits (1: x, 2: y,
/// 4: z; a clear bit is -1).
pub fn cube_corners() -> Vec<[f32; 3]> {
    (0..8)
        .map(|i| {
            let s = |bit: i32| if i & bit == 0 { -1.0 } else { 1.0 };
            [s(1), s(2), s(4)]
        })
        .collect()
}

/// The six faces of [`cube_corners`], counter-clockwise seen from outside.
pub const CUBE_QUADS: [[u32; 4]; 6] =
    [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];

/// The unit octahedron's points: `+x, -x, +y, -y, +z, -z`.
pub const OCTAHEDRON_POINTS: [[f32; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, -1.0],
];

/// The eight faces of [`OCTAHEDRON_POINTS`], counter-clockwise seen from outside.
pub const OCTAHEDRON_FACES: [[u32; 3]; 8] =
    [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
