//! The `reyes-render` command: arguments, wiring, exit codes. All rendering is in the library.
//!
//! Exit codes: 0 success; 2 usage or scene errors (including bad overrides and an unknown
//! output format); 1 render or I/O errors (a full disk, a file too large, a full standard
//! output); 130 and 143 when SIGINT or SIGTERM stopped it. Every error is one line on stderr,
//! usage errors included, and no partial output file is ever left behind (the film stage
//! writes atomically, through an unnamed temporary file where the system allows, and
//! interrupted writes remove theirs). Scene warnings (RIB requests or features not supported)
//! go to stderr, one line each, before rendering. Nothing printed can panic ([`term`]): a
//! closed standard output ends the printing quietly.
//!
//! `reyes-render measure SCENE --object NAME [--samples N] [--seed N]` (the first argument
//! `measure`; a scene file of that name is `./measure`) measures the volume and centre of mass
//! of a closed object or CSG solid instead of rendering (patent FIG. 23; see
//! `reyes_measure`), with the same exit codes.
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod args;
mod hooks;
mod output;
mod signals;
mod term;

use std::ffi::OsStr;
use std::fmt::Display;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Once;
use std::time::Instant;

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use reyes_film::{FilmError, WriteOptions};
use reyes_measure::{MeasureOptions, measure};
use reyes_render::{RenderError, RenderOptions, render};
use reyes_rib::RiOptions;
use reyes_scene::Scene;

use args::{Args, MeasureArgs};
use hooks::Pause;
use term::say;

/// How a run ends other than in plain success: the exit code and the line to print, if any
/// (none after `--help` or `--version`, or when standard output was closed on them).
pub(crate) struct Exit {
    code: u8,
    message: Option<String>,
}

impl Exit {
    /// `reyes-render: error: MSG`, exit `code`.
    pub(crate) fn error(code: u8, msg: impl Display) -> Exit {
        Exit { code, message: Some(format!("error: {msg}")) }
    }

    /// Stopped by a signal while `path` was being rendered or written: it was not written.
    fn stopped(stop: signals::Stop, path: &Path) -> Exit {
        let message = format!("interrupted by {}: {} was not written", stop.name, path.display());
        Exit { code: stop.code, message: Some(message) }
    }

    /// Stopped by a signal between outputs.
    fn stopped_between(stop: signals::Stop) -> Exit {
        Exit { code: stop.code, message: Some(format!("interrupted by {}", stop.name)) }
    }
}

fn main() -> ExitCode {
    let result = if std::env::args_os().nth(1).as_deref() == Some(OsStr::new("measure")) {
        measure_main(std::env::args_os().skip(1))
    } else {
        render_main()
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Exit { code, message }) => {
            if let Some(m) = message {
                say(m);
            }
            ExitCode::from(code)
        }
    }
}

/// A failed parse: `--help` and `--version` print as clap prints them (exit 0); a usage error
/// is one line, clap's message and its suggestion if it has one, exit 2.
fn parse_failed(e: clap::Error, help: &str) -> Exit {
    if !e.use_stderr() {
        return match e.print().map_err(term::stdout_failed) {
            Ok(()) | Err(Ok(())) => Exit { code: 0, message: None },
            Err(Err(exit)) => exit,
        };
    }
    let mut line = message_line(&e.render().to_string());
    use clap::error::ContextKind;
    for kind in [ContextKind::SuggestedArg, ContextKind::SuggestedValue] {
        if let Some(suggested) = e.get(kind) {
            line.push_str(&format!("; did you mean '{suggested}'?"));
        }
    }
    Exit::error(2, format_args!("{line} (see {help})"))
}

/// The message of clap's error text (`error: MESSAGE`, possibly over several lines, before
/// the paragraphs of tips, usage and the pointer to `--help`) as one line.
fn message_line(text: &str) -> String {
    let first = text.split("\n\n").next().unwrap_or_default();
    let line = first.lines().map(str::trim).filter(|l| !l.is_empty()).collect::<Vec<_>>();
    let line = line.join(" ");
    line.strip_prefix("error: ").unwrap_or(&line).to_string()
}

/// `reyes-render measure ...`: `args` starts at `measure`.
fn measure_main(args: impl Iterator<Item = std::ffi::OsString>) -> Result<(), Exit> {
    // Measuring polls no cancel flag and writes no file: SIGINT and SIGTERM keep their
    // default, which ends it at once.
    signals::install(false).map_err(|e| Exit::error(1, format_args!("signals: {e}")))?;
    let args = MeasureArgs::try_parse_from(args)
        .map_err(|e| parse_failed(e, "reyes-render measure --help"))?;
    let scene = reyes_scene::load(&args.scene).map_err(|e| Exit::error(e.exit_code(), &e))?;
    let opts =
        MeasureOptions { samples: args.samples, seed: args.seed.unwrap_or(scene.hider.seed) };
    let m = measure(&scene, &args.scene, &args.object, &opts)
        .map_err(|e| Exit::error(e.exit_code(), &e))?;
    term::print(&m.to_string())
}

fn render_main() -> Result<(), Exit> {
    signals::install(true).map_err(|e| Exit::error(1, format_args!("signals: {e}")))?;
    let args = Args::try_parse().map_err(|e| parse_failed(e, "--help"))?;

    // Check the output before spending time on the render.
    let ext = args.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("exr" | "png")) {
        return Err(Exit::error(
            2,
            format_args!(
                "{}: output: unknown image format, use .exr or .png",
                args.output.display()
            ),
        ));
    }
    if !directory_of(&args.output).is_dir() {
        return Err(Exit::error(
            1,
            format_args!("{}: output directory does not exist", args.output.display()),
        ));
    }

    let options = RiOptions { strict: args.strict, frames: args.frames.clone().map(|f| f.0) };
    let loaded = reyes_rib::load_scene_file(&args.scene, &options)
        .map_err(|e| Exit::error(e.exit_code(), &e))?;
    print_warnings(&loaded.warnings);
    if loaded.frames.is_empty() {
        return Err(Exit::error(2, format_args!("{}: no frame to render", args.scene.display())));
    }
    let numbered = loaded.frames.len() > 1 || loaded.frames.iter().any(|f| f.number.is_some());
    let jobs: Vec<(Scene, PathBuf, Vec<PathBuf>)> = loaded
        .frames
        .into_iter()
        .map(|frame| {
            let mut scene = frame.scene;
            if args.z_infinite {
                scene.outputs.zbackground = reyes_scene::ZBackground::Infinite;
            }
            if let Some(seed) = args.seed {
                scene.hider.seed = seed;
            }
            if let Some(s) = args.samples {
                scene.hider.pixel_samples = s;
                // The filter table depends on the sample grid: a filter valid on the scene's
                // grid can weigh no stratum of another.
                scene = reyes_scene::validate(scene).map_err(|issue| {
                    Exit::error(
                        2,
                        format_args!(
                            "{}: --samples {}x{}: {}: {}",
                            args.scene.display(),
                            s.0,
                            s.1,
                            issue.path,
                            issue.message
                        ),
                    )
                })?;
            }
            if let Some(w) = reyes_render::settings::pattern_fallback(&scene) {
                say(format_args!("{}: warning: {w}", args.scene.display()));
            }
            let main = output::frame_path(&args.output, frame.number, numbered);
            let extras = frame
                .displays
                .iter()
                .filter(|d| d.extra)
                .filter_map(|d| {
                    let path = output::extra_path(&args.output, &d.name, frame.number, numbered);
                    if path.is_none() {
                        say(format_args!(
                            "{}: warning: Display: \"{}\" is not written: only .exr and .png outputs are",
                            d.at, d.name
                        ));
                    }
                    path
                })
                .collect();
            Ok((scene, main, extras))
        })
        .collect::<Result<_, Exit>>()?;

    // What a writer killed where the file system has no O_TMPFILE left behind.
    let mut dirs: Vec<PathBuf> = Vec::new();
    for path in jobs.iter().flat_map(|(_, main, extras)| std::iter::once(main).chain(extras)) {
        let dir = directory_of(path);
        if !dirs.contains(&dir) {
            reyes_film::remove_stale_temporaries(&dir);
            dirs.push(dir);
        }
    }

    let hooks = Hooks::from_env();
    for (scene, main, extras) in &jobs {
        render_frame(&args, scene, main, extras, &hooks)?;
        if let Some(stop) = signals::received() {
            return Err(Exit::stopped_between(stop));
        }
    }
    Ok(())
}

/// The directory a file `path` goes to (`.` for a bare name).
fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
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
            0 => say(&warnings[i]),
            n => say(format_args!("{} ({n} more like it)", warnings[i])),
        }
    }
}

/// The test hooks of [`hooks`], each pausing once per run.
struct Hooks {
    pause: Pause,
    named_temporary: bool,
    once: Once,
}

impl Hooks {
    fn from_env() -> Hooks {
        Hooks {
            pause: hooks::pause(),
            named_temporary: hooks::named_temporary(),
            once: Once::new(),
        }
    }
}

/// The progress bar, cleared from the terminal however the frame ends.
struct Progress(Option<ProgressBar>);

impl Progress {
    fn tick(&self) {
        if let Some(b) = &self.0 {
            b.inc(1);
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(b) = &self.0 {
            b.finish_and_clear();
        }
    }
}

/// Renders one frame to `main` (and the same image to each of `extras`).
fn render_frame(
    args: &Args,
    scene: &Scene,
    main: &Path,
    extras: &[PathBuf],
    hooks: &Hooks,
) -> Result<(), Exit> {
    let progress = Progress((!args.quiet && std::io::stderr().is_terminal()).then(|| {
        let frame = reyes_render::frame_for(scene);
        let bar = ProgressBar::new(frame.bucket_count() as u64);
        if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} buckets {elapsed}") {
            bar.set_style(style);
        }
        bar
    }));
    let tick = || {
        progress.tick();
        if hooks.pause == Pause::Render {
            hooks.once.call_once(hooks::pause_rendering);
        }
    };
    let memory_limit = match args.memory_limit {
        Some(limit) => Some(limit),
        None => match std::env::var("REYES_MEMORY_LIMIT") {
            Ok(text) => Some(
                reyes_render::budget::parse_size(&text)
                    .map_err(|e| Exit::error(2, format_args!("REYES_MEMORY_LIMIT: {e}")))?,
            ),
            Err(_) => reyes_render::budget::default_memory_limit(),
        },
    };
    let opts = RenderOptions {
        threads: args.threads.map(usize::from),
        on_bucket: Some(&tick),
        memory_limit,
    };
    let started = Instant::now();
    let rendered = render(scene, &opts);
    let render_time = started.elapsed();
    drop(progress);
    let mut rendered = rendered.map_err(|e| match (e, signals::received()) {
        (RenderError::Cancelled, Some(stop)) => Exit::stopped(stop, main),
        (e, _) => Exit::error(e.exit_code(), format_args!("{}: {e}", args.scene.display())),
    })?;
    for w in &rendered.warnings {
        say(format_args!("{}: warning: {w}", args.scene.display()));
    }

    let mut metadata = reyes_film::Metadata::for_scene(scene, &args.scene.display().to_string());
    if scene.outputs.render_time {
        metadata.render_time = Some(render_time.as_secs_f32());
    }
    let picture = reyes_film::Picture {
        film: &rendered.film,
        aovs: rendered.aovs.as_ref().map(|a| (&a.film, a.layers.as_slice())),
        outputs: &scene.outputs,
        metadata: &metadata,
    };
    let t = Instant::now();
    for path in std::iter::once(main).chain(extras.iter().map(PathBuf::as_path)) {
        let pause = |temporary: Option<&Path>| {
            if hooks.pause == Pause::Write {
                hooks.once.call_once(|| hooks::pause_writing(path, temporary));
            }
        };
        let opts = WriteOptions {
            cancel: Some(reyes_render::cancel::flag()),
            after_first_chunk: Some(&pause),
            named_temporary: hooks.named_temporary,
        };
        reyes_film::write_picture(path, &picture, &opts).map_err(|e| {
            match (e, signals::received()) {
                (FilmError::Interrupted { path }, Some(stop)) => Exit::stopped(stop, &path),
                (e, _) => Exit::error(1, e),
            }
        })?;
    }
    rendered.stats.t_write = t.elapsed();
    rendered.stats.peak_memory = reyes_render::peak_memory();
    if args.stats {
        term::print(&rendered.stats.to_string())?;
    }
    Ok(())
}
