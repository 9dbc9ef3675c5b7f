//! Prepared textures (issue #32): files we make read back as their sources, level by level;
//! files in the other layouts the peers write (strips, 16-bit, 1 to 4 channels, several
//! directories) read as written; bad files are refused with one line naming them; a lookup in
//! one corner of a large file reads only the chunks it touches.

use std::io::Cursor;
use std::path::Path;

use reyes_texture::make::{MakeOptions, make_texture, read_level};
use reyes_texture::prepared::{MapKind, PreparedFile};
use reyes_texture::write::Depth;
use reyes_texture::{ColorSpace, TextureSystem, Wrap};

fn ok<T, E: std::fmt::Display>(r: Result<T, E>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

/// A deterministic pseudo-random value in [0, 1) for texel `k`, channel `c`.
fn value(k: usize, c: usize) -> f32 {
    let h = (k as u64 * 4 + c as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
    h as f32 / (1u64 << 24) as f32
}

/// The k-times 2 x 2 box reduction of a `n x n` RGBA image (n a power of two), computed
/// directly: each texel of level k is the mean of its 2^k x 2^k block.
fn box_reduction(texels: &[f32], n: usize, k: u32) -> Vec<f32> {
    let b = 1usize << k;
    let m = n / b;
    let mut out = vec![0.0f64; 4 * m * m];
    for y in 0..n {
        for x in 0..n {
            for c in 0..4 {
                out[4 * ((y / b) * m + x / b) + c] += f64::from(texels[4 * (y * n + x) + c]);
            }
        }
    }
    out.iter().map(|v| (v / (b * b) as f64) as f32).collect()
}

#[test]
fn make_texture_round_trips_float_exactly_and_levels_are_box_reductions() {
    let dir = ok(tempfile::tempdir());
    let (src, out) = (dir.path().join("src.exr"), dir.path().join("out.tex"));
    let n = 64usize;
    let texel = |x: usize, y: usize| {
        let k = y * n + x;
        (value(k, 0) * 4.0 - 1.0, value(k, 1), value(k, 2), value(k, 3))
    };
    ok(exr::prelude::write_rgba_file(&src, n, n, texel));
    let opts = MakeOptions { depth: Some(Depth::Float), ..MakeOptions::default() };
    ok(make_texture(&src, &out, &opts));
    let p = ok(PreparedFile::open(&out));
    assert_eq!(p.header.kind, MapKind::Plain);
    assert_eq!(p.header.format, "Plain Texture");
    assert_eq!(p.header.wrap, Some([Wrap::Periodic, Wrap::Periodic]));
    assert_eq!(p.header.channels, 4);
    assert_eq!(p.header.levels.len(), 7, "64 down to 1");
    let source: Vec<f32> = (0..n * n)
        .flat_map(|k| {
            let (r, g, b, a) = texel(k % n, k / n);
            [r, g, b, a]
        })
        .collect();
    let level0 = ok(read_level(&p, 0));
    assert_eq!(level0.texels, source, "level 0 is the source, bit for bit");
    for k in 1..7u32 {
        let got = ok(read_level(&p, k as usize));
        let want = box_reduction(&source, n, k);
        // The file's level is k successive 2 x 2 averages in f32; the reference is one f64
        // mean of 4^k values. Each f32 average rounds once (relative 2^-24) on values of
        // magnitude at most 3, so k levels differ by at most k * 3 * 2^-24 plus the final
        // rounding, under 1e-6 for k <= 6.
        let tol = (k as f32 + 1.0) * 3.0 * f32::EPSILON;
        for (a, b) in got.texels.iter().zip(&want) {
            assert!((a - b).abs() <= tol, "level {k}: {a} vs {b}");
        }
    }
}

#[test]
fn eight_bit_round_trip_is_within_quantisation_and_reads_through_the_system() {
    let dir = ok(tempfile::tempdir());
    let (src, out) = (dir.path().join("src.png"), dir.path().join("out.tx"));
    let n = 32u32;
    let img = image::RgbImage::from_fn(n, n, |x, y| {
        let k = (y * n + x) as usize;
        image::Rgb([0, 1, 2].map(|c| (value(k, c) * 256.0) as u8))
    });
    ok(img.save(&src));
    ok(make_texture(&src, &out, &MakeOptions::default()));
    let p = ok(PreparedFile::open(&out));
    assert_eq!(
        (p.header.channels, p.header.sample),
        (3, reyes_texture::prepared::SampleType::Uint(8))
    );
    let l0 = ok(read_level(&p, 0));
    for (k, px) in img.pixels().enumerate() {
        for c in 0..3 {
            // 8-bit in, 8-bit out: the stored code is the source's exactly.
            assert_eq!(l0.texels[4 * k + c], f32::from(px.0[c]) / 255.0);
        }
    }
    // Level 1 is the 2x2 mean quantised to 8 bits: within half a code of the exact mean.
    let l1 = ok(read_level(&p, 1));
    for y in 0..16usize {
        for x in 0..16usize {
            for c in 0..3 {
                let at = |dx: usize, dy: usize| {
                    f32::from(img.get_pixel((2 * x + dx) as u32, (2 * y + dy) as u32).0[c]) / 255.0
                };
                let mean = (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) / 4.0;
                let got = l1.texels[4 * (y * 16 + x) + c];
                assert!((got - mean).abs() <= 0.5 / 255.0 + 1e-6, "{got} vs {mean}");
            }
        }
    }
    // Through the system: a texel centre with a zero footprint reads the texel.
    let mut sys = ok(TextureSystem::new(1 << 20));
    let id = ok(sys.load(&out, ColorSpace::Linear));
    assert_eq!(sys.texture(id).levels.len(), 6);
    let px = img.get_pixel(5, 9).0;
    let v = sys.lookup(id, [5.5 / 32.0, 9.5 / 32.0], [0.0, 0.0], Wrap::Periodic);
    for c in 0..3 {
        assert!((v[c] - f32::from(px[c]) / 255.0).abs() < 1e-6, "{v:?} vs {px:?}");
    }
}

/// A strip TIFF of `levels` directories (each half the last), `channels` 16-bit samples,
/// written with the tiff crate's own strip encoder, as another tool would.
fn strip_tiff(path: &Path, n: u32, channels: u32) -> Vec<Vec<u16>> {
    use tiff::encoder::{TiffEncoder, colortype};
    let mut bytes = Cursor::new(Vec::new());
    let mut enc = ok(TiffEncoder::new(&mut bytes));
    let mut all = Vec::new();
    let mut side = n;
    let mut seed = 0usize;
    while side >= 1 {
        let data: Vec<u16> = (0..(side * side * channels) as usize)
            .map(|k| (value(k + seed, 0) * 65535.0) as u16)
            .collect();
        seed += 7919;
        match channels {
            1 => ok(enc.write_image::<colortype::Gray16>(side, side, &data)),
            3 => ok(enc.write_image::<colortype::RGB16>(side, side, &data)),
            _ => ok(enc.write_image::<colortype::RGBA16>(side, side, &data)),
        }
        all.push(data);
        if side == 1 {
            break;
        }
        side /= 2;
    }
    ok(std::fs::write(path, bytes.into_inner()));
    all
}

#[test]
fn strip_files_of_one_three_and_four_channels_read_as_written_at_every_level() {
    let dir = ok(tempfile::tempdir());
    for channels in [1u32, 3, 4] {
        let file = dir.path().join(format!("strips{channels}.tif"));
        let written = strip_tiff(&file, 16, channels);
        let p = ok(PreparedFile::open(&file));
        assert_eq!(p.header.levels.len(), 5);
        assert!(!p.header.levels[0].tiled);
        for (k, data) in written.iter().enumerate() {
            let level = ok(read_level(&p, k));
            let c = channels as usize;
            for t in 0..data.len() / c {
                let want: Vec<f32> = (0..c).map(|i| f32::from(data[t * c + i]) / 65535.0).collect();
                let got = &level.texels[4 * t..4 * t + 4];
                match c {
                    1 => assert_eq!(got, [want[0], want[0], want[0], 1.0]),
                    3 => assert_eq!(got, [want[0], want[1], want[2], 1.0]),
                    _ => assert_eq!(got, want.as_slice()),
                }
            }
        }
    }
}

#[test]
fn bad_files_are_refused_naming_the_file() {
    let dir = ok(tempfile::tempdir());
    let (src, good) = (dir.path().join("src.png"), dir.path().join("good.tex"));
    ok(image::GrayImage::from_fn(64, 64, |x, _| image::Luma([x as u8])).save(&src));
    ok(make_texture(&src, &good, &MakeOptions::default()));
    let bytes = ok(std::fs::read(&good));
    let mut sys = ok(TextureSystem::new(1 << 20));
    let missing = dir.path().join("missing.tex");
    let e = sys.load(&missing, ColorSpace::Linear).err().unwrap_or_else(|| panic!("loaded"));
    assert_eq!(e.exit_code(), 1);
    // Truncated: the tile data lies before the directories, so cutting the file's end loses
    // the last directory; cutting the middle leaves chunks ending past the file.
    for cut in [bytes.len() / 2, bytes.len() - 10, 12] {
        let f = dir.path().join(format!("cut{cut}.tex"));
        ok(std::fs::write(&f, &bytes[..cut]));
        let e =
            sys.load(&f, ColorSpace::Linear).err().unwrap_or_else(|| panic!("cut {cut} loaded"));
        let text = e.to_string();
        assert_eq!(e.exit_code(), 2, "{text}");
        assert!(text.starts_with(&format!("{}: texture: ", f.display())), "{text}");
        assert!(!text.contains('\n'), "{text}");
    }
    let junk = dir.path().join("junk.tex");
    ok(std::fs::write(&junk, b"II*\0garbage follows here"));
    let e = sys.load(&junk, ColorSpace::Linear).err().unwrap_or_else(|| panic!("loaded"));
    assert_eq!(e.exit_code(), 2, "{e}");
}

#[test]
fn a_lookup_in_one_corner_of_a_large_file_reads_only_its_tiles() {
    let dir = ok(tempfile::tempdir());
    let (src, out) = (dir.path().join("big.png"), dir.path().join("big.tex"));
    let n = 1024u32;
    ok(image::GrayImage::from_fn(n, n, |x, y| image::Luma([(x ^ y) as u8])).save(&src));
    ok(make_texture(&src, &out, &MakeOptions::default()));
    let file_len = ok(std::fs::metadata(&out)).len();
    let mut sys = ok(TextureSystem::new(64 << 20));
    let id = ok(sys.load(&out, ColorSpace::Linear));
    let header = sys.prepared_bytes_read();
    for k in 0..100 {
        let s = (k % 10) as f32 / 1000.0 + 0.001;
        let _ = sys.lookup(id, [s, s], [0.0, 0.0], Wrap::Clamp);
    }
    let read = sys.prepared_bytes_read() - header;
    // Every lookup lies within texels 0..12 of level 0: one 32 x 32 tile of 1-byte samples
    // (1024 bytes), read through an 8 kB buffer. The whole file is ~1.4 MB.
    assert!(read <= 8192 + 1024, "read {read} bytes of {file_len}");
    assert!(sys.stats().cache.peak <= 4 * 32 * 32 * 4, "{:?}", sys.stats().cache);
}

/// Files another RenderMan tool made: OpenImageIO's `maketx` (8-bit, 64 x 64 deflate tiles;
/// and `--prman -d float`, 32 x 32 tiles), from `tests/data/small.png` (12 x 10), checked in
/// (`maketx small.png -o small_maketx.tx --wrap clamp`; `maketx small.png -o
/// small_prman_float.tx --prman -d float --wrap periodic`). Level 0 reads as the source.
#[test]
fn files_made_by_maketx_read_as_their_source() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let src = ok(image::open(data.join("small.png"))).to_rgb8();
    for (name, wrap, float) in
        [("small_maketx.tx", Wrap::Clamp, false), ("small_prman_float.tx", Wrap::Periodic, true)]
    {
        let p = ok(PreparedFile::open(&data.join(name)));
        assert_eq!(p.header.kind, MapKind::Plain, "{name}");
        assert_eq!(p.header.wrap, Some([wrap, wrap]), "{name}");
        let sizes: Vec<(u32, u32)> = p.header.levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(12, 10), (6, 5), (3, 2), (1, 1)], "{name}");
        let l0 = ok(read_level(&p, 0));
        for (k, px) in src.pixels().enumerate() {
            for c in 0..3 {
                let want = f32::from(px.0[c]) / 255.0;
                // 8-bit: the code itself. Float: maketx's v / 255 in f32, which may round
                // differently from ours by one unit in the last place (at most 2^-24 near 1).
                let tol = if float { f32::EPSILON } else { 0.0 };
                let got = l0.texels[4 * k + c];
                assert!((got - want).abs() <= tol, "{name} texel {k}.{c}: {got} vs {want}");
            }
        }
    }
}

/// A classic little-endian TIFF of one 4 x 2 strip of 8-bit grey with no
/// PhotometricInterpretation tag, as Pixie's `texmake` writes, plus a texture format tag.
fn tiff_without_photometric() -> Vec<u8> {
    let pixels: [u8; 8] = [0, 10, 20, 30, 200, 210, 220, 255];
    let format = b"Pixie Texture\0";
    let mut f = Vec::new();
    f.extend_from_slice(b"II*\0");
    f.extend_from_slice(&8u32.to_le_bytes());
    let n: u16 = 9;
    let ifd_len = 2 + 12 * n as usize + 4;
    let data_at = 8 + ifd_len as u32;
    let format_at = data_at + pixels.len() as u32;
    let entry = |f: &mut Vec<u8>, tag: u16, ty: u16, count: u32, value: u32| {
        f.extend_from_slice(&tag.to_le_bytes());
        f.extend_from_slice(&ty.to_le_bytes());
        f.extend_from_slice(&count.to_le_bytes());
        f.extend_from_slice(&value.to_le_bytes());
    };
    f.extend_from_slice(&n.to_le_bytes());
    entry(&mut f, 256, 3, 1, 4);
    entry(&mut f, 257, 3, 1, 2);
    entry(&mut f, 258, 3, 1, 8);
    entry(&mut f, 259, 3, 1, 1);
    entry(&mut f, 273, 4, 1, data_at);
    entry(&mut f, 277, 3, 1, 1);
    entry(&mut f, 278, 3, 1, 2);
    entry(&mut f, 279, 4, 1, pixels.len() as u32);
    entry(&mut f, 33302, 2, format.len() as u32, format_at);
    f.extend_from_slice(&0u32.to_le_bytes());
    f.extend_from_slice(&pixels);
    f.extend_from_slice(format);
    f
}

#[test]
fn a_file_without_photometric_interpretation_reads() {
    let dir = ok(tempfile::tempdir());
    let file = dir.path().join("pixie.tex");
    ok(std::fs::write(&file, tiff_without_photometric()));
    let p = ok(PreparedFile::open(&file));
    assert_eq!(p.header.format, "Pixie Texture");
    let l0 = ok(read_level(&p, 0));
    let grey: Vec<f32> = l0.texels.chunks(4).map(|c| c[0]).collect();
    let want: Vec<f32> =
        [0u8, 10, 20, 30, 200, 210, 220, 255].iter().map(|&v| f32::from(v) / 255.0).collect();
    assert_eq!(grey, want);
}
