//! Golden-image regression: render each scene of `golden/manifest.ron` at its reduced size and
//! compare with the blessed reference `golden/NAME.exr`.
//!
//! Tolerance, from what can legitimately differ: the renderer is deterministic, so on one
//! machine the render is bit-identical; across machines only floating-point details
//! (transcendental functions in shading and filters, fused multiply-add) can differ. Such a
//! difference can at worst flip one sample across an edge, which moves a pixel by at most the
//! largest filter-table weight times the sample's value. So the per-channel maximum absolute
//! error allowed is `w_max * max(1, peak)` (one flipped sample in a pixel), and the mean
//! absolute error allowed is that divided by 100 (such flips in at most 1% of pixels). A real
//! regression (a shifted edge, a wrong colour, a lost object) exceeds both.
//!
//! A scene that writes AOVs has every layer compared too ([`check_aovs`]): a layer filtered
//! with the beauty's filter under the same rule (its own peak); a layer of a pixel-own filter
//! (`Zmin`, `Nearest`, `Min`, `Max`: ids, depth), where one flipped sample can change a pixel
//! entirely, by the number of pixels that differ, at most 1%. Half layers are compared after
//! rounding the render to half, as the reference was stored. A layer stored with lossy DWAA
//! compression differs from the render by the codec's quantisation, which the format does not
//! bound: it is checked only against gross regressions, a mean error of at most 0.5% and a
//! maximum of 10% of the layer's peak (the codec's measured error on `aovs.ron` is a mean of
//! 0.06% and a maximum of 1.7%).

use std::path::{Path, PathBuf};

use reyes_film::Film;
use serde::Deserialize;

use reyes_render::settings::Stages;
use reyes_render::{RenderOptions, render};

/// One golden case.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Scene name: `scenes/NAME.ron` (else `scenes/NAME.rib`), reference `golden/NAME.exr`.
    pub scene: String,
    /// Render width (at most about 256).
    pub width: u32,
    /// Render height.
    pub height: u32,
    /// Render with this hider instead of the scene's own (so one scene can have a golden
    /// image from each hider); the reference is then `golden/NAME-raytraced.exr` or
    /// `golden/NAME-stochastic.exr`.
    #[serde(default)]
    pub method: Option<reyes_scene::HiderMethod>,
    /// The frame rendered of an animated scene (one with `${...}` expressions,
    /// docs/scene-format.md#animation), which needs one; the reference is then
    /// `golden/NAME-frameN.exr`.
    #[serde(default)]
    pub frame: Option<i32>,
}

impl Case {
    /// The case's name: the scene's, with the hider appended when it is overridden.
    pub fn name(&self) -> String {
        let scene = match self.frame {
            None => self.scene.clone(),
            Some(n) => format!("{}-frame{n}", self.scene),
        };
        match self.method {
            None => scene,
            Some(reyes_scene::HiderMethod::Stochastic) => format!("{scene}-stochastic"),
            Some(reyes_scene::HiderMethod::RayTrace) => format!("{scene}-raytraced"),
        }
    }
}

/// Per-channel comparison of two images.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// Mean absolute error of R, G, B, A.
    pub mean: [f32; 4],
    /// Maximum absolute error of R, G, B, A.
    pub max: [f32; 4],
    /// Allowed mean.
    pub mean_tolerance: f32,
    /// Allowed maximum.
    pub max_tolerance: f32,
}

impl Comparison {
    /// Within tolerance.
    pub fn passed(&self) -> bool {
        self.mean.iter().all(|&m| m <= self.mean_tolerance)
            && self.max.iter().all(|&m| m <= self.max_tolerance)
    }
}

/// Errors of the golden harness (one line each).
#[derive(Debug)]
pub struct GoldenError(pub String);

impl std::fmt::Display for GoldenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for GoldenError {}

fn err(e: impl std::fmt::Display) -> GoldenError {
    GoldenError(e.to_string())
}

/// The workspace root (where `golden/` and `scenes/` are).
pub fn workspace_root() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    root.canonicalize().unwrap_or(root)
}

/// Reads, parses and validates the scene file at `path` as [`reyes_scene::load`] does, an
/// animated one (with `${...}` expressions) at frame `frame`, which it then needs; a frame
/// given for a scene that is not animated changes nothing.
pub fn load_scene(
    path: &Path,
    frame: Option<i32>,
) -> Result<reyes_scene::Scene, reyes_scene::LoadError> {
    let text = reyes_scene::read_text(path)?;
    if !reyes_scene::animate::is_animated(&text) {
        return reyes_scene::parse_files(&text, path);
    }
    let Some(frame) = frame else {
        return Err(reyes_scene::SceneError {
            file: path.to_path_buf(),
            line: None,
            col: None,
            field: "${...}".into(),
            message: "the scene is animated: give the frame to render".into(),
        }
        .into());
    };
    let text = reyes_scene::animate::substitute(&text, frame, path)?;
    reyes_scene::parse_files(&text, path)
}

/// Read `golden/manifest.ron`.
pub fn manifest(root: &Path) -> Result<Vec<Case>, GoldenError> {
    let path = root.join("golden/manifest.ron");
    let text =
        std::fs::read_to_string(&path).map_err(|e| err(format!("{}: {e}", path.display())))?;
    ron::from_str(&text).map_err(|e| err(format!("{}: {e}", path.display())))
}

/// Render a case: its scene at the case's size (the fov spans the shorter side, so the
/// framing is kept when the aspect ratio is), on all cores.
pub fn render_case(root: &Path, case: &Case) -> Result<(Film, f32), GoldenError> {
    let scene = case_scene(root, case)?;
    let film = render(&scene, &RenderOptions::default()).map_err(err)?.film;
    Ok((film, max_weight(&scene)?))
}

/// The case's scene at the case's size.
fn case_scene(root: &Path, case: &Case) -> Result<reyes_scene::Scene, GoldenError> {
    let path = root.join("scenes").join(format!("{}.ron", case.scene));
    let rib = root.join("scenes").join(format!("{}.rib", case.scene));
    // A scene only in RIB (one whose shaders RON cannot name): its first frame.
    let mut scene = if !path.exists() && rib.exists() {
        let source = reyes_rib::Source::open(&rib).map_err(err)?;
        let loaded = reyes_rib::load(source, &reyes_rib::RiOptions::default()).map_err(err)?;
        loaded.frames.into_iter().next().ok_or_else(|| err("the RIB file has no frame"))?.scene
    } else {
        load_scene(&path, case.frame).map_err(err)?
    };
    scene.image.width = case.width;
    scene.image.height = case.height;
    if let Some(method) = case.method {
        scene.hider.method = method;
    }
    Ok(scene)
}

/// Compare every AOV layer of a case whose scene writes AOVs with the reference's layer of
/// the same name (see the module documentation). Returns one line per failing layer (empty:
/// all pass, or the scene writes no AOVs).
pub fn check_aovs(root: &Path, case: &Case) -> Result<Vec<String>, GoldenError> {
    let scene = case_scene(root, case)?;
    if scene.outputs.aovs.is_empty() {
        return Ok(Vec::new());
    }
    let w_max = max_weight(&scene)?;
    let rendered = render(&scene, &RenderOptions::default()).map_err(err)?;
    let Some(aovs) = rendered.aovs else { return Err(err("the scene's AOVs were not rendered")) };
    let reference_path = root.join("golden").join(format!("{}.exr", case.name()));
    let reference = reyes_film::read_layers(&reference_path).map_err(err)?;
    let n = (case.width * case.height) as usize;
    let mut failures = Vec::new();
    for (layer, aov) in aovs.layers.iter().zip(&scene.outputs.aovs) {
        let pixel_own = aov.filter_or_default() != reyes_scene::AovFilter::Filter;
        for (k, c) in layer.channels.iter().enumerate() {
            let name = format!("{}.{c}", layer.name);
            let Some(r) = reference.iter().find(|r| r.name == name) else {
                failures.push(format!("{name}: not in the reference"));
                continue;
            };
            if r.values.len() != n {
                failures.push(format!("{name}: {} pixels, expected {n}", r.values.len()));
                continue;
            }
            let actual =
                aovs.film.data().iter().skip(layer.start + k).step_by(aovs.film.channels());
            let actual = actual.map(|&v| reyes_film::as_stored(v, r.half));
            let (mut sum, mut max, mut differ, mut peak) = (0.0f64, 0.0f32, 0usize, 1.0f32);
            for (a, &b) in actual.zip(&r.values) {
                let d = (a - b).abs();
                let d = if d.is_nan() { f32::INFINITY } else { d };
                sum += f64::from(d);
                max = max.max(d);
                differ += usize::from(a.to_bits() != b.to_bits());
                peak = peak.max(b.abs());
            }
            let mean = (sum / n as f64) as f32;
            if layer.compression == reyes_scene::Compression::Dwaa {
                if mean > 5e-3 * peak || max > 0.1 * peak {
                    failures.push(format!(
                        "{name} (DWAA): mean error {mean:.3e}, max {max:.3e} (allowed {:.3e}, {:.3e})",
                        5e-3 * peak,
                        0.1 * peak
                    ));
                }
            } else if pixel_own {
                if differ * 100 > n {
                    failures.push(format!("{name}: {differ} of {n} pixels differ (at most 1%)"));
                }
            } else if max > w_max * peak || mean > w_max * peak / 100.0 {
                failures.push(format!(
                    "{name}: mean error {mean:.3e}, max {max:.3e} (allowed {:.3e}, {:.3e})",
                    w_max * peak / 100.0,
                    w_max * peak
                ));
            }
        }
    }
    Ok(failures)
}

/// The largest filter-table weight (in magnitude) of `scene`'s hider, the `w_max` of the
/// tolerance.
pub fn max_weight(scene: &reyes_scene::Scene) -> Result<f32, GoldenError> {
    let table = Stages::new(scene, |hider| hider).map_err(err)?.table;
    Ok(table.weights().iter().fold(0.0f32, |m, &w| m.max(w.abs())))
}

/// Compare `actual` with `reference` under the tolerance for filter weight `w_max`.
pub fn compare(actual: &Film, reference: &Film, w_max: f32) -> Result<Comparison, GoldenError> {
    if (actual.width(), actual.height()) != (reference.width(), reference.height()) {
        return Err(err(format!(
            "size {}x{} differs from the reference's {}x{}",
            actual.width(),
            actual.height(),
            reference.width(),
            reference.height()
        )));
    }
    let mut mean = [0.0f64; 4];
    let mut max = [0.0f32; 4];
    let mut peak = 1.0f32;
    for (a, r) in actual.rgba().iter().zip(reference.rgba()) {
        for c in 0..4 {
            let d = (a[c] - r[c]).abs();
            let d = if d.is_nan() { f32::INFINITY } else { d };
            mean[c] += d as f64;
            max[c] = max[c].max(d);
            peak = peak.max(r[c].abs());
        }
    }
    let n = actual.rgba().len().max(1) as f64;
    let max_tolerance = w_max * peak;
    Ok(Comparison {
        mean: mean.map(|m| (m / n) as f32),
        max,
        mean_tolerance: max_tolerance / 100.0,
        max_tolerance,
    })
}

/// Result of checking one case.
pub enum Outcome {
    /// Within tolerance.
    Pass(Comparison),
    /// Outside tolerance; the actual image and a difference image were written.
    Fail(Comparison, PathBuf),
    /// No reference exists.
    Missing(PathBuf),
}

/// Where failures are written.
pub fn out_dir(root: &Path) -> PathBuf {
    root.join("target/golden")
}

/// Check one case against its reference.
pub fn check(root: &Path, case: &Case) -> Result<Outcome, GoldenError> {
    let reference_path = root.join("golden").join(format!("{}.exr", case.name()));
    let (actual, w_max) = render_case(root, case)?;
    if !reference_path.exists() {
        return Ok(Outcome::Missing(reference_path));
    }
    let reference = reyes_film::read_exr(&reference_path).map_err(err)?;
    let cmp = compare(&actual, &reference, w_max)?;
    if cmp.passed() {
        return Ok(Outcome::Pass(cmp));
    }
    let dir = out_dir(root);
    std::fs::create_dir_all(&dir).map_err(|e| err(format!("{}: {e}", dir.display())))?;
    let actual_path = dir.join(format!("{}.actual.exr", case.name()));
    reyes_film::write(&actual_path, &actual).map_err(err)?;
    let diff = difference(&actual, &reference);
    reyes_film::write(&dir.join(format!("{}.diff.png", case.name())), &diff).map_err(err)?;
    Ok(Outcome::Fail(cmp, actual_path))
}

/// Absolute difference image, scaled by 10 so small differences show.
pub fn difference(a: &Film, b: &Film) -> Film {
    let rgba: Vec<[f32; 4]> = a
        .rgba()
        .iter()
        .zip(b.rgba())
        .map(|(p, q)| {
            [
                10.0 * (p[0] - q[0]).abs(),
                10.0 * (p[1] - q[1]).abs(),
                10.0 * (p[2] - q[2]).abs(),
                1.0,
            ]
        })
        .collect();
    let z = vec![f32::INFINITY; rgba.len()];
    Film::from_pixels(a.width(), a.height(), rgba, z)
        .unwrap_or_else(|| Film::new(a.width(), a.height()))
}

/// Render a case and write it as the new reference, plus a PNG beside it in `target/golden`
/// to look at. Returns the PNG path.
pub fn bless(root: &Path, case: &Case) -> Result<PathBuf, GoldenError> {
    let scene = case_scene(root, case)?;
    let rendered = render(&scene, &RenderOptions::default()).map_err(err)?;
    let film = rendered.film;
    let reference = root.join("golden").join(format!("{}.exr", case.name()));
    match &rendered.aovs {
        // Every layer, as the binary writes it (the metadata names the scene file).
        Some(aovs) => {
            let name = format!("scenes/{}.ron", case.scene);
            let metadata = reyes_film::Metadata::for_scene(&scene, &name);
            let picture = reyes_film::Picture {
                film: &film,
                aovs: Some((&aovs.film, &aovs.layers)),
                outputs: &scene.outputs,
                metadata: &metadata,
                placement: None,
                early: None,
            };
            reyes_film::write_picture(&reference, &picture, &Default::default()).map_err(err)?;
        }
        None => reyes_film::write(&reference, &film).map_err(err)?,
    }
    let dir = out_dir(root);
    std::fs::create_dir_all(&dir).map_err(|e| err(format!("{}: {e}", dir.display())))?;
    let png = dir.join(format!("{}.png", case.name()));
    reyes_film::write(&png, &film).map_err(err)?;
    Ok(png)
}
