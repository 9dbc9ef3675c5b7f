//! Requests of later RenderMan than the 3.2 Specification, and its corners: inline archives,
//! search paths, RIS requests told once, DynamicLoad refused, height-field patches, and the
//! built-in teapot.

use std::fs;
use std::path::Path;

use glam::{DVec3, Vec3};
use reyes_render::{RenderOptions, render};
use reyes_rib::ri::teapot;
use reyes_rib::{RiOptions, Source, load, load_scene_file};
use reyes_scene::{Basis, Material, Shape, Wrap, object_to_world};

use super::{rib, scene};

#[test]
fn inline_archives_are_recorded_and_replayed_by_read_archive() {
    // Run in place, the sphere would be geometry outside the world: an error.
    let text = "ArchiveBegin \"ball\"
  AttributeBegin
    Color [1 0 0]
    Sphere 1 -1 1 360
  AttributeEnd
ArchiveEnd
ArchiveBegin \"pair\"
  ReadArchive \"ball\"
  Translate 0 3 0
  ReadArchive \"ball\"
ArchiveEnd
Projection \"perspective\"
WorldBegin
Translate 0 0 5
ReadArchive \"ball\"
Translate 2 0 0
ReadArchive \"pair\"
WorldEnd
";
    let loaded = rib(text).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let s = &loaded.frames[0].scene;
    let centres: Vec<Vec3> = s
        .objects
        .iter()
        .map(|o| object_to_world(&o.transform).project_point3(Vec3::ZERO))
        .collect();
    assert_eq!(
        centres,
        [Vec3::new(0.0, 0.0, 5.0), Vec3::new(2.0, 0.0, 5.0), Vec3::new(2.0, 3.0, 5.0)]
    );
    for o in &s.objects {
        assert!(matches!(o.material, Material::DefaultSurface { color: [1.0, 0.0, 0.0], .. }));
    }
}

#[test]
fn inline_archives_report_at_their_own_lines_and_catch_cycles() {
    let text = "ArchiveBegin \"a\"
  Attribute \"user\" \"float frobs\" [1]
  ReadArchive \"b\"
ArchiveEnd
ArchiveBegin \"b\"
  ReadArchive \"a\"
ArchiveEnd
WorldBegin
ReadArchive \"a\"
WorldEnd
";
    assert_eq!(
        rib(text).err().map(|e| e.to_string()).as_deref(),
        Some(
            "test.rib:6:3: ReadArchive: inline archives read each other in a cycle: \"a\" -> \"b\" -> \"a\""
        )
    );
    let refused = load_scene_file_text(text).expect_err("a cycle");
    // The warning raised while replaying "a" is at the request's own line in "a".
    let shown: Vec<String> = refused.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        shown,
        ["test.rib:2:20: warning: Attribute: \"user\" \"frobs\" is not supported: ignored"]
            .map(|w| w.replace("test.rib", &refused_file(&refused)))
    );
    // Seventy archives, each reading the next: deeper than replays nest.
    let mut deep: String = (0..70)
        .map(|k| format!("ArchiveBegin \"a{k}\" ReadArchive \"a{}\" ArchiveEnd\n", k + 1))
        .collect();
    deep.push_str("ArchiveBegin \"a70\" Sphere 1 -1 1 360 ArchiveEnd\nWorldBegin\nReadArchive \"a0\"\nWorldEnd\n");
    let e = rib(&deep).expect_err("too deep");
    assert_eq!(
        e.to_string(),
        "test.rib:64:20: ReadArchive: inline archives nested more than 64 deep"
    );
    assert_eq!(
        rib("ArchiveBegin \"open\"\nSphere 1 -1 1 360\n").err().map(|e| e.to_string()).as_deref(),
        Some("test.rib:1:1: ArchiveBegin: no ArchiveEnd before the end of the input")
    );
    assert_eq!(
        rib("ArchiveEnd\n").err().map(|e| e.to_string()).as_deref(),
        Some("test.rib:1:1: ArchiveEnd: no ArchiveBegin is open")
    );
}

/// Loads `text` from a file `test.rib` in a temporary folder through `load_scene_file`.
fn load_scene_file_text(text: &str) -> Result<reyes_rib::Loaded, reyes_rib::Refusal> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("test.rib");
    fs::write(&path, text).unwrap();
    load_scene_file(&path, &RiOptions::default())
}

/// The file name a refusal's warnings carry (the temporary file's path).
fn refused_file(refused: &reyes_rib::Refusal) -> String {
    refused.warnings.first().map(|w| w.at.file.to_string()).unwrap_or_default()
}

fn write(dir: &Path, name: &str, text: &str) {
    let path = dir.join(name);
    fs::create_dir_all(path.parent().unwrap()).unwrap();
    fs::write(path, text).unwrap();
}

#[test]
fn search_paths_find_archives_and_textures_with_ampersand_and_at() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(d, "other/deep.rib", "Disk 0 1 360\n");
    write(d, "parts/ball.rib", "Sphere 1 -1 1 360\n");
    write(d, "maps/wood.png", "not read at load time");
    write(d, "beside.png", "not read at load time");
    // The archive path: "other", then "parts" before it (& is the previous path). The
    // texture path: "maps", then @ (the naming file's folder). Shader and procedural paths
    // are taken without a word.
    let main = "Option \"searchpath\" \"archive\" [\"other\"]
Option \"searchpath\" \"archive\" [\"parts:&\"]
Option \"searchpath\" \"string texture\" [\"maps:@\"]
Option \"searchpath\" \"shader\" [\"shaders:&\"] \"procedural\" [\"@\"]
Projection \"perspective\"
WorldBegin
Translate 0 0 5
ReadArchive \"ball.rib\"
ReadArchive \"deep.rib\"
Surface \"paintedplastic\" \"texturename\" \"wood.png\"
Sphere 1 -1 1 360
Surface \"paintedplastic\" \"texturename\" \"beside.png\"
Sphere 1 -1 1 360
Surface \"paintedplastic\" \"texturename\" \"lost.png\"
Sphere 1 -1 1 360
WorldEnd
";
    write(d, "main.rib", main);
    let path = d.join("main.rib");
    let loaded = load_scene_file(&path, &RiOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let s = &loaded.frames[0].scene;
    assert!(matches!(s.objects[0].shape, Shape::Sphere { .. }), "parts/ball.rib");
    assert!(matches!(s.objects[1].shape, Shape::Disk { .. }), "other/deep.rib");
    let map = |i: usize| s.objects[i].maps.color.as_ref().map(|m| m.file.clone());
    assert_eq!(map(2), Some(d.join("maps/wood.png").display().to_string()));
    assert_eq!(map(3), Some(d.join("beside.png").display().to_string()));
    // Found nowhere: the default resolution, with a warning naming the path.
    assert_eq!(map(4), Some(d.join("lost.png").display().to_string()));
    let shown: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        shown,
        [format!(
            "{}:14:1: warning: Surface: texture \"lost.png\" is not found along the texture search path {:?}: {:?} is used",
            path.display(),
            format!("{}:@", d.join("maps").display()),
            d.join("lost.png").display().to_string()
        )]
    );
    // An archive found nowhere along its path is the error of an unreadable archive.
    write(d, "lost.rib", &main.replace("\"deep.rib\"", "\"beside.rib\""));
    let refused = load_scene_file(&d.join("lost.rib"), &RiOptions::default()).expect_err("lost");
    assert_eq!(
        refused.to_string(),
        format!(
            "{}:9:1: ReadArchive: cannot read \"beside.rib\": not found along the archive search path {:?}",
            d.join("lost.rib").display(),
            format!("{}:{}", d.join("parts").display(), d.join("other").display())
        )
    );
    assert_eq!(refused.exit_code(), 1);
}

#[test]
fn ris_requests_are_told_once_per_request_name() {
    let text = "Integrator \"PxrPathTracer\" \"pt\" \"int maxPathLength\" [10]
Projection \"perspective\"
WorldBegin
Pattern \"PxrTexture\" \"tex\" \"string filename\" [\"wood.tex\"]
Bxdf \"PxrSurface\" \"a\" \"reference color diffuseColor\" [\"tex:resultRGB\"]
Light \"PxrDomeLight\" \"dome\" \"float intensity\" [1]
Bxdf \"PxrDisney\" \"b\" \"color baseColor\" [0.8 0.2 0.1]
Light \"PxrRectLight\" \"key\"
Translate 0 0 5
Sphere 1 -1 1 360
WorldEnd
";
    let loaded = rib(text).unwrap_or_else(|e| panic!("{e}"));
    let shown: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    let told = |at: &str, name: &str| {
        format!(
            "test.rib:{at}: warning: {name}: RenderMan's RIS requests are not supported (this renderer runs the shading of the RenderMan Interface 3.2); every {name} request is ignored"
        )
    };
    assert_eq!(
        shown,
        [
            told("1:1", "Integrator"),
            told("4:1", "Pattern"),
            told("5:1", "Bxdf"),
            told("6:1", "Light")
        ]
    );
    assert_eq!(loaded.frames[0].scene.lights.len(), 0);
    let strict = RiOptions { strict: true, ..RiOptions::default() };
    let e = load(Source::from_bytes("test.rib", text.as_bytes().to_vec()), &strict)
        .expect_err("strict");
    assert_eq!(
        e.to_string(),
        "test.rib:1:1: Integrator: RenderMan's RIS requests are not supported (this renderer runs the shading of the RenderMan Interface 3.2); every Integrator request is ignored (--strict)"
    );
}

#[test]
fn dynamic_load_is_refused_in_one_line() {
    let text = "WorldBegin\nProcedural \"DynamicLoad\" [\"sphere.so\" \"1 2\"] [-1 1 -1 1 -1 1]\nWorldEnd\n";
    assert_eq!(
        rib(text).err().map(|e| e.to_string()).as_deref(),
        Some(
            "test.rib:2:1: Procedural: \"DynamicLoad\" runs the native plug-in \"sphere.so\", and native plug-ins are not loaded: write its geometry as RIB (DelayedReadArchive reads it)"
        )
    );
}

#[test]
fn height_field_patches_spread_x_and_y_over_the_surface_parameters() {
    let z7x4: Vec<String> = (0..28).map(|k| format!("{}", k as f32 * 0.5 - 3.0)).collect();
    let s = scene(&super::world(&format!(
        "Patch \"bilinear\" \"Pz\" [1 2 3 4]
         Patch \"bicubic\" \"Pz\" [0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15]
         PatchMesh \"bicubic\" 7 \"nonperiodic\" 4 \"nonperiodic\" \"Pz\" [{}]
         Basis \"b-spline\" 1 \"b-spline\" 1
         PatchMesh \"bilinear\" 4 \"periodic\" 2 \"nonperiodic\" \"Pz\" [0 0 0 0 1 1 1 1]",
        z7x4.join(" ")
    )));
    assert_eq!(
        s.objects[0].shape,
        Shape::BilinearPatch {
            points: [[0.0, 0.0, 1.0], [1.0, 0.0, 2.0], [0.0, 1.0, 3.0], [1.0, 1.0, 4.0]]
        }
    );
    let points = |i: usize| match &s.objects[i].shape {
        Shape::PatchMesh { points, .. } => points.clone(),
        other => panic!("{other:?}"),
    };
    let want = |nu: usize, du: f32, dv: f32, z: &dyn Fn(usize) -> f32, n: usize| -> Vec<[f32; 3]> {
        (0..n).map(|k| [(k % nu) as f32 / du, (k / nu) as f32 / dv, z(k)]).collect()
    };
    assert_eq!(points(1), want(4, 3.0, 3.0, &|k| k as f32, 16));
    assert_eq!(points(2), want(7, 6.0, 3.0, &|k| k as f32 * 0.5 - 3.0, 28));
    // Along a periodic direction the last point comes back to the first: i / nu.
    assert_eq!(points(3), want(4, 4.0, 1.0, &|k| if k < 4 { 0.0 } else { 1.0 }, 8));
    match &s.objects[3].shape {
        Shape::PatchMesh { uwrap, vwrap, .. } => {
            assert_eq!((*uwrap, *vwrap), (Wrap::Periodic, Wrap::Nonperiodic))
        }
        other => panic!("{other:?}"),
    }
    // One height per point.
    let e = rib(&super::world("Patch \"bilinear\" \"Pz\" [1 2 3]")).expect_err("3 heights");
    assert!(e.to_string().contains("parameter \"Pz\""), "{e}");
}

/// The teapot stood up for a y-up view, as RIB files do, the spout to the right.
fn teapot_view(body: &str) -> String {
    format!(
        "Format 64 48 1 ScreenWindow -4 4 -3 3 PixelSamples 4 4 PixelFilter \"box\" 1 1
         WorldBegin Translate 0 -1.5 10 Rotate -90 1 0 0 {body} WorldEnd"
    )
}

#[test]
fn the_teapot_is_the_newell_data_set_in_its_own_orientation_and_size() {
    // The current Basis is not the teapot's: its nets are Bezier.
    let s = scene(&teapot_view("Basis \"b-spline\" 1 \"b-spline\" 1 Geometry \"teapot\""));
    assert_eq!(s.objects.len(), 32);
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for (o, net) in s.objects.iter().zip(teapot::patches()) {
        match &o.shape {
            Shape::PatchMesh {
                nu: 4,
                nv: 4,
                ubasis: Basis::Bezier,
                vbasis: Basis::Bezier,
                points,
                ..
            } => {
                assert_eq!(points[..], net[..]);
                for p in points {
                    lo = lo.min(Vec3::from(*p));
                    hi = hi.max(Vec3::from(*p));
                }
            }
            other => panic!("{other:?}"),
        }
    }
    // The bound of its control points: z up from the base on z = 0 to the knob at 3.15,
    // the handle to x = -3, the spout to x = 3.525, y within 2.
    assert_eq!((lo, hi), (Vec3::new(-3.0, -2.0, 0.0), Vec3::new(3.525, 2.0, 3.15)));
    // The surface reaches the bound where patch corners lie on it: the bottom's centre, the
    // knob, the handle's outer edge and the body's widest ring.
    let corners: Vec<DVec3> = s
        .objects
        .iter()
        .flat_map(|o| reyes_scene::patches::bezier_patches(&o.shape, None))
        .flat_map(|b| [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].map(|(u, v)| b.eval(u, v).p))
        .collect();
    for p in [
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 3.15),
        DVec3::new(-3.0, 0.0, 1.8),
        DVec3::new(0.0, -2.0, 0.9),
    ] {
        assert!(corners.iter().any(|c| (*c - p).length() < 1e-6), "{p}");
    }
}

/// The alpha of a render, row by row from the top.
fn alpha(text: &str) -> Vec<f32> {
    render(&scene(text), &RenderOptions::default())
        .unwrap()
        .film
        .rgba()
        .iter()
        .map(|p| p[3])
        .collect()
}

#[test]
fn the_teapot_renders_as_its_patches_given_as_patch_requests() {
    let geometry = alpha(&teapot_view("Geometry \"teapot\""));
    let patches: String = teapot::patches()
        .iter()
        .map(|net| {
            let p: Vec<String> = net.iter().flatten().map(|x| x.to_string()).collect();
            format!("Patch \"bicubic\" \"P\" [{}]\n", p.join(" "))
        })
        .collect();
    let as_patches = alpha(&teapot_view(&patches));
    assert_eq!(geometry, as_patches, "the silhouettes differ");
    // Seen from the front, 8 pixels a unit: handle at x = -3 (column 8), spout to the right,
    // base on row 36, knob at y = 1.65 (row 10.8); the covered area lies inside that box.
    let covered: Vec<(usize, usize)> =
        (0..64 * 48).filter(|&k| geometry[k] > 0.0).map(|k| (k % 64, k / 64)).collect();
    let columns = (covered.iter().map(|c| c.0).min(), covered.iter().map(|c| c.0).max());
    let rows = (covered.iter().map(|c| c.1).min(), covered.iter().map(|c| c.1).max());
    assert_eq!(columns.0, Some(8), "the handle's outer edge");
    assert!(columns.1.is_some_and(|c| (56..=59).contains(&c)), "the spout's tip: {columns:?}");
    assert_eq!(rows, (Some(10), Some(35)), "knob and base");
    let area: f32 = geometry.iter().sum();
    assert!(area > 0.5 * 6.525 * 3.15 * 64.0 && area < 6.525 * 3.15 * 64.0, "{area}");
}
