//! What is fuzzed, and what counts as a failure.
//!
//! - [`Target::Ron`]: `reyes_scene::parse` (RON syntax, then validation), in process.
//! - [`Target::Rib`]: `reyes_rib::load` (lexer, reader, RI state machine, validation of every
//!   frame), in process.
//! - [`Target::Sl`]: the shading-language compiler (`reyes_sl::compile_str`: preprocessor,
//!   parser, checker), and each shader it accepts run by the grid machine over a 4x4 grid
//!   under a small instruction budget, in process.
//! - [`Target::Tex`]: a texture file (issue #32): the prepared-texture reader and the
//!   picture decoders (`TextureSystem::load`), then lookups of every kind that read its
//!   chunks, `texture info`, and `MakeShadow` of it, in process.
//! - [`Target::Render`]: a whole render of the scene, shrunk by [`shrink`], in a child process
//!   under a memory cap and a time limit ([`render_child`] is what the child runs).
//!
//! A failure is a panic; an error that breaks the loaders' promise (one line, naming the file,
//! at a position inside the text); and, for renders, a child killed by a signal (an abort, a
//! stack overflow, the memory cap), exiting 101 (a panic), exiting otherwise than 0, 1 or 2,
//! failing without its one-line message, or outliving its time limit. Rejecting the scene
//! (exit 2) or failing the render cleanly (exit 1) is not a failure.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::{Mutex, OnceLock};

use reyes_rib::{Format, RiOptions, Source};
use reyes_scene::Scene;

/// A fuzz target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// The RON loader and validator.
    Ron,
    /// The RIB reader, RI state machine and validator.
    Rib,
    /// Small renders in child processes.
    Render,
    /// The shading-language compiler and grid machine.
    Sl,
    /// Texture files: prepared TIFF and pictures, loaded and looked up.
    Tex,
}

impl Target {
    /// The target named `s` (`ron`, `rib`, `render`).
    pub fn parse(s: &str) -> Option<Target> {
        match s {
            "ron" => Some(Target::Ron),
            "rib" => Some(Target::Rib),
            "render" => Some(Target::Render),
            "sl" => Some(Target::Sl),
            "tex" => Some(Target::Tex),
            _ => None,
        }
    }

    /// The name, as [`Target::parse`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            Target::Ron => "ron",
            Target::Rib => "rib",
            Target::Render => "render",
            Target::Sl => "sl",
            Target::Tex => "tex",
        }
    }
}

/// The file name the in-process targets give their input (errors must name it).
pub fn file_name(format: Format) -> &'static str {
    match format {
        Format::Ron => "fuzz.ron",
        Format::Rib => "fuzz.rib",
    }
}

/// How one execution went, when it did not fail.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The scene was accepted (and, for renders, rendered and written).
    Accepted,
    /// The scene was rejected, or the render failed, with a proper error.
    Rejected,
}

/// A failure: what kind, and the details (panic message, exit status, stderr).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failure {
    /// `panic`, `bad-error`, `signal`, `exit`, `hang`, `abort`.
    pub kind: &'static str,
    /// One line saying what happened.
    pub message: String,
}

impl Failure {
    /// A failure of `kind` with `message`.
    pub fn new(kind: &'static str, message: impl Into<String>) -> Failure {
        Failure { kind, message: message.into() }
    }

    /// The part of the message that identifies the bug: panics are told apart by their
    /// location, the rest by kind and the message's first words.
    pub fn signature(&self) -> String {
        let first = self.message.lines().next().unwrap_or("");
        match self.kind {
            "panic" => format!("panic {}", first.split(": ").next().unwrap_or(first)),
            _ => format!("{} {}", self.kind, first.chars().take(60).collect::<String>()),
        }
    }
}

/// The last panic's location and message, written by the hook [`quiet_panics`] installs.
static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);

/// Replaces the panic hook by one that records the panic for [`run_in_process`] instead of
/// printing it (a fuzz run would otherwise print every panic it catches).
pub fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| {
        let payload = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "(no message)".into());
        let at = info.location().map(|l| format!("{}:{}", l.file(), l.line())).unwrap_or_default();
        if let Ok(mut last) = LAST_PANIC.lock() {
            *last = Some(format!("{at}: {}", payload.replace('\n', " ")));
        }
    }));
}

/// A planted bug, for the fuzzer's own tests (see `reyes-fuzz worker`).
type Canary = Box<dyn Fn(&[u8]) + Send + Sync>;
static CANARY: OnceLock<Canary> = OnceLock::new();

/// Plants `canary`: every in-process execution calls it first with the input.
pub fn set_canary(canary: Canary) {
    let _ = CANARY.set(canary);
}

/// Runs `input` through the loader of `format`, in this process; a panic is caught.
pub fn run_in_process(format: Format, input: &[u8]) -> Result<Verdict, Failure> {
    let run = || {
        if let Some(canary) = CANARY.get() {
            canary(input);
        }
        check_load(format, input)
    };
    match catch_unwind(AssertUnwindSafe(run)) {
        Ok(r) => r,
        Err(_) => {
            let msg = LAST_PANIC.lock().ok().and_then(|mut l| l.take());
            Err(Failure::new("panic", msg.unwrap_or_else(|| "panic".into())))
        }
    }
}

/// The file name the shading-language target gives its input (errors must name it).
pub const SL_FILE: &str = "fuzz.sl";

/// The instruction budget of a fuzzed shader's run: enough for every seed shader, small
/// enough that a mutant's endless loop ends in milliseconds (as the budget error).
pub const SL_BUDGET: u64 = 200_000;

/// Compiles `input` as a shader and runs what compiles over a 4x4 grid, in this process; a
/// panic is caught. A compile error must keep the compiler's promise (one line,
/// `fuzz.sl:line:col: ...` at a line inside the text); a run may fail only with the
/// machine's own errors (the budget, an input that does not fit, an unsupported construct).
pub fn run_sl(input: &[u8]) -> Result<Verdict, Failure> {
    let run = || {
        if let Some(canary) = CANARY.get() {
            canary(input);
        }
        check_sl(input)
    };
    match catch_unwind(AssertUnwindSafe(run)) {
        Ok(r) => r,
        Err(_) => {
            let msg = LAST_PANIC.lock().ok().and_then(|mut l| l.take());
            Err(Failure::new("panic", msg.unwrap_or_else(|| "panic".into())))
        }
    }
}

fn check_sl(input: &[u8]) -> Result<Verdict, Failure> {
    let text = String::from_utf8_lossy(input);
    let shader = match reyes_sl::compile_str(SL_FILE, &text, &[]) {
        Ok(shader) => shader,
        Err(e) => {
            let message = e.to_string();
            let bad = |why: &str| Err(Failure::new("bad-error", format!("{why}: {message:?}")));
            if message.contains(['\n', '\r']) {
                return bad("error of more than one line");
            }
            // Errors inside the text name it with its line; an #include that is not found
            // names the including line too.
            let Some(rest) = message.strip_prefix(&format!("{SL_FILE}:")) else {
                return bad("error not naming the file");
            };
            let line: Option<usize> = rest.split(':').next().and_then(|l| l.parse().ok());
            let lines = text.lines().count().max(1) + 1;
            if line.is_none_or(|l| l == 0 || l > lines) {
                return bad("error at a line outside the text");
            }
            return Ok(Verdict::Rejected);
        }
    };
    let mut grid = reyes_sl::exec::GridContext::new(&shader, 4, 4);
    grid.set_budget(SL_BUDGET);
    match grid.run() {
        Ok(_) => Ok(Verdict::Accepted),
        Err(e) if e.to_string().contains(['\n', '\r']) => {
            Err(Failure::new("bad-error", format!("run error of more than one line: {e}")))
        }
        Err(_) => Ok(Verdict::Rejected),
    }
}

/// The file name the texture target writes its input to (errors must name it).
pub const TEX_FILE: &str = "fuzz.tex";

/// Writes `input` to a scratch file and loads it as a texture; what loads is looked up as a
/// texture, an environment and a shadow map (reading its chunks), described as `texture
/// info` does, and made into a shadow map. An error must be one line naming the file; a
/// panic is caught.
pub fn run_tex(input: &[u8]) -> Result<Verdict, Failure> {
    let run = || {
        if let Some(canary) = CANARY.get() {
            canary(input);
        }
        check_tex(input)
    };
    match catch_unwind(AssertUnwindSafe(run)) {
        Ok(r) => r,
        Err(_) => {
            let msg = LAST_PANIC.lock().ok().and_then(|mut l| l.take());
            Err(Failure::new("panic", msg.unwrap_or_else(|| "panic".into())))
        }
    }
}

fn check_tex(input: &[u8]) -> Result<Verdict, Failure> {
    use reyes_texture::{ColorSpace, TextureSystem, lookup::Options};
    let dir = std::env::temp_dir().join(format!("reyes-fuzz-tex-{}", std::process::id()));
    let io = |e: std::io::Error| Failure::new("exit", format!("scratch file: {e}"));
    std::fs::create_dir_all(&dir).map_err(io)?;
    let file = dir.join(TEX_FILE);
    std::fs::write(&file, input).map_err(io)?;
    let name = file.display().to_string();
    let promise = |e: &reyes_texture::TextureError| {
        let message = e.to_string();
        if message.contains(['\n', '\r']) {
            return Err(Failure::new(
                "bad-error",
                format!("error of more than one line: {message:?}"),
            ));
        }
        if !message.starts_with(&name) {
            return Err(Failure::new(
                "bad-error",
                format!("error not naming the file: {message:?}"),
            ));
        }
        Ok(())
    };
    if let Err(e) = reyes_texture::tool::describe(&file) {
        promise(&e)?;
    }
    let shadow = dir.join("fuzz.shd");
    if let Err(e) = reyes_texture::make::make_shadow(&file, &shadow) {
        promise(&e)?;
    }
    let mut sys = TextureSystem::new(1 << 20).map_err(io)?;
    let id = match sys.load(&file, ColorSpace::Linear) {
        Ok(id) => id,
        Err(e) => {
            promise(&e)?;
            return Ok(Verdict::Rejected);
        }
    };
    let o = Options { samples: 4, ..Options::default() };
    for k in 0..8 {
        let v = k as f32 / 7.0;
        let corners = [[v, 0.3], [v + 0.1, 0.3], [v, 0.9], [v + 0.2, 1.0]];
        let _ = sys.texture_corners(id, corners, &o);
        let _ = sys.environment(id, &[[v - 0.5, 0.3, 0.8]], &o);
        let _ = sys.shadow(id, &[[v, 0.2, 3.0]], &o);
    }
    let _ = sys.range(id);
    Ok(Verdict::Accepted)
}

/// Loads `input` and checks the errors' promises.
fn check_load(format: Format, input: &[u8]) -> Result<Verdict, Failure> {
    let name = file_name(format);
    match load(format, input) {
        Ok(_) => Ok(Verdict::Accepted),
        Err(Error { message, line }) => {
            let bad = |why: &str| Err(Failure::new("bad-error", format!("{why}: {message:?}")));
            if message.contains(['\n', '\r']) {
                return bad("error of more than one line");
            }
            if !message.starts_with(name) {
                return bad("error not naming the file");
            }
            let lines = input.iter().filter(|&&c| c == b'\n').count() + 1;
            if line.is_some_and(|l| l == 0 || l > lines) {
                return bad("error at a line outside the text");
            }
            Ok(Verdict::Rejected)
        }
    }
}

/// A loader's error: its one-line display and, for RON, its line.
#[derive(Debug)]
pub struct Error {
    /// The error as displayed.
    pub message: String,
    /// The line it names, when the loader says (RON).
    pub line: Option<usize>,
}

/// The validated scenes of `input` read as `format` (a RON file is one scene; a RIB file one
/// per frame), as the reyes-render command loads them: RON text not in UTF-8 is read lossily,
/// as from standard input.
pub fn load(format: Format, input: &[u8]) -> Result<Vec<Scene>, Error> {
    let name = file_name(format);
    match format {
        Format::Ron => {
            let text = String::from_utf8_lossy(input);
            reyes_scene::parse(&text, Path::new(name))
                .map(|s| vec![s])
                .map_err(|e| Error { message: e.to_string(), line: e.line })
        }
        Format::Rib => reyes_rib::load(Source::from_bytes(name, input), &RiOptions::default())
            .map(|l| l.frames.into_iter().map(|f| f.scene).collect())
            .map_err(|e| Error { message: e.to_string(), line: None }),
    }
}

/// The format of a render input: by content, as the command decides for standard input.
pub fn detect(input: &[u8]) -> Format {
    reyes_rib::detect(Path::new("-"), input)
}

/// The largest image a fuzzed render makes.
pub const MAX_IMAGE: (u32, u32) = (32, 24);
/// The most pixel samples per axis.
pub const MAX_SAMPLES: u32 = 4;
/// The finest shading rate (pixels per micropolygon).
pub const MIN_SHADING_RATE: f32 = 0.25;
/// The deepest ray tree and the most rays per vertex.
pub const MAX_RAYS: u32 = 2;
/// The most frames of a RIB file rendered.
pub const MAX_FRAMES: usize = 2;

/// Makes a scene small to render, changing only what sets the amount of work, not what
/// is drawn: the image to at most 32x24 (the camera's screen window is kept, so the picture
/// is the same, coarser), at most 4x4 samples, a shading rate of at least 1/4 pixel (the scene's and each object's), ray trees
/// at most 2 deep with at most 2 rays per vertex.
pub fn shrink(scene: &mut Scene) {
    scene.image.width = scene.image.width.min(MAX_IMAGE.0);
    scene.image.height = scene.image.height.min(MAX_IMAGE.1);
    let h = &mut scene.hider;
    h.pixel_samples.0 = h.pixel_samples.0.min(MAX_SAMPLES);
    h.pixel_samples.1 = h.pixel_samples.1.min(MAX_SAMPLES);
    h.shading_rate = h.shading_rate.max(MIN_SHADING_RATE);
    for o in &mut scene.objects {
        if let Some(rate) = &mut o.shading_rate {
            *rate = rate.max(MIN_SHADING_RATE);
        }
    }
    let rt = &mut scene.raytrace;
    rt.max_depth = rt.max_depth.min(MAX_RAYS);
    rt.vertex_rays = rt.vertex_rays.min(MAX_RAYS);
}

/// What the render child does with its input file: load it as the command does, shrink each
/// frame (the first [`MAX_FRAMES`]), validate it again, render it on one thread and write it as
/// EXR and PNG into `out`. Returns the exit code: 0 rendered, 2 scene rejected, 1 render or
/// write failed; every error is one line on stderr.
pub fn render_child(input: &Path, out: &Path) -> u8 {
    let bytes = match std::fs::read(input) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("{}: cannot read: {e}", input.display());
            return 1;
        }
    };
    let scenes = match load(detect(&bytes), &bytes) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{}", e.message);
            return 2;
        }
    };
    for (i, mut scene) in scenes.into_iter().take(MAX_FRAMES).enumerate() {
        shrink(&mut scene);
        let scene = match reyes_scene::validate(scene) {
            Ok(s) => s,
            Err(issue) => {
                eprintln!("shrunk scene: {}: {}", issue.path, issue.message);
                return 2;
            }
        };
        // The memory budget the command line would use under this child's address-space cap.
        let opts = reyes_render::RenderOptions {
            threads: Some(1),
            memory_limit: reyes_render::budget::default_memory_limit(),
            ..Default::default()
        };
        let rendered = match reyes_render::render(&scene, &opts) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("render: {e}");
                return e.exit_code();
            }
        };
        for ext in ["exr", "png"] {
            let path = out.join(format!("frame{i}.{ext}"));
            if let Err(e) = reyes_film::write(&path, &rendered.film) {
                eprintln!("{e}");
                return 1;
            }
        }
    }
    0
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "Scene(image: (width: 640, height: 480), camera: (eye: (0.0, 0.0, -5.0), \
        look_at: (0.0, 0.0, 0.0), fov: 40.0), hider: (pixel_samples: (8, 8), shading_rate: 0.01), \
        raytrace: (max_depth: 9, vertex_rays: 16), objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 1.0, 1.0)), \
        shading_rate: Some(0.001))])";

    #[test]
    fn shrinking_bounds_the_work_and_keeps_the_scene_valid() {
        let mut scene = load(Format::Ron, SCENE.as_bytes()).unwrap().remove(0);
        shrink(&mut scene);
        assert_eq!((scene.image.width, scene.image.height), MAX_IMAGE);
        assert_eq!(scene.hider.pixel_samples, (MAX_SAMPLES, MAX_SAMPLES));
        assert_eq!(scene.hider.shading_rate, MIN_SHADING_RATE);
        assert_eq!(scene.objects[0].shading_rate, Some(MIN_SHADING_RATE));
        assert_eq!((scene.raytrace.max_depth, scene.raytrace.vertex_rays), (MAX_RAYS, MAX_RAYS));
        assert!(reyes_scene::validate(scene).is_ok());
    }

    #[test]
    fn rejections_are_verdicts_and_broken_promises_failures() {
        assert_eq!(run_in_process(Format::Ron, SCENE.as_bytes()), Ok(Verdict::Accepted));
        assert_eq!(run_in_process(Format::Ron, b"Scene(image: (width: 0"), Ok(Verdict::Rejected));
        assert_eq!(
            run_in_process(Format::Rib, b"WorldBegin Sphere 1 -1 1 360 WorldEnd"),
            Ok(Verdict::Accepted)
        );
        assert_eq!(run_in_process(Format::Rib, b"Sphere [[["), Ok(Verdict::Rejected));
    }

    #[test]
    fn panic_signatures_keep_the_location_only() {
        let f = Failure::new("panic", "crates/x/src/a.rs:10: index 5 out of range");
        let g = Failure::new("panic", "crates/x/src/a.rs:10: index 6 out of range");
        assert_eq!(f.signature(), g.signature());
        assert_ne!(f.signature(), Failure::new("panic", "crates/x/src/a.rs:11: x").signature());
    }
}
