//! Criterion benchmark of the hider's inner loop (issue #7): one synthetic 16x16-pixel bucket,
//! 4x4 samples per pixel, rendered by `Hider::render_bucket` again and again.
//!
//! The bucket holds two overlapping layers of about one-pixel quads, built like a diced grid
//! (neighbouring quads share their jittered vertices), the front one at depth about 11 and the
//! back one at about 13 — as a diced sphere puts its front and back halves in one bucket. Three
//! cases use the same quads:
//! - `static`: pinhole camera (path P);
//! - `moving`: every quad moves (12, 5) pixels over the shutter (path M);
//! - `defocused`: a thin lens focused at depth 6, blurring the layers by about 4 pixels
//!   (path D).
//!
//! Throughput is in sample tests (`Stats::hits + Stats::misses` of one bucket, the
//! (sample, micropolygon) pairs whose inside test runs), so criterion's "elem/s" is sample tests
//! per second on one core. The time per iteration is the whole of `render_bucket` (sample
//! generation, the sampling loops and the resolve); after each case the bench also prints the
//! rate over the sampling loops alone, from `Stats::sample_ns`.
//!
//! A second group, `hider_samples`, renders the `static` case at 8x8, 16x16, 32x32 and 64x64
//! samples per pixel: with the work per sample test constant, its elem/s stays flat (issue #31
//! asks for within 1.5x from 8x8 to 64x64). Occlusion culling's per-pixel depth once rescanned
//! all of a pixel's samples on every sample's first occluder, `ns^2` a pixel, and this group is
//! where that shows; so did the sample-major sample arrays, which made a micropolygon's scan
//! read a new cache line per sample index (docs/performance.md, 2026-12-05).
//!
//! Run with `cargo bench -p reyes-hider --bench inner` (or `-- hider_samples` for the second
//! group alone).

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use reyes_hider::{Frame, Hider, HiderConfig, LensSetup, Micropolygon, Scratch, flags};
use reyes_sampling::{hash, unit};

/// The image is 3x3 buckets of 16x16 pixels with no border; the bench renders the middle one,
/// whose top-left pixel is raster (16, 16).
const BUCKET: usize = 4;

fn frame() -> Frame {
    Frame::new(48, 48, 0, 16, 16)
}

/// A diced grid of quads of side about `pitch` pixels covering raster `[x0, x1] x [y0, y1]`
/// at depth about `z`, every vertex jittered by up to 15% of the pitch (deterministically from
/// `seed`) and shared by the quads around it.
fn grid(
    seed: u64,
    pitch: f32,
    z: f32,
    (x0, y0): (f32, f32),
    (x1, y1): (f32, f32),
) -> Vec<Micropolygon> {
    let nx = ((x1 - x0) / pitch).ceil() as usize;
    let ny = ((y1 - y0) / pitch).ceil() as usize;
    let vertex = |i: usize, j: usize| -> [f32; 3] {
        let jx = unit(hash(seed, &[0, i as u64, j as u64])) - 0.5;
        let jy = unit(hash(seed, &[1, i as u64, j as u64])) - 0.5;
        [
            x0 + (i as f32 + 0.3 * jx) * pitch,
            y0 + (j as f32 + 0.3 * jy) * pitch,
            // A gentle slope, as across a sphere's front or back.
            z + 0.02 * i as f32 - 0.015 * j as f32,
        ]
    };
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let shade = unit(hash(seed, &[2, i as u64, j as u64]));
            out.push(Micropolygon::opaque(
                [vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)],
                [[0.2 + 0.6 * shade, 0.4, 0.3]; 4],
            ));
        }
    }
    out
}

/// One benchmark case: a hider and the micropolygons of its bucket.
struct Case {
    name: &'static str,
    hider: Hider,
    mpolys: Vec<Micropolygon>,
    list: Vec<u32>,
}

/// The case's quads: both layers over a region grown by `margin` pixels around the bucket
/// (for motion, upstream of it), each moved by `speed` over the shutter, keeping those whose
/// bound (grown by the lens blur, if any) touches the bucket.
fn case(name: &'static str, speed: [f32; 2], lens: Option<LensSetup>) -> Case {
    case_with(name, speed, lens, HiderConfig::default())
}

fn case_with(
    name: &'static str,
    speed: [f32; 2],
    lens: Option<LensSetup>,
    config: HiderConfig,
) -> Case {
    let config = HiderConfig { lens, ..config };
    let hider = Hider::new(config, frame());
    let (lo, hi) = (16.0 - 6.0 - speed[0], 16.0 - 6.0 - speed[1]);
    let mut mpolys = grid(7, 0.95, 11.0, (lo, hi), (38.0, 38.0));
    mpolys.extend(grid(11, 1.05, 13.0, (lo + 0.3, hi + 0.2), (38.0, 38.0)));
    for mp in &mut mpolys {
        if speed != [0.0, 0.0] {
            mp.speed = [[speed[0], speed[1], 0.0]; 4];
            mp.flags |= flags::MOVING;
        }
    }
    let f = frame();
    let list = mpolys
        .iter()
        .enumerate()
        .filter(|(_, mp)| {
            let (mut lo, mut hi) = mp.bound();
            if let Some(l) = &lens {
                l.grow(&mut lo, &mut hi, config.hither, config.yon);
            }
            f.buckets_touched([lo[0], lo[1]], [hi[0], hi[1]]).is_some_and(
                |[(bx0, bx1), (by0, by1)]| (bx0..=bx1).contains(&1) && (by0..=by1).contains(&1),
            )
        })
        .map(|(m, _)| m as u32)
        .collect();
    Case { name, hider, mpolys, list }
}

fn cases() -> Vec<Case> {
    // About 772 pixels per unit at depth 1 (640 pixels across a 45-degree view); a lens of
    // radius 0.062 focused at depth 6 moves a point at depth 11-13 by 3.6-4.3 pixels.
    let lens = LensSetup::new(0.062, 6.0, 772.0, -772.0);
    vec![
        case("static", [0.0, 0.0], None),
        case("moving", [12.0, 5.0], None),
        case("defocused", [0.0, 0.0], Some(lens)),
    ]
}

fn inner(c: &mut Criterion) {
    run_group(c, "hider_inner", cases());
}

fn samples(c: &mut Criterion) {
    let at = |name, n| {
        case_with(name, [0.0, 0.0], None, HiderConfig { nx: n, ny: n, ..HiderConfig::default() })
    };
    let cases = vec![at("8x8", 8), at("16x16", 16), at("32x32", 32), at("64x64", 64)];
    run_group(c, "hider_samples", cases);
}

fn run_group(c: &mut Criterion, name: &str, cases: Vec<Case>) {
    let mut group = c.benchmark_group(name);
    for case in cases {
        let mut scratch = Scratch::new();
        case.hider.render_bucket(BUCKET, &case.mpolys, &case.list, &mut scratch);
        let once = scratch.stats;
        let tests = once.hits + once.misses;
        group.throughput(Throughput::Elements(tests));
        scratch.stats = Default::default();
        group.bench_function(case.name, |b| {
            b.iter(|| {
                let out = case.hider.render_bucket(
                    BUCKET,
                    black_box(&case.mpolys),
                    black_box(&case.list),
                    &mut scratch,
                );
                black_box(out.rgba[0]);
            })
        });
        let all = scratch.stats;
        let runs = all.micropolygons / once.micropolygons.max(1);
        if runs == 0 {
            continue; // filtered out on the command line
        }
        println!(
            "{}: {} micropolygons, {} sample tests ({:.1}% hits) per bucket; over {} runs \
             the sampling loops ran at {:.1} M tests/s, the resolve took {:.0}% of the hider",
            case.name,
            case.list.len(),
            tests,
            100.0 * once.hits as f64 / tests.max(1) as f64,
            runs,
            (all.hits + all.misses) as f64 / (all.sample_ns.max(1) as f64 * 1e-9) / 1e6,
            100.0 * all.resolve_ns as f64 / (all.sample_ns + all.resolve_ns).max(1) as f64,
        );
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    targets = inner, samples
}
criterion_main!(benches);
