//! reyes-texture: texture maps for shading and displacement.
//!
//! Stage: set up before rendering, read while grids are shaded. [`TextureSystem::load`]
//! decodes a PNG, JPEG, TIFF or OpenEXR file ([`load`]), converts it to linear RGBA `f32` by
//! its declared [`ColorSpace`], builds its MIP pyramid (each level the 2 x 2 box average of
//! the one below, [`mip`]) and writes the pyramid, in tiles of [`TILE`] x [`TILE`] texels, to
//! an unnamed temporary file. Lookups ([`TextureSystem::lookup`], [`filter`]) read tiles
//! through one cache shared by every thread ([`cache`]) whose resident tiles never exceed
//! its byte bound: a scene with more texture than that bound still renders, reading evicted
//! tiles back from the file.
//!
//! Invariants: a lookup is a pure function of the texture's pixels and the lookup's
//! arguments, never of the cache's state (a tile read back is bit for bit the tile
//! written), so renders stay deterministic for any thread count; the resident bytes of the
//! cache stay at or below its bound; no lookup panics or returns a non-finite value for
//! finite input (a non-finite texel is stored as 0).
#![deny(missing_docs)]

pub mod cache;
pub mod filter;
pub mod load;
pub mod lookup;
pub mod make;
pub mod mip;
pub mod noise;
pub mod prepared;
mod tiffpatch;
pub mod tool;
pub mod write;

use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

pub use cache::CacheStats;

/// Texels along each side of a tile.
pub const TILE: usize = 32;
/// Floats per tile (RGBA).
pub const TILE_FLOATS: usize = TILE * TILE * 4;
/// Bytes per tile in memory and in the backing file.
pub const TILE_BYTES: u64 = (TILE_FLOATS * 4) as u64;

/// How a file's stored values relate to linear light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorSpace {
    /// IEC 61966-2-1 sRGB: colour channels are decoded by the sRGB transfer function
    /// (alpha is linear).
    Srgb,
    /// The values are linear already (the usual case for OpenEXR and for data maps such as
    /// displacement or roughness).
    Linear,
}

/// What a lookup outside `[0, 1]` reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wrap {
    /// The texture repeats (RenderMan's `"periodic"`).
    Periodic,
    /// The edge texels extend outward (`"clamp"`).
    Clamp,
    /// Zero in every channel, alpha included (`"black"`).
    Black,
}

/// Errors of loading a texture map. Each names the file.
#[derive(Debug, thiserror::Error)]
pub enum TextureError {
    /// The file cannot be read (exit code 1).
    #[error("{}: texture: cannot read: {source}", file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not an image the decoders understand, or its size is out of range (exit
    /// code 2: bad input).
    #[error("{}: texture: {message}", file.display())]
    Decode {
        /// The file.
        file: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// The pyramid could not be written to its temporary backing file (exit code 1).
    #[error("texture cache: cannot write the backing file for {}: {source}", file.display())]
    Backing {
        /// The texture being stored.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

impl TextureError {
    /// The process exit code: 2 for a file that is not a usable image, 1 for I/O.
    pub fn exit_code(&self) -> u8 {
        match self {
            TextureError::Decode { .. } => 2,
            _ => 1,
        }
    }
}

/// A loaded texture, named by its position in the system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TextureId(pub u32);

/// One level of a pyramid: its size and where its tiles are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Level {
    /// Texels across.
    pub width: u32,
    /// Texels down.
    pub height: u32,
    /// A tile's texels across and down ([`TILE`] in the backing file; a prepared file's own
    /// tile or strip size).
    pub tile_w: u32,
    /// A tile's rows.
    pub tile_h: u32,
    /// Tiles across (`ceil(width / tile_w)`).
    pub tiles_x: u32,
    /// The cache key of the level's first tile; tiles follow row by row. For the backing
    /// file, the index of the tile in it.
    pub first_tile: u64,
    /// `None`: the tiles are in the backing file; `Some(k)`: level `k` of the texture's
    /// prepared file, read chunk by chunk.
    pub stored: Option<u32>,
}

/// A loaded texture: its pyramid's levels and the range of its values.
#[derive(Debug, Clone)]
pub struct Texture {
    /// The file it came from.
    pub file: PathBuf,
    /// Level 0 (the image) first, down to 1 x 1 (a prepared file's levels as stored).
    pub levels: Vec<Level>,
    /// Smallest value of each channel over the image (after colour conversion).
    pub min: [f32; 4],
    /// Largest value of each channel. Filtered values are convex combinations of texels, so
    /// every lookup lies in `[min, max]` per channel (with `Black` wrap, also 0). For a
    /// prepared file of integer samples, the type's range `[0, 1]`; of float samples, the
    /// range over every level, read when the file is opened only if [`TextureSystem::range`]
    /// is asked.
    pub max: [f32; 4],
    /// Channels in the file (1 to 4; a decoded image's are 4).
    pub channels: u32,
    /// What the map is (a decoded image: [`prepared::MapKind::Plain`]).
    pub kind: prepared::MapKind,
    /// The prepared file's header, if it is one.
    pub header: Option<prepared::Header>,
    /// The colour space its values are converted from.
    pub space: ColorSpace,
    prepared: Option<std::sync::Arc<prepared::PreparedFile>>,
}

/// Totals of a system's loading and lookups (for `--stats` and the benchmark).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TextureStats {
    /// Textures loaded.
    pub textures: u64,
    /// Texels of every pyramid (all levels).
    pub texels: u64,
    /// Bytes of every pyramid in the backing file.
    pub pyramid_bytes: u64,
    /// Time spent decoding files and building pyramids.
    pub load_time: Duration,
    /// Filtered lookups ([`TextureSystem::lookup`] calls).
    pub lookups: u64,
    /// The cache's counts.
    pub cache: CacheStats,
}

/// Every texture of a render, and the tile cache they share.
#[derive(Debug)]
pub struct TextureSystem {
    textures: Vec<Texture>,
    /// The pyramids' tiles, [`TILE_BYTES`] each, in little-endian `f32`.
    backing: Mutex<File>,
    next_tile: u64,
    /// The next cache key of a prepared file's chunk (apart from the backing file's tiles).
    next_chunk: u64,
    cache: cache::Cache,
    lookups: AtomicU64,
    /// Set when reading a tile back failed (the lookup then read zeros).
    failed: AtomicBool,
    texels: u64,
    load_time: Duration,
}

impl TextureSystem {
    /// An empty system whose cache holds at most `cache_bytes` of tiles (at least one tile
    /// is always read, even under a bound smaller than a tile, but then none is kept).
    pub fn new(cache_bytes: u64) -> std::io::Result<TextureSystem> {
        Ok(TextureSystem {
            textures: Vec::new(),
            backing: Mutex::new(tempfile::tempfile()?),
            next_tile: 0,
            next_chunk: 1 << 62,
            cache: cache::Cache::new(cache_bytes),
            lookups: AtomicU64::new(0),
            failed: AtomicBool::new(false),
            texels: 0,
            load_time: Duration::ZERO,
        })
    }

    /// Decode `file` in `space`, build its pyramid and store it; the id to look it up by.
    pub fn load(&mut self, file: &Path, space: ColorSpace) -> Result<TextureId, TextureError> {
        let start = Instant::now();
        let mut head = [0u8; 4];
        let io = |source| TextureError::Io { file: file.to_path_buf(), source };
        let n = File::open(file).and_then(|mut f| std::io::Read::read(&mut f, &mut head));
        if prepared::is_tiff(&head[..n.map_err(io)?]) {
            let p = prepared::PreparedFile::open(file)?;
            let h = &p.header;
            if h.levels.len() > 1 || !h.format.is_empty() {
                h.check_chunks().map_err(|message| TextureError::Decode {
                    file: file.to_path_buf(),
                    message,
                })?;
                let id = self.add_prepared(p, space);
                self.load_time += start.elapsed();
                return Ok(id);
            }
        }
        let image = load::decode(file, space)?;
        let (min, max) = image.range();
        let pyramid = mip::Pyramid::build(image);
        let backing = |source| TextureError::Backing { file: file.to_path_buf(), source };
        let mut levels = Vec::with_capacity(pyramid.levels.len());
        let mut out = self.backing.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        out.seek(SeekFrom::Start(self.next_tile * TILE_BYTES)).map_err(backing)?;
        let mut writer = std::io::BufWriter::new(&mut *out);
        let mut bytes = vec![0u8; TILE_BYTES as usize];
        for level in &pyramid.levels {
            let tiles_x = level.width.div_ceil(TILE as u32);
            let tiles_y = level.height.div_ceil(TILE as u32);
            levels.push(Level {
                width: level.width,
                height: level.height,
                tile_w: TILE as u32,
                tile_h: TILE as u32,
                tiles_x,
                first_tile: self.next_tile,
                stored: None,
            });
            for ty in 0..tiles_y {
                for tx in 0..tiles_x {
                    level.tile_bytes(tx, ty, &mut bytes);
                    writer.write_all(&bytes).map_err(backing)?;
                    self.next_tile += 1;
                }
            }
            self.texels += u64::from(level.width) * u64::from(level.height);
        }
        writer.flush().map_err(backing)?;
        drop(writer);
        drop(out);
        self.textures.push(Texture {
            file: file.to_path_buf(),
            levels,
            min,
            max,
            channels: 4,
            kind: prepared::MapKind::Plain,
            header: None,
            space,
            prepared: None,
        });
        self.load_time += start.elapsed();
        Ok(TextureId(self.textures.len() as u32 - 1))
    }

    /// Adds an opened prepared file: its levels as stored, read chunk by chunk on demand.
    fn add_prepared(&mut self, p: prepared::PreparedFile, space: ColorSpace) -> TextureId {
        let h = p.header.clone();
        let mut levels = Vec::with_capacity(h.levels.len());
        for (k, d) in h.levels.iter().enumerate() {
            let chunks = u64::from(d.chunks_x) * u64::from(d.height.div_ceil(d.chunk_h));
            levels.push(Level {
                width: d.width,
                height: d.height,
                tile_w: d.chunk_w,
                tile_h: d.chunk_h,
                tiles_x: d.chunks_x,
                first_tile: self.next_chunk,
                stored: Some(k as u32),
            });
            self.next_chunk += chunks;
            self.texels += u64::from(d.width) * u64::from(d.height);
        }
        let float = matches!(h.sample, prepared::SampleType::Float(_));
        let (min, max) = if float { ([f32::MIN; 4], [f32::MAX; 4]) } else { ([0.0; 4], [1.0; 4]) };
        let min = if matches!(h.sample, prepared::SampleType::Int(_)) { [-1.0; 4] } else { min };
        self.textures.push(Texture {
            file: p.path.clone(),
            levels,
            min,
            max,
            channels: h.channels,
            kind: h.kind,
            header: Some(h),
            space,
            prepared: Some(std::sync::Arc::new(p)),
        });
        TextureId(self.textures.len() as u32 - 1)
    }

    /// The range of every channel of texture `id` (see [`Texture::max`]): for a prepared file
    /// of float samples, read from every chunk of every level (once; later calls read the
    /// cache's tiles).
    pub fn range(&self, id: TextureId) -> ([f32; 4], [f32; 4]) {
        let t = &self.textures[id.0 as usize];
        if t.min != [f32::MIN; 4] {
            return (t.min, t.max);
        }
        let (mut lo, mut hi) = ([f32::INFINITY; 4], [f32::NEG_INFINITY; 4]);
        for level in &t.levels {
            let tiles = u64::from(level.tiles_x) * u64::from(level.height.div_ceil(level.tile_h));
            for k in 0..tiles {
                let tile = self.tile(t, level, level.first_tile + k);
                let (tw, th) = (level.tile_w as usize, level.tile_h as usize);
                let (x0, y0) = (
                    (k % u64::from(level.tiles_x)) as usize * tw,
                    (k / u64::from(level.tiles_x)) as usize * th,
                );
                for y in 0..th.min(level.height as usize - y0) {
                    for x in 0..tw.min(level.width as usize - x0) {
                        let px = &tile[4 * (y * tw + x)..4 * (y * tw + x) + 4];
                        for c in 0..4 {
                            lo[c] = lo[c].min(px[c]);
                            hi[c] = hi[c].max(px[c]);
                        }
                    }
                }
            }
        }
        (lo, hi)
    }

    /// Bytes read from prepared files so far (their headers and the chunks lookups touched).
    pub fn prepared_bytes_read(&self) -> u64 {
        self.textures.iter().filter_map(|t| t.prepared.as_ref()).map(|p| p.bytes_read()).sum()
    }

    /// The texture `id`.
    pub fn texture(&self, id: TextureId) -> &Texture {
        &self.textures[id.0 as usize]
    }

    /// Counts one lookup (for the statistics).
    pub(crate) fn count_lookup(&self) {
        self.lookups.fetch_add(1, Ordering::Relaxed);
    }

    /// The RGBA value of texture `id` box-filtered over the footprint centred at `(s, t)`
    /// with extents `ds` and `dt` in texture coordinates (`[0, 1]` across the image, `t`
    /// down), read through `wrap` ([`filter`] says how). `width` scales the footprint
    /// (RenderMan's `"width"`): 0 reads the finest level, bilinearly, at `(s, t)` alone.
    pub fn lookup(&self, id: TextureId, st: [f32; 2], dst: [f32; 2], wrap: Wrap) -> [f32; 4] {
        self.lookups.fetch_add(1, Ordering::Relaxed);
        let texture = &self.textures[id.0 as usize];
        let mut reader = filter::Reader::new(self);
        filter::lookup(texture, &mut reader, st, dst, wrap)
    }

    /// Tile `tile` (a cache key) of `level` of `texture`, through the cache: from the
    /// backing file, or a chunk decoded from the prepared file (colour-converted).
    pub(crate) fn tile(
        &self,
        texture: &Texture,
        level: &Level,
        tile: u64,
    ) -> std::sync::Arc<[f32]> {
        let got = match (level.stored, &texture.prepared) {
            (Some(k), Some(p)) => self.cache.get_with(tile, || {
                let mut texels = p.read_chunk(k as usize, (tile - level.first_tile) as u32)?;
                if texture.space == ColorSpace::Srgb {
                    for px in texels.chunks_exact_mut(4) {
                        for v in &mut px[..3] {
                            *v = load::srgb_to_linear(*v);
                        }
                    }
                }
                Ok(std::sync::Arc::from(texels))
            }),
            _ => self.cache.get(tile, &self.backing),
        };
        match got {
            Ok(t) => t,
            Err(_) => {
                self.failed.store(true, Ordering::Relaxed);
                let n = (level.tile_w * level.tile_h * 4) as usize;
                std::sync::Arc::from(vec![0.0; n.max(TILE_FLOATS)])
            }
        }
    }

    /// True if some tile could not be read back from the backing file (the lookups that
    /// needed it read zeros): the render should fail rather than write that picture.
    pub fn read_failed(&self) -> bool {
        self.failed.load(Ordering::Relaxed)
    }

    /// The totals so far.
    pub fn stats(&self) -> TextureStats {
        TextureStats {
            textures: self.textures.len() as u64,
            texels: self.texels,
            pyramid_bytes: self.next_tile * TILE_BYTES,
            load_time: self.load_time,
            lookups: self.lookups.load(Ordering::Relaxed),
            cache: self.cache.stats(),
        }
    }
}
