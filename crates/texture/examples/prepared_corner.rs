//! Benchmark of issue #32: a prepared 8192 x 8192 RGB 8-bit texture (made here, tiled and
//! MIP-mapped, ~256 MB) read only in one corner. Prints what the render paid: bytes read from
//! the file, the cache's peak, the tiles read, and the process's resident memory before and
//! after the lookups. Counts, not timings: they do not depend on the machine.
//!
//! `cargo run --release -p reyes-texture --example prepared_corner`

use reyes_texture::load::Image;
use reyes_texture::mip::Pyramid;
use reyes_texture::prepared::MapKind;
use reyes_texture::write::{Depth, Spec, write};
use reyes_texture::{ColorSpace, TextureSystem, Wrap};

fn rss_kb() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let line = status.lines().find(|l| l.starts_with("VmRSS:")).unwrap_or("VmRSS: 0 kB");
    line.split_whitespace().nth(1).and_then(|v| v.parse().ok()).unwrap_or(0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n = 8192u32;
    let dir = tempfile::tempdir()?;
    let file = dir.path().join("big.tex");
    {
        let texels: Vec<f32> = (0..n * n)
            .flat_map(|k| {
                let (x, y) = (k % n, k / n);
                [
                    ((x ^ y) & 255) as f32 / 255.0,
                    (x & 255) as f32 / 255.0,
                    (y & 255) as f32 / 255.0,
                    1.0,
                ]
            })
            .collect();
        let pyramid = Pyramid::build(Image { width: n, height: n, texels });
        let spec = Spec {
            kind: MapKind::Plain,
            wrap: [Wrap::Periodic; 2],
            depth: Depth::Byte,
            channels: 3,
            matrices: None,
            fov_cot: None,
        };
        write(&file, &pyramid.levels, &spec)?;
    }
    let size = std::fs::metadata(&file)?.len();
    let before = rss_kb();
    let mut sys = TextureSystem::new(64 << 20)?;
    let id = sys.load(&file, ColorSpace::Linear)?;
    let header = sys.prepared_bytes_read();
    // 100,000 lookups in the corner s, t in [0, 1/64] (128 x 128 texels of level 0), with
    // footprints from a texel to 16 texels.
    let mut sum = 0.0f32;
    for k in 0..100_000u32 {
        let s = (k % 317) as f32 / 317.0 / 64.0;
        let t = (k % 211) as f32 / 211.0 / 64.0;
        let w = (1 + k % 16) as f32 / n as f32;
        sum += sys.lookup(id, [s, t], [w, w], Wrap::Periodic)[0];
    }
    let read = sys.prepared_bytes_read();
    let stats = sys.stats();
    println!("file: {size} bytes ({} levels)", sys.texture(id).levels.len());
    println!("header read at load: {header} bytes");
    println!("bytes read in all: {read} ({:.3}% of the file)", 100.0 * read as f64 / size as f64);
    println!(
        "tile requests {}, tiles read {}, cache peak {} bytes",
        stats.cache.requests, stats.cache.misses, stats.cache.peak
    );
    println!("resident memory: {before} kB before loading, {} kB after the lookups", rss_kb());
    println!("(checksum {sum})");
    Ok(())
}
