//! The tile cache: tiles of every pyramid, read from the backing file on a miss and evicted
//! least recently used first, shared by every thread behind one lock.
//!
//! Invariants: the bytes of the tiles it holds never exceed its bound (a tile is inserted
//! only after enough older ones are evicted, and not at all when the bound is below one
//! tile); a tile's contents are exactly the bytes written to the backing file. A tile a
//! lookup is still reading when it is evicted stays alive until that lookup drops it, so
//! at any moment at most one tile per running lookup lies outside the bound.

use std::collections::{BTreeMap, HashMap};
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::sync::{Arc, Mutex, PoisonError};

use crate::{TILE_BYTES, TILE_FLOATS};

/// The cache's counts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CacheStats {
    /// The bound, in bytes.
    pub bound: u64,
    /// Bytes of tiles held now.
    pub resident: u64,
    /// The most bytes of tiles ever held at once.
    pub peak: u64,
    /// Tile requests.
    pub requests: u64,
    /// Requests that read the backing file.
    pub misses: u64,
    /// Tiles evicted to stay within the bound.
    pub evictions: u64,
}

#[derive(Debug, Default)]
struct State {
    /// Tile index to its texels and the tick of its last use.
    tiles: HashMap<u64, (Arc<[f32]>, u64)>,
    /// Tick of last use to tile index: the least recently used tile first.
    by_use: BTreeMap<u64, u64>,
    tick: u64,
    stats: CacheStats,
}

/// A bounded tile cache.
#[derive(Debug)]
pub struct Cache {
    bound: u64,
    state: Mutex<State>,
}

impl Cache {
    /// An empty cache of `bound` bytes.
    pub fn new(bound: u64) -> Cache {
        let state =
            State { stats: CacheStats { bound, ..CacheStats::default() }, ..State::default() };
        Cache { bound, state: Mutex::new(state) }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Tile `tile`: from the cache, or read from `backing` (and kept if the bound allows).
    pub fn get(&self, tile: u64, backing: &Mutex<File>) -> std::io::Result<Arc<[f32]>> {
        self.get_with(tile, || read_tile(tile, backing))
    }

    /// Tile `key` (of any size): from the cache, or made by `load` (and kept if the bound
    /// allows). Resident bytes count each tile's own size, 4 bytes a float.
    pub fn get_with(
        &self,
        key: u64,
        load: impl FnOnce() -> std::io::Result<Arc<[f32]>>,
    ) -> std::io::Result<Arc<[f32]>> {
        let tile = key;
        {
            let mut s = self.lock();
            s.stats.requests += 1;
            s.tick += 1;
            let tick = s.tick;
            if let Some((texels, used)) = s.tiles.get_mut(&tile) {
                let (texels, old) = (texels.clone(), std::mem::replace(used, tick));
                s.by_use.remove(&old);
                s.by_use.insert(tick, tile);
                return Ok(texels);
            }
            s.stats.misses += 1;
        }
        let texels = load()?;
        let size = 4 * texels.len() as u64;
        let mut s = self.lock();
        if let Some((existing, _)) = s.tiles.get(&tile) {
            // Another thread read it meanwhile: the same bytes.
            return Ok(existing.clone());
        }
        if size > self.bound {
            return Ok(texels);
        }
        while s.stats.resident + size > self.bound {
            let Some((_, victim)) = s.by_use.pop_first() else { break };
            if let Some((gone, _)) = s.tiles.remove(&victim) {
                s.stats.resident -= 4 * gone.len() as u64;
            }
            s.stats.evictions += 1;
        }
        s.tick += 1;
        let tick = s.tick;
        s.tiles.insert(tile, (texels.clone(), tick));
        s.by_use.insert(tick, tile);
        s.stats.resident += size;
        s.stats.peak = s.stats.peak.max(s.stats.resident);
        Ok(texels)
    }

    /// The counts so far.
    pub fn stats(&self) -> CacheStats {
        self.lock().stats
    }
}

/// Read tile `tile` from the backing file.
fn read_tile(tile: u64, backing: &Mutex<File>) -> std::io::Result<Arc<[f32]>> {
    let mut bytes = vec![0u8; TILE_BYTES as usize];
    {
        let mut file = backing.lock().unwrap_or_else(PoisonError::into_inner);
        file.seek(SeekFrom::Start(tile * TILE_BYTES))?;
        file.read_exact(&mut bytes)?;
    }
    let mut texels = Vec::with_capacity(TILE_FLOATS);
    texels.extend(bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])));
    Ok(Arc::from(texels))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn backing(tiles: u64) -> Mutex<File> {
        let mut f = tempfile::tempfile().unwrap_or_else(|e| panic!("{e}"));
        for t in 0..tiles {
            let v: Vec<u8> = (0..TILE_FLOATS)
                .flat_map(|k| ((t * 1000 + k as u64) as f32).to_le_bytes())
                .collect();
            f.write_all(&v).unwrap_or_else(|e| panic!("{e}"));
        }
        Mutex::new(f)
    }

    /// Resident bytes stay within the bound while every tile reads back exactly.
    #[test]
    fn stays_within_its_bound_and_reads_back_exactly() {
        let file = backing(10);
        let cache = Cache::new(3 * TILE_BYTES + 5);
        for round in 0..3u64 {
            for t in 0..10u64 {
                let tile = (t * 7 + round) % 10;
                let texels = cache.get(tile, &file).unwrap_or_else(|e| panic!("{e}"));
                assert_eq!(texels[5], (tile * 1000 + 5) as f32);
                assert!(cache.stats().resident <= 3 * TILE_BYTES);
            }
        }
        let s = cache.stats();
        assert_eq!(s.peak, 3 * TILE_BYTES);
        assert_eq!(s.requests, 30);
        assert!(s.evictions > 0 && s.misses > 10, "{s:?}");
        // A hit is not a miss.
        let before = cache.stats().misses;
        let last = (9 * 7 + 2) % 10;
        let _ = cache.get(last, &file);
        assert_eq!(cache.stats().misses, before);
    }

    /// Under a bound below one tile nothing is kept, and lookups still work.
    #[test]
    fn a_bound_below_a_tile_keeps_nothing() {
        let file = backing(2);
        let cache = Cache::new(100);
        for _ in 0..3 {
            let texels = cache.get(1, &file).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(texels[0], 1000.0);
        }
        assert_eq!(cache.stats().resident, 0);
        assert_eq!(cache.stats().misses, 3);
    }
}
