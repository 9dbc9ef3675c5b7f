//! Criterion benchmark of reading big meshes (issue #15): a 1000 x 1000 grid of quads (one
//! million faces, 1 002 001 points, with normals and uvs) written once as OBJ and as binary
//! little-endian PLY into a temporary folder, then read again and again with
//! `reyes_meshio::read`. Throughput is in faces, so "elem/s" is faces read per second.
//!
//! Run with `cargo bench -p reyes-meshio --bench read`; peak memory is measured separately
//! with `/usr/bin/time -v` on `examples/read.rs` (see its doc).
//!
//! Measured 2026-12-03 on the project's 2-core machine (other builds running beside it):
//! OBJ (124 MB) 1.45 s (690k faces/s), peak RSS 309 MB; binary PLY (49 MB) 0.225 s
//! (4.45M faces/s), peak RSS 101 MB.

use std::hint::black_box;
use std::io::BufWriter;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

#[path = "grid.rs"]
mod grid;

fn read(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mesh = grid::grid(1000);
    let obj = dir.path().join("grid.obj");
    let ply = dir.path().join("grid.ply");
    let mut w = BufWriter::new(std::fs::File::create(&obj).expect("create grid.obj"));
    reyes_meshio::write_obj(&mesh, &mut w).expect("write grid.obj");
    drop(w);
    let mut w = BufWriter::new(std::fs::File::create(&ply).expect("create grid.ply"));
    reyes_meshio::write_ply_binary(&mesh, &mut w, false).expect("write grid.ply");
    drop(w);

    let mut group = c.benchmark_group("read_1m_faces");
    group.sample_size(10).measurement_time(Duration::from_secs(20));
    group.throughput(Throughput::Elements(mesh.face_count() as u64));
    for (name, path) in [("obj", &obj), ("ply_binary", &ply)] {
        group.bench_function(name, |b| {
            b.iter(|| {
                let m = reyes_meshio::read(black_box(path)).expect("read back");
                assert_eq!(m.face_count(), 1_000_000);
                m
            })
        });
    }
    group.finish();
}

criterion_group!(benches, read);
criterion_main!(benches);
