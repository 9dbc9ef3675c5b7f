//! Pieces of a frame (docs/farm.md): the fingerprint that says which render a piece belongs
//! to, the header every tile and checkpoint file carries, the tile file, and
//! `reyes-render merge`, which reassembles tiles into the frame's output.
//!
//! Invariant: the merged file is the single render's, byte for byte. Every bucket's window
//! is stored whole ([`reyes_film::tiles`]) and added in bucket raster order
//! ([`reyes_render::buckets::assemble`]), and the file is written by the same function,
//! from the same scene settings (carried in the header), as a whole render writes it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use reyes_film::{FilmError, StoredBucket, WriteOptions};
use reyes_render::BucketResult;
use reyes_render::buckets::{scene_buckets, tile};
use reyes_scene::Scene;
use serde::{Deserialize, Serialize};

use crate::Exit;

/// What every tile and checkpoint file says about the render it is a piece of.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct Header {
    /// The renderer's version: pieces of different versions are never mixed.
    pub version: String,
    /// [`fingerprint`] of the render.
    pub fingerprint: String,
    /// `(i, n)`: tile i of n; `(0, 0)` for a checkpoint's bucket file.
    pub tile: (usize, usize),
    /// The frame number (a RIB frame, or `--frames` of a RON scene).
    pub frame: Option<i32>,
    /// The scene file as named on the command line (the output's metadata names it).
    pub scene_path: String,
    /// Render time of the piece in seconds, when the scene writes render times.
    pub render_time: Option<f32>,
    /// The scene's settings (image, camera, hider, outputs, lights), without its geometry:
    /// all the merge needs to write the frame's file.
    pub scene: Scene,
}

impl Header {
    pub(crate) fn new(
        scene: &Scene,
        scene_path: &str,
        frame: Option<i32>,
        tile: (usize, usize),
    ) -> Header {
        let mut settings = scene.clone();
        settings.objects.clear();
        settings.solids.clear();
        Header {
            version: env!("CARGO_PKG_VERSION").to_string(),
            fingerprint: fingerprint(scene),
            tile,
            frame,
            scene_path: scene_path.to_string(),
            render_time: None,
            scene: settings,
        }
    }

    pub(crate) fn to_text(&self) -> String {
        ron::to_string(self).unwrap_or_default()
    }

    /// The header `text` of the file `path`; its scene settings must validate (the merge
    /// lays out buckets and writes a file from them).
    pub(crate) fn parse(path: &Path, text: &str) -> Result<Header, Exit> {
        let header: Header = ron::from_str(text).map_err(|e| {
            Exit::error(
                2,
                format_args!(
                    "{}: reyesTile: not a tile header of this version: {e}",
                    path.display()
                ),
            )
        })?;
        if let Err(issue) = reyes_scene::validate(header.scene.clone()) {
            return Err(Exit::error(
                2,
                format_args!(
                    "{}: reyesTile: scene.{}: {}",
                    path.display(),
                    issue.path,
                    issue.message
                ),
            ));
        }
        Ok(header)
    }
}

/// Which render a piece belongs to: a hash of everything that decides the pixels (the whole
/// scene after the command line's overrides, `--crop` and the seed among them, serialised
/// as RON) and the renderer's version, as 16 hex digits. The thread count, the tile and the
/// output name are not in it: they do not change a bucket.
pub(crate) fn fingerprint(scene: &Scene) -> String {
    let text = ron::to_string(scene).unwrap_or_default();
    let words: Vec<u64> = text
        .as_bytes()
        .chunks(8)
        .map(|c| c.iter().rev().fold(0u64, |w, &b| w << 8 | u64::from(b)))
        .chain([text.len() as u64])
        .collect();
    let version =
        env!("CARGO_PKG_VERSION").bytes().fold(0u64, |w, b| w.rotate_left(8) ^ u64::from(b));
    format!("{:016x}", reyes_sampling::hash(version, &words))
}

/// The buckets of `scene` a render draws: those of its crop window, or tile `i/n` of them.
pub(crate) fn buckets_of(
    scene: &Scene,
    tile_of: Option<(usize, usize)>,
) -> Result<Vec<usize>, String> {
    let all = scene_buckets(scene, &reyes_render::frame_for(scene));
    match tile_of {
        None => Ok(all),
        Some((i, n)) => tile(&all, i, n).map(<[usize]>::to_vec).ok_or_else(|| {
            format!(
                "--tile {i}/{n}: the frame has {} buckets, so at most {} tiles",
                all.len(),
                all.len()
            )
        }),
    }
}

/// What the tile's buckets add to the film, over the pixels they cover (for part 0).
fn preview(
    width: u32,
    height: u32,
    results: &[(usize, BucketResult)],
) -> (reyes_film::Film, (u32, u32)) {
    let (film, _) =
        reyes_render::buckets::assemble(width, height, None, results.iter().map(|(_, r)| r));
    let mut rect: Option<[i64; 4]> = None;
    for w in results.iter().filter_map(|(_, r)| r.window.as_ref().or(None)) {
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

/// Write the bucket results `results` of a piece to `path` with `header`.
pub(crate) fn write_piece(
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
pub(crate) struct Piece {
    pub path: PathBuf,
    pub header: Header,
    pub buckets: Vec<(usize, BucketResult)>,
}

/// Read the piece `path`: exit 1 if it cannot be read, 2 if it is not a piece.
pub(crate) fn read_piece(path: &Path) -> Result<Piece, Exit> {
    let file = reyes_film::read_buckets(path).map_err(|e| match e {
        FilmError::Io { .. } => Exit::error(1, &e),
        e => Exit::error(2, e),
    })?;
    let header = Header::parse(path, &file.header)?;
    let buckets = file
        .buckets
        .into_iter()
        .map(|s| (s.bucket, BucketResult { window: s.window, aov: s.aov }))
        .collect();
    Ok(Piece { path: path.to_path_buf(), header, buckets })
}

/// `reyes-render merge TILE... -o OUT`: every tile of one render, each once, reassembled.
pub(crate) fn merge(tiles: &[PathBuf], output: &Path) -> Result<(), Exit> {
    let bad = |msg: std::fmt::Arguments| Exit::error(2, msg);
    let pieces = tiles.iter().map(|p| read_piece(p)).collect::<Result<Vec<_>, _>>()?;
    let Some(first) = pieces.first() else {
        return Err(bad(format_args!("merge: no tile files given")));
    };
    let h0 = &first.header;
    let mut by_tile: BTreeMap<usize, &Piece> = BTreeMap::new();
    for p in &pieces {
        let h = &p.header;
        if h.tile.0 == 0 {
            return Err(bad(format_args!(
                "{}: a checkpoint's bucket file, not a tile",
                p.path.display()
            )));
        }
        if h.version != h0.version {
            return Err(bad(format_args!(
                "{}: rendered by reyes-render {}, {} by {}: tiles of different versions do not merge",
                p.path.display(),
                h.version,
                first.path.display(),
                h0.version
            )));
        }
        if h.fingerprint != h0.fingerprint || h.frame != h0.frame {
            return Err(bad(format_args!(
                "{}: a tile of a different render than {} (its scene, frame, seed or settings differ)",
                p.path.display(),
                first.path.display()
            )));
        }
        if h.tile.1 != h0.tile.1 {
            return Err(bad(format_args!(
                "{}: tile {}/{}, but {} is tile {}/{}: the frame was split differently",
                p.path.display(),
                h.tile.0,
                h.tile.1,
                first.path.display(),
                h0.tile.0,
                h0.tile.1
            )));
        }
        if let Some(other) = by_tile.insert(h.tile.0, p) {
            return Err(bad(format_args!(
                "tile {}/{} given twice: {} and {}",
                h.tile.0,
                h.tile.1,
                other.path.display(),
                p.path.display()
            )));
        }
    }
    let n = h0.tile.1;
    let missing: Vec<String> =
        (1..=n).filter(|i| !by_tile.contains_key(i)).map(|i| format!("{i}/{n}")).collect();
    if !missing.is_empty() {
        let tiles = if missing.len() == 1 { "tile" } else { "tiles" };
        return Err(bad(format_args!(
            "merge: {tiles} {} missing (the frame has {n} tiles)",
            missing.join(", ")
        )));
    }
    let scene = &h0.scene;
    let mut results: BTreeMap<usize, BucketResult> = BTreeMap::new();
    for (&i, p) in &by_tile {
        let own = buckets_of(scene, Some((i, n)))
            .map_err(|e| bad(format_args!("{}: {e}", p.path.display())))?;
        for (b, r) in &p.buckets {
            if own.binary_search(b).is_err() {
                return Err(bad(format_args!(
                    "{}: holds bucket {b}, which is not in tile {i}/{n}",
                    p.path.display()
                )));
            }
            results.insert(*b, r.clone());
        }
    }
    let render_time = pieces.iter().map(|p| p.header.render_time).sum::<Option<f32>>();
    crate::write_frame(
        scene,
        &h0.scene_path,
        &results,
        render_time,
        output,
        &WriteOptions::default(),
    )
}
