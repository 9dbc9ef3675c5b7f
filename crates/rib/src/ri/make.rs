//! `MakeTexture`, `MakeBump`, `MakeLatLongEnvironment`, `MakeCubeFaceEnvironment` and
//! `MakeShadow` (Spec 3.2, 4.3): prepared textures made when the request is read
//! (reyes-texture's `make`), so that the frames after it find them.
//!
//! Names resolve as archives do: relative to the RIB file naming them. A picture that cannot
//! be made into a map is an error naming the request; `MakeShadow` of a depth map that does
//! not exist yet (a multipass file whose depth pass is a frame of the same file: frames render
//! after the whole file is read, so its depth map is not there) is a warning, and the shadow
//! lookups of that map then read unshadowed with a warning of their own.
//! `MakeBump` is not supported (a warning): bump maps are PRMan's, and no shader of the
//! Specification reads one.

use reyes_texture::Wrap;
use reyes_texture::make::{MakeOptions, make_cube, make_latlong, make_shadow, make_texture};
use reyes_texture::prepared::wrap_of;

use super::frame::Machine;
use crate::{Request, RequestKind as K, RibError};

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
        let result = match r.kind {
            K::MakeTexture => {
                let opts = MakeOptions {
                    wrap: [wrap(2)?, wrap(3)?],
                    filter: filter(4),
                    width: widths(5),
                    ..MakeOptions::default()
                };
                make_texture(&path(self, 0)?, &path(self, 1)?, &opts)
            }
            K::MakeLatLongEnvironment => {
                let opts =
                    MakeOptions { filter: filter(2), width: widths(3), ..MakeOptions::default() };
                make_latlong(&path(self, 0)?, &path(self, 1)?, &opts)
            }
            K::MakeCubeFaceEnvironment => {
                let faces: Vec<_> = (0..6).map(|i| path(self, i)).collect::<Result<_, _>>()?;
                let opts = MakeOptions {
                    fov: r.float(7).unwrap_or(90.0),
                    filter: filter(8),
                    width: widths(9),
                    ..MakeOptions::default()
                };
                let faces: [&std::path::Path; 6] = std::array::from_fn(|k| faces[k].as_path());
                make_cube(faces, &path(self, 6)?, &opts)
            }
            K::MakeShadow => {
                let src = path(self, 0)?;
                if !src.exists() {
                    let w = r.warning(format!(
                        "the depth map {} does not exist (a depth pass of this file renders after the whole file is read, and Display \"zfile\" is not written yet): no shadow map is made",
                        src.display()
                    ));
                    self.warnings.push(w);
                    return Ok(());
                }
                make_shadow(&src, &path(self, 1)?)
            }
            _ => {
                let w = r.warning("not supported (bump maps): ignored");
                self.warn_once(format!("request {}", r.name()), w);
                return Ok(());
            }
        };
        result.map_err(|e| r.error(e.to_string()))
    }
}
