//! The `reyes-render` command: arguments, wiring, exit codes. All rendering is in the library.
//!
//! Exit codes: 0 success; 2 usage or scene errors (including bad overrides and an unknown
//! output format); 1 render or I/O errors. Every error is one line on stderr, and no partial
//! output file is ever left behind (the film stage writes atomically). Scene warnings (RIB
//! requests or features not supported) go to stderr, one line each, before rendering.
//!
//! `reyes-render measure SCENE --object NAME [--samples N] [--seed N]` (the first argument
//! `measure`; a scene file of that name is `./measure`) measures the volume and centre of mass
//! of a closed object or CSG solid instead of rendering (patent FIG. 23; see
//! `reyes_measure`), with the same exit codes.

mod args;
mod output;

use std::ffi::OsStr;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use reyes_measure::{MeasureOptions, measure};
use reyes_render::{RenderOptions, render};
use reyes_rib::RiOptions;
use reyes_scene::Scene;

use args::{Args, MeasureArgs};

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

    let options = RiOptions { strict: args.strict, frames: args.frames.clone().map(|f| f.0) };
    let loaded = match reyes_rib::load_scene_file(&args.scene, &options) {
        Ok(l) => l,
        Err(e) => return fail(e.exit_code(), e),
    };
    print_warnings(&loaded.warnings);
    if loaded.frames.is_empty() {
        return fail(2, format_args!("{}: no frame to render", args.scene.display()));
    }
    let numbered = loaded.frames.len() > 1 || loaded.frames.iter().any(|f| f.number.is_some());
    for frame in loaded.frames {
        let mut scene = frame.scene;
        if let Some(seed) = args.seed {
            scene.hider.seed = seed;
        }
        if let Some(s) = args.samples {
            scene.hider.pixel_samples = s;
        }
        let main = output::frame_path(&args.output, frame.number, numbered);
        let extras: Vec<PathBuf> = frame
            .displays
            .iter()
            .filter(|d| d.extra)
            .filter_map(|d| {
                let path = output::extra_path(&args.output, &d.name, frame.number, numbered);
                if path.is_none() {
                    eprintln!(
                        "reyes-render: {}: warning: Display: \"{}\" is not written: only .exr and .png outputs are",
                        d.at, d.name
                    );
                }
                path
            })
            .collect();
        if let Err(code) = render_frame(&args, &scene, &main, &extras) {
            return code;
        }
    }
    ExitCode::SUCCESS
}

/// Scene warnings, one line each; a message repeated at other places is shown once, at its
/// first place, with the count of the others.
fn print_warnings(warnings: &[reyes_rib::Warning]) {
    let mut seen: Vec<(&str, usize, usize)> = Vec::new();
    for (i, w) in warnings.iter().enumerate() {
        match seen.iter_mut().find(|(m, _, _)| *m == w.message) {
            Some(entry) => entry.2 += 1,
            None => seen.push((&w.message, i, 0)),
        }
    }
    for (_, i, more) in seen {
        match more {
            0 => eprintln!("reyes-render: {}", warnings[i]),
            n => eprintln!("reyes-render: {} ({n} more like it)", warnings[i]),
        }
    }
}

/// Renders one frame to `main` (and the same image to each of `extras`).
fn render_frame(
    args: &Args,
    scene: &Scene,
    main: &Path,
    extras: &[PathBuf],
) -> Result<(), ExitCode> {
    let progress = if !args.quiet && std::io::stderr().is_terminal() {
        let frame = reyes_render::frame_for(scene);
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
    let memory_limit = match args.memory_limit {
        Some(limit) => Some(limit),
        None => match std::env::var("REYES_MEMORY_LIMIT") {
            Ok(text) => Some(
                reyes_render::budget::parse_size(&text)
                    .map_err(|e| fail(2, format_args!("REYES_MEMORY_LIMIT: {e}")))?,
            ),
            Err(_) => reyes_render::budget::default_memory_limit(),
        },
    };
    let opts = RenderOptions {
        threads: args.threads.map(usize::from),
        on_bucket: Some(&tick),
        memory_limit,
    };
    let mut rendered = render(scene, &opts)
        .map_err(|e| fail(e.exit_code(), format_args!("{}: {e}", args.scene.display())))?;
    if let Some(b) = &progress {
        b.finish_and_clear();
    }
    let t = Instant::now();
    for path in std::iter::once(main).chain(extras.iter().map(PathBuf::as_path)) {
        reyes_film::write(path, &rendered.film).map_err(|e| fail(1, e))?;
    }
    rendered.stats.t_write = t.elapsed();
    rendered.stats.peak_memory = reyes_render::peak_memory();
    if args.stats {
        print!("{}", rendered.stats);
    }
    Ok(())
}
