//! The merge: the tiles of one frame reassembled into the whole render's file
//! (`reyes-render merge`, docs/farm.md).
//!
//! Invariant: the merged file is the single render's, byte for byte. Every bucket's window
//! is stored whole ([`reyes_film::tiles`]) and added in bucket raster order
//! ([`reyes_render::buckets::assemble`]), and the file is written by the same function, from
//! the same scene settings (carried in the header), as a whole render writes it
//! ([`crate::output::FramePicture`]). Nothing is written unless every tile of one render is
//! given, each once.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use reyes_film::WriteOptions;
use reyes_render::BucketResult;

use crate::output::{create_directory_of, write_assembled};
use crate::piece::{Piece, read_piece};
use crate::tile::buckets_of;
use crate::{FarmError, Tile, one_line};

/// Merge the tile files `tiles` (every tile of one frame, each once, in any order) into
/// `output` (.exr or .png, its directory made if missing): exit 2 for tiles that do not make
/// one frame, 1 for a file that cannot be read or written.
pub fn merge(tiles: &[PathBuf], output: &Path, opts: &WriteOptions) -> Result<(), FarmError> {
    let pieces = tiles.iter().map(|p| read_piece(p)).collect::<Result<Vec<_>, _>>()?;
    let Some(first) = pieces.first() else {
        return Err(FarmError::invalid(format_args!("merge: no tile files given")));
    };
    let by_tile = check(&pieces)?;
    let h0 = &first.header;
    let n = h0.tile.1;
    let scene = &h0.scene;
    let mut results: BTreeMap<usize, BucketResult> = BTreeMap::new();
    for (&i, p) in &by_tile {
        let name = one_line(p.path.display());
        let own = buckets_of(scene, Some(Tile { index: i, count: n }))
            .map_err(|e| FarmError::invalid(format_args!("{name}: {e}")))?;
        for (b, r) in &p.buckets {
            if own.binary_search(b).is_err() {
                return Err(FarmError::invalid(format_args!(
                    "{name}: holds bucket {b}, which is not in tile {i}/{n}"
                )));
            }
            results.insert(*b, r.clone());
        }
    }
    let render_time = pieces.iter().map(|p| p.header.render_time).sum::<Option<f32>>();
    create_directory_of(output)?;
    write_assembled(scene, &h0.scene_path, &results, render_time, output, opts)?;
    Ok(())
}

/// The pieces by tile index, if they are every tile of one render, each once.
fn check(pieces: &[Piece]) -> Result<BTreeMap<usize, &Piece>, FarmError> {
    let bad = |msg: std::fmt::Arguments| FarmError::invalid(msg);
    let first = &pieces[0];
    let (h0, name0) = (&first.header, one_line(first.path.display()));
    let mut by_tile: BTreeMap<usize, &Piece> = BTreeMap::new();
    for p in pieces {
        let (h, name) = (&p.header, one_line(p.path.display()));
        if h.tile.0 == 0 {
            return Err(bad(format_args!("{name}: a checkpoint's bucket file, not a tile")));
        }
        if h.version != h0.version {
            return Err(bad(format_args!(
                "{name}: rendered by reyes-render {}, {name0} by {}: tiles of different versions do not merge",
                one_line(&h.version),
                one_line(&h0.version)
            )));
        }
        if h.fingerprint != h0.fingerprint || h.frame != h0.frame {
            return Err(bad(format_args!(
                "{name}: a tile of a different render than {name0} (its scene, frame, seed or settings differ)"
            )));
        }
        if h.tile.1 != h0.tile.1 {
            return Err(bad(format_args!(
                "{name}: tile {}/{}, but {name0} is tile {}/{}: the frame was split differently",
                h.tile.0, h.tile.1, h0.tile.0, h0.tile.1
            )));
        }
        if let Some(other) = by_tile.insert(h.tile.0, p) {
            return Err(bad(format_args!(
                "tile {}/{} given twice: {} and {name}",
                h.tile.0,
                h.tile.1,
                one_line(other.path.display())
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
    Ok(by_tile)
}
