//! `cargo xtask compare A B`: how closely two renders agree, as the peer comparison of
//! `crates/rib/tests/data/peers/README.md` measures it: PSNR over the whole image (values in 0..1, peak 1)
//! of each of R, G, B and alpha, of RGB together, and each image's channel means. Also the
//! RMS and the largest absolute difference of each channel. With `--diff OUT.png`, also how
//! many pixels differ by more than 0.01 in some channel, and a picture of where: `|a - b|`
//! times 10 per channel, alpha 1, to look at.
//!
//! Inputs are both OpenEXR (linear, premultiplied RGBA as `reyes_film::read_exr` reads it) or
//! both PNG (the values as stored, scaled to 0..1: straight colour through the scene's view
//! transform, which is why a PNG is not compared with an EXR), told apart by their first
//! bytes. Two images whose pixels are all equal (R, G, B and alpha; an EXR's Z is not read)
//! are reported as identical, not as a PSNR; a channel equal everywhere shows `identical` in
//! place of its PSNR.

use std::path::Path;

use reyes_film::Film;

/// The two formats compare reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Exr,
    Png,
}

impl Format {
    fn name(self) -> &'static str {
        match self {
            Format::Exr => "OpenEXR",
            Format::Png => "PNG",
        }
    }
}

/// The image at `path` and its format, told by its first bytes (OpenEXR's magic number, the
/// PNG signature).
fn read(path: &Path) -> Result<(Format, Film), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        let film = reyes_film::read_exr(path).map_err(|e| e.to_string())?;
        return Ok((Format::Exr, film));
    }
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        let image = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .map_err(|e| format!("{}: {e}", path.display()))?
            .to_rgba32f();
        let (width, height) = image.dimensions();
        let rgba: Vec<[f32; 4]> = image.pixels().map(|p| p.0).collect();
        let z = vec![f32::INFINITY; rgba.len()];
        let film = Film::from_pixels(width, height, rgba, z)
            .ok_or_else(|| format!("{}: bad PNG size", path.display()))?;
        return Ok((Format::Png, film));
    }
    Err(format!("{}: neither OpenEXR nor PNG", path.display()))
}

/// Whether two values are the same: equal, or the same bits (two NaNs of one pattern).
fn same(x: f32, y: f32) -> bool {
    x == y || x.to_bits() == y.to_bits()
}

/// Whether channels `channels` of `a` and `b` are the same in every pixel.
fn same_channels(a: &Film, b: &Film, channels: &[usize]) -> bool {
    a.rgba().iter().zip(b.rgba()).all(|(p, q)| channels.iter().all(|&c| same(p[c], q[c])))
}

/// PSNR in dB of channels `channels` of `b` against `a` (peak 1), over every pixel.
fn psnr(a: &Film, b: &Film, channels: &[usize]) -> f64 {
    let mut se = 0.0f64;
    let mut n = 0usize;
    for (p, q) in a.rgba().iter().zip(b.rgba()) {
        for &c in channels {
            se += f64::from(p[c] - q[c]).powi(2);
            n += 1;
        }
    }
    10.0 * (n as f64 / se.max(1e-30)).log10()
}

/// The PSNR of `channels` to one decimal, or `identical` where they are equal everywhere.
fn db(a: &Film, b: &Film, channels: &[usize]) -> String {
    if same_channels(a, b, channels) {
        "identical".into()
    } else {
        format!("{:.1}", psnr(a, b, channels))
    }
}

/// Per channel (R, G, B, alpha): the RMS of `b - a` over every pixel, and the largest `|b - a|`.
fn rms_max(a: &Film, b: &Film) -> ([f64; 4], [f64; 4]) {
    let (mut se, mut max) = ([0.0f64; 4], [0.0f64; 4]);
    for (p, q) in a.rgba().iter().zip(b.rgba()) {
        for c in 0..4 {
            let d = f64::from(p[c] - q[c]);
            se[c] += d * d;
            max[c] = max[c].max(d.abs());
        }
    }
    let n = a.rgba().len().max(1) as f64;
    (se.map(|v| (v / n).sqrt()), max)
}

fn means(f: &Film) -> [f64; 4] {
    let mut m = [0.0f64; 4];
    for p in f.rgba() {
        for c in 0..4 {
            m[c] += f64::from(p[c]);
        }
    }
    m.map(|v| v / f.rgba().len().max(1) as f64)
}

/// The comparison of the images at `a` and `b` as printed, one line each; with `diff`, the
/// difference picture written there.
pub fn report(a: &str, b: &str, diff: Option<&str>) -> Result<Vec<String>, String> {
    let ((format_a, fa), (format_b, fb)) = (read(Path::new(a))?, read(Path::new(b))?);
    if format_a != format_b {
        return Err(format!(
            "{a} is {} and {b} is {}: compare two OpenEXR files or two PNG files (a PNG holds \
             display values through the view transform, an OpenEXR linear light)",
            format_a.name(),
            format_b.name()
        ));
    }
    if (fa.width(), fa.height()) != (fb.width(), fb.height()) {
        return Err(format!(
            "sizes differ: {}x{} and {}x{}",
            fa.width(),
            fa.height(),
            fb.width(),
            fb.height()
        ));
    }
    let mut lines = Vec::new();
    if same_channels(&fa, &fb, &[0, 1, 2, 3]) {
        lines.push(format!(
            "identical: R, G, B and alpha equal in all {} pixels ({}x{})",
            fa.rgba().len(),
            fa.width(),
            fa.height()
        ));
    } else {
        lines.push(format!(
            "PSNR dB: R {}, G {}, B {}, RGB {}, alpha {}",
            db(&fa, &fb, &[0]),
            db(&fa, &fb, &[1]),
            db(&fa, &fb, &[2]),
            db(&fa, &fb, &[0, 1, 2]),
            db(&fa, &fb, &[3])
        ));
        let (rms, max) = rms_max(&fa, &fb);
        lines.push(format!(
            "RMS: R {:.5}, G {:.5}, B {:.5}, A {:.5}; max |a - b|: R {:.4}, G {:.4}, B {:.4}, A {:.4}",
            rms[0], rms[1], rms[2], rms[3], max[0], max[1], max[2], max[3]
        ));
    }
    for (name, f) in [(a, &fa), (b, &fb)] {
        let m = means(f);
        lines
            .push(format!("means {name}: R {:.4} G {:.4} B {:.4} A {:.4}", m[0], m[1], m[2], m[3]));
    }
    if let Some(out) = diff {
        let d: Vec<[f32; 4]> = fa
            .rgba()
            .iter()
            .zip(fb.rgba())
            .map(|(p, q)| [0, 1, 2, 3].map(|c| (p[c] - q[c]).abs()))
            .collect();
        let changed = d.iter().filter(|p| p.iter().any(|&v| v > 0.01)).count();
        lines.push(format!("pixels differing by more than 0.01: {changed} of {}", d.len()));
        let pixels: Vec<[f32; 4]> = d
            .iter()
            .map(|p| {
                [
                    (10.0 * p[0].max(p[3])).min(1.0),
                    (10.0 * p[1].max(p[3])).min(1.0),
                    (10.0 * p[2].max(p[3])).min(1.0),
                    1.0,
                ]
            })
            .collect();
        let z = vec![0.0; pixels.len()];
        let film = Film::from_pixels(fa.width(), fa.height(), pixels, z)
            .ok_or_else(|| "difference image has the wrong size".to_string())?;
        reyes_film::write(Path::new(out), &film).map_err(|e| e.to_string())?;
    }
    Ok(lines)
}

pub fn run(args: &[String]) -> Result<(), String> {
    let (a, b, diff) = match args {
        [a, b] => (a, b, None),
        [a, b, flag, out] if flag == "--diff" => (a, b, Some(out.as_str())),
        _ => {
            return Err("usage: cargo xtask compare A B [--diff OUT.png] (A and B both OpenEXR \
                        or both PNG)"
                .into());
        }
    };
    for line in report(a, b, diff)? {
        println!("{line}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w x h` film whose pixel `i` is `pixel(i)`.
    fn film(w: u32, h: u32, pixel: impl Fn(usize) -> [f32; 4]) -> Film {
        let n = (w * h) as usize;
        Film::from_pixels(w, h, (0..n).map(pixel).collect(), vec![f32::INFINITY; n])
            .unwrap_or_else(|| panic!("size"))
    }

    /// A gradient with partial alpha, so that PNG's straight colour and 8-bit codes matter.
    fn gradient(i: usize) -> [f32; 4] {
        let x = i as f32 / 48.0;
        [0.5 * x, 0.25, 1.0 - x, 0.5 + 0.5 * x]
    }

    /// Writes `film` as `name` in `dir` (format by extension, as the renderer writes it).
    fn written(dir: &Path, name: &str, film: &Film) -> String {
        let path = dir.join(name);
        reyes_film::write(&path, film).unwrap_or_else(|e| panic!("{e}"));
        path.to_string_lossy().into_owned()
    }

    fn tmp() -> tempfile::TempDir {
        tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"))
    }

    /// Two copies of one PNG (the case that failed with an OpenEXR error) and of one EXR are
    /// identical, said in words, with no PSNR; the difference picture is all black.
    #[test]
    fn identical_images_are_reported_identical() {
        let dir = tmp();
        let f = film(8, 6, gradient);
        for ext in ["png", "exr"] {
            let (a, b) = (
                written(dir.path(), &format!("a.{ext}"), &f),
                written(dir.path(), &format!("b.{ext}"), &f),
            );
            let diff = dir.path().join(format!("diff-{ext}.png"));
            let lines =
                report(&a, &b, Some(&diff.to_string_lossy())).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(
                lines[0], "identical: R, G, B and alpha equal in all 48 pixels (8x6)",
                "{ext}"
            );
            assert!(lines.iter().all(|l| !l.contains("PSNR") && !l.contains("RMS")), "{lines:?}");
            assert_eq!(
                lines.last().map(String::as_str),
                Some("pixels differing by more than 0.01: 0 of 48")
            );
            let picture = image::open(&diff).unwrap_or_else(|e| panic!("{e}")).to_rgba8();
            assert!(picture.pixels().all(|p| p.0 == [0, 0, 0, 255]), "{ext}");
        }
    }

    /// Images that differ get their PSNR: one pixel's red off by `d` in a 48-pixel EXR is
    /// `10 log10(48 / d^2)` dB in R, three times the samples in RGB; equal channels say
    /// `identical`. A PNG pair is read as its stored codes over 255.
    #[test]
    fn different_images_get_their_psnr() {
        let dir = tmp();
        let base = film(8, 6, gradient);
        let d = 0.125f32;
        let moved = film(8, 6, |i| {
            let mut p = gradient(i);
            if i == 5 {
                p[0] += d;
            }
            p
        });
        let (a, b) = (written(dir.path(), "a.exr", &base), written(dir.path(), "b.exr", &moved));
        let lines = report(&a, &b, None).unwrap_or_else(|e| panic!("{e}"));
        let r = 10.0 * (48.0 / f64::from(d).powi(2)).log10();
        let rgb = 10.0 * (144.0 / f64::from(d).powi(2)).log10();
        assert_eq!(
            lines[0],
            format!("PSNR dB: R {r:.1}, G identical, B identical, RGB {rgb:.1}, alpha identical")
        );
        assert!(lines[1].starts_with("RMS: "), "{lines:?}");
        // The same pictures as PNG: pixel 5's red code moves, nothing else does.
        let (a, b) = (written(dir.path(), "a.png", &base), written(dir.path(), "b.png", &moved));
        let codes = |p: &str| image::open(p).unwrap_or_else(|e| panic!("{e}")).to_rgba8();
        let (ca, cb) = (codes(&a), codes(&b));
        let changed: Vec<usize> = ca
            .pixels()
            .zip(cb.pixels())
            .enumerate()
            .filter(|(_, (p, q))| p != q)
            .map(|(i, _)| i)
            .collect();
        assert_eq!(changed, [5]);
        let step = (f64::from(ca.pixels().nth(5).unwrap_or_else(|| panic!("pixel")).0[0])
            - f64::from(cb.pixels().nth(5).unwrap_or_else(|| panic!("pixel")).0[0]))
            / 255.0;
        let lines = report(&a, &b, None).unwrap_or_else(|e| panic!("{e}"));
        let r = 10.0 * (48.0 / step.powi(2)).log10();
        assert!(
            lines[0].starts_with(&format!("PSNR dB: R {r:.1}, G identical, B identical")),
            "{lines:?}"
        );
    }

    /// A PNG is not compared with an EXR, and a file of neither format is named.
    #[test]
    fn mixed_or_unknown_inputs_are_refused() {
        let dir = tmp();
        let f = film(2, 2, gradient);
        let (png, exr) = (written(dir.path(), "a.png", &f), written(dir.path(), "a.exr", &f));
        let e = report(&png, &exr, None).err().unwrap_or_else(|| panic!("compared"));
        assert!(e.contains("is PNG") && e.contains("is OpenEXR"), "{e}");
        let text = dir.path().join("a.txt");
        std::fs::write(&text, "not an image").unwrap_or_else(|e| panic!("{e}"));
        let e = report(&png, &text.to_string_lossy(), None).err().unwrap_or_else(|| panic!("read"));
        assert!(e.ends_with("a.txt: neither OpenEXR nor PNG"), "{e}");
    }
}
