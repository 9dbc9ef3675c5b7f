//! Tiles: which buckets tile `i` of `n` renders (docs/farm.md, "Tiles and merge").
//!
//! Invariant: a tile is whole buckets, runs of consecutive buckets in raster order
//! ([`reyes_render::buckets::tile`]) of the buckets the frame draws (its crop window's, with
//! one), so the tiles of a split cover each bucket exactly once, whatever `n`.

use std::fmt;
use std::str::FromStr;

use reyes_render::buckets::{scene_buckets, tile};
use reyes_scene::Scene;

/// Tile `index` of `count` (1 <= index <= count) of a frame's buckets: `I/N` as text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tile {
    /// Which tile, from 1.
    pub index: usize,
    /// How many tiles the frame is split into.
    pub count: usize,
}

impl FromStr for Tile {
    type Err = String;

    /// `I/N` with 1 <= I <= N.
    fn from_str(s: &str) -> Result<Tile, String> {
        let bad = || format!("expected I/N with 1 <= I <= N, got '{s}'");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) =
            (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if index == 0 || index > count { Err(bad()) } else { Ok(Tile { index, count }) }
    }
}

impl fmt::Display for Tile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// A split into more tiles than the frame has buckets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("--tile {tile}: the frame has {buckets} buckets, so at most {buckets} tiles")]
pub struct TooManyTiles {
    /// The tile asked for.
    pub tile: Tile,
    /// The buckets the frame draws.
    pub buckets: usize,
}

/// The buckets of `scene` a render draws, in raster order: those of its crop window (every
/// bucket without one), or tile `tile` of them.
pub fn buckets_of(scene: &Scene, tile_of: Option<Tile>) -> Result<Vec<usize>, TooManyTiles> {
    let all = scene_buckets(scene, &reyes_render::frame_for(scene));
    match tile_of {
        None => Ok(all),
        Some(t) => tile(&all, t.index, t.count)
            .map(<[usize]>::to_vec)
            .ok_or(TooManyTiles { tile: t, buckets: all.len() }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_parse_as_i_of_n() {
        assert_eq!("3/7".parse(), Ok(Tile { index: 3, count: 7 }));
        assert_eq!(" 1 / 1 ".parse::<Tile>().map(|t| t.to_string()), Ok("1/1".to_string()));
        for bad in ["0/3", "4/3", "3", "a/b", "-1/2"] {
            assert!(bad.parse::<Tile>().is_err(), "{bad}");
        }
        let e = TooManyTiles { tile: Tile { index: 1, count: 21 }, buckets: 20 };
        assert_eq!(e.to_string(), "--tile 1/21: the frame has 20 buckets, so at most 20 tiles");
    }
}
