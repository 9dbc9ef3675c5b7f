//! Polygon meshes with vertex data (docs/scene-format.md, `Mesh` and `MeshFile`): a UV sphere
//! mesh with exact normals shades with the sphere's analytic normal and without them is
//! faceted; per-point `st` places a texture; one mesh read from OBJ and from PLY renders
//! bit for bit the same.

use std::path::{Path, PathBuf};

use glam::DVec3;
use reyes_meshio::MeshData;
use reyes_render::{RenderOptions, Rendered, render};
use reyes_scene::{Faces, Scene, Shape};
use reyes_testkit::textures::checker;
use reyes_texture::load::srgb_to_linear;

fn parse(text: &str, file: &Path) -> Scene {
    reyes_scene::parse(text, file).unwrap_or_else(|e| panic!("{e}"))
}

fn rendered(scene: &Scene) -> Rendered {
    let opts = RenderOptions { threads: Some(2), ..Default::default() };
    render(scene, &opts).unwrap_or_else(|e| panic!("{e}"))
}

/// Channel `c` of the AOV layer named `name` at pixel `(x, y)`.
fn aov(r: &Rendered, name: &str, x: u32, y: u32, c: usize) -> f32 {
    let a = r.aovs.as_ref().expect("the scene writes AOVs");
    let layer = a.layers.iter().find(|l| l.name == name).unwrap_or_else(|| panic!("no {name}"));
    a.film.value(x, y, layer.start + c)
}

fn aov3(r: &Rendered, name: &str, x: u32, y: u32) -> DVec3 {
    DVec3::from_array([0, 1, 2].map(|c| f64::from(aov(r, name, x, y, c))))
}

/// Segments around the z axis and from pole to pole of [`uv_sphere`].
const AROUND: usize = 48;
const POLES: usize = 24;

/// A unit UV sphere about the origin: the two poles and `POLES - 1` rings of `AROUND`
/// points (no seam duplicate), quads between rings and triangles at the poles, wound so that
/// every face's `dP/du x dP/dv` points out; normals equal to the points (exact); uvs
/// `(theta / 2 pi, (phi + pi / 2) / pi)` (the seam shares its points, so `s` jumps there).
fn uv_sphere() -> MeshData {
    let mut points = vec![[0.0, 0.0, -1.0f32]];
    let mut uvs = vec![[0.0, 0.0f32]];
    for j in 1..POLES {
        let phi = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * j as f64 / POLES as f64;
        for i in 0..AROUND {
            let theta = std::f64::consts::TAU * i as f64 / AROUND as f64;
            let p = [phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin()];
            points.push(p.map(|c| c as f32));
            uvs.push([i as f32 / AROUND as f32, j as f32 / POLES as f32]);
        }
    }
    points.push([0.0, 0.0, 1.0]);
    uvs.push([0.0, 1.0]);
    let ring = |j: usize, i: usize| (1 + (j - 1) * AROUND + i % AROUND) as u32;
    let north = (points.len() - 1) as u32;
    let (mut indices, mut ends) = (Vec::new(), Vec::new());
    let mut face = |f: &[u32]| {
        indices.extend_from_slice(f);
        ends.push(indices.len() as u32);
    };
    for i in 0..AROUND {
        face(&[0, ring(1, i + 1), ring(1, i)]);
    }
    for j in 1..POLES - 1 {
        for i in 0..AROUND {
            face(&[ring(j, i), ring(j, i + 1), ring(j + 1, i + 1), ring(j + 1, i)]);
        }
    }
    for i in 0..AROUND {
        face(&[north, ring(POLES - 1, i), ring(POLES - 1, i + 1)]);
    }
    MeshData {
        normals: Some(points.clone()),
        points,
        uvs: Some(uvs),
        indices,
        ends,
        ..MeshData::default()
    }
}

fn faces(mesh: &MeshData) -> Faces {
    let mut f = Faces::new();
    for face in mesh.faces() {
        f.push(face);
    }
    f
}

/// The unit sphere scene of the AOV tests (aovs.rs), centred at (0.3, -0.2, 4) before the
/// camera at the origin looking down +z (camera space is world space), 64 x 64, fov 40, one
/// sample at each pixel's centre, with `shape` for its sphere.
fn sphere_scene(shape: Shape) -> Scene {
    let mut scene = parse(
        "Scene(image: (width: 64, height: 64),
          camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 40.0),
          hider: (pixel_samples: (1, 1), jitter: false, filter: (kind: Box, width: 1.0),
                  shading_rate: 0.25),
          objects: [(shape: Sphere(radius: 1.0), transform: [Translate((0.3, -0.2, 4.0))],
                     material: Matte(color: (1.0, 1.0, 1.0)))],
          outputs: (aovs: [(source: N, filter: Some(Nearest)), (source: P, filter: Some(Nearest)),
                           (source: ObjectId)]))",
        Path::new("meshes.ron"),
    );
    scene.objects[0].shape = shape;
    reyes_scene::validate(scene).unwrap_or_else(|e| panic!("{e:?}"))
}

/// Each pixel whose centre ray meets the unit sphere at cosine >= 0.3: the ray's direction,
/// the ray-sphere point and the sphere's normal there.
fn sphere_pixels() -> Vec<(u32, u32, DVec3, DVec3)> {
    let centre = DVec3::new(0.3, -0.2, 4.0);
    let k = 32.0 / 20f64.to_radians().tan();
    let mut out = Vec::new();
    for y in 0..64 {
        for x in 0..64 {
            let d = DVec3::new((x as f64 + 0.5 - 32.0) / k, (32.0 - y as f64 - 0.5) / k, 1.0)
                .normalize();
            let b = d.dot(centre);
            let disc = b * b - (centre.length_squared() - 1.0);
            if disc < 0.0 {
                continue;
            }
            let hit = d * (b - disc.sqrt());
            let n = hit - centre;
            if n.dot(-d) >= 0.3 {
                out.push((x, y, d, n));
            }
        }
    }
    out
}

#[test]
fn a_uv_sphere_mesh_with_normals_shades_with_the_analytic_normal() {
    let mesh = uv_sphere();
    let shape = Shape::Mesh {
        points: mesh.points.clone(),
        faces: faces(&mesh),
        colors: None,
        normals: mesh.normals.clone(),
        st: None,
    };
    let r = rendered(&sphere_scene(shape));
    // The tolerance. Normals equal points here and every interpolation (over a face, over a
    // micropolygon) uses the same weights for both, so N is (P - C) normalised: N differs
    // from the sphere's normal at the ray-sphere point by the angle the two points subtend
    // at the centre. The mesh lies inside the sphere by at most the depth of a face's centre,
    // 1 - cos^2(D / 2) <= D^2 / 4 with D = 2 pi / 48 the angular size of a face (both ways),
    // 4.3e-3; along a ray meeting the sphere at cosine c that is s / c, subtending at most
    // s / (c (1 - s)). The micropolygons add what they add on the analytic sphere
    // (aovs.rs): 5.2e-4 / c^3, and 2.3e-3 for crack-free dicing's polylines.
    let d = std::f64::consts::TAU / AROUND as f64;
    let s = d * d / 4.0;
    let (mut checked, mut worst) = (0, 0.0f64);
    for (x, y, ray, truth) in sphere_pixels() {
        assert_eq!(aov(&r, "object_id", x, y, 0), 1.0, "({x},{y})");
        let n = aov3(&r, "N", x, y);
        let c = truth.dot(-ray);
        let tol = s / (c * (1.0 - s)) + 5.2e-4 / c.powi(3) + 2.3e-3 + 1e-5;
        let err = (n - truth).length();
        worst = worst.max(err);
        assert!(err < tol, "({x},{y}): N {n} vs the sphere's {truth}: {err} > {tol}");
        checked += 1;
    }
    assert!(checked > 300, "only {checked} pixels checked");
    eprintln!("smooth mesh sphere: {checked} pixels, worst |N - truth| {worst:.2e}");
}

#[test]
fn a_uv_sphere_mesh_without_normals_is_faceted() {
    let mesh = uv_sphere();
    let shape = Shape::Mesh {
        points: mesh.points.clone(),
        faces: faces(&mesh),
        colors: None,
        normals: None,
        st: None,
    };
    let r = rendered(&sphere_scene(shape));
    // The faces are planar (the quads are isosceles trapezoids between two rings), so the
    // N of every pixel is one face's plane normal (translation leaves normals alone), to
    // float rounding; and it strays from the sphere's by up to about half a face's angle.
    let normals: Vec<DVec3> = mesh
        .faces()
        .map(|f| {
            let p = |k: usize| DVec3::from(mesh.points[f[k] as usize].map(f64::from));
            (p(1) - p(0)).cross(p(2) - p(0)).normalize()
        })
        .collect();
    let mut worst = 0.0f64;
    let mut distinct: Vec<usize> = Vec::new();
    for (x, y, _, truth) in sphere_pixels() {
        let n = aov3(&r, "N", x, y);
        let (face, off) = normals
            .iter()
            .enumerate()
            .map(|(k, m)| (k, (n - *m).length()))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, f64::INFINITY));
        assert!(off < 1e-4, "({x},{y}): N {n} is no face's normal ({off})");
        if !distinct.contains(&face) {
            distinct.push(face);
        }
        worst = worst.max((n - truth).length());
    }
    assert!(worst > 0.03, "faceting shows: worst {worst}");
    assert!(distinct.len() > 50, "{} faces seen", distinct.len());
}

/// A 64 x 64 checkerboard of 8-texel checks, grey levels 40 and 215 (sRGB), in `dir`.
fn checker_file(dir: &Path) -> PathBuf {
    let file = dir.join("checker.png");
    checker(64, 8, 40, 215).save(&file).unwrap_or_else(|e| panic!("{e}"));
    file
}

/// The head-on checkerboard of lookdev.rs, on a one-quad mesh whose `st` mirrors the
/// texture in s: pixel `(x, y)` shows texel `(63 - x, y)`, the opposite check of the one
/// the face's own `(u, v)` would show (64 is a multiple of twice the check), so the picture
/// tells `st` from `(u, v)` everywhere.
#[test]
fn mesh_st_places_the_texture() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let file = checker_file(dir.path());
    let scene = parse(
        &format!(
            "Scene(image: (width: 64, height: 64),
              camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                       screen_window: Some((-1.0, 1.0, -1.0, 1.0))),
              hider: (pixel_samples: (4, 4), filter: (kind: Box, width: 1.0)),
              objects: [(shape: Mesh(points: [(-1.0, 1.0, 5.0), (1.0, 1.0, 5.0),
                                              (1.0, -1.0, 5.0), (-1.0, -1.0, 5.0)],
                                     faces: [[0, 1, 2, 3]],
                                     st: Some([(1.0, 0.0), (0.0, 0.0), (0.0, 1.0), (1.0, 1.0)])),
                         material: Constant(color: (1.0, 1.0, 1.0)),
                         maps: (color: Some((file: {file:?}, color_space: Srgb))))])"
        ),
        Path::new("st.ron"),
    );
    let r = rendered(&scene);
    let (lo, hi) = (srgb_to_linear(40.0 / 255.0), srgb_to_linear(215.0 / 255.0));
    let texel = |x: i32, y: i32| {
        if ((x.div_euclid(8) + y.div_euclid(8)) % 2 + 2) % 2 == 0 { hi } else { lo }
    };
    let mut exact = 0;
    for y in 0..64 {
        for x in 0..64 {
            let p = r.film.pixel(x as u32, y as u32).unwrap_or_else(|| panic!("pixel"));
            let want = texel(63 - x, y);
            let uniform = (-1..=1).all(|dy| (-1..=1).all(|dx| texel(63 - x - dx, y + dy) == want));
            if uniform {
                // As head-on in lookdev.rs: float rounding of the bilinear weights only.
                assert!((p[0] - want).abs() < 1e-5, "({x}, {y}): {} vs {want}", p[0]);
                exact += 1;
            }
        }
    }
    assert_eq!(exact, 64 * 36);
}

/// The smooth sphere as a `MeshFile` scene naming `name` (in the scene's folder).
fn mesh_file_scene(dir: &Path, name: &str) -> Scene {
    let file = dir.join("scene.ron");
    parse(
        &format!(
            "Scene(image: (width: 48, height: 48),
              camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 40.0),
              hider: (pixel_samples: (2, 2)),
              lights: [Distant(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0))],
              objects: [(shape: MeshFile(path: {name:?}), transform: [Translate((0.3, -0.2, 4.0))],
                         material: Plastic(color: (1.0, 0.5, 0.2)))])"
        ),
        &file,
    )
}

#[test]
fn one_mesh_from_obj_and_from_ply_renders_the_same_bits() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let mesh = uv_sphere();
    let mut obj = Vec::new();
    reyes_meshio::write_obj(&mesh, &mut obj).unwrap_or_else(|e| panic!("{e}"));
    std::fs::write(dir.path().join("sphere.obj"), obj).unwrap_or_else(|e| panic!("{e}"));
    let mut ply = Vec::new();
    reyes_meshio::write_ply_binary(&mesh, &mut ply, false).unwrap_or_else(|e| panic!("{e}"));
    std::fs::write(dir.path().join("sphere.ply"), ply).unwrap_or_else(|e| panic!("{e}"));
    let from_obj = mesh_file_scene(dir.path(), "sphere.obj");
    let from_ply = mesh_file_scene(dir.path(), "sphere.ply");
    // Both are the mesh written, with its normals and uvs (as st).
    for scene in [&from_obj, &from_ply] {
        let Shape::Mesh { points, normals, st, faces: f, .. } = &scene.objects[0].shape else {
            panic!("a mesh: {:?}", scene.objects[0].shape.name())
        };
        assert_eq!(points.len(), mesh.points.len());
        assert_eq!(f.len(), mesh.face_count());
        assert!(normals.is_some() && st.is_some());
    }
    let (a, b) = (rendered(&from_obj), rendered(&from_ply));
    let bits = |r: &Rendered| -> Vec<u32> {
        (0..48)
            .flat_map(|y| (0..48).map(move |x| (x, y)))
            .flat_map(|(x, y)| r.film.pixel(x, y).unwrap_or([f32::NAN; 4]))
            .map(f32::to_bits)
            .collect()
    };
    let (a, b) = (bits(&a), bits(&b));
    assert!(a.iter().any(|&v| v != 0), "the sphere is drawn");
    assert!(a == b, "OBJ and PLY render differently");
}

#[test]
fn a_mesh_file_group_picks_its_faces_and_a_missing_group_lists_the_names() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\ng first\nf 1 2 3\ng second\nf 1 3 4\nf 3 5 4\n";
    std::fs::write(dir.path().join("two.obj"), obj).unwrap_or_else(|e| panic!("{e}"));
    let scene = |group: &str| {
        format!(
            "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
              objects: [(shape: MeshFile(path: \"two.obj\", group: Some({group:?})),
                         material: Matte(color: (1.0, 1.0, 1.0)))])"
        )
    };
    let file = dir.path().join("g.ron");
    let s = parse(&scene("second"), &file);
    let Shape::Mesh { points, faces, .. } = &s.objects[0].shape else { panic!("a mesh") };
    // Points 0, 2, 3 and 4 (renumbered 0..4 in order), the two faces of `second`.
    assert_eq!(points, &vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 5.0]]);
    assert_eq!(Vec::<Vec<u32>>::from(faces), vec![vec![0, 1, 2], vec![1, 3, 2]]);
    // At the `Some(` of the group, column 66 of line 2 (14 spaces and 51 characters before).
    let e = reyes_scene::parse(&scene("third"), &file).unwrap_err().to_string();
    let want = format!(
        "{}:2:66: objects[0].shape.group: {}: no group or object named \"third\"; the file \
         has: first, second",
        file.display(),
        dir.path().join("two.obj").display()
    );
    assert_eq!(e, want);
}

/// The UV sphere lit from the side by a distant light (so shading shows the normal), with
/// or without its normals, under the hider `method`, 64 x 64 at 4 x 4 samples.
fn lit_sphere(normals: bool, method: &str, moving: bool) -> Scene {
    let mesh = uv_sphere();
    let mut scene = parse(
        &format!(
            "Scene(image: (width: 64, height: 64),
              camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 40.0,
                       shutter: (open: 0.0, close: 1.0)),
              hider: (method: {method}, pixel_samples: (4, 4), filter: (kind: Gaussian, width: 2.0),
                      seed: 3),
              lights: [Ambient(intensity: 0.1),
                       Distant(from: (-2.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), intensity: 1.0)],
              objects: [(shape: Sphere(radius: 1.0), transform: [Rotate(angle: 30.0, axis: (1.0, 0.0, 0.0)),
                                                                 Translate((0.3, -0.2, 4.0))],
                         {motion}
                         interpolation: Gouraud, material: Matte(color: (0.9, 0.8, 0.7)))])",
            motion = if moving {
                "motion: [(time: 0.0, transform: [Rotate(angle: 30.0, axis: (1.0, 0.0, 0.0)), Translate((0.3, -0.2, 4.0))]),
                          (time: 1.0, transform: [Rotate(angle: 40.0, axis: (1.0, 0.0, 0.0)), Translate((0.4, -0.2, 4.0))])],"
            } else {
                ""
            }
        ),
        Path::new("lit.ron"),
    );
    scene.objects[0].shape = Shape::Mesh {
        points: mesh.points.clone(),
        faces: faces(&mesh),
        colors: None,
        normals: normals.then(|| mesh.normals.clone()).flatten(),
        st: None,
    };
    reyes_scene::validate(scene).unwrap_or_else(|e| panic!("{e:?}"))
}

// The ray-tracing hider shades the smooth mesh as the dicer does: same interpolated normals
// (smooth triangles and smooth bilinear patches there, bilinear grids here), so the two
// hiders agree as on the analytic shapes of raytrace.rs (above 35 dB, for the same reasons:
// edge samples and Gouraud against shading at the hit), still and under a rotating,
// translating placement (normals carried by the inverse transpose at the ray's time). Flat
// normals in the ray engine would leave the facets' shading steps (a 7.5-degree turn of the
// normal across each edge) against the dicer's smooth picture: about 10 dB less when still
// (measured 55 dB smooth, 45 dB faceted), required to be at least 3 dB less.
#[test]
fn both_hiders_shade_a_smooth_mesh_alike() {
    let mut report = Vec::new();
    for moving in [false, true] {
        let reyes = rendered(&lit_sphere(true, "Stochastic", moving)).film;
        let rays = rendered(&lit_sphere(true, "RayTrace", moving)).film;
        let flat = rendered(&lit_sphere(false, "RayTrace", moving)).film;
        let (p, q) =
            (reyes_testkit::image::psnr(&reyes, &rays), reyes_testkit::image::psnr(&reyes, &flat));
        report.push(format!("moving {moving}: smooth {p:.1} dB, against faceted rays {q:.1} dB"));
        assert!(p > 35.0, "moving {moving}: PSNR {p:.1} dB");
        if !moving {
            // (Under motion blur the facets' steps blur away too, so only the still picture
            // tells the normals apart this way.)
            assert!(q < p - 3.0, "faceted {q:.1} dB vs smooth {p:.1} dB");
        }
    }
    eprintln!("smooth mesh, stochastic vs ray-tracing hider: {}", report.join("; "));
}
