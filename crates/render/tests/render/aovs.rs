//! AOVs against analytic truth (docs/outputs.md): a sphere's normal and position, a moving
//! square's motion vector, ids across an edge, the shading components adding up to the
//! beauty, and the beauty itself unchanged by asking for AOVs, for any thread count.

use std::path::Path;

use reyes_render::{RenderOptions, Rendered, render};
use reyes_scene::{AovSource, Scene};

fn parse(text: &str) -> Scene {
    reyes_scene::parse(text, Path::new("aovs.ron")).unwrap_or_else(|e| panic!("{e}"))
}

fn rendered(scene: &Scene, threads: usize) -> Rendered {
    let opts = RenderOptions { threads: Some(threads), ..Default::default() };
    render(scene, &opts).unwrap_or_else(|e| panic!("{e}"))
}

/// Channel `c` of the AOV layer named `name` at pixel `(x, y)`.
fn aov(r: &Rendered, name: &str, x: u32, y: u32, c: usize) -> f32 {
    let a = r.aovs.as_ref().expect("the scene writes AOVs");
    let layer = a.layers.iter().find(|l| l.name == name).unwrap_or_else(|| panic!("no {name}"));
    a.film.value(x, y, layer.start + c)
}

/// A unit sphere centred at (0.3, -0.2, 4) seen from the origin looking down +z (camera space
/// is world space), 64x64 pixels, fov 40, one sample per pixel at its centre (`jitter: false`
/// places the only stratum's sample there), so each pixel's AOVs are those of the ray through
/// its centre.
const SPHERE: &str = "Scene(image: (width: 64, height: 64),
    camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 40.0),
    hider: (pixel_samples: (1, 1), jitter: false, filter: (kind: Box, width: 1.0),
            shading_rate: 0.25),
    objects: [(shape: Sphere(radius: 1.0), transform: [Translate((0.3, -0.2, 4.0))],
               material: Matte(color: (1.0, 1.0, 1.0)))],
    outputs: (aovs: [(source: N, filter: Some(Nearest)), (source: P, filter: Some(Nearest)),
                     (source: ObjectId)]))";

#[test]
fn a_spheres_normal_and_position_are_its_analytic_ones() {
    // Without crack-free dicing every vertex is on the sphere. With it (the default) the
    // vertices on patch boundaries lie on their side's shared polyline instead, whose chords
    // stray from the sphere by at most the edge tolerance, 0.05 pixel here (the flatness
    // bound; the relative bound, 1/512 of the sphere's 50-pixel extent, is looser), checked
    // in camera-space depth too (split/edge.rs): at depth z <= 4 that is 0.05 z / k <=
    // 2.3e-3 units. Such a vertex is shaded, and its P and N taken, at the surface point,
    // so N = P - C still holds exactly; but the micropolygon, and so the sample's place in
    // it, may be off the sphere by that much more.
    let mut exact = parse(SPHERE);
    exact.hider.crack_free = false;
    sphere_aovs_are_analytic(&exact, 0.0);
    let k = 32.0 / 20f64.to_radians().tan();
    sphere_aovs_are_analytic(&parse(SPHERE), 0.05 * 4.0 / k);
}

/// [`a_spheres_normal_and_position_are_its_analytic_ones`] for `scene`, its micropolygons'
/// vertices at most `delta` off the sphere.
fn sphere_aovs_are_analytic(scene: &Scene, delta: f64) {
    let r = rendered(scene, 2);
    let centre = glam::DVec3::new(0.3, -0.2, 4.0);
    // Raster (x + 0.5, y + 0.5) is the ray (dx, dy, 1) with dx = (x + 0.5 - 32) / k and
    // dy = (32 - y - 0.5) / k, k = 32 / tan(20 deg).
    let k = 32.0 / 20f64.to_radians().tan();
    let (mut checked, mut worst_p, mut worst_n) = (0, 0.0f64, 0.0f64);
    for y in 0..64 {
        for x in 0..64 {
            let d = glam::DVec3::new((x as f64 + 0.5 - 32.0) / k, (32.0 - y as f64 - 0.5) / k, 1.0)
                .normalize();
            // Ray-sphere: |t d - c|^2 = 1, nearest root.
            let b = d.dot(centre);
            let disc = b * b - (centre.length_squared() - 1.0);
            let id = aov(&r, "object_id", x, y, 0);
            let p = glam::DVec3::new(
                f64::from(aov(&r, "P", x, y, 0)),
                f64::from(aov(&r, "P", x, y, 1)),
                f64::from(aov(&r, "P", x, y, 2)),
            );
            let n = glam::DVec3::new(
                f64::from(aov(&r, "N", x, y, 0)),
                f64::from(aov(&r, "N", x, y, 1)),
                f64::from(aov(&r, "N", x, y, 2)),
            );
            if disc < 0.0 {
                assert_eq!(id, 0.0, "({x},{y}) misses the sphere");
                assert_eq!((p, n), (glam::DVec3::ZERO, glam::DVec3::ZERO), "({x},{y})");
                continue;
            }
            let hit = d * (b - disc.sqrt());
            let truth_n = hit - centre;
            // Away from the silhouette (where a sample may fall off the faceted sphere).
            if truth_n.dot(-d) < 0.3 {
                continue;
            }
            assert_eq!(id, 1.0, "({x},{y})");
            checked += 1;
            // N and P are interpolated at the sample with the same weights from vertices
            // where N = (P - centre) / r exactly, so N is the normal at P to float rounding
            // (values near 4 in f32: 1e-6 relative, a few 1e-6 absolute).
            let n_at_p = p - centre;
            worst_n = worst_n.max((n - n_at_p).length());
            assert!((n - n_at_p).length() < 2e-5, "({x},{y}): N {n} vs (P - C) {n_at_p}");
            // P against the ray-sphere point: P is interpolated bilinearly at the sample
            // over the micropolygon, whose bilinear surface through four points of the sphere
            // lies inside it by at most its sagitta d^2 / (8 r), d its diagonal in 3D. At
            // shading rate 0.25 projected edges are 0.5 pixel, up to twice that where a grid
            // is stretched: a projected diagonal of at most sqrt(2) px, and a pixel at depth
            // z <= 4 is z / k <= 0.0455 units, so 0.064. Where the surface meets the ray at
            // cosine c the 3D diagonal is up to 1/c longer and the error along the ray 1/c
            // larger again: |P - hit| <= 0.064^2 / 8 / c^3 = 5.2e-4 / c^3.
            let cos = truth_n.dot(-d);
            let err = (p - hit).length();
            worst_p = worst_p.max(err * cos.powi(3));
            let tol = 5.2e-4 / cos.powi(3) + delta;
            assert!(err < tol, "({x},{y}): P {p} vs ray-sphere {hit}, {err}");
            // And the normal is the analytic one: N - truth = (P - hit) / r, the same error.
            assert!((n - truth_n).length() < tol + 2e-5, "({x},{y}): N {n} vs {truth_n}");
        }
    }
    assert!(checked > 300, "only {checked} pixels checked");
    eprintln!(
        "sphere: {checked} pixels, worst |P - hit| cos^3 {worst_p:.2e}, |N - (P-C)| {worst_n:.2e}"
    );
}

/// A square of side 1 facing the camera at depth 5, moving +0.4 in x and -0.2 in y (world,
/// y up) over the shutter, 64x64, fov 90, so raster x = 32 + 32 x / z and its motion is
/// `(32 * 0.4 / 5, 32 * 0.2 / 5)` = (2.56, 1.28) pixels per shutter interval (raster y down).
const MOVING_SQUARE: &str = "Scene(image: (width: 64, height: 64),
    camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 90.0,
             shutter: (open: 0.0, close: 1.0)),
    hider: (pixel_samples: (4, 4)),
    objects: [(shape: BilinearPatch(points: ((-0.5, -0.5, 5.0), (0.5, -0.5, 5.0),
                                            (-0.5, 0.5, 5.0), (0.5, 0.5, 5.0))),
               motion: [(time: 0.0, transform: []),
                        (time: 1.0, transform: [Translate((0.4, -0.2, 0.0))])],
               material: Constant(color: (1.0, 1.0, 1.0)))],
    outputs: (aovs: [(source: DPdtime, filter: Some(Zmin)), (source: ObjectId),
                     (source: DPdtime, name: Some(\"filtered\"))]))";

#[test]
fn a_moving_squares_motion_vector_is_its_velocity() {
    let r = rendered(&parse(MOVING_SQUARE), 2);
    let expect = [32.0 * 0.4 / 5.0, 32.0 * 0.2 / 5.0];
    let mut covered = 0;
    for y in 0..64 {
        for x in 0..64 {
            let v = [aov(&r, "dPdtime", x, y, 0), aov(&r, "dPdtime", x, y, 1)];
            if aov(&r, "object_id", x, y, 0) == 0.0 {
                assert_eq!(v, [0.0, 0.0], "({x},{y}) background");
                continue;
            }
            covered += 1;
            // Every vertex moves by the same raster displacement (speed is computed in f32
            // from raster positions near 32: rounding 4e-6 each), and the Shepard weights sum
            // to 1 within a few ulps.
            for a in 0..2 {
                assert!(
                    (f64::from(v[a]) - expect[a]).abs() < 1e-4,
                    "({x},{y}): {v:?} vs {expect:?}"
                );
            }
        }
    }
    // The square sweeps 6.4 x 6.4 pixels plus its motion: about 9 x 8 pixels see it.
    assert!(covered > 40, "{covered}");
    // Filtered with the beauty's filter the motion is weighted by coverage like the colour:
    // an interior pixel (covered by every sample through the whole shutter) has it exactly
    // times its filter weight sum, 1 to f32 rounding.
    let (cx, cy) = (32 + 1, 32);
    let f = [aov(&r, "filtered", cx, cy, 0), aov(&r, "filtered", cx, cy, 1)];
    let alpha = r.film.pixel(cx, cy).unwrap_or_default()[3];
    assert!((alpha - 1.0).abs() < 1e-5, "centre pixel alpha {alpha}");
    for a in 0..2 {
        assert!((f64::from(f[a]) - expect[a]).abs() < 1e-4, "filtered {f:?} vs {expect:?}");
    }
}

/// Two abutting squares covering the image, ids 1 (left) and 2 (right), whose shared edge
/// crosses pixel columns at a slant (raster x 25.3 at the bottom, 22.7 at the top), so many
/// pixels hold both.
const TWO_SQUARES: &str = "Scene(image: (width: 48, height: 48),
    camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 90.0),
    hider: (pixel_samples: (4, 4)),
    objects: [
      (shape: BilinearPatch(points: ((-2.2, -2.2, 2.0), (0.11, -2.2, 2.0),
                                     (-2.2, 2.2, 2.0), (-0.11, 2.2, 2.0))),
       material: Constant(color: (1.0, 0.0, 0.0))),
      (shape: BilinearPatch(points: ((0.11, -2.2, 2.0), (2.2, -2.2, 2.0),
                                     (-0.11, 2.2, 2.0), (2.2, 2.2, 2.0))),
       material: Constant(color: (0.0, 1.0, 0.0)))],
    outputs: (aovs: [(source: ObjectId), (source: MaterialId, filter: Some(Nearest)),
                     (source: ObjectId, name: Some(\"id_min\"), filter: Some(Min)),
                     (source: ObjectId, name: Some(\"id_max\"), filter: Some(Max))]))";

#[test]
fn ids_are_exact_integers_on_both_sides_of_an_edge() {
    let r = rendered(&parse(TWO_SQUARES), 2);
    let (mut left, mut right, mut mixed) = (0, 0, 0);
    for y in 0..48 {
        for x in 0..48 {
            for name in ["object_id", "material_id", "id_min", "id_max"] {
                let id = aov(&r, name, x, y, 0);
                assert!(id == 1.0 || id == 2.0, "{name} ({x},{y}) = {id}: not an id");
            }
            let (lo, hi) = (aov(&r, "id_min", x, y, 0), aov(&r, "id_max", x, y, 0));
            match (lo, hi) {
                (1.0, 1.0) => left += 1,
                (2.0, 2.0) => right += 1,
                _ => mixed += 1,
            }
            // Two different materials, numbered in order of first appearance: where a pixel
            // sees one square, its material id is its object id.
            if lo == hi {
                assert_eq!(aov(&r, "material_id", x, y, 0), lo, "({x},{y})");
                assert_eq!(aov(&r, "object_id", x, y, 0), lo, "({x},{y})");
            }
        }
    }
    // The edge crosses one or two pixels of each of the 48 rows; such a pixel shows both
    // squares unless all 16 of its samples fall on one side, which needs the edge within about
    // an eighth of a pixel of its side: most rows have one.
    eprintln!("ids: {left} pixels left, {right} right, {mixed} on the edge");
    assert!(left > 900 && right > 900 && mixed >= 36, "{left} {right} {mixed}");
    // Asking for an averaged id is refused, at the field.
    let bad =
        TWO_SQUARES.replace("(source: ObjectId),", "(source: ObjectId, filter: Some(Filter)),");
    let err = reyes_scene::parse(&bad, Path::new("ids.ron")).err().map(|e| e.to_string());
    let err = err.unwrap_or_default();
    assert!(err.contains("outputs.aovs[0].filter: ids are never averaged"), "{err}");
    assert!(!err.contains('\n') && err.starts_with("ids.ron:"), "{err}");
}

/// The demo scene's materials and lights (ambient, distant, point; Matte and Plastic, one
/// transparent) with every component, ungrouped and per light group.
fn components_scene() -> Scene {
    let mut scene = parse(
        &std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/aovs.ron"))
            .unwrap_or_else(|e| panic!("{e}")),
    );
    scene.image = reyes_scene::Image::new(96, 72);
    scene
}

#[test]
fn the_shading_components_add_up_to_the_beauty() {
    let scene = components_scene();
    let r = rendered(&scene, 2);
    let sum = |x, y, c, names: &[&str]| -> f64 {
        names.iter().map(|n| f64::from(aov(&r, n, x, y, c))).sum()
    };
    let mut worst = 0.0f64;
    for y in 0..72 {
        for x in 0..96 {
            let beauty = r.film.pixel(x, y).unwrap_or_default();
            for (c, &value) in beauty.iter().enumerate().take(3) {
                let b = f64::from(value);
                // Ci is the beauty, bit for bit: the same composite, the same splat.
                assert_eq!(aov(&r, "Ci", x, y, c).to_bits(), value.to_bits(), "({x},{y})");
                // Each point's terms add up to its colour to f32 rounding (a few ulps of
                // values <= 1), then both are composited and filtered with the same weights
                // (summed in f64): a few 1e-7 relative plus 1e-7 absolute.
                let all = sum(x, y, c, &["__ambient", "__diffuse", "__specular"]);
                let tol = 1e-6 * b.abs() + 1e-6;
                worst = worst.max((all - b).abs());
                assert!((all - b).abs() <= tol, "({x},{y}) c{c}: {all} vs beauty {b}");
                // The groups key (the distant light) and fill (ambient and point) hold every
                // light, and these materials have no unlit terms: they add up alike.
                let grouped = sum(
                    x,
                    y,
                    c,
                    &[
                        "__diffuse_key",
                        "__specular_key",
                        "__ambient_fill",
                        "__diffuse_fill",
                        "__specular_fill",
                    ],
                );
                // Half layers (key's): 11 bits, 2^-11 relative of each term.
                let tol = 2e-3 * b.abs() + 1e-4;
                assert!((grouped - b).abs() <= tol, "({x},{y}) c{c}: groups {grouped} vs {b}");
            }
        }
    }
    eprintln!("components: worst |ambient + diffuse + specular - beauty| {worst:.2e}");
}

#[test]
fn asking_for_aovs_leaves_the_beauty_unchanged_for_any_thread_count() {
    let mut with = components_scene();
    // A shader output variable too (no object has a shader: a layer of zeros), and the
    // midpoint depth of depth maps, which turns occlusion culling off: the beauty is the
    // same bit for bit either way.
    with.outputs.aovs.push(reyes_scene::Aov::output("glow", None));
    with.outputs.aovs.push(reyes_scene::Aov::new(AovSource::ZMidpoint));
    let mut without = with.clone();
    without.outputs = Default::default();
    let plain = rendered(&without, 1);
    assert!(plain.aovs.is_none());
    let bits = |r: &Rendered| -> Vec<u32> {
        r.film.rgba().iter().flatten().chain(r.film.z()).map(|v| v.to_bits()).collect()
    };
    let one = rendered(&with, 1);
    assert_eq!(bits(&one), bits(&plain), "the beauty changed");
    for threads in [2, 8] {
        let many = rendered(&with, threads);
        assert_eq!(bits(&many), bits(&plain), "{threads} threads");
        let (a, b) = (one.aovs.as_ref(), many.aovs.as_ref());
        let data = |r: Option<&reyes_render::aovs::RenderedAovs>| {
            r.map(|a| a.film.data().iter().map(|v| v.to_bits()).collect::<Vec<_>>())
        };
        assert_eq!(data(a), data(b), "AOVs differ with {threads} threads");
    }
    // Every source is in the scene.
    for source in AovSource::ALL {
        assert!(with.outputs.aovs.iter().any(|a| a.source == source), "{source:?}");
    }
}

#[test]
fn every_hider_path_gives_the_same_beauty_with_aovs() {
    // A lens (path D), motion (path M) and both: the traced resolution composites as before.
    for file in ["motion-dof", "depth-of-field", "csg", "transparency"] {
        let path = format!("{}/../../scenes/{file}.ron", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut plain = parse(&text);
        plain.image = reyes_scene::Image::new(64, 48);
        let mut with = plain.clone();
        with.outputs.aovs = [AovSource::Ci, AovSource::Z, AovSource::N, AovSource::DPdtime]
            .map(reyes_scene::Aov::new)
            .to_vec();
        let (a, b) = (rendered(&plain, 2), rendered(&with, 2));
        assert_eq!(a.film, b.film, "{file}");
        let ci = b.aovs.as_ref().map(|x| x.film.clone());
        let ci = ci.unwrap_or_else(|| panic!("{file}: no AOVs"));
        for (k, p) in b.film.rgba().iter().enumerate() {
            for (c, v) in p.iter().enumerate().take(3) {
                assert_eq!(ci.data()[k * ci.channels() + c].to_bits(), v.to_bits(), "{file}");
            }
        }
    }
}
