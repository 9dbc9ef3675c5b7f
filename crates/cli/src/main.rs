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
//! `reyes_measure`), with the same exit codes. Likewise `reyes-render merge TILE... -o OUT`
//! reassembles the tiles of `--tile` renders ([`pieces`]), and `reyes-render farm slurm|status`
//! submits and follows a Slurm job ([`farm`]); a scene file named `merge` or `farm` is
//! `./merge` or `./farm` (docs/farm.md).
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod args;
mod checkpoint;
mod farm;
mod hooks;
mod output;
mod pieces;
mod progress;
mod signals;
mod term;

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::ffi::OsStr;
use std::fmt::Display;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Once;
use std::time::{Duration, Instant};

use clap::Parser;
use reyes_film::{FilmError, WriteOptions};
use reyes_measure::{MeasureOptions, measure};
use reyes_render::{BucketResult, RenderError, RenderOptions, render};
use reyes_rib::RiOptions;
use reyes_scene::Scene;

use args::{Args, MeasureArgs, MergeArgs};
use checkpoint::Checkpoint;
use hooks::Pause;
use pieces::Header;
use progress::Progress;
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
    let first = std::env::args_os().nth(1);
    let result = match first.as_deref().and_then(OsStr::to_str) {
        Some("measure") => measure_main(std::env::args_os().skip(1)),
        Some("merge") => merge_main(std::env::args_os().skip(1)),
        Some("farm") => farm::main(std::env::args_os().skip(1)),
        _ => render_main(),
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

/// `reyes-render merge TILE... -o OUT`: `args` starts at `merge`.
fn merge_main(args: impl Iterator<Item = std::ffi::OsString>) -> Result<(), Exit> {
    signals::install(true).map_err(|e| Exit::error(1, format_args!("signals: {e}")))?;
    let args = MergeArgs::try_parse_from(args)
        .map_err(|e| parse_failed(e, "reyes-render merge --help"))?;
    check_output(&args.output)?;
    pieces::merge(&args.tiles, &args.output).map_err(|e| match signals::received() {
        Some(stop) => Exit::stopped(stop, &args.output),
        None => e,
    })
}

/// The output's format and directory, checked before any work is done.
fn check_output(output: &Path) -> Result<(), Exit> {
    let ext = output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("exr" | "png")) {
        return Err(Exit::error(
            2,
            format_args!("{}: output: unknown image format, use .exr or .png", output.display()),
        ));
    }
    if !directory_of(output).is_dir() {
        return Err(Exit::error(
            1,
            format_args!("{}: output directory does not exist", output.display()),
        ));
    }
    Ok(())
}

fn render_main() -> Result<(), Exit> {
    signals::install(true).map_err(|e| Exit::error(1, format_args!("signals: {e}")))?;
    let args = Args::try_parse().map_err(|e| parse_failed(e, "--help"))?;

    // Check the output before spending time on the render.
    check_output(&args.output)?;
    if args.tile.is_some() && !is_exr(&args.output) {
        return Err(Exit::error(
            2,
            format_args!("{}: --tile: a tile is written as .exr", args.output.display()),
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
    let jobs: Vec<(Scene, Option<i32>, PathBuf, Vec<PathBuf>)> = loaded
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
                let flag = format!("--samples {}x{}", s.0, s.1);
                scene = revalidate(scene, &args.scene, &flag)?;
            }
            if let Some(crop) = args.crop {
                scene.image.crop = Some(crop.0);
                let [a, b, c, d] = crop.0;
                scene = revalidate(scene, &args.scene, &format!("--crop {a},{b},{c},{d}"))?;
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
            Ok((scene, frame.number, main, extras))
        })
        .collect::<Result<_, Exit>>()?;

    // What a writer killed where the file system has no O_TMPFILE left behind.
    let mut dirs: Vec<PathBuf> = Vec::new();
    for path in jobs.iter().flat_map(|(_, _, main, extras)| std::iter::once(main).chain(extras)) {
        let dir = directory_of(path);
        if !dirs.contains(&dir) {
            reyes_film::remove_stale_temporaries(&dir);
            dirs.push(dir);
        }
    }

    let hooks = Hooks::from_env();
    for (scene, number, main, extras) in &jobs {
        render_frame(&args, (scene, *number), main, extras, &hooks)?;
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

/// Validate `scene` again after the command line changed it (`flag`).
fn revalidate(scene: Scene, path: &Path, flag: &str) -> Result<Scene, Exit> {
    reyes_scene::validate(scene).map_err(|issue| {
        Exit::error(
            2,
            format_args!("{}: {flag}: {}: {}", path.display(), issue.path, issue.message),
        )
    })
}

fn is_exr(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// Renders one frame (numbered `number`) to `main` (and the same image to each of
/// `extras`); with `--tile`, the tile file to `main` alone.
fn render_frame(
    args: &Args,
    (scene, number): (&Scene, Option<i32>),
    main: &Path,
    extras: &[PathBuf],
    hooks: &Hooks,
) -> Result<(), Exit> {
    let scene_path = args.scene.display().to_string();
    let buckets = pieces::buckets_of(scene, args.tile)
        .map_err(|e| Exit::error(2, format_args!("{}: {e}", args.scene.display())))?;
    // The fingerprint serialises the whole scene: only pieces need it.
    let header = (args.tile.is_some() || args.checkpoint.is_some())
        .then(|| Header::new(scene, &scene_path, number, args.tile.unwrap_or((0, 0))));
    let (checkpoint, done) = match (&args.checkpoint, &header) {
        (Some(root), Some(h)) => {
            let (c, done) = Checkpoint::open(root, Header { tile: (0, 0), ..h.clone() })?;
            (Some(c), done)
        }
        _ => (None, BTreeMap::new()),
    };
    let resumed = buckets.iter().filter(|b| done.contains_key(b)).count() as u64;
    let mut label = String::new();
    if let Some(n) = number {
        label.push_str(&format!("frame {n} "));
    }
    if let Some((i, n)) = args.tile {
        label.push_str(&format!("tile {i}/{n} "));
    }
    let progress = Progress::new(
        args.quiet,
        std::io::stderr().is_terminal(),
        label,
        buckets.len() as u64,
        resumed,
        Duration::from_secs_f64(args.progress_every),
    );
    let tick = || {
        progress.tick();
        if hooks.pause == Pause::Render {
            hooks.once.call_once(hooks::pause_rendering);
        }
    };
    let save = |b: usize, r: &BucketResult| {
        if let Some(c) = &checkpoint {
            c.save(b, r);
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
    // A whole frame's EXR beauty is compressed while the frame renders, block by block as
    // its lines are final (the write then stores those blocks as they are; the file is the
    // same bytes). Not for tiles (their files hold bucket windows) or crop windows.
    let exr_out = is_exr(main) || extras.iter().any(|p| is_exr(p));
    let early = (exr_out && args.tile.is_none() && scene.image.crop.is_none())
        .then(|| {
            let named = reyes_render::aovs::AovSetup::for_scene(scene).is_some();
            reyes_film::EarlyBlocks::new(
                scene.image.width,
                scene.image.height,
                &scene.outputs,
                named,
            )
        })
        .flatten();
    let encode_early = |film: &reyes_film::Film, lines: std::ops::Range<u32>| {
        if let Some(e) = &early {
            e.encode(film, lines);
        }
    };
    let opts = RenderOptions {
        threads: args.threads.map(usize::from),
        on_film_lines: early.as_ref().map(|_| &encode_early as &reyes_render::OnFilmLines),
        on_bucket: Some(&tick),
        memory_limit,
        buckets: Some(&buckets),
        done: checkpoint.as_ref().map(|_| &done),
        on_result: checkpoint.as_ref().map(|_| &save as &reyes_render::OnResult),
        keep_buckets: args.tile.is_some(),
        shade_every_vertex: false,
    };
    let started = Instant::now();
    let rendered = render(scene, &opts);
    let render_time = started.elapsed();
    if rendered.is_ok() {
        progress.finish();
    }
    drop(progress);
    if let Some(failure) = checkpoint.as_ref().and_then(Checkpoint::failure) {
        return Err(Exit::error(1, failure));
    }
    let mut rendered = rendered.map_err(|e| match (e, signals::received()) {
        (RenderError::Cancelled, Some(stop)) => Exit::stopped(stop, main),
        (e, _) => Exit::error(e.exit_code(), format_args!("{}: {e}", args.scene.display())),
    })?;
    for w in &rendered.warnings {
        say(format_args!("{}: warning: {w}", args.scene.display()));
    }
    let render_time = scene.outputs.render_time.then_some(render_time.as_secs_f32());

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
        let written = if let (Some(_), Some(header)) = (args.tile, &header) {
            let header = Header { render_time, ..header.clone() };
            pieces::write_piece(path, &header, &rendered.buckets, &opts)
        } else {
            let aovs = rendered.aovs.as_ref().map(|a| (&a.film, a.layers.as_slice()));
            let film = (&rendered.film, aovs);
            write_picture(scene, &scene_path, film, (render_time, early.as_ref()), path, &opts)
        };
        written.map_err(|e| match (e, signals::received()) {
            (FilmError::Interrupted { path }, Some(stop)) => Exit::stopped(stop, &path),
            (e, _) => Exit::error(1, e),
        })?;
        if args.tile.is_some() {
            break; // a tile goes to its one file
        }
    }
    if let Some(c) = checkpoint {
        c.finish();
    }
    rendered.stats.t_write = t.elapsed();
    rendered.stats.peak_memory = reyes_render::peak_memory();
    if args.stats {
        term::print(&rendered.stats.to_string())?;
    }
    Ok(())
}

/// Write a frame's film (and AOVs) to `path` as the scene asks: with its crop window's
/// pixels only, and the metadata of the scene file `scene_path`. Both a whole render and
/// `reyes-render merge` write through here, so their files agree byte for byte.
fn write_picture(
    scene: &Scene,
    scene_path: &str,
    (film, aovs): (&reyes_film::Film, Option<(&reyes_film::AovFilm, &[reyes_film::AovLayer])>),
    (render_time, early): (Option<f32>, Option<&reyes_film::EarlyBlocks>),
    path: &Path,
    opts: &WriteOptions,
) -> Result<(), FilmError> {
    let mut metadata = reyes_film::Metadata::for_scene(scene, scene_path);
    metadata.render_time = render_time;
    let image = &scene.image;
    let rect = image.crop_pixels();
    // Only a crop copies the film: the whole frame is written from the render's own (a
    // copy would be the frame's largest allocation, at the peak of its memory).
    let (film, aovs, placement) = if image.crop.is_some() {
        let placement =
            reyes_film::Placement { full: (image.width, image.height), origin: (rect[0], rect[2]) };
        let aovs = aovs.map(|(a, l)| (Cow::Owned(a.crop(rect)), l));
        (Cow::Owned(film.crop(rect)), aovs, Some(placement))
    } else {
        (Cow::Borrowed(film), aovs.map(|(a, l)| (Cow::Borrowed(a), l)), None)
    };
    let picture = reyes_film::Picture {
        film: &film,
        aovs: aovs.as_ref().map(|(a, l)| (a.as_ref(), *l)),
        outputs: &scene.outputs,
        metadata: &metadata,
        placement,
        early,
    };
    reyes_film::write_picture(path, &picture, opts)
}

/// Write the frame that the bucket `results` of `scene` make (`reyes-render merge`).
pub(crate) fn write_frame(
    scene: &Scene,
    scene_path: &str,
    results: &BTreeMap<usize, BucketResult>,
    render_time: Option<f32>,
    path: &Path,
    opts: &WriteOptions,
) -> Result<(), Exit> {
    let aov = reyes_render::aovs::AovSetup::for_scene(scene);
    let channels = aov.as_ref().map(|a| a.plan.channels());
    let (film, aov_film) = reyes_render::buckets::assemble(
        scene.image.width,
        scene.image.height,
        channels,
        results.values(),
    );
    let aovs = aov.as_ref().zip(aov_film.as_ref()).map(|(a, f)| (f, a.layers.as_slice()));
    write_picture(scene, scene_path, (&film, aovs), (render_time, None), path, opts)
        .map_err(|e| Exit::error(1, e))
}
