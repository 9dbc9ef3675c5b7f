//! Texture lookups against analytic values: texel centres, footprints covering whole
//! periods of a checkerboard, wrap modes, formats and colour spaces, and the cache's bound.

use std::path::Path;

use reyes_texture::{ColorSpace, TILE_BYTES, TextureSystem, Wrap, load::srgb_to_linear};

/// A `size` x `size` greyscale checkerboard of `check`-texel squares, `lo` and `hi` bytes.
fn checker_png(path: &Path, size: u32, check: u32, lo: u8, hi: u8) {
    let img = image::GrayImage::from_fn(size, size, |x, y| {
        image::Luma([if (x / check + y / check).is_multiple_of(2) { hi } else { lo }])
    });
    img.save(path).unwrap_or_else(|e| panic!("{e}"));
}

fn system(bytes: u64) -> TextureSystem {
    TextureSystem::new(bytes).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn texel_centres_reproduce_texels_and_wide_footprints_the_mean() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let file = dir.path().join("checker.png");
    checker_png(&file, 64, 4, 51, 204);
    let mut sys = system(1 << 20);
    let id = sys.load(&file, ColorSpace::Srgb).unwrap_or_else(|e| panic!("{e}"));
    let (lo, hi) = (srgb_to_linear(51.0 / 255.0), srgb_to_linear(204.0 / 255.0));
    for (x, y) in [(0u32, 0u32), (5, 1), (63, 63), (17, 40)] {
        let st = [(x as f32 + 0.5) / 64.0, (y as f32 + 0.5) / 64.0];
        let want = if (x / 4 + y / 4) % 2 == 0 { hi } else { lo };
        let v = sys.lookup(id, st, [1.0 / 64.0, 1.0 / 64.0], Wrap::Periodic);
        assert!((v[0] - want).abs() < 1e-6 && v[3] == 1.0, "({x}, {y}): {v:?} vs {want}");
    }
    // A footprint of whole periods (8 texels = one period each way, and more) averages
    // the two colours exactly in every level it reads from, up to float rounding.
    let mean = 0.5 * (lo + hi);
    for w in [8.0f32, 16.0, 32.0, 64.0] {
        let v = sys.lookup(id, [0.5, 0.5], [w / 64.0, w / 64.0], Wrap::Periodic);
        assert!((v[0] - mean).abs() < 1e-5, "width {w}: {v:?} vs {mean}");
    }
    // Anisotropic: 64 texels long and one wide, along s; the probes average whole periods
    // along s, and across t the footprint stays inside one row of checks.
    let v = sys.lookup(id, [0.5, 2.5 / 64.0], [1.0, 1.0 / 64.0], Wrap::Periodic);
    assert!((v[0] - mean).abs() < 0.02 * mean, "anisotropic {v:?} vs {mean}");
}

#[test]
fn wrap_modes() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let file = dir.path().join("ramp.png");
    image::GrayImage::from_fn(4, 1, |x, _| image::Luma([[0u8, 85, 170, 255][x as usize]]))
        .save(&file)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut sys = system(1 << 20);
    let id = sys.load(&file, ColorSpace::Linear).unwrap_or_else(|e| panic!("{e}"));
    let at = |s: f32, wrap| sys.lookup(id, [s, 0.5], [0.0, 0.0], wrap)[0];
    assert!((at(1.125, Wrap::Periodic) - 0.0).abs() < 1e-6);
    assert!((at(-0.375, Wrap::Periodic) - 2.0 / 3.0).abs() < 1e-6);
    assert!((at(1.5, Wrap::Clamp) - 1.0).abs() < 1e-6);
    assert_eq!(sys.lookup(id, [1.5, 0.5], [0.0, 0.0], Wrap::Black), [0.0; 4]);
}

#[test]
fn exr_is_read_linear_and_unclamped() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let file = dir.path().join("hdr.exr");
    exr::prelude::write_rgba_file(&file, 2, 2, |x, y| {
        (4.0 + x as f32, 0.5 * y as f32, 0.25f32, 1.0f32)
    })
    .unwrap_or_else(|e| panic!("{e}"));
    let mut sys = system(1 << 20);
    let id = sys.load(&file, ColorSpace::Linear).unwrap_or_else(|e| panic!("{e}"));
    let v = sys.lookup(id, [0.75, 0.25], [0.0; 2], Wrap::Clamp);
    assert_eq!(v, [5.0, 0.0, 0.25, 1.0]);
    assert_eq!(sys.texture(id).max[0], 5.0);
}

/// The cache stays within its bound while the scene's textures are four times its size, and
/// every lookup reads what it would with an unbounded cache.
#[test]
fn cache_stays_within_its_bound_on_four_times_its_size() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let mut files = Vec::new();
    for k in 0..4u32 {
        let file = dir.path().join(format!("t{k}.png"));
        checker_png(&file, 256, 3 + k, 10 * k as u8, 250);
        files.push(file);
    }
    let load = |bytes| {
        let mut sys = system(bytes);
        let ids: Vec<_> = files
            .iter()
            .map(|f| sys.load(f, ColorSpace::Srgb).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        (sys, ids)
    };
    let (free, _) = load(u64::MAX);
    let total = free.stats().pyramid_bytes;
    let bound = total / 4;
    assert!(bound >= 8 * TILE_BYTES, "a real cache: {bound} bytes");
    let (tight, ids) = load(bound);
    let (free, _) = load(u64::MAX);
    std::thread::scope(|scope| {
        for thread in 0..2u32 {
            let (tight, free, ids) = (&tight, &free, &ids);
            scope.spawn(move || {
                for k in 0..40_000u32 {
                    let id = ids[((k + thread) % 4) as usize];
                    let s = (k as f32 * 0.618_034).fract();
                    let t = (k as f32 * 0.414_214 + thread as f32 * 0.5).fract();
                    let w = [0.0, 1.0 / 256.0, 0.02, 0.2][(k % 4) as usize];
                    let a = tight.lookup(id, [s, t], [w, 0.5 * w], Wrap::Periodic);
                    let b = free.lookup(id, [s, t], [w, 0.5 * w], Wrap::Periodic);
                    assert_eq!(a, b, "lookup {k}");
                    assert!(tight.stats().cache.resident <= bound);
                }
            });
        }
    });
    let s = tight.stats().cache;
    assert!(s.peak <= bound && s.peak + TILE_BYTES > bound, "{s:?} bound {bound}");
    assert!(s.evictions > 0, "{s:?}");
    assert!(!tight.read_failed());
}

/// A truncated OpenEXR file and one of a size beyond the limit are bad input naming the
/// file, not a crash or an allocation of the size it claims.
#[test]
fn broken_and_huge_exr_files_are_refused() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let good = dir.path().join("good.exr");
    exr::prelude::write_rgba_file(&good, 4, 4, |_, _| (1.0f32, 1.0f32, 1.0f32, 1.0f32))
        .unwrap_or_else(|e| panic!("{e}"));
    let bytes = std::fs::read(&good).unwrap_or_else(|e| panic!("{e}"));
    let cut = dir.path().join("cut.exr");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap_or_else(|e| panic!("{e}"));
    let mut sys = system(1 << 20);
    let e = sys.load(&cut, ColorSpace::Linear).err().unwrap_or_else(|| panic!("loaded"));
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(e.to_string().starts_with(&format!("{}: texture: ", cut.display())), "{e}");
    let huge = dir.path().join("huge.exr");
    let layer = exr::prelude::Layer::new(
        (70_000, 1),
        exr::prelude::LayerAttributes::default(),
        exr::prelude::Encoding::FAST_LOSSLESS,
        exr::prelude::SpecificChannels::rgba(|_| (0.5f32, 0.5f32, 0.5f32, 1.0f32)),
    );
    exr::prelude::WritableImage::write(&exr::prelude::Image::from_layer(layer))
        .to_file(&huge)
        .unwrap_or_else(|e| panic!("{e}"));
    let e = sys.load(&huge, ColorSpace::Linear).err().unwrap_or_else(|| panic!("loaded"));
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(e.to_string().contains("over the limit"), "{e}");
}
