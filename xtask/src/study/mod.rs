//! `cargo xtask study [--quick]`: regenerate every figure of docs/sampling.md into
//! docs/study/ from scratch, and `docs/study/results.md` with the measured numbers.
//!
//! The computations live in [`patterns`] and [`edges`] (tested there); [`figures`] draws the
//! PNGs with plotters; this file runs them at full size, times them and writes the results. `--quick` uses small sizes
//! (a smoke test of the whole pipeline, about a tenth of the time; its numbers are noisy).
//!
//! Text is drawn with a TrueType font read at run time: `$REYES_STUDY_FONT`, else DejaVu Sans
//! from the usual system places (Debian: `apt-get install fonts-dejavu-core`).

use std::error::Error;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
mod edges;
mod figures;
pub mod geometry;
mod patterns;

use edges::{EdgeCase, EdgeStudy, Measured, fit_slope};
use figures::{BANDS, error_figure, periodograms, picket_fence, time_figure, zone_plates};
use patterns::Sampler;

type Res<T = ()> = Result<T, Box<dyn Error>>;
type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

const FONT: &str = "sans-serif";

/// Colour of each sampler in every figure (Okabe-Ito palette).
fn colour(s: Sampler) -> RGBColor {
    match s {
        Sampler::Regular => RGBColor(0, 0, 0),
        Sampler::Random => RGBColor(150, 150, 150),
        Sampler::Fig5 => RGBColor(230, 159, 0),
        Sampler::Fig6 => RGBColor(0, 114, 178),
        Sampler::Fig7 => RGBColor(0, 158, 115),
        Sampler::Sobol => RGBColor(213, 94, 0),
        Sampler::SobolJoint => RGBColor(204, 121, 167),
    }
}

fn load_font() -> Res {
    let mut candidates: Vec<String> = std::env::var("REYES_STUDY_FONT").into_iter().collect();
    candidates.extend(
        [
            "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
            "/usr/share/fonts/TTF/DejaVuSans.ttf",
            "/usr/share/fonts/dejavu/DejaVuSans.ttf",
            "/usr/local/share/fonts/DejaVuSans.ttf",
            "/Library/Fonts/Arial.ttf",
            "C:\\Windows\\Fonts\\arial.ttf",
        ]
        .map(String::from),
    );
    for path in &candidates {
        if let Ok(bytes) = std::fs::read(path) {
            // plotters keeps fonts for the life of the program.
            let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
            register_font(FONT, FontStyle::Normal, bytes)
                .map_err(|_| format!("{path}: not a usable TrueType font"))?;
            return Ok(());
        }
    }
    Err("no TrueType font found: set REYES_STUDY_FONT=/path/to/font.ttf \
         (Debian: apt-get install fonts-dejavu-core)"
        .into())
}

/// Full-size or quick settings.
struct Sizes {
    /// Edges per (case, sampler, sample count).
    edges: usize,
    /// Periodogram windows per sampler.
    windows: u32,
    /// Zone plate side.
    zone: u32,
}

/// One edge case's RMSE per sampler, in the order of [`SIDES`].
type CaseResults = (EdgeCase, Vec<(Sampler, Vec<Measured>)>);

/// Adaptive sampling's settings in the study: (base n for n x n samples, `max_level`), all
/// with the joint sampler and the default threshold 0.1.
const ADAPTIVE: [(u32, u32); 3] = [(4, 2), (8, 1), (8, 2)];

/// One edge case's adaptive results, in the order of [`ADAPTIVE`]: RMSE and the mean samples
/// per pixel spent over the whole image.
type AdaptiveResults = (EdgeCase, Vec<(Measured, f64)>);

/// The hider fields of an [`ADAPTIVE`] setting.
fn adaptive_fields(max_level: u32) -> String {
    format!(", adaptive: (max_level: {max_level}, threshold: 0.1)")
}

/// Sample counts of the error curves: n x n per pixel.
const SIDES: [u32; 5] = [1, 2, 4, 8, 16];

pub fn run(root: &Path, args: &[String]) -> Res {
    let quick = args.iter().any(|a| a == "--quick");
    if let Some(a) = args.iter().find(|a| *a != "--quick") {
        return Err(format!("unknown argument {a} (usage: cargo xtask study [--quick])").into());
    }
    let sizes = if quick {
        Sizes { edges: 6, windows: 8, zone: 96 }
    } else {
        Sizes { edges: 64, windows: 64, zone: 192 }
    };
    load_font()?;
    let out = root.join("docs/study");
    std::fs::create_dir_all(&out)?;
    let start = Instant::now();
    let mut log = String::new();
    let mut step = |name: &str, t: Instant| {
        let line = format!("{name}: {:.1} s", t.elapsed().as_secs_f64());
        println!("study: {line}");
        log.push_str(&format!("| {name} | {:.1} |\n", t.elapsed().as_secs_f64()));
    };

    let t = Instant::now();
    figures::patterns(&out.join("patterns.png"))?;
    step("sample patterns (patterns.png)", t);

    let t = Instant::now();
    time_figure(&out.join("time.png"))?;
    step("time against position (time.png)", t);

    let t = Instant::now();
    let bands = periodograms(&out, sizes.windows)?;
    step("periodograms (periodograms.png, periodogram-radial.png)", t);

    let t = Instant::now();
    let picket = picket_fence(root, &out.join("picket-fence.png"))?;
    step("picket fence renders (picket-fence.png)", t);

    let t = Instant::now();
    zone_plates(&out.join("zone-plate.png"), sizes.zone)?;
    step("zone plates (zone-plate.png)", t);

    let t = Instant::now();
    let study = EdgeStudy { edges: sizes.edges, ..EdgeStudy::default() };
    let mut results = Vec::new();
    for case in EdgeCase::ALL {
        let tc = Instant::now();
        let mut rows = Vec::new();
        for sampler in Sampler::ALL {
            let mut m = Vec::new();
            for n in SIDES {
                m.push(study.measure(case, sampler, n)?);
            }
            rows.push((sampler, m));
        }
        println!("study:   {} ({:.1} s)", case.label(), tc.elapsed().as_secs_f64());
        results.push((case, rows));
    }
    let mut adaptive = Vec::new();
    for case in EdgeCase::ALL {
        let mut row = Vec::new();
        for (n, level) in ADAPTIVE {
            let extra = adaptive_fields(level);
            row.push(study.measure_adaptive(case, Sampler::SobolJoint, n, &extra)?);
        }
        adaptive.push((case, row));
    }
    error_figure(&out.join("edge-errors.png"), &study, &results, &adaptive)?;
    step("edge error curves (edge-errors.png)", t);

    let total = start.elapsed().as_secs_f64();
    let md = results_markdown(&study, &results, &adaptive, &picket, &bands, &log, total, quick);
    std::fs::write(out.join("results.md"), &md)?;
    println!("{md}");
    println!("study: wrote {} in {total:.1} s", out.display());
    Ok(())
}

fn samples_per_pixel() -> Vec<f64> {
    SIDES.iter().map(|&n| (n * n) as f64).collect()
}

fn rmse_of(m: &[Measured]) -> Vec<f64> {
    m.iter().map(|m| m.rmse).collect()
}

/// RMSE of `curve` (RMSE at [`SIDES`] squared samples per pixel) at `spp`, interpolated
/// linearly in log RMSE against log samples between the neighbouring counts.
fn rmse_at(curve: &[Measured], spp: f64) -> f64 {
    let xs = samples_per_pixel();
    let k = xs.iter().position(|&x| x >= spp).unwrap_or(xs.len() - 1).clamp(1, xs.len() - 1);
    let (x0, x1) = (xs[k - 1].ln(), xs[k].ln());
    let (y0, y1) = (curve[k - 1].rmse.ln(), curve[k].rmse.ln());
    (y0 + (y1 - y0) * (spp.ln() - x0) / (x1 - x0)).exp()
}

#[allow(clippy::too_many_arguments)]
fn results_markdown(
    study: &EdgeStudy,
    results: &[CaseResults],
    adaptive: &[AdaptiveResults],
    picket: &[(String, f64, f64)],
    bands: &[(Sampler, Vec<f64>)],
    log: &str,
    total: f64,
    quick: bool,
) -> String {
    let spp = samples_per_pixel();
    let mut md = String::from(
        "# Sampling study: measured numbers\n\nGenerated by `cargo xtask study`; do not edit. \
         See [../sampling.md](../sampling.md) for what they mean.\n\n",
    );
    if quick {
        md.push_str("**Quick run (`--quick`): small sizes, noisy numbers.**\n\n");
    }
    let _ = writeln!(
        md,
        "Edge study: {} random edges per cell of each table, {} x {} images, motion {} px over \
         the shutter, circle of confusion radius {} px; RMSE over every pixel the edge touches \
         (analytic value strictly between 0 and 1), +- one standard error with edges as the \
         independent units (`Measured::from_edges`).\n",
        study.edges, study.image, study.image, study.motion_px, study.blur_px
    );
    md.push_str("## Fitted convergence slopes (log RMSE against log samples per pixel)\n\n");
    md.push_str("| pattern |");
    for (case, _) in results {
        let _ = write!(md, " {} |", case.label());
    }
    md.push_str("\n|---|");
    for _ in results {
        md.push_str("---|");
    }
    md.push('\n');
    for (i, sampler) in Sampler::ALL.iter().enumerate() {
        let _ = write!(md, "| {} |", sampler.label());
        for (_, rows) in results {
            let _ = write!(md, " {:.2} |", fit_slope(&spp, &rmse_of(&rows[i].1)));
        }
        md.push('\n');
    }
    for (case, rows) in results {
        let _ = writeln!(md, "\n## RMSE, {}\n", case.label());
        md.push_str("| pattern |");
        for s in &spp {
            let _ = write!(md, " {s} spp |");
        }
        md.push_str("\n|---|");
        for _ in &spp {
            md.push_str("---|");
        }
        md.push('\n');
        for (sampler, m) in rows {
            let _ = write!(md, "| {} |", sampler.label());
            for m in m {
                let _ = write!(md, " {:.5} +- {:.5} |", m.rmse, m.se);
            }
            md.push('\n');
        }
    }
    for (sampler, title) in
        [(Sampler::Sobol, "Owen-Sobol"), (Sampler::SobolJoint, "The joint sampler (SobolJoint)")]
    {
        let _ = write!(
            md,
            "\n## {title} against Appendix A's jitter (FIG. 6): RMSE ratio\n\n\
             Standard error of a ratio from both standard errors (the two samplers see the same \
             edges, so this overstates it a little).\n\n"
        );
        md.push_str("| case | 16 spp | 64 spp | 256 spp |\n|---|---|---|---|\n");
        for (case, rows) in results {
            let get = |s: Sampler| &rows.iter().find(|r| r.0 == s).expect("sampler").1;
            let (sob, fig6) = (get(sampler), get(Sampler::Fig6));
            let _ = write!(md, "| {} |", case.label());
            for k in 2..5 {
                let r = sob[k].rmse / fig6[k].rmse;
                let se = r
                    * ((sob[k].se / sob[k].rmse).powi(2) + (fig6[k].se / fig6[k].rmse).powi(2))
                        .sqrt();
                let _ = write!(md, " {r:.3} +- {se:.3} |");
            }
            md.push('\n');
        }
    }
    md.push_str(
        "\n## Adaptive sampling against uniform sampling\n\n\
         The joint sampler with `n x n` base samples and `adaptive: (max_level: L, threshold: \
         0.1)`. Samples per pixel are those spent over the whole image (base samples of every \
         pixel plus the refined pixels' extra samples), divided by its pixels; the error is over \
         the edge pixels as above. `uniform at equal samples`: the uniform joint sampler's RMSE \
         at the same samples per pixel, interpolated on its curve (log-log); `of 16 x 16`: the \
         share of uniform 16 x 16's samples spent, and the RMSE against uniform 16 x 16's.\n\n\
         | case | setting | samples per pixel | RMSE | uniform at equal samples | ratio | of 16 x 16: samples | of 16 x 16: RMSE |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for ((case, row), (_, rows)) in adaptive.iter().zip(results) {
        let joint = &rows.iter().find(|r| r.0 == Sampler::SobolJoint).expect("joint").1;
        for ((n, level), (m, spp)) in ADAPTIVE.iter().zip(row) {
            let uniform = rmse_at(joint, *spp);
            let _ = writeln!(
                md,
                "| {} | {n} x {n}, L = {level} | {spp:.1} | {:.5} +- {:.5} | {uniform:.5} | {:.2} | {:.0} % | {:.2} |",
                case.label(),
                m.rmse,
                m.se,
                m.rmse / uniform,
                100.0 * spp / 256.0,
                m.rmse / joint[4].rmse,
            );
        }
    }
    md.push_str(
        "\n## Picket fence: uniform and adaptive sampling\n\n\
         `scenes/picket-fence-jittered.ron` with the joint sampler, RMSE of the red channel over \
         the image against a uniform 16 x 16 render of the same pattern with another seed (so \
         each number includes that render's own error).\n\n\
         | sampling | samples per pixel | RMSE against 16 x 16 |\n|---|---|---|\n",
    );
    for (label, spp, rmse) in picket {
        let _ = writeln!(md, "| {label} | {spp:.1} | {rmse:.5} |");
    }
    md.push_str(
        "\n## Periodogram power by frequency band\n\nMean of the averaged periodogram \
         (4 x 4 samples per pixel; 1 = white noise) over rings of frequency |k| in cycles per \
         pixel, zero frequency left out.\n\n| pattern |",
    );
    for (lo, hi) in BANDS {
        let _ = write!(md, " {lo}-{hi} |");
    }
    md.push_str("\n|---|");
    for _ in BANDS {
        md.push_str("---|");
    }
    md.push('\n');
    for (sampler, p) in bands {
        let _ = write!(md, "| {} |", sampler.label());
        for v in p {
            let _ = write!(md, " {v:.3} |");
        }
        md.push('\n');
    }
    md.push_str("\n## Wall time (2 cores)\n\n| step | seconds |\n|---|---|\n");
    md.push_str(log);
    let _ = writeln!(md, "| **total** | **{total:.1}** |");
    md
}

/// `v` with two significant digits.
fn significant(v: f64) -> String {
    let digits = (1 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}
