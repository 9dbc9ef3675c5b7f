//! Lazy dicing ([`Dicer`]) gives, bucket by bucket, exactly the eager dicer's lists (the same
//! micropolygons, bit for bit, in the same order) and the same counts, for any thread count,
//! while holding far fewer micropolygons at once.

mod common;

use std::path::{Path, PathBuf};

use common::*;
use reyes_dice::{DiceOptions, Dicer, VertexContext, VertexShader, dice_scene_with};
use reyes_hider::Micropolygon;
use reyes_scene::{CameraKey, Lens, Scene, Transform, TransformKey};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every scene of `scenes/` and the small benchmark scenes.
fn scene_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    for name in ["balls", "balls-motion", "balls-dof"] {
        files.push(root().join(format!("scenes/bench/{name}.ron")));
    }
    files
}

/// Dice `scene` lazily, row by row, checking every bucket against the eager dicer; returns
/// the most micropolygons held at once and the total.
fn check_lazy(scene: &Scene, options: &DiceOptions<'_>, what: &str) -> (u64, u64) {
    let frame = frame_of(scene);
    let eager = dice_scene_with(scene, &frame, options).expect("dice");
    let mut lazy = Dicer::new(scene, &frame, options).expect("dicer");
    assert_eq!(lazy.csg_trees(), eager.csg_trees.as_slice(), "{what}");
    let mut got: Vec<Micropolygon> = Vec::new();
    for row in 0..lazy.rows() {
        lazy.dice_row(row).unwrap_or_else(|e| panic!("{what}: {e}"));
        for b in (row * frame.buckets_x) as usize..((row + 1) * frame.buckets_x) as usize {
            lazy.copy_bucket(b, &mut got);
            let want: Vec<Micropolygon> =
                eager.buckets[b].iter().map(|&i| eager.mpolys[i as usize]).collect();
            assert_eq!(lazy.bucket_len(b), want.len(), "{what}: bucket {b}");
            assert!(
                bytemuck::cast_slice::<_, u8>(&got) == bytemuck::cast_slice::<_, u8>(&want),
                "{what}: bucket {b} differs"
            );
        }
        lazy.release_row(row);
    }
    assert_eq!(lazy.stats(), eager.stats, "{what}");
    (lazy.peak_micropolygons(), eager.stats.micropolygons)
}

#[test]
fn lazy_buckets_are_the_eager_buckets_for_every_scene() {
    for file in scene_files() {
        // An animated scene (scenes/animation.ron) at its first frame.
        let scene = reyes_testkit::golden::load_scene(&file, Some(1)).expect("scene");
        let (peak, total) =
            check_lazy(&scene, &DiceOptions::default(), &file.display().to_string());
        assert!(peak <= total, "{}: {peak} > {total}", file.display());
        if file.ends_with("bench/balls.ron") {
            // Four rows of spheres: about a third of them at once.
            assert!(peak * 4 < total, "balls: {peak} of {total} held at once");
        }
    }
}

/// A floor through the eye (hither splits, patches with no raster bound), a moving camera, a
/// lens, spheres moving across rows, a torus, all in small buckets.
fn awkward_scene(lens: Option<Lens>) -> Scene {
    let mut objects = vec![floor_through_the_eye(), tilted_torus()];
    for k in 0..6 {
        let x = -3.0 + k as f32 * 1.2;
        objects.push(object(sphere(0.5), vec![]).with_motion(vec![
            TransformKey { time: 0.0, transform: vec![Transform::Translate([x, -2.0, 8.0])] },
            TransformKey { time: 1.0, transform: vec![Transform::Translate([x + 0.5, 2.5, 8.0])] },
        ]));
    }
    let mut s = small_buckets_scene(busy_camera(lens), objects);
    s.camera.motion = vec![
        CameraKey {
            time: 0.0,
            eye: [0.0, 0.5, -1.0],
            look_at: [0.0, 0.0, 6.0],
            up: [0.0, 1.0, 0.0],
        },
        CameraKey {
            time: 1.0,
            eye: [0.3, 0.2, -1.0],
            look_at: [0.0, 0.3, 6.0],
            up: [0.0, 1.0, 0.0],
        },
    ];
    s
}

#[test]
fn lazy_buckets_are_the_eager_buckets_for_awkward_scenes() {
    let lens = Lens { focal_length: 0.5, f_stop: 4.0, focal_distance: 7.0 };
    for (k, s) in [awkward_scene(None), awkward_scene(Some(lens))].iter().enumerate() {
        check_lazy(s, &DiceOptions::default(), &format!("awkward {k}"));
    }
}

/// A vertex shader colouring by where the vertex is (deterministic, order-free).
struct ByPlace;

impl VertexShader for ByPlace {
    fn shade(&self, v: &VertexContext) -> ([f32; 3], [f32; 3]) {
        let f = |x: f32| x.fract().abs();
        (
            [f(v.p_world.x), f(v.object as f32 * 0.1 + v.patch_u[0]), f(v.surface as f32 * 0.3)],
            [0.0; 3],
        )
    }
}

#[test]
fn the_vertex_shader_sees_the_same_vertices_lazily() {
    let options = DiceOptions { vertex_shader: Some(&ByPlace), ..Default::default() };
    check_lazy(&awkward_scene(None), &options, "vertex shader");
}

/// FNV-1a over every bucket's micropolygons, diced lazily in a pool of `threads` threads.
fn lazy_digest(scene: &Scene, threads: usize) -> u64 {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
    pool.install(|| {
        let frame = frame_of(scene);
        let mut dicer = Dicer::new(scene, &frame, &DiceOptions::default()).expect("dicer");
        let mut h = Fnv::default();
        let mut got = Vec::new();
        for row in 0..dicer.rows() {
            dicer.dice_row(row).expect("row");
            for b in (row * frame.buckets_x) as usize..((row + 1) * frame.buckets_x) as usize {
                dicer.copy_bucket(b, &mut got);
                h.eat(bytemuck::cast_slice(&got));
            }
            dicer.release_row(row);
        }
        h.0
    })
}

#[test]
fn lazy_dicing_does_not_depend_on_threads() {
    let s = awkward_scene(None);
    let one = lazy_digest(&s, 1);
    assert_eq!(one, lazy_digest(&s, 2));
    assert_eq!(one, lazy_digest(&s, 5));
}

#[test]
fn a_frame_that_is_not_the_scene_layout_is_refused() {
    let s = awkward_scene(None);
    let frame = reyes_hider::Frame::new(100, 100, 0, 16, 16);
    assert!(Dicer::new(&s, &frame, &DiceOptions::default()).is_err());
}
