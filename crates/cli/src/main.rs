//! The `reyes-render` command: arguments, wiring, exit codes. All rendering is in the library.
//!
//! Exit codes: 0 success; 2 usage or scene errors (including bad overrides and an unknown
//! output format); 1 render or I/O errors. Every error is one line on stderr, and no partial
//! output file is ever left behind (the film stage writes atomically).
//!
//! `reyes-render measure SCENE --object NAME [--samples N] [--seed N]` (the first argument
//! `measure`; a scene file of that name is `./measure`) measures the volume and centre of mass
//! of a closed object or CSG solid instead of rendering (patent FIG. 23; see
//! `reyes_measure`), with the same exit codes.

use std::ffi::OsStr;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use reyes_measure::{DEFAULT_SAMPLES, MeasureOptions, measure};
use reyes_render::{RenderOptions, render};

/// Render a RON scene with a REYES micropolygon renderer and the stochastic hider of
/// US patent 4,897,806 (Appendix A).
#[derive(Parser, Debug)]
#[command(
    name = "reyes-render",
    version,
    after_help = "Mass properties (patent FIG. 23): reyes-render measure SCENE --object NAME \
                  [--samples N] [--seed N]\n  prints the volume and centre of mass of a closed \
                  object or CSG solid; see reyes-render measure --help"
)]
struct Args {
    /// Scene file (RON); see docs/scene-format.md.
    scene: PathBuf,
    /// Output image: .exr (32-bit float RGBA plus Z) or .png (8-bit sRGB with alpha).
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: Option<u16>,
    /// Override the scene's seed.
    #[arg(long, value_name = "N")]
    seed: Option<u64>,
    /// Override the scene's pixel samples, as NxM (each 1 to 64).
    #[arg(long, value_name = "NxM", value_parser = parse_samples)]
    samples: Option<(u32, u32)>,
    /// Print statistics (hits, misses, lerps, visible points, micropolygons, time per stage).
    #[arg(long)]
    stats: bool,
    /// No progress bar.
    #[arg(short, long)]
    quiet: bool,
}

/// Volume and centre of mass of a closed object or CSG solid (patent FIG. 23), by stratified
/// pseudo-random point sampling of its bounding box at shutter open: one jittered point in each
/// of about N equal cells, each tested for being inside. Prints each estimate with one standard
/// error, estimated from neighbouring cells paired (an overestimate).
#[derive(Parser, Debug)]
#[command(name = "reyes-render measure", bin_name = "reyes-render measure", version)]
struct MeasureArgs {
    /// Scene file (RON); see docs/scene-format.md.
    scene: PathBuf,
    /// The object (`objects[].name`) or CSG solid (`solids[].name`) to measure. Cylinders,
    /// cones and paraboloids count as closed by their end caps.
    #[arg(long, value_name = "NAME")]
    object: String,
    /// About how many sample points (one per cell).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SAMPLES)]
    samples: u64,
    /// Seed of the jitter (default: the scene's seed).
    #[arg(long, value_name = "N")]
    seed: Option<u64>,
}

fn parse_samples(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected NxM with N and M from 1 to 64, got '{s}'");
    let (a, b) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let n: u32 = a.trim().parse().map_err(|_| bad())?;
    let m: u32 = b.trim().parse().map_err(|_| bad())?;
    if !(1..=64).contains(&n) || !(1..=64).contains(&m) {
        return Err(bad());
    }
    Ok((n, m))
}

fn fail(code: u8, msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("reyes-render: error: {msg}");
    ExitCode::from(code)
}

/// `reyes-render measure ...`: `args` starts at `measure`.
fn measure_main(args: impl Iterator<Item = std::ffi::OsString>) -> ExitCode {
    let args = match MeasureArgs::try_parse_from(args) {
        Ok(a) => a,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    let scene = match reyes_scene::load(&args.scene) {
        Ok(s) => s,
        Err(e) => return fail(e.exit_code(), e),
    };
    let opts =
        MeasureOptions { samples: args.samples, seed: args.seed.unwrap_or(scene.hider.seed) };
    match measure(&scene, &args.scene, &args.object, &opts) {
        Ok(m) => {
            print!("{m}");
            ExitCode::SUCCESS
        }
        Err(e) => fail(e.exit_code(), e),
    }
}

fn main() -> ExitCode {
    if std::env::args_os().nth(1).as_deref() == Some(OsStr::new("measure")) {
        return measure_main(std::env::args_os().skip(1));
    }
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };

    // Check the output before spending time on the render.
    let ext = args.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("exr" | "png")) {
        return fail(
            2,
            format_args!(
                "{}: output: unknown image format, use .exr or .png",
                args.output.display()
            ),
        );
    }
    let dir = match args.output.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !dir.is_dir() {
        return fail(1, format_args!("{}: output directory does not exist", args.output.display()));
    }

    let mut scene = match reyes_scene::load(&args.scene) {
        Ok(s) => s,
        Err(e) => return fail(e.exit_code(), e),
    };
    if let Some(seed) = args.seed {
        scene.hider.seed = seed;
    }
    if let Some(s) = args.samples {
        scene.hider.pixel_samples = s;
    }

    let progress = if !args.quiet && std::io::stderr().is_terminal() {
        let frame = reyes_render::frame_for(&scene);
        let bar = ProgressBar::new(frame.bucket_count() as u64);
        if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} buckets {elapsed}") {
            bar.set_style(style);
        }
        Some(bar)
    } else {
        None
    };
    let tick = || {
        if let Some(b) = &progress {
            b.inc(1);
        }
    };
    let opts = RenderOptions { threads: args.threads.map(usize::from), on_bucket: Some(&tick) };
    let mut rendered = match render(&scene, &opts) {
        Ok(r) => r,
        Err(e) => return fail(1, e),
    };
    if let Some(b) = &progress {
        b.finish_and_clear();
    }
    let t = Instant::now();
    if let Err(e) = reyes_film::write(&args.output, &rendered.film) {
        return fail(1, e);
    }
    rendered.stats.t_write = t.elapsed();
    rendered.stats.peak_memory = reyes_render::peak_memory();
    if args.stats {
        print!("{}", rendered.stats);
    }
    ExitCode::SUCCESS
}
