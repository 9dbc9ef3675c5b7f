//! One run of the renderer as a front end asks for it: a scene file's frames, with the
//! front end's overrides applied, each rendered whole, as a tile, or resumed from a
//! checkpoint, and written to its outputs.
//!
//! A front end calls [`plan`] once (the scene loaded, the overrides applied and every frame's
//! outputs named, before anything is rendered), then for each frame [`FrameJob::open`],
//! [`FrameJob::render`], [`FrameJob::write`] (each of [`FrameJob::outputs`] in turn) and
//! [`FrameJob::finish`]. It keeps what is its own: printing, signals, the progress display.
//!
//! Invariant: what a frame renders is decided by the scene after the overrides alone; the
//! tile, the checkpoint and the thread count only decide which buckets are drawn now and
//! where they go, so every way of rendering a frame gives the same file.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use reyes_film::{EarlyBlocks, Film, WriteOptions};
use reyes_render::{BucketResult, RenderOptions, Rendered};
use reyes_rib::RiOptions;
use reyes_scene::Scene;

use crate::output::{
    FramePicture, check_output, create_directory_of, extra_path, frame_path, is_exr,
};
use crate::piece::{Header, write_piece};
use crate::tile::buckets_of;
use crate::{Checkpoint, FarmError, FrameList, Tile, one_line};

/// The front end's changes to every frame's scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// The hider's seed.
    pub seed: Option<u64>,
    /// The pixel samples, `(n, m)`.
    pub samples: Option<(u32, u32)>,
    /// The crop window `[x0, x1, y0, y1]`, in screen fractions.
    pub crop: Option<[f32; 4]>,
    /// Write +inf depth where nothing is visible.
    pub z_infinite: bool,
    /// Shading-language instructions one shader may run on one grid before the render stops
    /// (None: [`reyes_scene::sl::exec::DEFAULT_BUDGET`]; docs/shading.md).
    pub shader_max_ops: Option<u64>,
}

impl Overrides {
    /// `scene` (of the file named `path` in messages) with the overrides applied, validated
    /// again where a change can invalidate it (the filter table depends on the sample grid;
    /// a crop window must select pixels).
    pub fn apply(&self, mut scene: Scene, path: &Path) -> Result<Scene, FarmError> {
        if self.z_infinite {
            scene.outputs.zbackground = reyes_scene::ZBackground::Infinite;
        }
        if let Some(seed) = self.seed {
            scene.hider.seed = seed;
        }
        if let Some(s) = self.samples {
            scene.hider.pixel_samples = s;
            scene = revalidate(scene, path, &format!("--samples {}x{}", s.0, s.1))?;
        }
        if let Some(crop) = self.crop {
            scene.image.crop = Some(crop);
            let [a, b, c, d] = crop;
            scene = revalidate(scene, path, &format!("--crop {a},{b},{c},{d}"))?;
        }
        Ok(scene)
    }
}

/// Pixel samples as text: `NxM`, each from 1 to 64.
pub fn parse_samples(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("expected NxM with N and M from 1 to 64, got '{s}'");
    let (a, b) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let n: u32 = a.trim().parse().map_err(|_| bad())?;
    let m: u32 = b.trim().parse().map_err(|_| bad())?;
    if !(1..=64).contains(&n) || !(1..=64).contains(&m) {
        return Err(bad());
    }
    Ok((n, m))
}

/// A crop window as text: `X0,X1,Y0,Y1`, in screen fractions (validated with the scene).
pub fn parse_crop(s: &str) -> Result<[f32; 4], String> {
    let bad = || format!("expected X0,X1,Y0,Y1, four numbers from 0 to 1, got '{s}'");
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    <[f32; 4]>::try_from(v).map_err(|_| bad())
}

/// The memory budget of a render (docs/reliability.md): `explicit` if given, else
/// `$REYES_MEMORY_LIMIT` (a size, e.g. `4G`), else
/// [`reyes_render::budget::default_memory_limit`].
pub fn memory_limit(explicit: Option<u64>) -> Result<Option<u64>, FarmError> {
    if explicit.is_some() {
        return Ok(explicit);
    }
    match std::env::var("REYES_MEMORY_LIMIT") {
        Ok(text) => reyes_render::budget::parse_size(&text)
            .map(Some)
            .map_err(|e| FarmError::invalid(format_args!("REYES_MEMORY_LIMIT: {}", one_line(e)))),
        Err(_) => Ok(reyes_render::budget::default_memory_limit()),
    }
}

/// Validate `scene` again after the override `flag` changed it.
fn revalidate(scene: Scene, path: &Path, flag: &str) -> Result<Scene, FarmError> {
    reyes_scene::validate(scene).map_err(|issue| {
        FarmError::invalid(format_args!(
            "{}: {flag}: {}: {}",
            one_line(path.display()),
            one_line(issue.path),
            one_line(issue.message)
        ))
    })
}

/// What to render.
#[derive(Debug, Clone, Default)]
pub struct Request {
    /// The scene file (RON or RIB; `-`: standard input).
    pub scene: PathBuf,
    /// The output (`.exr` or `.png`; frame numbers go in as [`frame_path`] puts them). None:
    /// each RIB frame's main `Display` name ([`crate::output::display_output`]).
    pub output: Option<PathBuf>,
    /// What a RIB file gets away with (unknown shaders, exporter noise) is an error.
    pub strict: bool,
    /// `Procedural "RunProgram"` may run the programs the scene names
    /// ([`reyes_rib::Permissions`]).
    pub allow_run_program: bool,
    /// The frames to render (None: every frame of a RIB file; a RON scene's one).
    pub frames: Option<FrameList>,
    /// The changes to each frame's scene.
    pub overrides: Overrides,
    /// Render this tile of each frame, to a tile file (.exr) instead of the frame's file.
    pub tile: Option<Tile>,
    /// Write each finished bucket under this directory, and resume from what it holds.
    pub checkpoint: Option<PathBuf>,
}

/// One frame to render: its scene (overrides applied), number and outputs.
#[derive(Debug, Clone)]
pub struct FramePlan {
    /// The scene of the frame, validated.
    pub scene: Scene,
    /// The frame number (a RIB `FrameBegin`, or a frame of an animated RON scene).
    pub number: Option<i32>,
    /// The frame's file (or tile file).
    pub main: PathBuf,
    /// The RIB file's extra outputs (`Display "+name"`), the same image.
    pub extras: Vec<PathBuf>,
    /// `main` is a picture; false for a frame whose only outputs are depth maps (`main` is
    /// then the first of them).
    pub image: bool,
    /// Its depth outputs ([`crate::depth`]).
    pub depth: Vec<crate::depth::DepthOutput>,
    /// The `Make*` requests to run before it renders.
    pub makes: Vec<reyes_rib::MakeJob>,
    /// For the last frame, the `Make*` requests after it in the file, to run after it.
    pub makes_after: Vec<reyes_rib::MakeJob>,
}

/// Load the scene of `request` and name every frame's outputs, before anything is rendered;
/// what the user should hear about goes to `warn`, one line each (a message repeated at
/// other places of a RIB file once, with the count of the others).
pub fn plan(request: &Request, warn: &mut dyn FnMut(String)) -> Result<Vec<FramePlan>, FarmError> {
    let r = request;
    if let Some(output) = &r.output {
        check_main(output, r.tile.is_some())?;
    }
    let options = RiOptions { strict: r.strict, frames: r.frames.clone().map(|f| f.0) };
    let permissions = reyes_rib::Permissions { run_program: r.allow_run_program };
    let loaded = match reyes_rib::load_scene_file_with(&r.scene, &options, permissions) {
        Ok(loaded) => loaded,
        Err(refused) => {
            // What was tolerated before the error often explains it: shown first.
            summarise(&refused.warnings, warn);
            return Err(refused.into());
        }
    };
    summarise(&loaded.warnings, warn);
    let scene_path = one_line(r.scene.display());
    if loaded.frames.is_empty() {
        // A file of `Make*` requests alone still makes its maps.
        crate::depth::run_makes(&loaded.makes_after, warn)?;
        return Err(FarmError::invalid(format_args!("{scene_path}: no frame to render")));
    }
    // Numbered names only for a file of several frames (and a pattern in the name): a
    // single-frame file's `-o out.exr` is out.exr. Without -o, each frame's own Display name
    // is numbered only when frames share one.
    let several = loaded.several_frames || loaded.frames.len() > 1;
    let numbered = if r.output.is_some() { several } else { several && loaded.display_repeats };
    let mut plans = Vec::with_capacity(loaded.frames.len());
    let mut makes_after = loaded.makes_after;
    let count = loaded.frames.len();
    for (k, frame) in loaded.frames.into_iter().enumerate() {
        let depth = crate::depth::outputs(&frame.displays);
        let pictures: Vec<reyes_rib::Display> = frame
            .displays
            .iter()
            .filter(|d| !reyes_rib::is_depth_driver(&d.driver))
            .cloned()
            .collect();
        let (output, image) = match &r.output {
            Some(output) => (output.clone(), true),
            None => match crate::output::display_output(&pictures, warn) {
                Some(named) => {
                    check_main(&named, r.tile.is_some())?;
                    (named, true)
                }
                None if !depth.is_empty() => (depth[0].path.clone(), false),
                None => {
                    return Err(FarmError::invalid(format_args!(
                        "{scene_path}: no output: the file names no Display, give -o OUT.exr"
                    )));
                }
            },
        };
        let scene =
            if depth.is_empty() { frame.scene } else { crate::depth::with_depth(frame.scene) };
        let scene = r.overrides.apply(scene, &r.scene)?;
        if let Some(w) = reyes_render::settings::pattern_fallback(&scene) {
            warn(format!("{scene_path}: warning: {w}"));
        }
        let main = if image { frame_path(&output, frame.number, numbered) } else { output.clone() };
        let mut extras = Vec::new();
        for d in pictures.iter().filter(|d| d.extra) {
            match extra_path(&output, &d.name, frame.number, numbered) {
                Some(path) => extras.push(path),
                None => warn(format!(
                    "{}: warning: Display: \"{}\" is not written: only .exr and .png outputs are",
                    d.at,
                    one_line(&d.name)
                )),
            }
        }
        let after = if k + 1 == count { std::mem::take(&mut makes_after) } else { Vec::new() };
        plans.push(FramePlan {
            scene,
            number: frame.number,
            main,
            extras,
            image,
            depth,
            makes: frame.makes,
            makes_after: after,
        });
    }
    // What a writer killed where the file system has no O_TMPFILE left behind.
    let mut dirs: Vec<PathBuf> = Vec::new();
    for path in plans.iter().flat_map(|p| std::iter::once(&p.main).chain(&p.extras)) {
        let dir = crate::output::directory_of(path);
        if !dirs.contains(&dir) {
            reyes_film::remove_stale_temporaries(&dir);
            dirs.push(dir);
        }
    }
    Ok(plans)
}

/// Check a main output before anything is rendered ([`check_output`]); a tile is .exr.
fn check_main(output: &Path, tile: bool) -> Result<(), FarmError> {
    check_output(output, tile)?;
    if tile && !is_exr(output) {
        return Err(FarmError::invalid(format_args!(
            "{}: --tile: a tile is written as .exr",
            one_line(output.display())
        )));
    }
    Ok(())
}

/// The scene of `path` (RON or RIB) when it has exactly one frame, for the commands that
/// read one scene without rendering it (`reyes-render measure`); the warnings go to `warn`
/// as [`plan`]'s do, also when the file is refused.
pub fn load_one_frame(path: &Path, warn: &mut dyn FnMut(String)) -> Result<Scene, FarmError> {
    let mut loaded = match reyes_rib::load_scene_file(path, &RiOptions::default()) {
        Ok(loaded) => loaded,
        Err(refused) => {
            summarise(&refused.warnings, warn);
            return Err(refused.into());
        }
    };
    summarise(&loaded.warnings, warn);
    match loaded.frames.len() {
        1 => Ok(loaded.frames.remove(0).scene),
        n => Err(FarmError::invalid(format_args!(
            "{}: the file has {n} frames; this command reads a file of one frame",
            one_line(path.display())
        ))),
    }
}

/// Scene warnings to `warn`, one line each; a message repeated at other places is given
/// once, at its first place, with the count of the others.
fn summarise(warnings: &[reyes_rib::Warning], warn: &mut dyn FnMut(String)) {
    let mut seen: Vec<(&str, usize, usize)> = Vec::new();
    for (i, w) in warnings.iter().enumerate() {
        match seen.iter_mut().find(|(m, _, _)| *m == w.message) {
            Some(entry) => entry.2 += 1,
            None => seen.push((&w.message, i, 0)),
        }
    }
    for (_, i, more) in seen {
        match more {
            0 => warn(warnings[i].to_string()),
            n => warn(format!("{} ({n} more like it)", warnings[i])),
        }
    }
}

/// What [`WriteHooks::after_first_chunk`] calls: with the file being written and its
/// temporary file's name (None: unnamed).
pub type FirstChunkHook<'a> = dyn Fn(&Path, Option<&Path>) + Sync + 'a;

/// How a frame's files are written ([`FrameJob::write`]).
#[derive(Default)]
pub struct WriteHooks<'a> {
    /// Polled before each chunk: once set, the write stops with
    /// [`reyes_film::FilmError::Interrupted`] and its temporary file is removed.
    pub cancel: Option<&'a AtomicBool>,
    /// Called once per file, right after its first chunk reached its temporary file, with
    /// the file and the temporary file's name (None: unnamed); a test hook.
    pub after_first_chunk: Option<&'a FirstChunkHook<'a>>,
    /// Write through a named temporary file even where an unnamed one is possible.
    pub named_temporary: bool,
}

/// A frame rendered, not yet written.
pub struct RenderedFrame {
    /// The render: film, AOVs, statistics, the kept buckets of a tile.
    pub rendered: Rendered,
    /// How long the render took.
    pub render_time: Duration,
    /// What the user should hear about the render (a displacement beyond its declared
    /// bound), one line each.
    pub warnings: Vec<String>,
}

/// One frame of a [`Request`] being rendered: the buckets it draws, its checkpoint, its
/// outputs.
pub struct FrameJob<'a> {
    request: &'a Request,
    frame: &'a FramePlan,
    scene_path: String,
    buckets: Vec<usize>,
    /// The header of its pieces, when it makes any (a tile, a checkpoint).
    header: Option<Header>,
    checkpoint: Option<Checkpoint>,
    /// The EXR beauty's blocks, compressed while the frame renders.
    early: Option<EarlyBlocks>,
}

impl<'a> FrameJob<'a> {
    /// Set up `frame` of `request`: its buckets (a tile's), and its checkpoint, read back
    /// (an unreadable bucket file is a line to `warn`).
    pub fn open(
        request: &'a Request,
        frame: &'a FramePlan,
        warn: &mut dyn FnMut(String),
    ) -> Result<FrameJob<'a>, FarmError> {
        // The maps the file makes before this frame (a multipass file's shadow maps).
        crate::depth::run_makes(&frame.makes, warn)?;
        let scene = &frame.scene;
        let scene_path = request.scene.display().to_string();
        let buckets = buckets_of(scene, request.tile).map_err(|e| {
            FarmError::invalid(format_args!("{}: {e}", one_line(request.scene.display())))
        })?;
        // The fingerprint serialises the whole scene: only pieces need it.
        let header = (request.tile.is_some() || request.checkpoint.is_some())
            .then(|| Header::new(scene, &scene_path, frame.number, request.tile));
        let checkpoint = match (&request.checkpoint, &header) {
            (Some(root), Some(h)) => {
                Some(Checkpoint::open(root, Header { tile: (0, 0), ..h.clone() }, warn)?)
            }
            _ => None,
        };
        // A whole frame's EXR beauty is compressed while the frame renders, block by block
        // as its lines are final (the write then stores those blocks as they are; the file
        // is the same bytes). Not for tiles (their files hold bucket windows) or crops, nor
        // under an imager shader, which changes every pixel after the last line is final.
        let exr_out = is_exr(&frame.main) || frame.extras.iter().any(|p| is_exr(p));
        let plain = request.tile.is_none() && scene.image.crop.is_none();
        let early = (exr_out && plain && scene.shaders.imager.is_none())
            .then(|| {
                let named = reyes_render::aovs::AovSetup::for_scene(scene).is_some();
                EarlyBlocks::new(scene.image.width, scene.image.height, &scene.outputs, named)
            })
            .flatten();
        Ok(FrameJob { request, frame, scene_path, buckets, header, checkpoint, early })
    }

    /// The buckets this run draws (a tile's, a crop window's or the frame's).
    pub fn total(&self) -> u64 {
        self.buckets.len() as u64
    }

    /// Of those, the buckets read back from the checkpoint.
    pub fn resumed(&self) -> u64 {
        let Some(c) = &self.checkpoint else { return 0 };
        self.buckets.iter().filter(|b| c.done().contains_key(b)).count() as u64
    }

    /// The label of the frame's progress lines ([`crate::progress::label`]).
    pub fn label(&self) -> String {
        crate::progress::label(self.frame.number, self.request.tile)
    }

    /// Render the frame with `threads` worker threads (None: one per core) within
    /// `memory_limit` bytes, calling `on_bucket` as each bucket finishes (from worker
    /// threads).
    pub fn render(
        &self,
        threads: Option<usize>,
        memory_limit: Option<u64>,
        on_bucket: &(dyn Fn() + Sync),
    ) -> Result<RenderedFrame, FarmError> {
        let save = |b: usize, r: &BucketResult| {
            if let Some(c) = &self.checkpoint {
                c.save(b, r);
            }
        };
        let encode_early = |film: &Film, lines: std::ops::Range<u32>| {
            if let Some(e) = &self.early {
                e.encode(film, lines);
            }
        };
        let checkpoint = self.checkpoint.as_ref();
        let opts = RenderOptions {
            threads,
            on_film_lines: self.early.as_ref().map(|_| &encode_early as &reyes_render::OnFilmLines),
            on_bucket: Some(on_bucket),
            memory_limit,
            buckets: Some(&self.buckets),
            done: checkpoint.map(Checkpoint::done),
            on_result: checkpoint.map(|_| &save as &reyes_render::OnResult),
            keep_buckets: self.request.tile.is_some(),
            shade_every_vertex: false,
            shader_budget: self.request.overrides.shader_max_ops,
        };
        let started = Instant::now();
        let rendered = reyes_render::render(&self.frame.scene, &opts);
        let render_time = started.elapsed();
        if let Some(failure) = checkpoint.and_then(Checkpoint::failure) {
            return Err(FarmError::Failed(failure));
        }
        let rendered = rendered
            .map_err(|source| FarmError::Render { scene: self.scene_path.clone(), source })?;
        let scene = one_line(&self.scene_path);
        let warnings = rendered.warnings.iter().map(|w| format!("{scene}: warning: {w}")).collect();
        Ok(RenderedFrame { rendered, render_time, warnings })
    }

    /// The files the frame is written to: a tile's one file, else the main output and the
    /// extra outputs.
    pub fn outputs(&self) -> Vec<&'a Path> {
        if !self.frame.image {
            return Vec::new();
        }
        let main = std::iter::once(self.frame.main.as_path());
        let extras = self.frame.extras.iter().map(PathBuf::as_path);
        let n = if self.request.tile.is_some() { 1 } else { 1 + self.frame.extras.len() };
        main.chain(extras).take(n).collect()
    }

    /// Write the rendered frame to each of its [`FrameJob::outputs`] in turn, atomically: a
    /// tile file (its directory made if missing), or the frame's picture; the time it took
    /// and the peak memory go into its statistics.
    pub fn write(&self, frame: &mut RenderedFrame, hooks: &WriteHooks) -> Result<(), FarmError> {
        let started = Instant::now();
        let scene = &self.frame.scene;
        let render_time = scene.outputs.render_time.then_some(frame.render_time.as_secs_f32());
        let rendered = &frame.rendered;
        for path in self.outputs() {
            let after_first_chunk = |temporary: Option<&Path>| {
                if let Some(hook) = hooks.after_first_chunk {
                    hook(path, temporary);
                }
            };
            let opts = WriteOptions {
                cancel: hooks.cancel,
                after_first_chunk: Some(&after_first_chunk),
                named_temporary: hooks.named_temporary,
            };
            if let (Some(_), Some(header)) = (self.request.tile, &self.header) {
                create_directory_of(path)?;
                let header = Header { render_time, ..header.clone() };
                write_piece(path, &header, &rendered.buckets, &opts)?;
            } else {
                let picture = FramePicture {
                    scene,
                    scene_path: &self.scene_path,
                    film: &rendered.film,
                    aovs: rendered.aovs.as_ref().map(|a| (&a.film, a.layers.as_slice())),
                    render_time,
                    early: self.early.as_ref(),
                };
                picture.write(path, &opts)?;
            }
        }
        if self.request.tile.is_none() {
            crate::depth::write(scene, &frame.rendered, &self.frame.depth)?;
        }
        frame.rendered.stats.t_write = started.elapsed();
        frame.rendered.stats.peak_memory = reyes_render::peak_memory();
        Ok(())
    }

    /// Every output is written: with `announce`, name each file written, one line each to
    /// `say`; remove the checkpoint (a folder that cannot be removed is a line to `say`); run
    /// the `Make*` requests after the file's last frame.
    ///
    /// # Errors
    ///
    /// A `Make*` request after the file's last frame cannot make its map.
    pub fn finish(self, announce: bool, say: &mut dyn FnMut(String)) -> Result<(), FarmError> {
        if announce {
            let depth = self.frame.depth.iter().map(|d| d.path.as_path());
            for path in self.outputs().into_iter().chain(depth) {
                say(format!("wrote {}", one_line(path.display())));
            }
        }
        if let Some(c) = self.checkpoint {
            c.finish(say);
        }
        crate::depth::run_makes(&self.frame.makes_after, say)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn override_texts_parse() {
        assert_eq!(parse_samples("4x2"), Ok((4, 2)));
        assert_eq!(parse_samples(" 8 X 8 "), Ok((8, 8)));
        for bad in ["0x4", "4", "65x1", "axb"] {
            assert!(parse_samples(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_crop("0, 0.5,0.25,1"), Ok([0.0, 0.5, 0.25, 1.0]));
        assert!(parse_crop("0,1").is_err() && parse_crop("0,1,a,1").is_err());
    }

    #[test]
    fn overrides_apply_and_are_validated_again() {
        let scene = crate::test_scene();
        let crop = Some([0.0, 0.5, 0.0, 1.0]);
        let o = Overrides {
            seed: Some(9),
            samples: Some((3, 3)),
            crop,
            z_infinite: true,
            ..Overrides::default()
        };
        let s = o.apply(scene.clone(), Path::new("t.ron")).expect("valid");
        assert_eq!((s.hider.seed, s.hider.pixel_samples, s.image.crop), (9, (3, 3), crop));
        assert!(matches!(s.outputs.zbackground, reyes_scene::ZBackground::Infinite));
        let empty = Overrides { crop: Some([0.5, 0.5, 0.0, 1.0]), ..Overrides::default() };
        let e = empty.apply(scene, Path::new("t.ron")).expect_err("an empty crop");
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().starts_with("t.ron: --crop 0.5,0.5,0,1: image.crop: "), "{e}");
    }
}
