//! `MakeTexture`, `MakeBump`, `MakeLatLongEnvironment`, `MakeCubeFaceEnvironment` and
//! `MakeShadow` (Spec 3.2, 4.3): prepared textures (reyes-texture's `make`), made in file
//! order with the frames: each request is a [`MakeJob`] run after the frames before it have
//! rendered and before the frames after it, so that a multipass file's `MakeShadow` finds the
//! depth map its own earlier frame wrote (`Display "zfile"`), and a later frame its map.
//!
//! Names resolve as archives do: relative to the RIB file naming them (so do depth outputs,
//! [`Multipass`]). A request's arguments are checked when it is read; a picture that cannot be
//! made into a map is an error naming the request when it runs. `MakeShadow` of a depth map
//! that does not exist then (its depth pass not rendered: `--frames` left it out) is a
//! warning, and the shadow lookups of that map read unshadowed with a warning of their own.
//! `MakeBump` is not supported (a warning): bump maps are PRMan's, and no shader of the
//! Specification reads one.

use std::path::{Path, PathBuf};

use reyes_texture::Wrap;
use reyes_texture::make::{
    MakeOptions, check_options, make_cube, make_latlong, make_shadow, make_texture,
};
use reyes_texture::prepared::wrap_of;

use super::frame::Machine;
use crate::{Request, RequestKind as K, RibError};

/// One `Make*` request, its names resolved and its arguments checked, to run in its place
/// among the frames ([`MakeJob::run`]).
#[derive(Debug, Clone)]
pub struct MakeJob {
    /// `file:line:col` of the request, and its name: the start of its messages.
    at: String,
    name: &'static str,
    what: Make,
}

#[derive(Debug, Clone)]
enum Make {
    Texture(PathBuf, PathBuf, MakeOptions),
    LatLong(PathBuf, PathBuf, MakeOptions),
    Cube([PathBuf; 6], PathBuf, MakeOptions),
    Shadow(PathBuf, PathBuf),
}

impl MakeJob {
    /// Make the map: `Ok(Some(warning))` for a `MakeShadow` whose depth map does not exist
    /// (nothing is made), an error (one line, naming the request) when the map cannot be
    /// made.
    ///
    /// # Errors
    ///
    /// The picture cannot be read or made into a map, or the map cannot be written.
    pub fn run(&self) -> Result<Option<String>, String> {
        let result = match &self.what {
            Make::Texture(src, out, o) => make_texture(src, out, o),
            Make::LatLong(src, out, o) => make_latlong(src, out, o),
            Make::Cube(faces, out, o) => {
                make_cube(std::array::from_fn(|k| faces[k].as_path()), out, o)
            }
            Make::Shadow(src, out) => {
                if !src.exists() {
                    return Ok(Some(format!(
                        "{}: warning: {}: the depth map {} does not exist (no frame wrote it): no shadow map is made",
                        self.at,
                        self.name,
                        src.display()
                    )));
                }
                make_shadow(src, out)
            }
        };
        result.map(|()| None).map_err(|e| format!("{}: {}: {e}", self.at, self.name))
    }

    /// The file it makes.
    pub fn output(&self) -> &Path {
        match &self.what {
            Make::Texture(_, out, _) | Make::LatLong(_, out, _) | Make::Cube(_, out, _) => out,
            Make::Shadow(_, out) => out,
        }
    }
}

/// The multipass bookkeeping of a file being read: the `Make*` requests since the last frame
/// built (they run before the next one), and the files the file's own frames and requests
/// will write (depth outputs, made maps), which its shaders may name before they exist.
#[derive(Debug, Default)]
pub(crate) struct Multipass {
    pub(crate) pending: Vec<MakeJob>,
    pub(crate) made: Vec<PathBuf>,
}

/// True for a `Display` driver that writes a depth map (`"zfile"`) or a shadow map
/// (`"shadow"`).
pub fn is_depth_driver(driver: &str) -> bool {
    driver.eq_ignore_ascii_case("zfile") || driver.eq_ignore_ascii_case("shadow")
}

impl Machine {
    /// One of the `Make*` requests.
    pub(super) fn make(&mut self, r: &Request) -> Result<(), RibError> {
        let path = |m: &Self, i: usize| -> Result<std::path::PathBuf, RibError> {
            let name = r
                .string(i)
                .ok_or_else(|| r.error(format!("argument {} must be a file name", i + 1)))?;
            Ok(m.reader.resolve_archive(name, &r.at))
        };
        let wrap = |i: usize| -> Result<Wrap, RibError> {
            let w = r.string(i).unwrap_or("periodic");
            wrap_of(w).ok_or_else(|| {
                r.error(format!("unknown wrap mode \"{w}\" (periodic, clamp or black)"))
            })
        };
        let filter = |i: usize| r.string(i).unwrap_or("box").to_string();
        let widths = |i: usize| [r.float(i).unwrap_or(1.0), r.float(i + 1).unwrap_or(1.0)];
        let what = match r.kind {
            K::MakeTexture => {
                let opts = MakeOptions {
                    wrap: [wrap(2)?, wrap(3)?],
                    filter: filter(4),
                    width: widths(5),
                    ..MakeOptions::default()
                };
                Make::Texture(path(self, 0)?, path(self, 1)?, opts)
            }
            K::MakeLatLongEnvironment => {
                let opts =
                    MakeOptions { filter: filter(2), width: widths(3), ..MakeOptions::default() };
                Make::LatLong(path(self, 0)?, path(self, 1)?, opts)
            }
            K::MakeCubeFaceEnvironment => {
                let faces: Vec<_> = (0..6).map(|i| path(self, i)).collect::<Result<_, _>>()?;
                let opts = MakeOptions {
                    fov: r.float(7).unwrap_or(90.0),
                    filter: filter(8),
                    width: widths(9),
                    ..MakeOptions::default()
                };
                let faces: [PathBuf; 6] = std::array::from_fn(|k| faces[k].clone());
                Make::Cube(faces, path(self, 6)?, opts)
            }
            K::MakeShadow => Make::Shadow(path(self, 0)?, path(self, 1)?),
            _ => {
                let w = r.warning("not supported (bump maps): ignored");
                self.warn_once(format!("request {}", r.name()), w);
                return Ok(());
            }
        };
        // The options are checked now, the pictures when the request runs.
        let opts = match &what {
            Make::Texture(_, out, o) | Make::LatLong(_, out, o) | Make::Cube(_, out, o) => {
                Some((o, out))
            }
            Make::Shadow(..) => None,
        };
        if let Some((o, out)) = opts {
            check_options(o, out).map_err(|e| r.error(e.to_string()))?;
        }
        let job = MakeJob { at: r.at.to_string(), name: r.name(), what };
        self.multipass.made.push(job.output().to_path_buf());
        self.multipass.pending.push(job);
        Ok(())
    }
}
