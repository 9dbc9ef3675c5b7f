//! No input-controlled depth exhausts a stack: deep CSG trees in RON and in code, and a flat
//! union of 32768 operands through validation and the dicer's CSG set-up, each run on a thread
//! with the stack it gets in the renderer (8 MiB for loading on the main thread, 2 MiB for
//! the render threads that set up the dicer).

use std::path::Path;

use reyes_dice::CsgSetup;
use reyes_scene::{Csg, MAX_CSG_DEPTH, Solid, parse, validate};

/// Runs `f` on a thread with a stack of `mib` MiB and returns its result.
fn on_a_stack<T: Send + 'static>(mib: usize, f: impl FnOnce() -> T + Send + 'static) -> T {
    let worker = std::thread::Builder::new().stack_size(mib << 20).spawn(f);
    match worker.map(|h| h.join()) {
        Ok(Ok(value)) => value,
        _ => panic!("the deep input failed on a {mib} MiB stack"),
    }
}

/// A scene of `n` small spheres named `s0`, `s1`, ... and `solid` (RON) for its solids.
fn spheres(n: usize, solids: &str) -> String {
    let objects: Vec<String> = (0..n)
        .map(|i| {
            format!(
                "(name: \"s{i}\", shape: Sphere(radius: 0.01), transform: [Translate(({}, {}, 0.0))], material: Matte(color: (0.5, 0.5, 0.5)))",
                (i % 200) as f32 * 0.05,
                (i / 200) as f32 * 0.05
            )
        })
        .collect();
    format!(
        "Scene(\n  image: (width: 8, height: 6),\n  camera: (eye: (5.0, 4.0, -20.0), look_at: (5.0, 4.0, 0.0)),\n  objects: [\n{}\n  ],\n  solids: [{solids}],\n)\n",
        objects.join(",\n")
    )
}

/// The largest union validation allows (32768 operands, which the dicer folds into a chain of
/// 32767 binary operators) validates on the main thread's stack and is set up for rendering on
/// a render thread's: this overflowed the render threads' stacks before the CSG trees were
/// built without recursion.
#[test]
fn a_flat_union_of_32768_operands() {
    let n = 32768;
    let names: Vec<String> = (0..n).map(|i| format!("Object(\"s{i}\")")).collect();
    let text = spheres(n, &format!("(tree: Union([{}]))", names.join(", ")));
    let scene =
        on_a_stack(8, move || parse(&text, Path::new("flat.ron")).map_err(|e| e.to_string()));
    let scene = scene.unwrap_or_else(|e| panic!("{e}"));
    let (trees, operands) = on_a_stack(2, move || {
        let setup = CsgSetup::new(&scene);
        (setup.trees.len(), setup.leaf.iter().flatten().count())
    });
    assert_eq!((trees, operands), (1, n));
}

/// RON itself refuses nesting deeper than its limit, with one line and no overflow.
#[test]
fn ron_refuses_deep_nesting() {
    let depth = 100_000;
    let tree = format!(
        "{}Object(\"s0\"){}",
        "Difference(Object(\"s1\"), ".repeat(depth),
        ")".repeat(depth)
    );
    let text = spheres(2, &format!("(tree: {tree})"));
    let e = on_a_stack(8, move || parse(&text, Path::new("deep.ron")).err().map(|e| e.to_string()));
    let e = e.unwrap_or_default();
    assert!(e.ends_with("nesting is too deep") && !e.contains('\n'), "{e}");
}

/// `n` operators nested in a chain, `Difference(Object, Difference(Object, ...))`, over
/// objects `s0`..`sn`.
fn chain(n: usize) -> Csg {
    let mut tree = Csg::Object(format!("s{n}"));
    for i in (0..n).rev() {
        tree = Csg::Difference(Box::new(Csg::Object(format!("s{i}"))), Box::new(tree));
    }
    tree
}

/// A tree built in code (as a front end might) is validated to [`MAX_CSG_DEPTH`] operators
/// deep; one more is refused at the operator past the limit.
#[test]
fn validation_limits_the_depth_of_a_tree() {
    let with = |n: usize| {
        let text = spheres(n + 1, "");
        let mut scene = parse(&text, Path::new("deep.ron")).unwrap_or_else(|e| panic!("{e}"));
        scene.solids = vec![Solid { name: String::new(), tree: chain(n) }];
        on_a_stack(8, move || validate(scene).map(|_| ()).map_err(|i| (i.path, i.message)))
    };
    assert_eq!(with(MAX_CSG_DEPTH), Ok(()));
    let (path, message) = with(MAX_CSG_DEPTH + 1).err().unwrap_or_default();
    let mut want = "solids[0].tree".to_string();
    want.push_str(&"[1]".repeat(MAX_CSG_DEPTH));
    assert_eq!(path, want);
    assert_eq!(message, "CSG operators may nest at most 128 deep, this one is 129 deep");
}

/// Ray trees are at most `raytrace.max_depth` deep, which validation limits to 64: two facing
/// mirrors at that depth render on a 2 MiB render thread (the ray-tracing hider recurses once
/// per bounce), and a deeper limit is refused.
#[test]
fn ray_trees_between_facing_mirrors() {
    let scene = |depth: u32| {
        format!(
            "Scene(
  image: (width: 4, height: 4),
  camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 10.0),
  hider: (method: RayTrace, pixel_samples: (1, 1)),
  lights: [Ambient(intensity: 1.0)],
  objects: [
    (shape: Disk(height: 5.0, radius: 100.0), material: Matte(color: (0.5, 0.5, 0.5)),
     reflect: Some((color: (1.0, 1.0, 1.0)))),
    (shape: Disk(height: -5.0, radius: 100.0), material: Matte(color: (0.5, 0.5, 0.5)),
     reflect: Some((color: (1.0, 1.0, 1.0)))),
  ],
  raytrace: (max_depth: {depth}, min_weight: 0.0),
)
"
        )
    };
    let e = parse(&scene(65), Path::new("mirrors.ron")).err().map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("mirrors.ron:12:25: raytrace.max_depth: must be in 0..=64, got 65")
    );
    let valid = parse(&scene(64), Path::new("mirrors.ron")).unwrap_or_else(|e| panic!("{e}"));
    let rendered = on_a_stack(8, move || {
        let opts = reyes_render::RenderOptions { threads: Some(1), ..Default::default() };
        reyes_render::render(&valid, &opts)
            .map(|r| r.stats.rays.map_or(0, |rays| rays.secondary.reflection))
            .map_err(|e| e.to_string())
    });
    // Every pixel's ray bounces 64 times.
    assert!(rendered.as_ref().is_ok_and(|&n| n >= 16 * 64), "{rendered:?}");
}
