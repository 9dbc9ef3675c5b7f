//! Validation matches the render setup: a scene that passes validation always has a camera
//! basis, a finite world-to-camera matrix and projection, and a filter table, as the renderer
//! builds them; and a filter the film cannot build a table for never passes validation.
//!
//! The laws run the renderer's own setup code (`reyes_render::settings::Stages`, the dicer's
//! camera check through `dice_scene` of a scene with no objects) on random cameras and
//! filters, the extremes included (denormal and huge distances, nearly parallel up vectors,
//! filters far narrower than a pixel).

use std::path::Path;

use proptest::prelude::*;
use reyes_dice::{CameraSetup, dice_scene};
use reyes_render::frame_for;
use reyes_render::settings::Stages;
use reyes_scene::{Filter, FilterKind, Scene, parse, validate};

const BASE: &str = r#"Scene(
  image: (width: 8, height: 6),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), fov: 35.0),
  hider: (pixel_samples: (2, 2)),
)
"#;

fn base() -> Scene {
    parse(BASE, Path::new("setup.ron")).unwrap_or_else(|e| panic!("{e}"))
}

/// The render setup of `scene`: its filter table and its camera, as the renderer builds them.
fn set_up(scene: &Scene) -> Result<(), String> {
    Stages::new(scene, |h| h).map_err(|e| e.to_string())?;
    dice_scene(scene, &frame_for(scene)).map_err(|e| e.to_string())?;
    let camera = CameraSetup::new(scene);
    if !camera.world_to_camera().is_finite() {
        return Err("world to camera is not finite".into());
    }
    if !(camera.raster_scale().is_finite() && camera.raster_centre().is_finite()) {
        return Err("raster mapping is not finite".into());
    }
    if let Some(lens) = camera.lens() {
        let (x, y) = lens.coc(camera.hither());
        if !(x.is_finite() && y.is_finite()) {
            return Err("lens blur is not finite".into());
        }
    }
    Ok(())
}

/// A magnitude from 1e-40 to 1e30 (denormals included), either sign.
fn magnitude() -> impl Strategy<Value = f32> {
    (-40i32..=30, 1.0f32..10.0, any::<bool>())
        .prop_map(|(e, m, neg)| {
            let v = m * 10f32.powi(e);
            if neg { -v } else { v }
        })
        .prop_filter("finite", |v| v.is_finite())
}

fn vector() -> impl Strategy<Value = [f32; 3]> {
    prop_oneof![
        [magnitude(), magnitude(), magnitude()],
        magnitude().prop_map(|m| [m, 0.0, 0.0]),
        magnitude().prop_map(|m| [0.0, 0.0, m]),
        [-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0],
    ]
}

fn kind() -> impl Strategy<Value = FilterKind> {
    proptest::sample::select(FilterKind::ALL.to_vec())
}

/// A width from far below a pixel to a few pixels.
fn width() -> impl Strategy<Value = f32> {
    prop_oneof![0.001f32..3.0, (-20i32..0).prop_map(|e| 10f32.powi(e)), 0.0f32..0.02]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// Validation accepts a filter exactly when the renderer can build its table, for every
    /// kind, width and sample grid, with the original stratum pairing or not.
    #[test]
    fn a_filter_is_valid_exactly_when_it_has_a_table(
        kind in kind(),
        width in width(),
        height in proptest::option::of(width()),
        nx in 1u32..6,
        ny in 1u32..6,
        permute in any::<bool>(),
    ) {
        let mut scene = base();
        scene.hider.filter = Filter { kind, width, height };
        scene.hider.pixel_samples = (nx, ny);
        scene.hider.original.permute = permute;
        let valid = validate(scene.clone());
        let setup = set_up(&scene);
        prop_assert_eq!(valid.is_ok(), setup.is_ok(), "{:?} vs {:?}", valid.err(), setup.err());
        if let Err(issue) = validate(scene) {
            prop_assert!(issue.path.starts_with("hider.filter"), "{}", issue.path);
        }
    }

    /// A camera that passes validation can be set up: it has a basis, and its world-to-camera
    /// matrix, raster mapping and lens blur are finite.
    #[test]
    fn a_valid_camera_can_be_set_up(
        eye in vector(),
        look_at in vector(),
        up in vector(),
        fov in prop_oneof![0.0001f32..179.9, (-40i32..0).prop_map(|e| 10f32.powi(e))],
        window in proptest::option::of((magnitude(), magnitude(), magnitude(), magnitude())),
        lens in proptest::option::of((magnitude(), magnitude(), magnitude())),
    ) {
        let mut scene = base();
        scene.camera.eye = eye;
        scene.camera.look_at = look_at;
        scene.camera.up = up;
        scene.camera.fov = fov;
        scene.camera.screen_window = window.map(|(a, b, c, d)| [a.min(b), a.max(b), c.min(d), c.max(d)]);
        scene.camera.lens = lens.map(|(f, s, d)| reyes_scene::Lens {
            focal_length: f.abs(),
            f_stop: s.abs(),
            focal_distance: d.abs(),
        });
        if let Ok(scene) = validate(scene) {
            prop_assert!(set_up(&scene).is_ok(), "{:?}: {:?}", scene.camera, set_up(&scene).err());
        }
    }
}

/// The degenerate views an independent run found rendering to "dicing failed" (exit 1) are
/// validation errors at the field, and a view just inside single precision renders.
#[test]
fn views_at_the_edge_of_single_precision() {
    let with = |eye: [f32; 3], look_at: [f32; 3], up: [f32; 3]| {
        let mut scene = base();
        scene.camera.eye = eye;
        scene.camera.look_at = look_at;
        scene.camera.up = up;
        (validate(scene.clone()).map(|_| ()).map_err(|i| i.path), set_up(&scene).is_ok())
    };
    let y = [0.0, 1.0, 0.0];
    // A denormal apart, and 4e20 apart (the squared length overflows).
    assert_eq!(with([0.0; 3], [0.0, 0.0, 1e-40], y), (Err("camera.look_at".into()), false));
    assert_eq!(with([0.0, 0.0, -2e20], [0.0, 0.0, 2e20], y), (Err("camera.look_at".into()), false));
    // 1e19 apart is fine.
    assert_eq!(with([0.0; 3], [0.0, 0.0, 1e19], y), (Ok(()), true));
    // Up vectors parallel after rounding: too small to cross, too large to cross.
    let z = [0.0, 0.0, 1.0];
    assert_eq!(with([0.0; 3], z, [1e-30, 1e-30, 0.0]), (Err("camera.up".into()), false));
    assert_eq!(with([0.0; 3], z, [3e38, 3e38, 0.0]), (Err("camera.up".into()), false));
    // An eye so far out that the world-to-camera translation overflows (up . eye).
    let e = with([3e38, 3e38, 0.0], [3e38, 3e38, 1.0], [1.0, 1.0, 0.0]);
    assert_eq!(e.0, Err("camera.eye".into()));
}

/// The filters an independent run found failing at render time (exit 1) are validation
/// errors at `hider.filter`.
#[test]
fn filters_narrower_than_the_strata() {
    let with = |kind: FilterKind, width: f32, n: u32| {
        let mut scene = base();
        scene.hider.filter = Filter::new(kind, width);
        scene.hider.pixel_samples = (n, n);
        validate(scene).map(|_| ()).map_err(|i| i.path)
    };
    assert_eq!(with(FilterKind::Gaussian, 0.1, 2), Err("hider.filter".into()));
    assert_eq!(with(FilterKind::Box, 1e-20, 2), Err("hider.filter".into()));
    assert_eq!(with(FilterKind::RiDisk, 0.6, 2), Err("hider.filter".into()));
    // On a 3x3 grid a stratum centre lies on the pixel centre: any width weighs it.
    assert_eq!(with(FilterKind::RiDisk, 0.6, 3), Ok(()));
    assert_eq!(with(FilterKind::Gaussian, 0.1, 1), Ok(()));
}
