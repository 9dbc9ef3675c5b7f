//! The `reyes-render` command: arguments, wiring, signals, exit codes and printing. Rendering
//! is the reyes-render library's; frames in pieces (tiles, merge, checkpoints, progress lines,
//! output names, Slurm jobs) are reyes-farm's; shader tools are reyes-sl's.
//!
//! Exit codes: 0 success; 2 usage or scene errors (bad overrides, an unknown output format);
//! 1 render or I/O errors (a full disk, a file too large, a full standard output); 130 and 143
//! when SIGINT or SIGTERM stopped it. Every error is one line on stderr, usage errors included
//! (control characters escaped, [`term::say`]), and no partial output file is ever left
//! behind (the film stage writes atomically, and interrupted writes remove theirs). Scene
//! warnings go to stderr, one line each, before rendering; nothing printed can panic.
//!
//! A first argument `measure` (FIG. 23's mass properties), `merge` (tiles reassembled), `farm`
//! (Slurm jobs, [`farm`]), `shader` (`check`, `info`) or `texture` (`make`, `info`) chooses
//! another command with the same exit codes; a scene file of one of those names is `./measure` etc. (docs/farm.md).
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod args;
mod farm;
mod signals;
mod term;

use std::ffi::{OsStr, OsString};
use std::fmt::Display;
use std::path::Path;
use std::process::ExitCode;

use clap::Parser;
use reyes_farm::testing::TestHooks;
use reyes_farm::{FarmError, FrameJob, Overrides, Request};
use reyes_film::WriteOptions;
use reyes_measure::{MeasureOptions, measure};

use args::{Args, MeasureArgs, MergeArgs};
use term::{Progress, say};

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
}

impl From<FarmError> for Exit {
    fn from(e: FarmError) -> Exit {
        Exit::error(e.exit_code(), e)
    }
}

/// What `e` means for the rendering of `path`: the stop, if a signal cancelled the render
/// or interrupted the write.
fn failed(e: FarmError, path: &Path) -> Exit {
    if let (Some(file), Some(stop)) = (e.cancelled(path), signals::received()) {
        return Exit::stopped(stop, file);
    }
    e.into()
}

fn main() -> ExitCode {
    let first = std::env::args_os().nth(1);
    let rest = || std::env::args_os().skip(1);
    let result = match first.as_deref().and_then(OsStr::to_str) {
        Some("measure") => measure_main(rest()),
        Some("merge") => merge_main(rest()),
        Some("farm") => farm::main(rest()),
        Some("shader") => tool_main(rest(), reyes_sl::tool::run_parts),
        Some("texture") => tool_main(rest(), reyes_texture::tool::run),
        _ => render_main(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Exit { code, message }) => {
            message.into_iter().for_each(say);
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
    // clap's text is `error: MESSAGE`, possibly over several lines, before the paragraphs of
    // tips, usage and the pointer to `--help`: the message as one line.
    let text = e.render().to_string();
    let first = text.split("\n\n").next().unwrap_or_default();
    let words: Vec<&str> = first.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
    let joined = words.join(" ");
    let mut line = joined.strip_prefix("error: ").unwrap_or(&joined).to_string();
    use clap::error::ContextKind;
    for kind in [ContextKind::SuggestedArg, ContextKind::SuggestedValue] {
        if let Some(suggested) = e.get(kind) {
            line.push_str(&format!("; did you mean '{suggested}'?"));
        }
    }
    Exit::error(2, format_args!("{line} (see {help})"))
}

/// Install the signal handlers (with `stop`, SIGINT and SIGTERM stop the command: it polls
/// the cancel flag) and parse `args` (the command's name first), its help `help`.
fn parse<T: Parser>(
    args: impl Iterator<Item = OsString>,
    stop: bool,
    help: &str,
) -> Result<T, Exit> {
    signals::install(stop)?;
    T::try_parse_from(args).map_err(|e| parse_failed(e, help))
}

/// `reyes-render measure ...`: `args` starts at `measure`.
fn measure_main(args: impl Iterator<Item = OsString>) -> Result<(), Exit> {
    // Measuring polls no cancel flag and writes no file: SIGINT and SIGTERM keep their
    // default, which ends it at once.
    let args: MeasureArgs = parse(args, false, "reyes-render measure --help")?;
    let scene = reyes_farm::load_one_frame(&args.scene, &mut |w| say(w))?;
    let opts =
        MeasureOptions { samples: args.samples, seed: args.seed.unwrap_or(scene.hider.seed) };
    let m = measure(&scene, &args.scene, &args.object, &opts)
        .map_err(|e| Exit::error(e.exit_code(), &e))?;
    term::print(&m.to_string())
}

/// `reyes-render shader check|info ...` ([`reyes_sl::tool`]) and `texture make|info ...`
/// ([`reyes_texture::tool`]): `args` starts at the command; `run` gives stdout, errors, code.
fn tool_main(args: impl Iterator<Item = OsString>, run: ToolRun) -> Result<(), Exit> {
    let (stdout, errors, code) =
        run(&args.skip(1).map(|a| a.to_string_lossy().into()).collect::<Vec<_>>());
    errors.iter().for_each(say);
    term::print(&stdout)?;
    if code == 0 { Ok(()) } else { Err(Exit { code, message: None }) }
}
type ToolRun = fn(&[String]) -> (String, Vec<String>, u8);

/// `reyes-render merge TILE... -o OUT`: `args` starts at `merge`.
fn merge_main(args: impl Iterator<Item = OsString>) -> Result<(), Exit> {
    let args: MergeArgs = parse(args, true, "reyes-render merge --help")?;
    reyes_farm::output::check_output(&args.output, true)?;
    let written = reyes_farm::merge(&args.tiles, &args.output, &WriteOptions::default());
    written.map_err(|e| match signals::received() {
        Some(stop) => Exit::stopped(stop, &args.output),
        None => e.into(),
    })
}

/// `reyes-render SCENE -o OUT ...`: each frame rendered and written to its outputs (a tile
/// to its file), stopping between frames when a signal came.
fn render_main() -> Result<(), Exit> {
    let args: Args = parse(std::env::args_os(), true, "--help")?;
    let (seed, samples, crop) = (args.seed, args.samples, args.crop);
    let (z_infinite, shader_max_ops) = (args.z_infinite, args.shader_max_ops);
    let request = Request {
        scene: args.scene.clone(),
        output: args.output.clone(),
        strict: args.strict,
        allow_run_program: args.allow_run_program,
        frames: args.frames.clone(),
        overrides: Overrides { seed, samples, crop, z_infinite, shader_max_ops },
        tile: args.tile,
        checkpoint: args.checkpoint.clone(),
    };
    let frames = reyes_farm::plan(&request, &mut |w| say(w))?;
    let memory_limit = reyes_farm::job::memory_limit(args.memory_limit)?;
    let hooks = TestHooks::from_env();
    for frame in &frames {
        let job = FrameJob::open(&request, frame, &mut |w| say(w))?;
        let progress = Progress::new(&args, &job);
        let tick = || {
            progress.tick();
            hooks.after_bucket(&say);
        };
        let rendered = job.render(args.threads.map(usize::from), memory_limit, &tick);
        progress.finish(rendered.is_ok());
        let mut rendered = rendered.map_err(|e| failed(e, &frame.main))?;
        rendered.warnings.iter().for_each(say);
        let pause = |path: &Path, temp: Option<&Path>| hooks.after_first_chunk(path, temp, &say);
        let write = hooks.write_hooks(&pause);
        job.write(&mut rendered, &write).map_err(|e| failed(e, &frame.main))?;
        job.finish(!args.quiet, &mut |w| say(w))?;
        if args.stats {
            term::print(&rendered.rendered.stats.to_string())?;
        }
        if let Some(stop) = signals::received() {
            let message = Some(format!("interrupted by {}", stop.name));
            return Err(Exit { code: stop.code, message });
        }
    }
    Ok(())
}
