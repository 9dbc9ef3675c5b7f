//! Filtered texture lookups per second on one core (docs/performance.md): the wood map of
//! scenes/textures/ read at pseudo-random points with footprints from below a texel (level 0,
//! bilinear) to a fifth of the image (trilinear, anisotropic up to 16 probes), through a cache
//! that holds the whole pyramid, then through one of a quarter of it.
//!
//! `cargo run --release -p reyes-texture --example lookups_per_second`

use std::path::Path;
use std::time::Instant;

use reyes_texture::{ColorSpace, TextureSystem, Wrap};

fn main() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/textures/wood.png");
    for (name, bytes) in [("whole pyramid cached", 1u64 << 30), ("a quarter cached", 368_640)] {
        let mut sys = TextureSystem::new(bytes).unwrap_or_else(|e| panic!("{e}"));
        let id = sys.load(&file, ColorSpace::Srgb).unwrap_or_else(|e| panic!("{e}"));
        for (label, w, aniso) in [
            ("level 0 (footprint < 1 texel)", 0.5 / 256.0, 1.0),
            ("isotropic, 4 texels", 4.0 / 256.0, 1.0),
            ("anisotropic 8:1, 2 x 16 texels", 16.0 / 256.0, 8.0),
        ] {
            let n = 2_000_000u32;
            let start = Instant::now();
            let mut sum = 0.0f32;
            for k in 0..n {
                let s = (k as f32 * 0.618_034).fract();
                let t = (k as f32 * 0.414_214).fract();
                sum += sys.lookup(id, [s, t], [w, w / aniso], Wrap::Periodic)[0];
            }
            let secs = start.elapsed().as_secs_f64();
            println!(
                "{name}: {label}: {:.2} million lookups/s (checksum {sum:.1})",
                f64::from(n) / secs / 1e6
            );
        }
        let c = sys.stats().cache;
        println!(
            "{name}: cache peak {} kB of {} kB, {} misses of {} requests",
            c.peak / 1024,
            c.bound.min(1 << 30) / 1024,
            c.misses,
            c.requests
        );
    }
}
