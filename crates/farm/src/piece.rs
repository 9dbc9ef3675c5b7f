//! Pieces of a frame (docs/farm.md): the header every tile and checkpoint bucket file
//! carries, and those files written and read back. The file itself (whole bucket windows in
//! a multi-part OpenEXR file) is [`reyes_film::tiles`].
//!
//! Invariant: a piece holds every one of its buckets' windows whole, border included, bit for
//! bit, and its header names the render it belongs to ([`fingerprint()`]) and carries the
//! scene settings the merge needs, so a piece is never mixed into another render.

use std::path::{Path, PathBuf};

use reyes_film::{FilmError, StoredBucket, WriteOptions};
use reyes_render::BucketResult;
use reyes_scene::Scene;
use serde::{Deserialize, Serialize};

use crate::{FarmError, Tile, VERSION, fingerprint, one_line};

/// What every tile and checkpoint file says about the render it is a piece of.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Header {
    /// The renderer's version: pieces of different versions are never mixed.
    pub version: String,
    /// [`fingerprint()`] of the render.
    pub fingerprint: String,
    /// `(i, n)`: tile i of n; `(0, 0)` for a checkpoint's bucket file.
    pub tile: (usize, usize),
    /// The frame number (a RIB frame, or a frame of an animated RON scene).
    pub frame: Option<i32>,
    /// The scene file as the front end named it (the output's metadata names it).
    pub scene_path: String,
    /// Render time of the piece in seconds, when the scene writes render times.
    pub render_time: Option<f32>,
    /// The scene's settings (image, camera, hider, outputs, lights), without its geometry:
    /// all the merge needs to write the frame's file.
    pub scene: Scene,
}

impl Header {
    /// The header of tile `tile` (None: a checkpoint's bucket file) of frame `frame` of
    /// `scene`, read from the file the front end names `scene_path`.
    pub fn new(scene: &Scene, scene_path: &str, frame: Option<i32>, tile: Option<Tile>) -> Header {
        let mut settings = scene.clone();
        settings.objects.clear();
        settings.solids.clear();
        Header {
            version: VERSION.to_string(),
            fingerprint: fingerprint(scene),
            tile: tile.map_or((0, 0), |t| (t.index, t.count)),
            frame,
            scene_path: scene_path.to_string(),
            render_time: None,
            scene: settings,
        }
    }

    /// The header as the file stores it (RON).
    pub fn to_text(&self) -> String {
        ron::to_string(self).unwrap_or_default()
    }

    /// The header `text` of the file `path`; its scene settings must validate (the merge
    /// lays out buckets and writes a file from them).
    pub fn parse(path: &Path, text: &str) -> Result<Header, FarmError> {
        let path = one_line(path.display());
        let header: Header = ron::from_str(text).map_err(|e| {
            FarmError::invalid(format_args!(
                "{path}: reyesTile: not a tile header of this version: {}",
                one_line(e)
            ))
        })?;
        if let Err(issue) = reyes_scene::validate(header.scene.clone()) {
            return Err(FarmError::invalid(format_args!(
                "{path}: reyesTile: scene.{}: {}",
                one_line(issue.path),
                one_line(issue.message)
            )));
        }
        Ok(header)
    }
}

/// What the buckets of a piece add to the film, over the pixels they cover (its part 0, a
/// picture a person can open), and where that picture's top-left pixel is.
fn preview(
    width: u32,
    height: u32,
    results: &[(usize, BucketResult)],
) -> (reyes_film::Film, (u32, u32)) {
    let (film, _) =
        reyes_render::buckets::assemble(width, height, None, results.iter().map(|(_, r)| r));
    let mut rect: Option<[i64; 4]> = None;
    for w in results.iter().filter_map(|(_, r)| r.window.as_ref()) {
        let r = [
            i64::from(w.x0),
            i64::from(w.x0) + i64::from(w.w),
            i64::from(w.y0),
            i64::from(w.y0) + i64::from(w.h),
        ];
        rect = Some(match rect {
            None => r,
            Some(q) => [q[0].min(r[0]), q[1].max(r[1]), q[2].min(r[2]), q[3].max(r[3])],
        });
    }
    let clip = |v: i64, n: u32| v.clamp(0, i64::from(n)) as u32;
    let [x0, x1, y0, y1] = match rect {
        Some([a, b, c, d]) => [clip(a, width), clip(b, width), clip(c, height), clip(d, height)],
        None => [0, 0, 0, 0],
    };
    if x0 >= x1 || y0 >= y1 {
        return (film.crop([0, 1.min(width), 0, 1.min(height)]), (0, 0));
    }
    (film.crop([x0, x1, y0, y1]), (x0, y0))
}

/// Write the bucket results `results` of a piece to `path` with `header`, atomically.
pub fn write_piece(
    path: &Path,
    header: &Header,
    results: &[(usize, BucketResult)],
    opts: &WriteOptions,
) -> Result<(), FilmError> {
    let image = &header.scene.image;
    let (film, origin) = preview(image.width, image.height, results);
    let stored: Vec<StoredBucket> = results
        .iter()
        .filter(|(_, r)| r.window.is_some() || r.aov.is_some())
        .map(|(b, r)| StoredBucket { bucket: *b, window: r.window.clone(), aov: r.aov.clone() })
        .collect();
    reyes_film::write_buckets(
        path,
        &header.to_text(),
        (&film, origin, (image.width, image.height)),
        &stored,
        opts,
    )
}

/// A piece read back: its header and its bucket results.
#[derive(Debug)]
pub struct Piece {
    /// The file it was read from.
    pub path: PathBuf,
    /// Its header.
    pub header: Header,
    /// Its buckets' results, as stored (raster order).
    pub buckets: Vec<(usize, BucketResult)>,
}

/// Read the piece `path`: [`FarmError::Film`] (exit 1) if it cannot be read,
/// [`FarmError::NotAPiece`] or [`FarmError::Invalid`] (exit 2) if it is not a piece.
pub fn read_piece(path: &Path) -> Result<Piece, FarmError> {
    let file = reyes_film::read_buckets(path).map_err(|e| match e {
        FilmError::Io { .. } => FarmError::Film(e),
        e => FarmError::NotAPiece(e),
    })?;
    let header = Header::parse(path, &file.header)?;
    let buckets = file
        .buckets
        .into_iter()
        .map(|s| (s.bucket, BucketResult { window: s.window, aov: s.aov }))
        .collect();
    Ok(Piece { path: path.to_path_buf(), header, buckets })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_read_back_and_name_their_render() {
        let scene = crate::test_scene();
        let tile = Some(Tile { index: 2, count: 3 });
        let h = Header::new(&scene, "shots/t.ron", Some(7), tile);
        assert_eq!((h.tile, h.frame, h.version.as_str()), ((2, 3), Some(7), VERSION));
        assert!(h.scene.objects.is_empty(), "settings only, no geometry");
        let back = Header::parse(Path::new("t.exr"), &h.to_text()).expect("parse");
        assert_eq!(
            (back.fingerprint, back.tile, back.scene_path),
            (h.fingerprint, (2, 3), h.scene_path)
        );
        let e = Header::parse(Path::new("a\nb.exr"), "Nonsense(").expect_err("refused");
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().starts_with("a\\nb.exr: reyesTile: not a tile header"), "{e}");
        assert_eq!(e.to_string().lines().count(), 1);
    }

    #[test]
    fn fingerprints_follow_what_decides_the_pixels() {
        let scene = crate::test_scene();
        let f = fingerprint(&scene);
        assert_eq!(f.len(), 16);
        assert!(f.bytes().all(|b| b.is_ascii_hexdigit()));
        assert_eq!(fingerprint(&scene.clone()), f, "a function of the scene");
        let mut cropped = scene.clone();
        cropped.image.crop = Some([0.0, 0.5, 0.0, 1.0]);
        assert_ne!(fingerprint(&cropped), f);
    }
}
