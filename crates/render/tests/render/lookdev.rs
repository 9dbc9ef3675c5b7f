//! Look development against analytic truth (docs/lookdev.md): a checkerboard texture seen
//! head-on and at a grazing angle, the texture cache's bound, constant and sinusoidal
//! displacement, displacement under motion blur, depth of field and CSG, the displacement
//! bound's warning and count, and emission above 1.

use std::path::{Path, PathBuf};

use reyes_render::{RenderOptions, Rendered, render};
use reyes_scene::Scene;
use reyes_testkit::textures::checker;
use reyes_texture::load::srgb_to_linear;

fn parse(text: &str) -> Scene {
    reyes_scene::parse(text, Path::new("lookdev.ron")).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn rendered(scene: &Scene, threads: usize) -> Rendered {
    let opts = RenderOptions { threads: Some(threads), ..Default::default() };
    render(scene, &opts).unwrap_or_else(|e| panic!("{e}"))
}

/// A 64 x 64 checkerboard of 8-texel checks, grey levels 40 and 215 (sRGB), in `dir`.
fn checker_file(dir: &Path) -> PathBuf {
    let file = dir.join("checker.png");
    checker(64, 8, 40, 215).save(&file).unwrap_or_else(|e| panic!("{e}"));
    file
}

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"))
}

/// The two linear levels of [`checker_file`], dark and light.
fn levels() -> (f32, f32) {
    (srgb_to_linear(40.0 / 255.0), srgb_to_linear(215.0 / 255.0))
}

/// A square filling a 64 x 64 orthographic view, one texel per pixel, unlit: texel `(x, y)`
/// is pixel `(x, y)`. Where a texel's 3 x 3 neighbourhood is one check, the pixel is the
/// texel's value: every vertex of the micropolygons covering the pixel reads a footprint of
/// about one texel (level 0, bilinear between texels of that value), whatever the dicer's
/// exact grid. Elsewhere (a check's border) the value lies between the two levels, and the
/// whole picture's mean is the texture's.
#[test]
fn a_checkerboard_seen_head_on_reproduces_its_texels() {
    let dir = tempdir();
    let file = checker_file(dir.path());
    let scene = parse(&format!(
        "Scene(image: (width: 64, height: 64),
          camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                   screen_window: Some((-1.0, 1.0, -1.0, 1.0))),
          hider: (pixel_samples: (4, 4), filter: (kind: Box, width: 1.0)),
          objects: [(shape: BilinearPatch(points: ((-1.0, 1.0, 5.0), (1.0, 1.0, 5.0),
                                                  (-1.0, -1.0, 5.0), (1.0, -1.0, 5.0))),
                     material: Constant(color: (1.0, 1.0, 1.0)),
                     maps: (color: Some((file: {file:?}, color_space: Srgb))))])"
    ));
    let r = rendered(&scene, 2);
    let (lo, hi) = levels();
    let texel = |x: i32, y: i32| {
        if ((x.div_euclid(8) + y.div_euclid(8)) % 2 + 2) % 2 == 0 { hi } else { lo }
    };
    let (mut exact, mut sum) = (0, 0.0f64);
    for y in 0..64 {
        for x in 0..64 {
            let p = r.film.pixel(x as u32, y as u32).unwrap_or_else(|| panic!("pixel"));
            sum += f64::from(p[0]);
            let want = texel(x, y);
            let uniform = (-1..=1).all(|dy| (-1..=1).all(|dx| texel(x + dx, y + dy) == want));
            if uniform {
                // Float rounding of the bilinear weights only.
                assert!((p[0] - want).abs() < 1e-5, "({x}, {y}): {} vs {want}", p[0]);
                exact += 1;
            } else {
                assert!(p[0] >= lo - 1e-5 && p[0] <= hi + 1e-5, "({x}, {y}): {}", p[0]);
            }
            assert!((p[3] - 1.0).abs() < 1e-6, "({x}, {y}) covered");
        }
    }
    // 6 x 6 of every 8 x 8 check.
    assert_eq!(exact, 64 * 36);
    // Blurring at the borders keeps the mean: each border pixel mixes the two levels, half
    // of the border lying on each side; 1% allows for the border's asymmetry at the
    // picture's edge (clamped footprints there).
    let mean = sum / 4096.0;
    let want = f64::from(0.5 * (lo + hi));
    assert!((mean - want).abs() < 0.01 * want, "mean {mean} vs {want}");
}

/// `F(x) = integral from 0 to x of the square wave that is +1 on [0, 1) and -1 on [1, 2)`,
/// periodic: the triangle wave `1 - |x mod 2 - 1|`.
fn square_integral(x: f64) -> f64 {
    1.0 - (x.rem_euclid(2.0) - 1.0).abs()
}

/// The mean over `[x0, x1]` of that square wave (its value at `x0` on an empty interval).
fn square_mean(x0: f64, x1: f64) -> f64 {
    if x1 - x0 < 1e-12 {
        return if x0.rem_euclid(2.0) < 1.0 { 1.0 } else { -1.0 };
    }
    (square_integral(x1) - square_integral(x0)) / (x1 - x0)
}

/// The grazing-angle scene: the plane y = 0 from z = 1 to z = 101 seen from one unit above
/// it, looking along +z, the checkerboard repeated 100 times each way (checks of 1/8 unit),
/// with the texture filter `width`.
fn grazing(file: &Path, width: f32) -> Scene {
    parse(&format!(
        "Scene(image: (width: 128, height: 96),
          camera: (eye: (0.0, 1.0, 0.0), look_at: (0.0, 1.0, 1.0), fov: 60.0, yon: 1000.0),
          hider: (pixel_samples: (4, 4), filter: (kind: Box, width: 1.0)),
          objects: [(shape: BilinearPatch(points: ((-50.0, 0.0, 1.0), (50.0, 0.0, 1.0),
                                                  (-50.0, 0.0, 101.0), (50.0, 0.0, 101.0))),
                     material: Constant(color: (1.0, 1.0, 1.0)),
                     maps: (color: Some((file: {file:?}, color_space: Srgb,
                                         repeat: (100.0, 100.0), width: {width:?}))))])"
    ))
}

/// The checkerboard of [`grazing`] box-filtered over pixel `(px, py)`, analytically: the
/// pixel is cut into 8 x 8 cells, each cell's corners are carried to the plane (raster
/// `(rx, ry)` is the ray `((rx - 64) / k, -(ry - 48) / k, 1)` from the eye, `k = 48 /
/// tan(30 deg)`), and the checkerboard `m + a sq(8 s) sq(8 t)` is averaged exactly over the
/// rectangle of texture coordinates that bounds each cell (`s = x + 50`, `t = z - 1`).
/// `None` for a pixel that does not lie wholly on the plane.
fn reference(px: u32, py: u32) -> Option<f64> {
    let (lo, hi) = levels();
    let (m, a) = (f64::from(0.5 * (hi + lo)), f64::from(0.5 * (hi - lo)));
    let k = 48.0 / 30f64.to_radians().tan();
    let hit = |rx: f64, ry: f64| -> Option<(f64, f64)> {
        let dy = -(ry - 48.0) / k;
        if dy >= 0.0 {
            return None;
        }
        let z = -1.0 / dy;
        let x = z * (rx - 64.0) / k;
        ((1.0..=101.0).contains(&z) && x.abs() <= 50.0).then_some((x + 50.0, z - 1.0))
    };
    const N: u32 = 8;
    let mut sum = 0.0;
    for j in 0..N {
        for i in 0..N {
            let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)].map(|(ci, cj)| {
                hit(
                    f64::from(px) + f64::from(ci) / f64::from(N),
                    f64::from(py) + f64::from(cj) / f64::from(N),
                )
            });
            let mut s = (f64::INFINITY, f64::NEG_INFINITY);
            let mut t = (f64::INFINITY, f64::NEG_INFINITY);
            for c in corners {
                let (cs, ct) = c?;
                s = (s.0.min(cs), s.1.max(cs));
                t = (t.0.min(ct), t.1.max(ct));
            }
            sum += m + a * square_mean(8.0 * s.0, 8.0 * s.1) * square_mean(8.0 * t.0, 8.0 * t.1);
        }
    }
    Some(sum / f64::from(N * N))
}

/// At a grazing angle the filtered checkerboard converges to the mean grey, with no
/// aliasing bands: against the analytic box-filtered checkerboard ([`reference`]), the
/// render's error stays small in every row, while the same render with the filter off
/// (`width: 0`, the finest level at each vertex) aliases into bands many times larger.
///
/// Tolerances. The renderer's filter is not the reference's box: a texture lookup averages
/// over one micropolygon's footprint (about a pixel, shading rate 1) with a trilinear
/// kernel about twice as wide as the MIP level's texel, then the hider box-filters the
/// micropolygons over the pixel. Where a pixel holds W checks along an axis, a box of W
/// checks leaves at most `a / W` of the square wave's amplitude `a`, and a wider kernel
/// less: so the two differ by at most about `a / W` per axis, plus the stochastic
/// sampling's noise (16 samples, micropolygons of slowly varying colour there). The rows
/// compared are those whose pixels hold at least 4 checks along t (z >= 6), where `a / W
/// <= a / 4`: each row's RMS error must be below `a / 4`, and the far rows (z >= 20, at
/// least 13 checks per pixel) within `a / 8` of the mean grey, on average over the row.
#[test]
fn a_checkerboard_at_a_grazing_angle_converges_to_grey_without_bands() {
    let dir = tempdir();
    let file = checker_file(dir.path());
    let (lo, hi) = levels();
    let (m, a) = (f64::from(0.5 * (hi + lo)), f64::from(0.5 * (hi - lo)));
    let k = 48.0 / 30f64.to_radians().tan();
    let errors = |width: f32| {
        let r = rendered(&grazing(&file, width), 2);
        let mut rows = Vec::new();
        for py in 49..96u32 {
            let z = k / (f64::from(py) + 0.5 - 48.0);
            // Pixels that hold 4 checks or more along t: dz = z^2 / k per pixel.
            if z * z / k < 4.0 / 8.0 {
                continue;
            }
            let (mut se, mut n, mut mean) = (0.0, 0.0, 0.0);
            for px in 0..128 {
                let Some(want) = reference(px, py) else { continue };
                let got = f64::from(r.film.pixel(px, py).unwrap_or_else(|| panic!("pixel"))[0]);
                se += (got - want).powi(2);
                mean += got;
                n += 1.0;
            }
            if n > 0.0 {
                rows.push((z, (se / n).sqrt(), mean / n));
            }
        }
        rows
    };
    let filtered = errors(1.0);
    assert!(filtered.len() >= 8, "{filtered:?}");
    for &(z, rms, mean) in &filtered {
        assert!(rms < a / 4.0, "z {z}: RMS error {rms} against a / 4 = {}", a / 4.0);
        if z >= 20.0 {
            assert!((mean - m).abs() < a / 8.0, "z {z}: row mean {mean} vs grey {m}");
        }
    }
    // Point sampling aliases: where pixels hold 12 checks or more along t (z >= 12) its
    // error is the square wave's full amplitude spread over 16 samples, a / 4 at best, and
    // several times the filtered one over those rows together. Not in every row: a row whose
    // vertices all land on texel edges gets the mean from the finest level's bilinear lookup
    // by coincidence (with the grids of the shading rate's area, z = 33 does, at 2.2e-4,
    // where its neighbours alias at 0.03 to 0.06). So the rows are compared as a whole, and
    // most of them must alias on their own.
    let point = errors(0.0);
    let far: Vec<_> = filtered.iter().zip(&point).filter(|(f, _)| f.0 >= 12.0).collect();
    let rms = |e: &mut dyn Iterator<Item = f64>| {
        let (s, n) = e.fold((0.0, 0.0), |(s, n), x| (s + x * x, n + 1.0));
        (s / n).sqrt()
    };
    let (f_rms, p_rms) =
        (rms(&mut far.iter().map(|(f, _)| f.1)), rms(&mut far.iter().map(|(_, p)| p.1)));
    assert!(far.len() >= 4 && p_rms > 5.0 * f_rms, "point sampling {p_rms} vs filtered {f_rms}");
    let aliased = far.iter().filter(|(f, p)| p.1 > 5.0 * f.1).count();
    assert!(2 * aliased > far.len(), "{aliased} of {} rows alias: {far:?}", far.len());
}

/// The coverage (alpha summed over the picture) of `r`, in pixels.
fn coverage(r: &Rendered) -> f64 {
    r.film.rgba().iter().map(|p| f64::from(p[3])).sum()
}

/// A sphere of radius `radius` displaced by the constant `d` (`None`: not displaced) at
/// the origin, seen by an orthographic camera over `[-2, 2]^2` on `size x size` pixels, with
/// `extra` camera fields and object fields.
fn sphere_scene(size: u32, radius: f32, d: Option<f32>, camera: &str, object: &str) -> Scene {
    let displacement = d.map_or(String::new(), |d| {
        format!(", displacement: Some((source: Constant({d:?}), bound: Some({:?})))", d.abs())
    });
    parse(&format!(
        "Scene(image: (width: {size}, height: {size}),
          camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0), projection: Orthographic,
                   screen_window: Some((-2.0, 2.0, -2.0, 2.0)){camera}),
          hider: (pixel_samples: (4, 4), filter: (kind: Box, width: 1.0)),
          lights: [Ambient(intensity: 1.0)],
          objects: [(name: \"ball\", shape: Sphere(radius: {radius:?}),
                     material: Matte(color: (1.0, 1.0, 1.0)){displacement}{object})])"
    ))
}

/// A sphere of radius r displaced by a constant d has the silhouette of a sphere of radius
/// r + d: its coverage is pi (r + d)^2 in pixels, up to the chord error of its
/// micropolygons and the hider's sampling.
///
/// Tolerance: micropolygons about 1 pixel on a side (shading rate 1) on a silhouette of
/// radius R = 64 pixels make a polygon whose area falls short of the disk's by at most
/// the sagitta `1 / (8 R)` per unit of perimeter, `pi / 4` pixels in all; the 16 stratified
/// samples of each of the ~400 edge pixels miss its coverage by at most 1/16 each, with
/// errors that mostly cancel (1/16 * sqrt(400) = 1.25 pixels at 1 sigma). So |area - pi
/// R^2| < 6 pixels: a radius error of 6 / (2 pi R) = 0.015 pixels, where d is 16 pixels.
#[test]
fn a_sphere_displaced_by_a_constant_has_radius_r_plus_d() {
    let (size, scale) = (256u32, 64.0f64); // pixels per unit
    for d in [0.25f32, -0.2] {
        let r = rendered(&sphere_scene(size, 1.0, Some(d), "", ""), 2);
        let want = std::f64::consts::PI * (scale * f64::from(1.0 + d)).powi(2);
        let got = coverage(&r);
        assert!((got - want).abs() < 6.0, "d {d}: coverage {got} vs pi (r + d)^2 = {want}");
        assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    }
}

/// Displacement under motion blur, depth of field and CSG: a unit sphere displaced by 0.25
/// renders as a sphere of radius 1.25 does, sample for sample, when both move the same way,
/// are seen through the same lens or are cut by the same CSG difference. The two use the
/// same samples (same seed), so they differ only where their micropolygons do: within a
/// chord error (0.015 pixels of radius, above) of the silhouette, and in each pixel by at
/// most the fraction of samples such a sliver covers. Over the picture the coverage differs
/// by at most the silhouette's length times the chord error, and each pixel's alpha by one
/// sample in 16 for a still edge, two under motion or a lens (an edge sweeps or blurs over
/// more pixels, still one sliver per sample).
#[test]
fn displacement_works_with_motion_blur_depth_of_field_and_csg() {
    displaced_matches_the_larger_sphere(&[
        (
            "motion",
            ", shutter: (open: 0.0, close: 1.0)",
            ", motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Translate((0.5, 0.2, 0.0))])]",
        ),
        ("lens", ", lens: Some((f_stop: 2.0, focal_length: 1.0, focal_distance: 8.0))", ""),
    ]);
}

/// The still case of [`displacement_works_with_motion_blur_depth_of_field_and_csg`]. It fails
/// because displaced surfaces are not diced crack-free (docs/geometry.md): neighbouring grids
/// diced at different counts leave T-junction cracks of about a sagitta (0.003 pixel here),
/// and seen along the sphere's axis the cracks of the front and back halves line up, so a
/// sample can see the background through both. With the grids of the shading rate's area
/// (issue #13, point 3) 45 pixels inside the displaced disk lose a sample (14 before), four of
/// them two, where the bound is one. Removing the `ignore` is part of making displacement
/// crack-free.
#[test]
#[ignore = "owner: the lead (crack-free displacement): T-junction cracks of the front and back halves line up along the axis"]
fn displacement_still_matches_the_larger_sphere() {
    displaced_matches_the_larger_sphere(&[("still", "", "")]);
}

/// The body of the two tests above, over `cases` of `(name, camera fields, object fields)`.
fn displaced_matches_the_larger_sphere(cases: &[(&str, &str, &str)]) {
    for &(name, camera, object) in cases {
        let shown = sphere_scene(128, 1.0, Some(0.25), camera, object);
        // Displaced surfaces are not diced crack-free (displacement would move their shared
        // boundary points apart; crates/dice/src/lazy.rs), so the plain sphere is diced the
        // same way, its boundary on the surface (crack-free, its outline's chords may stray
        // 0.05 pixel, a coverage difference of up to 2/3 0.05 250 = 8 px^2).
        let mut truth = sphere_scene(128, 1.25, None, camera, object);
        truth.hider.crack_free = false;
        let (a, b) = (rendered(&shown, 2), rendered(&truth, 2));
        let (ca, cb) = (coverage(&a), coverage(&b));
        // Perimeter 2 pi 40 = 250 pixels, chord error 0.015: 4 pixels of area.
        assert!((ca - cb).abs() < 4.0, "{name}: coverage {ca} vs {cb}");
        let worst = a
            .film
            .rgba()
            .iter()
            .zip(b.film.rgba())
            .map(|(p, q)| (p[3] - q[3]).abs())
            .fold(0.0f32, f32::max);
        let one = if name == "still" { 1.0 / 16.0 } else { 2.0 / 16.0 };
        assert!(worst <= one + 1e-5, "{name}: worst pixel alpha difference {worst}");
    }
}

/// CSG: a displaced sphere minus a box-like sphere is the plain sphere of radius r + d minus
/// the same: a difference through the displaced operand shows its inside, so displacement
/// and the end caps of CSG operands meet.
#[test]
fn displacement_works_in_csg() {
    let scene = |shape: &str, displacement: &str| {
        parse(&format!(
            "Scene(image: (width: 128, height: 128),
              camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0), projection: Orthographic,
                       screen_window: Some((-2.0, 2.0, -2.0, 2.0))),
              hider: (pixel_samples: (4, 4), filter: (kind: Box, width: 1.0)),
              lights: [Ambient(intensity: 1.0)],
              objects: [
                (name: \"a\", shape: {shape}, material: Matte(color: (1.0, 1.0, 1.0)){displacement}),
                (name: \"b\", shape: Sphere(radius: 0.8), transform: [Translate((0.9, 0.0, -0.5))],
                 material: Matte(color: (1.0, 0.0, 0.0)))],
              solids: [(name: \"cut\", tree: Difference(Object(\"a\"), Object(\"b\")))])"
        ))
    };
    let shown = rendered(
        &scene(
            "Sphere(radius: 1.0)",
            ", displacement: Some((source: Constant(0.25), bound: Some(0.25)))",
        ),
        2,
    );
    // Diced as the displaced operand is, without crack-free dicing (see above).
    let mut plain = scene("Sphere(radius: 1.25)", "");
    plain.hider.crack_free = false;
    let truth = rendered(&plain, 2);
    let (ca, cb) = (coverage(&shown), coverage(&truth));
    assert!((ca - cb).abs() < 4.0, "coverage {ca} vs {cb}");
    // The red inside of the cut shows in both, as much.
    let red = |r: &Rendered| r.film.rgba().iter().map(|p| f64::from(p[0] - p[1])).sum::<f64>();
    assert!(red(&truth) > 200.0, "the cut shows the subtracted sphere's inside");
    assert!(
        (red(&shown) - red(&truth)).abs() < 0.03 * red(&truth),
        "{} vs {}",
        red(&shown),
        red(&truth)
    );
}

/// A sinusoidal displacement of a plane matches the analytic height field in the depth: the
/// plane z = 5 facing the camera, displaced by `A sin(2 pi 3 u)` along its normal (-z, toward
/// the camera), has camera depth `5 - A sin(2 pi 3 u)` at every pixel centre.
///
/// Tolerance: the Z AOV box-filters the depth over each pixel, which averages the sine over
/// one pixel of its 32-pixel period (a factor `sinc(1/32)`, 0.16% of A); micropolygons about
/// a pixel wide follow it on chords, off by at most `A (pi / 32)^2 / 2` (0.5% of A); 1% of A.
#[test]
fn a_sinusoidal_displacement_matches_the_analytic_height_field_in_z() {
    let amp = 0.2f32;
    let scene = parse(&format!(
        "Scene(image: (width: 64, height: 64),
          camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                   screen_window: Some((-1.0, 1.0, -1.0, 1.0))),
          hider: (pixel_samples: (4, 4), filter: (kind: Box, width: 1.0)),
          lights: [Ambient(intensity: 1.0)],
          objects: [(shape: BilinearPatch(points: ((-1.5, 1.5, 5.0), (1.5, 1.5, 5.0),
                                                  (-1.5, -1.5, 5.0), (1.5, -1.5, 5.0))),
                     material: Matte(color: (1.0, 1.0, 1.0)),
                     displacement: Some((source: Wave(frequency: (3.0, 0.0)), amount: {amp:?},
                                         bound: Some({amp:?}))))],
          outputs: (aovs: [(source: Z, filter: Some(Filter))]))"
    ));
    // The patch's normal (p1 - p0) x (p2 - p0) = (3, 0, 0) x (0, -3, 0) = (0, 0, -9): toward
    // the camera, so displacing by +h brings the surface nearer: z = 5 - h.
    let r = rendered(&scene, 2);
    let a = r.aovs.as_ref().unwrap_or_else(|| panic!("AOVs"));
    let layer = a.layers.iter().find(|l| l.name == "z").unwrap_or_else(|| panic!("no z"));
    let mut worst = 0.0f32;
    for y in 0..64 {
        for x in 0..64 {
            // Pixel centre x_world = (x + 0.5) / 32 - 1; u = (x_world + 1.5) / 3.
            let u = ((x as f32 + 0.5) / 32.0 - 1.0 + 1.5) / 3.0;
            let want = 5.0 - amp * (std::f32::consts::TAU * 3.0 * u).sin();
            let got = a.film.value(x, y, layer.start);
            worst = worst.max((got - want).abs());
        }
    }
    assert!(worst < 0.01 * amp, "worst depth error {worst} (A = {amp})");
}

/// A noise-displaced sphere of radius 0.6, 0.75 units of displacement at most (the noise's
/// bound), about 0.25 in fact, with the declared `bound`. Small grids (16 micropolygons,
/// about 4 pixels a side) and buckets make the split stage's margin (a quarter of a patch's
/// extent plus 2 pixels, about 3 pixels) far smaller than the displacement (up to 16
/// pixels), so only a bound grown by the displacement keeps lazy dicing from missing.
fn bumpy(bound: &str) -> Scene {
    parse(&format!(
        "Scene(image: (width: 96, height: 96),
          camera: (eye: (0.0, 0.0, -3.0), look_at: (0.0, 0.0, 0.0), fov: 40.0),
          hider: (pixel_samples: (3, 3), bucket_size: (8, 8), max_grid_size: 16),
          lights: [Ambient(intensity: 1.0)],
          objects: [(name: \"rock\", shape: Sphere(radius: 0.6),
                     material: Matte(color: (1.0, 1.0, 1.0)),
                     displacement: Some((source: Noise(frequency: 3.0, octaves: 2),
                                         amount: 0.25{bound})))])"
    ))
}

/// Leaving out the displacement bound gives the warning, and the picture has no holes: it is
/// the picture rendered with a generous declared bound, pixel for pixel (the effective
/// bound is the larger of the declared one and the source's own, so both split and bucket
/// alike), and lazy dicing never met a bound that missed. A declared bound the displacement
/// exceeds is warned about and its escapes counted, the picture again the same.
#[test]
fn a_missing_or_short_displacement_bound_warns_and_leaves_no_holes() {
    let missing = rendered(&bumpy(""), 2);
    assert!(
        missing.warnings.iter().any(|w| w.contains("without a displacement bound")),
        "{:?}",
        missing.warnings
    );
    assert!(!missing.stats.dice.eager, "a patch bound missed");
    // Noise of 2 octaves reaches at most 2 + 1 = 3 (noise::fbm_bound), times 0.25.
    let generous = rendered(&bumpy(", bound: Some(0.75)"), 2);
    assert!(generous.warnings.is_empty(), "{:?}", generous.warnings);
    assert_eq!(missing.film.rgba(), generous.film.rgba());
    let lookdev = |r: &Rendered| r.stats.lookdev.unwrap_or_else(|| panic!("lookdev stats"));
    assert_eq!(lookdev(&generous).escapes, 0);
    // The middle of the rock is covered wholly: no micropolygon went missing.
    for y in 36..60 {
        for x in 36..60 {
            let a = missing.film.pixel(x, y).unwrap_or_else(|| panic!("pixel"))[3];
            assert!((a - 1.0).abs() < 1e-6, "hole at ({x}, {y}): alpha {a}");
        }
    }
    let short = rendered(&bumpy(", bound: Some(0.01)"), 2);
    assert!(lookdev(&short).escapes > 0);
    // Noise's own bound is loose, so the escapes, counted as diced, are what is reported.
    assert!(
        short.warnings.iter().any(|w| w.contains("micropolygons were displaced beyond")),
        "{:?}",
        short.warnings
    );
    assert_eq!(short.film.rgba(), generous.film.rgba());
    // The same picture for any thread count.
    assert_eq!(rendered(&bumpy(""), 1).film.rgba(), missing.film.rgba());
}

/// The texture cache stays within its bound on a scene with four times its texture memory,
/// and the picture is the one an unbounded cache gives, for any thread count. The scene's
/// shading rate makes the lookups' footprints fine enough that the texels they read do not
/// fit in the bound: 0.15 since dicing aims at the rate's area (issue #13; at 0.25 the
/// coarser grids read coarser MIP levels, which fit, and nothing is evicted).
#[test]
fn the_texture_cache_stays_within_its_bound_on_four_times_its_size() {
    let dir = tempdir();
    let maps: Vec<PathBuf> = (0..4u32)
        .map(|k| {
            let file = dir.path().join(format!("map{k}.png"));
            checker(256, 4 + k, 30 * k as u8, 240).save(&file).unwrap_or_else(|e| panic!("{e}"));
            file
        })
        .collect();
    let scene = |bytes: u64| {
        let objects: Vec<String> = maps
            .iter()
            .enumerate()
            .map(|(k, file)| {
                let x = k as f32 - 1.5;
                format!(
                    "(shape: Sphere(radius: 0.45), transform: [Translate(({x:?}, 0.0, 0.0))],
                      material: Constant(color: (1.0, 1.0, 1.0)),
                      maps: (color: Some((file: {file:?}, color_space: Srgb))))"
                )
            })
            .collect();
        parse(&format!(
            "Scene(image: (width: 256, height: 64),
              camera: (eye: (0.0, 0.0, -3.0), look_at: (0.0, 0.0, 0.0), fov: 40.0),
              hider: (pixel_samples: (2, 2), shading_rate: 0.15),
              objects: [{}],
              texture_cache: (max_bytes: {bytes}))",
            objects.join(", ")
        ))
    };
    let free = rendered(&scene(1 << 30), 2);
    let total = free.stats.lookdev.unwrap_or_else(|| panic!("stats")).textures.pyramid_bytes;
    let bound = total / 4;
    for threads in [1, 2] {
        let tight = rendered(&scene(bound), threads);
        let t = tight.stats.lookdev.unwrap_or_else(|| panic!("stats")).textures;
        assert_eq!(t.pyramid_bytes, total);
        assert!(t.cache.peak <= bound, "peak {} over the bound {bound}", t.cache.peak);
        assert!(t.cache.evictions > 0, "the bound was reached: {:?}", t.cache);
        assert_eq!(tight.film.rgba(), free.film.rgba(), "{threads} threads");
    }
}

/// Emission adds to the shaded colour whatever the lights, and values above 1 reach the
/// film (and so the EXR, which stores the film's floats) unclamped.
#[test]
fn emission_above_one_passes_unclamped() {
    let scene = parse(
        "Scene(image: (width: 16, height: 16),
          camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                   screen_window: Some((-1.0, 1.0, -1.0, 1.0))),
          objects: [(shape: BilinearPatch(points: ((-2.0, 2.0, 5.0), (2.0, 2.0, 5.0),
                                                  (-2.0, -2.0, 5.0), (2.0, -2.0, 5.0))),
                     material: Matte(color: (0.5, 0.5, 0.5)),
                     emission: Some((4.0, 2.5, 0.0)))])",
    );
    let r = rendered(&scene, 1);
    for p in r.film.rgba() {
        // No lights: the matte's own term is 0, the emission all there is.
        assert!((p[0] - 4.0).abs() < 1e-5 && (p[1] - 2.5).abs() < 1e-5 && p[2] == 0.0, "{p:?}");
    }
    let dir = tempdir();
    let out = dir.path().join("glow.exr");
    reyes_film::write(&out, &r.film).unwrap_or_else(|e| panic!("{e}"));
    let read = reyes_film::read_exr(&out).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(read.pixel(3, 3).map(|p| p[0]), Some(4.0));
}

/// The committed maps of scenes/textures/ are what `cargo xtask textures` makes, texel for
/// texel (reyes_testkit::textures), so the look-development scenes can be remade.
#[test]
fn the_scene_textures_are_the_generated_ones() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/textures");
    for (name, made) in reyes_testkit::textures::scene_maps() {
        let file = dir.join(name);
        let read = image::open(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert!(read.as_bytes() == made.as_bytes(), "{name} differs: run cargo xtask textures");
    }
}

/// A strongly bumped closed ball drawn with its back faces culled covers exactly what it
/// covers drawn two-sided: culling decides a grid's facing from the surface's own normal, not
/// from the bumped shading normal, which near the silhouette tilts away from the eye on a
/// front face (and culled whole front-facing grids of lookdev.ron's checkered ball once). The
/// two renders use the same samples on the same front faces, so every pixel's alpha must be
/// the same bit for bit.
#[test]
fn bump_mapping_never_culls_a_front_face() {
    let scene = |cull: bool| {
        parse(&format!(
            "Scene(image: (width: 96, height: 96),
              camera: (eye: (0.0, 0.0, -6.0), look_at: (0.0, 0.0, 0.0), fov: 30.0),
              hider: (pixel_samples: (4, 4), cull_back_faces: {cull}),
              lights: [Ambient(intensity: 0.3), Distant(from: (1.0, 1.0, -1.0))],
              objects: [(shape: Sphere(radius: 1.2), transform: [Rotate(angle: 90.0, axis: (1.0, 0.0, 0.0))],
                         material: Plastic(color: (0.9, 0.25, 0.2)),
                         bump: Some((source: Noise(frequency: 6.0, octaves: 3), amount: 0.15)))])"
        ))
    };
    let (culled, both) = (rendered(&scene(true), 2), rendered(&scene(false), 2));
    let alpha = |r: &Rendered| r.film.rgba().iter().map(|p| p[3].to_bits()).collect::<Vec<_>>();
    let (a, b) = (alpha(&culled), alpha(&both));
    let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert_eq!(differ, 0, "{differ} pixels differ in coverage with back faces culled");
    assert!(culled.stats.dice.culled > both.stats.dice.culled, "no back face was culled");
}
