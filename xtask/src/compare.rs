//! `cargo xtask compare A.exr B.exr`: how closely two renders agree, as the peer comparison
//! of `../shared/peers/README.md` measures it: PSNR over the whole image (values in 0..1,
//! peak 1) of each of R, G, B and alpha, of RGB together, and each image's channel means.
//! Also the RMS and the largest absolute difference of each channel.
//! With `--diff OUT.png`, also how many pixels differ by more than 0.01 in some channel,
//! and a picture of where: `|a - b|` times 10 per channel, alpha 1, to look at.

use std::path::Path;

use reyes_film::Film;

/// PSNR in dB of channel `c` of `b` against `a` (peak 1), over every pixel.
pub fn psnr(a: &Film, b: &Film, channels: &[usize]) -> f64 {
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

pub fn run(args: &[String]) -> Result<(), String> {
    let (a, b, diff) = match args {
        [a, b] => (a, b, None),
        [a, b, flag, out] if flag == "--diff" => (a, b, Some(out)),
        _ => return Err("usage: cargo xtask compare A.exr B.exr [--diff OUT.png]".into()),
    };
    let read = |p: &str| reyes_film::read_exr(Path::new(p)).map_err(|e| e.to_string());
    let (fa, fb) = (read(a)?, read(b)?);
    if (fa.width(), fa.height()) != (fb.width(), fb.height()) {
        return Err(format!(
            "sizes differ: {}x{} and {}x{}",
            fa.width(),
            fa.height(),
            fb.width(),
            fb.height()
        ));
    }
    println!(
        "PSNR dB: R {:.1}, G {:.1}, B {:.1}, RGB {:.1}, alpha {:.1}",
        psnr(&fa, &fb, &[0]),
        psnr(&fa, &fb, &[1]),
        psnr(&fa, &fb, &[2]),
        psnr(&fa, &fb, &[0, 1, 2]),
        psnr(&fa, &fb, &[3])
    );
    let (rms, max) = rms_max(&fa, &fb);
    println!(
        "RMS: R {:.5}, G {:.5}, B {:.5}, A {:.5}; max |a - b|: R {:.4}, G {:.4}, B {:.4}, A {:.4}",
        rms[0], rms[1], rms[2], rms[3], max[0], max[1], max[2], max[3]
    );
    for (name, f) in [(a, &fa), (b, &fb)] {
        let m = means(f);
        println!("means {name}: R {:.4} G {:.4} B {:.4} A {:.4}", m[0], m[1], m[2], m[3]);
    }
    if let Some(out) = diff {
        let d: Vec<[f32; 4]> = fa
            .rgba()
            .iter()
            .zip(fb.rgba())
            .map(|(p, q)| [0, 1, 2, 3].map(|c| (p[c] - q[c]).abs()))
            .collect();
        let changed = d.iter().filter(|p| p.iter().any(|&v| v > 0.01)).count();
        println!("pixels differing by more than 0.01: {changed} of {}", d.len());
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
    Ok(())
}
