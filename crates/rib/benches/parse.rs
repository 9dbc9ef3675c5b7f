//! Benchmark of the RIB reader on one `PointsPolygons` of a million quads (a 1000 x 1000 grid:
//! nverts, verts and "P" arrays), generated in memory; reports MB/s and, once before timing, the
//! peak resident memory the parse adds over the geometry's own size.
//!
//! Invariant: the parse is checked (counts of the arrays), so a fast wrong parser cannot pass.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, Throughput};
use reyes_rib::{Reader, RequestKind, Source};

/// Quads along each side of the grid.
const N: usize = 1000;

/// The RIB text of the grid: `PointsPolygons [4 ...] [v ...] "P" [x y z ...]`.
fn grid_rib() -> Vec<u8> {
    let mut s = String::with_capacity(64 << 20);
    s.push_str("# one million quads\nWorldBegin\nPointsPolygons [");
    for _ in 0..N * N {
        s.push_str("4 ");
    }
    s.push_str("]\n[");
    let w = N + 1;
    for j in 0..N {
        for i in 0..N {
            let v = j * w + i;
            let _ = write!(s, "{} {} {} {} ", v, v + 1, v + w + 1, v + w);
        }
        s.push('\n');
    }
    s.push_str("]\n\"P\" [");
    for j in 0..w {
        for i in 0..w {
            let (x, y) = (i as f32 / N as f32, j as f32 / N as f32);
            let z = 0.25 * (x * 6.0).sin() * (y * 4.0).cos();
            let _ = write!(s, "{x:.6} {y:.6} {z:.6} ");
        }
        s.push('\n');
    }
    s.push_str("]\nWorldEnd\n");
    s.into_bytes()
}

/// Many small requests: 100,000 attribute blocks (800,003 requests) of the peers' shape (AttributeBegin, Color,
/// MotionBegin with two Translates, Sphere with a parameter, AttributeEnd).
fn spheres_rib() -> Vec<u8> {
    let mut s = String::with_capacity(16 << 20);
    s.push_str("WorldBegin\nSurface \"plastic\" \"Ka\" [1] \"Kd\" [0.7] \"Ks\" [0.5] \"roughness\" [0.1]\n");
    for i in 0..100_000 {
        let (x, y) = ((i % 400) as f32 * 0.25 - 50.0, (i / 400) as f32 * 0.25 - 30.0);
        let _ = write!(
            s,
            "AttributeBegin\n Color [0.300 0.400 {:.3}]\n MotionBegin [0 1] Translate {x:.3} {y:.3} 60.235 Translate {:.3} {y:.3} 60.235 MotionEnd\n Sphere 1 -1 1 360 \"Cs\" [1 0 0]\nAttributeEnd\n",
            (i % 1000) as f32 / 1000.0,
            x + 1.0
        );
    }
    s.push_str("WorldEnd\n");
    s.into_bytes()
}

/// Parses many small requests; returns how many.
fn parse_requests(bytes: Vec<u8>) -> usize {
    let mut reader = Reader::new(Source::from_bytes("spheres.rib", bytes));
    let mut n = 0;
    while let Some(r) = reader.next_request().expect("the generated RIB is valid") {
        black_box(&r);
        n += 1;
    }
    assert_eq!(n, 3 + 100_000 * 8);
    n
}

/// Parses the text and checks the polygon's arrays; returns the point count.
fn parse(bytes: Vec<u8>) -> usize {
    let mut reader = Reader::new(Source::from_bytes("grid.rib", bytes));
    let mut points = 0;
    while let Some(r) = reader.next_request().expect("the generated RIB is valid") {
        if r.kind == RequestKind::PointsPolygons {
            assert_eq!(r.ints(0).map(<[i32]>::len), Some(N * N));
            assert_eq!(r.ints(1).map(<[i32]>::len), Some(4 * N * N));
            points = r.param("P").and_then(|p| p.floats()).map_or(0, |p| p.len() / 3);
            assert_eq!(points, (N + 1) * (N + 1));
            black_box(&r);
        }
    }
    points
}

/// A field of /proc/self/status in KiB (Linux), if readable.
fn status_kib(field: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(field))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The bytes of the grid's geometry held plainly: f32 points and i32 counts and indices.
const GEOMETRY: usize = 4 * (N * N + 4 * N * N + 3 * (N + 1) * (N + 1));

/// One timed run of `f` on a copy of `bytes`: its seconds, and the peak RSS it added beyond
/// the copy, in bytes (None where Linux's /proc/self/clear_refs is not there to reset it).
fn timed<T>(bytes: &[u8], f: impl FnOnce(Vec<u8>) -> T) -> (f64, Option<f64>) {
    // Reset the high-water mark to the current RSS (Linux >= 4.0), so VmHWM measures the run.
    let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let input = bytes.to_vec();
    let copied = status_kib("VmRSS:");
    let t = Instant::now();
    f(input);
    let secs = t.elapsed().as_secs_f64();
    let peak = status_kib("VmHWM:");
    match (reset, copied, peak) {
        (true, Some(copied), Some(peak)) => {
            (secs, Some(peak.saturating_sub(copied) as f64 * 1024.0))
        }
        _ => (secs, None),
    }
}

/// One timed, measured parse: MB/s and the peak RSS it adds, against the geometry's size.
fn memory_report(bytes: &[u8]) {
    let (secs, added) = timed(bytes, parse);
    eprintln!(
        "grid: {:.1} MB of RIB, {} quads, parsed once in {:.3} s = {:.1} MB/s",
        bytes.len() as f64 / 1e6,
        N * N,
        secs,
        bytes.len() as f64 / 1e6 / secs
    );
    match added {
        Some(added) => eprintln!(
            "grid: geometry (f32 points + i32 indices) {:.1} MB; peak RSS added by the parse {:.1} MB = {:.2}x the geometry (input copy excluded)",
            GEOMETRY as f64 / 1e6,
            added / 1e6,
            added / GEOMETRY as f64
        ),
        None => {
            eprintln!("grid: peak memory not measurable here (needs Linux /proc/self/clear_refs)")
        }
    }
}

/// The whole front-end: the same text into a validated scene (one mesh of a million quads).
fn load_scene(bytes: Vec<u8>) -> usize {
    let loaded = reyes_rib::load(Source::from_bytes("grid.rib", bytes), &Default::default())
        .expect("the generated RIB is a valid scene");
    match &loaded.frames[0].scene.objects[0].shape {
        reyes_scene::Shape::Mesh { faces, .. } => {
            assert_eq!(faces.len(), N * N);
            faces.len()
        }
        other => panic!("{other:?}"),
    }
}

/// One timed, measured load into the scene model, as [`memory_report`] measures the parse.
fn scene_report(bytes: &[u8]) {
    let (secs, added) = timed(bytes, load_scene);
    eprintln!(
        "grid to scene: loaded and validated once in {:.3} s = {:.1} MB/s",
        secs,
        bytes.len() as f64 / 1e6 / secs
    );
    if let Some(added) = added {
        eprintln!(
            "grid to scene: peak RSS added {:.1} MB = {:.2}x the geometry",
            added / 1e6,
            added / GEOMETRY as f64
        );
    }
}

fn main() {
    let bytes = grid_rib();
    memory_report(&bytes);
    scene_report(&bytes);
    let mut c = Criterion::default().configure_from_args().sample_size(10);
    let mut g = c.benchmark_group("rib");
    g.throughput(Throughput::Bytes(bytes.len() as u64));
    g.bench_function("points_polygons_1m_quads", |b| {
        b.iter_batched(|| bytes.clone(), parse, criterion::BatchSize::PerIteration)
    });
    g.bench_function("points_polygons_1m_quads_to_scene", |b| {
        b.iter_batched(|| bytes.clone(), load_scene, criterion::BatchSize::PerIteration)
    });
    let small = spheres_rib();
    g.throughput(Throughput::Bytes(small.len() as u64));
    g.bench_function("small_requests_800k", |b| {
        b.iter_batched(|| small.clone(), parse_requests, criterion::BatchSize::PerIteration)
    });
    g.finish();
    c.final_summary();
}
