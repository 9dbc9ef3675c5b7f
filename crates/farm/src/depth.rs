//! Depth outputs of a frame (`Display "name" "zfile" "z"` and `"shadow" "z"`) and the
//! `Make*` requests of a multipass RIB file, run in their place among the frames.
//!
//! A depth output is the frame's camera-space depth per pixel, the least over the pixel's
//! own samples (RenderMan's `depthfilter "min"`, its default), written with Pixar's two
//! matrices ([`reyes_dice::depth_map_matrices`]): a `"zfile"` as a plain float map for
//! `MakeShadow`, a `"shadow"` as a shadow map `shadow()` reads directly. Pixels where the
//! frame sees nothing hold the scene's `zbackground` (infinite by default: never a
//! shadow). Like the maps a file makes, its names resolve relative to the RIB file. The
//! depth is rendered as an AOV of the frame's scene ([`DEPTH_LAYER`]), written to its EXR
//! too when the frame also has a picture.

use std::path::{Path, PathBuf};

use reyes_rib::{Display, MakeJob, is_depth_driver};
use reyes_scene::{Aov, AovFilter, AovSource, Scene};
use reyes_texture::prepared::MapKind;

use crate::{FarmError, one_line};

/// The AOV layer the depth outputs are read from.
pub const DEPTH_LAYER: &str = "depthmap";

/// One depth output of a frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DepthOutput {
    /// The file, resolved relative to the RIB file that named it.
    pub path: PathBuf,
    /// A shadow map (`"shadow"`), else a depth map for `MakeShadow` (`"zfile"`).
    pub shadow: bool,
}

/// The depth outputs among a frame's `displays`.
pub fn outputs(displays: &[Display]) -> Vec<DepthOutput> {
    displays
        .iter()
        .filter(|d| is_depth_driver(&d.driver))
        .map(|d| {
            let dir = Path::new(&*d.at.file).parent().unwrap_or(Path::new(""));
            DepthOutput { path: dir.join(&d.name), shadow: d.driver.eq_ignore_ascii_case("shadow") }
        })
        .collect()
}

/// `scene` rendering its depth for depth outputs: the [`DEPTH_LAYER`] AOV.
pub fn with_depth(mut scene: Scene) -> Scene {
    let mut aov = Aov::new(AovSource::Z);
    aov.name = Some(DEPTH_LAYER.to_string());
    aov.filter = Some(AovFilter::Min);
    scene.outputs.aovs.push(aov);
    scene
}

/// Write the depth outputs `outputs` of the rendered frame of `scene`.
pub fn write(
    scene: &Scene,
    rendered: &reyes_render::Rendered,
    outputs: &[DepthOutput],
) -> Result<(), FarmError> {
    if outputs.is_empty() {
        return Ok(());
    }
    let missing = || FarmError::failed(format_args!("the frame's depth was not rendered"));
    let aovs = rendered.aovs.as_ref().ok_or_else(missing)?;
    let layer = aovs.layers.iter().find(|l| l.name == DEPTH_LAYER).ok_or_else(missing)?;
    let film = &aovs.film;
    let (w, h, ch) = (film.width(), film.height(), film.channels());
    let z: Vec<f32> = film.data().chunks(ch).map(|p| p[layer.start]).collect();
    let (world_to_screen, world_to_camera) = reyes_dice::depth_map_matrices(scene);
    for out in outputs {
        let kind = if out.shadow { MapKind::Shadow } else { MapKind::Plain };
        reyes_texture::make::write_depth(
            &out.path,
            w,
            h,
            &z,
            world_to_screen,
            world_to_camera,
            kind,
        )
        .map_err(|e| FarmError::failed(format_args!("{}: {e}", one_line(out.path.display()))))?;
    }
    Ok(())
}

/// Run the `Make*` requests `makes` in order: a warning (a depth map no frame wrote) to
/// `warn`.
///
/// # Errors
///
/// A map cannot be made: the request's one-line error.
pub fn run_makes(makes: &[MakeJob], warn: &mut dyn FnMut(String)) -> Result<(), FarmError> {
    for job in makes {
        match job.run() {
            Ok(Some(w)) => warn(w),
            Ok(None) => {}
            Err(e) => return Err(FarmError::invalid(format_args!("{e}"))),
        }
    }
    Ok(())
}
