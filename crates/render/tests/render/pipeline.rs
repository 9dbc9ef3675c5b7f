//! End-to-end rendering tests: analytic coverage through the whole pipeline (scene, dicer,
//! hider, film), determinism across thread counts, and the golden images.

use reyes_render::{RenderOptions, render};
use reyes_testkit::geometry::coverage_of_pixel as pixel_coverage;
use reyes_testkit::golden::{self, Outcome};

/// A white triangle facing a camera at the origin, 90 degree fov on a 64x64 image, so a point
/// (x, y, 1) lands on raster (32 + 32x, 32 - 32y). Returns the scene text and the triangle
/// in raster coordinates.
fn triangle_scene(n: u32, seed: u64) -> (String, Vec<(f64, f64)>) {
    let raster = [(9.3, 11.7), (55.1, 20.2), (23.6, 52.9)];
    let to_eye = |(x, y): (f64, f64)| ((x - 32.0) / 32.0, (32.0 - y) / 32.0);
    let pts: Vec<String> = raster
        .iter()
        .map(|&r| {
            let (x, y) = to_eye(r);
            format!("({x:.9}, {y:.9}, 1.0)")
        })
        .collect();
    let text = format!(
        "Scene(image: (width: 64, height: 64),
           camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 90.0),
           hider: (pixel_samples: ({n}, {n}), filter: (kind: Box, width: 1.0), seed: {seed}),
           objects: [(shape: Mesh(points: [{}], faces: [[0, 1, 2]]),
                      material: Constant(color: (1.0, 1.0, 1.0)))])",
        pts.join(", ")
    );
    (text, raster.to_vec())
}

#[test]
fn coverage_of_a_known_triangle_converges_within_the_stratified_bound() {
    // Theory (as in the hider's test): a pixel cut by one straight edge, sampled with one
    // uniform point in each cell of an n x n grid, has coverage variance at most
    // (2n - 1) / (4 n^4): at most 2n - 1 cells are cut, each a Bernoulli indicator of
    // variance <= 1/4 weighted 1/n^2. Pixels holding a corner are excluded. The RMS over all
    // edge pixels and 4 seeds (several hundred pixels) estimates the true RMS to within a few
    // percent, so the bound plus 15% cannot be exceeded by a correct renderer.
    let mut rms = Vec::new();
    for n in [2u32, 4, 8] {
        let (mut sum, mut count) = (0.0f64, 0usize);
        for seed in 0..4 {
            let (text, tri) = triangle_scene(n, seed);
            let scene = reyes_scene::parse(&text, std::path::Path::new("triangle.ron")).unwrap();
            let film = render(&scene, &RenderOptions::default()).unwrap().film;
            for py in 0..64u32 {
                for px in 0..64u32 {
                    let exact = pixel_coverage(&tri, px as f64, py as f64);
                    let corner = tri.iter().any(|&(x, y)| {
                        x >= px as f64 - 1.0
                            && x <= px as f64 + 2.0
                            && y >= py as f64 - 1.0
                            && y <= py as f64 + 2.0
                    });
                    if exact == 0.0 || exact == 1.0 || corner {
                        // Fully inside or outside pixels must be exact.
                        if !corner {
                            let a = film.pixel(px, py).unwrap()[3] as f64;
                            assert!((a - exact).abs() < 1e-6, "pixel ({px},{py}) {a} vs {exact}");
                        }
                        continue;
                    }
                    let a = film.pixel(px, py).unwrap()[3] as f64;
                    sum += (a - exact).powi(2);
                    count += 1;
                }
            }
        }
        rms.push((n, (sum / count as f64).sqrt()));
    }
    reyes_testkit::geometry::assert_stratified(&rms, "the edge pixels of 4 seeds");
}

fn exr_bytes(threads: usize, bucket: u32) -> Vec<u8> {
    let root = golden::workspace_root();
    let mut scene = reyes_scene::load(&root.join("scenes/transparency.ron")).unwrap();
    scene.image.width = 120;
    scene.image.height = 90;
    scene.hider.bucket_size = (bucket, bucket);
    crate::sampling::exr_bytes(&scene, threads)
}

#[test]
fn output_is_byte_identical_for_any_thread_count() {
    let one = exr_bytes(1, 16);
    assert_eq!(one, exr_bytes(2, 16));
    assert_eq!(one, exr_bytes(8, 16));
}

#[test]
fn golden_images() {
    let root = golden::workspace_root();
    let mut failures = Vec::new();
    for case in golden::manifest(&root).unwrap() {
        match golden::check(&root, &case).unwrap() {
            Outcome::Pass(_) => {
                // A scene with AOVs: every layer against the reference's.
                for f in golden::check_aovs(&root, &case).unwrap() {
                    failures.push(format!("{}: {f}", case.name()));
                }
            }
            Outcome::Fail(c, path) => failures.push(format!(
                "{}: mean {:?} max {:?} over tolerance {} / {}; see {}",
                case.name(),
                c.mean,
                c.max,
                c.mean_tolerance,
                c.max_tolerance,
                path.display()
            )),
            Outcome::Missing(path) => failures.push(format!(
                "{}: no reference {} (render it, look at it, then `cargo xtask bless`)",
                case.name(),
                path.display()
            )),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_scene_has_a_golden_case() {
    let root = golden::workspace_root();
    let cases: Vec<String> =
        golden::manifest(&root).unwrap().into_iter().map(|c| c.scene).collect();
    for entry in std::fs::read_dir(root.join("scenes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) == Some("ron") {
            let name = path.file_stem().unwrap().to_string_lossy().to_string();
            assert!(cases.contains(&name), "scenes/{name}.ron has no golden case");
        }
    }
}

/// `on_film_lines` hands on every line of the film once, in order, and only once no later
/// bucket adds to it: the lines as they were when handed on are the final film's, bit for
/// bit, for any thread count, bucket size and filter border (a wide filter's windows reach
/// further into the rows above). The EXR written with the blocks compressed from them
/// ([`reyes_film::EarlyBlocks`]) is the EXR written without, byte for byte.
#[test]
fn film_lines_are_handed_on_once_final_and_their_blocks_make_the_same_file() {
    use std::sync::Mutex;
    let root = golden::workspace_root();
    for (bucket, filter) in [(16, None), (8, Some(6.0)), (4, Some(10.0))] {
        let mut scene = reyes_scene::load(&root.join("scenes/transparency.ron")).unwrap();
        scene.image.width = 120;
        scene.image.height = 90;
        scene.hider.bucket_size = (bucket, bucket);
        if let Some(width) = filter {
            scene.hider.filter.width = width;
            scene.hider.filter.height = None;
        }
        let mut files = Vec::new();
        for threads in [1, 2, 8] {
            let what = format!("bucket {bucket}, filter {filter:?}, {threads} threads");
            let seen: Mutex<Vec<(std::ops::Range<u32>, Vec<u32>)>> = Mutex::new(Vec::new());
            let early = reyes_film::EarlyBlocks::new(120, 90, &scene.outputs, false).unwrap();
            let on_lines = |film: &reyes_film::Film, lines: std::ops::Range<u32>| {
                let w = film.width() as usize;
                let (a, b) = (lines.start as usize * w, lines.end as usize * w);
                let bits = film.rgba()[a..b].iter().flatten().chain(&film.z()[a..b]);
                seen.lock().unwrap().push((lines.clone(), bits.map(|v| v.to_bits()).collect()));
                early.encode(film, lines);
            };
            let opts = RenderOptions {
                threads: Some(threads),
                on_film_lines: Some(&on_lines),
                ..Default::default()
            };
            let film = render(&scene, &opts).unwrap().film;
            let seen = seen.into_inner().unwrap();
            let mut next = 0;
            for (lines, bits) in &seen {
                assert_eq!(lines.start, next, "{what}: {seen:?}");
                assert!(lines.end > lines.start, "{what}");
                let w = film.width() as usize;
                let (a, b) = (lines.start as usize * w, lines.end as usize * w);
                let now = film.rgba()[a..b].iter().flatten().chain(&film.z()[a..b]);
                let now: Vec<u32> = now.map(|v| v.to_bits()).collect();
                let ranges: Vec<_> = seen.iter().map(|s| s.0.clone()).collect();
                assert!(
                    &now == bits,
                    "{what}: lines {lines:?} changed after they were handed on {ranges:?}"
                );
                next = lines.end;
            }
            assert_eq!(next, 90, "{what}: every line");
            // Not all at the end: lines came early, row by row.
            assert!(seen.len() > 2, "{what}: {} ranges", seen.len());

            let metadata = reyes_film::Metadata::for_scene(&scene, "t.ron");
            let dir = tempfile::tempdir().unwrap();
            let write = |name: &str, e: Option<&reyes_film::EarlyBlocks>| {
                let picture = reyes_film::Picture {
                    film: &film,
                    aovs: None,
                    outputs: &scene.outputs,
                    metadata: &metadata,
                    placement: None,
                    early: e,
                };
                let path = dir.path().join(name);
                reyes_film::write_picture(&path, &picture, &Default::default()).unwrap();
                std::fs::read(&path).unwrap()
            };
            let plain = write("plain.exr", None);
            assert!(write("early.exr", Some(&early)) == plain, "{what}: the files differ");
            files.push(plain);
        }
        assert!(files.windows(2).all(|p| p[0] == p[1]), "bucket {bucket}: thread counts differ");
    }
}

#[test]
fn a_frame_too_large_for_the_memory_limit_is_refused_with_parts_that_add_up() {
    let scene = crate::scene_file("spheres", |s| {
        s.image.width = 4000;
        s.image.height = 3000;
    });
    let opts = reyes_render::RenderOptions {
        memory_limit: Some(64 << 20),
        ..reyes_render::RenderOptions::default()
    };
    let e = reyes_render::render(&scene, &opts).err().expect("rendered over the limit");
    let reyes_render::RenderError::WontFit { need, film, buckets, base, limit } = &e else {
        panic!("{e}")
    };
    assert_eq!(*need, film + buckets + base, "{e}");
    assert_eq!(*limit, 64);
    let shown = e.to_string();
    for part in [need, film, buckets, base] {
        assert!(shown.contains(&format!("{part} MB")), "{shown}");
    }
}
