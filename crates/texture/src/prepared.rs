//! Prepared RenderMan textures: TIFF files holding one directory per MIP level, tiled or in
//! strips, 8/16/32-bit integer or 16/32/64-bit float samples, 1 to 4 channels, with Pixar's
//! private tags saying what the map is. This is the layout of PRMan's `txmake`, Aqsis's
//! `teqser`, Pixie's `texmake` and our own `MakeTexture` ([`crate::write`]).
//!
//! The header (every directory's size and layout, the tags) is read when the file is opened;
//! texels are read a chunk (a tile or a strip) at a time, when a lookup first touches it,
//! through the system's tile cache. So a texture costs only the chunks a render reads.
//!
//! Invariants: [`PreparedFile::open`] checks everything a later chunk read depends on (the
//! sample format, the channel count, that every chunk's bytes lie inside the file), so a
//! truncated or malformed file is refused when the scene loads, naming the file; a chunk read
//! returns exactly `chunk_w * chunk_h` RGBA texels (padding and missing channels filled:
//! grey replicated to RGB, alpha 1), non-finite values as 0. Integer samples read as
//! `v / max` (8-bit `v / 255`), floats as stored.

use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;

use crate::tiffpatch::{Patched, directories_needing_a_patch};
use crate::{TextureError, Wrap, load::MAX_SIDE};

/// Pixar's TIFF tag: the texture format string ("Plain Texture", "Shadow", ...).
pub const TAG_TEXTUREFORMAT: u16 = 33302;
/// Pixar's TIFF tag: the wrap modes, `"swrap,twrap"` (Aqsis writes a space).
pub const TAG_WRAPMODES: u16 = 33303;
/// Pixar's TIFF tag: the cotangent of half the field of view of cube-face maps.
pub const TAG_FOVCOT: u16 = 33304;
/// Pixar's TIFF tag: the world-to-screen matrix of a shadow map (16 floats, row vectors).
pub const TAG_WORLDTOSCREEN: u16 = 33305;
/// Pixar's TIFF tag: the world-to-camera matrix of a shadow map.
pub const TAG_WORLDTOCAMERA: u16 = 33306;

/// What a map is for, from its texture format string.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapKind {
    /// A plain texture (`texture()`); also any TIFF without the tag.
    Plain,
    /// A latitude-longitude environment map.
    LatLong,
    /// A cube-face environment map: six faces in three columns and two rows.
    CubeFace,
    /// A shadow (depth) map, with its matrices.
    Shadow,
}

impl MapKind {
    /// The kind a texture format string names (any renderer's spelling), `Plain` when unknown.
    pub fn from_format(format: &str) -> MapKind {
        let f = format.to_ascii_lowercase();
        if f.contains("shadow") {
            MapKind::Shadow
        } else if f.contains("cube") {
            MapKind::CubeFace
        } else if f.contains("latlong") || f.contains("cylinder") || f.contains("environment") {
            MapKind::LatLong
        } else {
            MapKind::Plain
        }
    }

    /// The texture format string we write (PRMan's).
    pub fn format(self) -> &'static str {
        match self {
            MapKind::Plain => "Plain Texture",
            MapKind::LatLong => "LatLong Environment",
            MapKind::CubeFace => "CubeFace Environment",
            MapKind::Shadow => "Shadow",
        }
    }
}

/// How samples are stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleType {
    /// Unsigned integers of this many bits (8, 16 or 32).
    Uint(u8),
    /// Signed integers of this many bits.
    Int(u8),
    /// IEEE floats of this many bits (16, 32 or 64).
    Float(u8),
}

/// One directory (MIP level) of a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DirInfo {
    /// Texels across and down.
    pub width: u32,
    /// Texels down.
    pub height: u32,
    /// A chunk's size (a tile's; a strip's is the width by its rows).
    pub chunk_w: u32,
    /// A chunk's rows.
    pub chunk_h: u32,
    /// Chunks across.
    pub chunks_x: u32,
    /// True for tiles, false for strips.
    pub tiled: bool,
    /// True if each channel is stored in chunks of its own (PlanarConfiguration 2, as PRMan
    /// and `maketx --prman` write).
    pub planar: bool,
}

/// The most texels of a chunk read as a prepared texture's: a chunk is decoded whole into the
/// cache (a strip of 16k x 1k; tiles are far smaller).
pub const MAX_CHUNK_TEXELS: u64 = 1 << 24;

impl Header {
    /// Refuses chunks over [`MAX_CHUNK_TEXELS`] (a picture in one huge strip is decoded whole
    /// instead, as a plain image).
    pub fn check_chunks(&self) -> Result<(), String> {
        for l in &self.levels {
            if u64::from(l.chunk_w) * u64::from(l.chunk_h) > MAX_CHUNK_TEXELS {
                return Err(format!(
                    "chunks of {} x {} texels are over the limit of {MAX_CHUNK_TEXELS}",
                    l.chunk_w, l.chunk_h
                ));
            }
        }
        Ok(())
    }
}

/// What a prepared file's header says.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    /// The texture format string as written ("" when the tag is absent).
    pub format: String,
    /// The kind it names.
    pub kind: MapKind,
    /// The wrap modes in s and t (None: not given).
    pub wrap: Option<[Wrap; 2]>,
    /// The wrap modes as written.
    pub wrap_text: String,
    /// Cube faces: the cotangent of half their field of view.
    pub fov_cot: Option<f32>,
    /// Shadow maps: world to the map's screen space (x, y in [-1, 1], y up), row vectors.
    /// Pixie writes world to NDC (x, y in [0, 1], y down) under this tag: its file is told by
    /// its format string and the matrix converted here, so this is always screen space.
    pub world_to_screen: Option<[f32; 16]>,
    /// Shadow maps: world to the light's camera space.
    pub world_to_camera: Option<[f32; 16]>,
    /// Channels per texel (1 to 4 are read; more are refused).
    pub channels: u32,
    /// How samples are stored.
    pub sample: SampleType,
    /// The MIP levels used, finest first: the first directory and each following one that is
    /// half the one before (rounded either way), as stored.
    pub levels: Vec<DirInfo>,
    /// Directories in the file (some may not be levels).
    pub directories: u32,
}

/// A reader that counts the bytes it reads (for the benchmark's figures).
struct Counting<R> {
    inner: R,
    count: Arc<AtomicU64>,
}

impl<R: Read> Read for Counting<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.count.fetch_add(n as u64, Ordering::Relaxed);
        Ok(n)
    }
}

impl<R: Seek> Seek for Counting<R> {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        self.inner.seek(pos)
    }
}

type TiffReader = Decoder<Patched<Counting<BufReader<File>>>>;

/// An open prepared file: its header and a decoder positioned on some directory.
pub struct PreparedFile {
    /// The file.
    pub path: PathBuf,
    /// What its header says.
    pub header: Header,
    /// A decoder per level, opened when the level is first read (each holds its directory's
    /// chunk offsets, read once).
    decoders: Vec<Mutex<Option<TiffReader>>>,
    /// The directories' patch ([`crate::tiffpatch`]) and the file's length.
    patch: crate::tiffpatch::Patch,
    len: u64,
    bytes_read: Arc<AtomicU64>,
}

impl std::fmt::Debug for PreparedFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PreparedFile").field("path", &self.path).finish_non_exhaustive()
    }
}

/// True if `head` (a file's first bytes) starts a TIFF file (either byte order, or BigTIFF).
pub fn is_tiff(head: &[u8]) -> bool {
    head.starts_with(b"II*\0")
        || head.starts_with(b"MM\0*")
        || head.starts_with(b"II+\0")
        || head.starts_with(b"MM\0+")
}

fn tag_f32s(d: &mut TiffReader, tag: u16, n: usize) -> Result<Option<Vec<f32>>, String> {
    let Some(v) = d.find_tag(Tag::Unknown(tag)).map_err(|e| e.to_string())? else {
        return Ok(None);
    };
    let v = match v {
        tiff::decoder::ifd::Value::List(_) => v.into_f32_vec(),
        one => one.into_f32().map(|x| vec![x]),
    }
    .map_err(|e| format!("tag {tag}: {e}"))?;
    if v.len() != n {
        return Err(format!("tag {tag} has {} values, not {n}", v.len()));
    }
    Ok(Some(v))
}

fn tag_text(d: &mut TiffReader, tag: u16) -> Result<Option<String>, String> {
    match d.find_tag(Tag::Unknown(tag)).map_err(|e| e.to_string())? {
        None => Ok(None),
        Some(v) => v
            .into_string()
            .map(|s| Some(s.trim_end_matches('\0').to_string()))
            .map_err(|e| format!("tag {tag}: {e}")),
    }
}

/// The wrap mode a word names (every renderer's spelling).
pub fn wrap_of(word: &str) -> Option<Wrap> {
    Some(match word.trim().to_ascii_lowercase().as_str() {
        "periodic" | "repeat" => Wrap::Periodic,
        "clamp" => Wrap::Clamp,
        "black" | "trunc" => Wrap::Black,
        _ => return None,
    })
}

/// One directory's layout, checked against the file's length.
fn directory(d: &mut TiffReader, file_len: u64) -> Result<(DirInfo, u32, SampleType), String> {
    let (width, height) = d.dimensions().map_err(|e| e.to_string())?;
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(format!("{width} x {height} texels is out of range (1 to {MAX_SIDE} a side)"));
    }
    let u =
        |d: &mut TiffReader, tag: Tag| d.find_tag_unsigned::<u32>(tag).map_err(|e| e.to_string());
    let channels = u(d, Tag::SamplesPerPixel)?.unwrap_or(1);
    if !(1..=4).contains(&channels) {
        return Err(format!("{channels} channels (1 to 4 are read)"));
    }
    let planar = match u(d, Tag::PlanarConfiguration)?.unwrap_or(1) {
        1 => false,
        2 => true,
        p => return Err(format!("PlanarConfiguration {p}")),
    };
    let bits = d
        .find_tag_unsigned_vec::<u32>(Tag::BitsPerSample)
        .map_err(|e| e.to_string())?
        .unwrap_or_else(|| vec![1]);
    if bits.is_empty() || bits.iter().any(|&b| b != bits[0]) {
        return Err("channels of different sizes".into());
    }
    let formats = d.find_tag_unsigned_vec::<u32>(Tag::SampleFormat).map_err(|e| e.to_string())?;
    let format = formats.and_then(|f| f.first().copied()).unwrap_or(1);
    let sample = match (format, bits[0]) {
        (1, 8 | 16 | 32) => SampleType::Uint(bits[0] as u8),
        (2, 8 | 16 | 32) => SampleType::Int(bits[0] as u8),
        (3, 16 | 32 | 64) => SampleType::Float(bits[0] as u8),
        (f, b) => return Err(format!("{b}-bit samples of format {f} are not read")),
    };
    let tiled = d.get_chunk_type() == tiff::decoder::ChunkType::Tile;
    let (offsets, counts) = if tiled {
        (Tag::TileOffsets, Tag::TileByteCounts)
    } else {
        (Tag::StripOffsets, Tag::StripByteCounts)
    };
    let offsets = d.find_tag_unsigned_vec::<u64>(offsets).map_err(|e| e.to_string())?;
    let counts = d.find_tag_unsigned_vec::<u64>(counts).map_err(|e| e.to_string())?;
    let (Some(offsets), Some(counts)) = (offsets, counts) else {
        return Err("no chunk offsets or byte counts".into());
    };
    let (chunk_w, chunk_h) = d.chunk_dimensions();
    if chunk_w == 0 || chunk_h == 0 {
        return Err("a chunk of zero size".into());
    }

    let chunks_x = width.div_ceil(chunk_w);
    let planes = if planar { u64::from(channels) } else { 1 };
    let chunks = u64::from(chunks_x) * u64::from(height.div_ceil(chunk_h)) * planes;
    if offsets.len() as u64 != chunks || counts.len() as u64 != chunks {
        return Err(format!(
            "{} chunk offsets and {} byte counts for {chunks} chunks",
            offsets.len(),
            counts.len()
        ));
    }
    for (o, c) in offsets.iter().zip(&counts) {
        if o.checked_add(*c).is_none_or(|end| end > file_len) {
            return Err(format!(
                "truncated: a chunk at byte {o} of {c} bytes ends past the file's {file_len}"
            ));
        }
    }
    Ok((DirInfo { width, height, chunk_w, chunk_h, chunks_x, tiled, planar }, channels, sample))
}

/// Pixie's world-to-NDC matrix (x, y in [0, 1], y down) as world to screen ([-1, 1], y up):
/// screen x = 2 ndc x - w, screen y = w - 2 ndc y, on the homogeneous columns.
fn ndc_to_screen(m: &[f32]) -> [f32; 16] {
    let mut out = [0.0; 16];
    for r in 0..4 {
        let (x, y, z, w) = (m[4 * r], m[4 * r + 1], m[4 * r + 2], m[4 * r + 3]);
        out[4 * r..4 * r + 4].copy_from_slice(&[2.0 * x - w, w - 2.0 * y, z, w]);
    }
    out
}

impl PreparedFile {
    /// Opens `path` and reads its header.
    ///
    /// # Errors
    ///
    /// [`TextureError::Io`] if it cannot be opened or read; [`TextureError::Decode`] if it is
    /// not a TIFF file, or one this reader cannot use (see the module).
    pub fn open(path: &Path) -> Result<PreparedFile, TextureError> {
        let io = |source| TextureError::Io { file: path.to_path_buf(), source };
        let bad = |message: String| TextureError::Decode { file: path.to_path_buf(), message };
        let file = File::open(path).map_err(io)?;
        let file_len = file.metadata().map_err(io)?.len();
        let bytes_read = Arc::new(AtomicU64::new(0));
        let mut counted = Counting { inner: BufReader::new(file), count: bytes_read.clone() };
        let (tail, pokes) = directories_needing_a_patch(&mut counted, file_len).map_err(io)?;
        let patch = (tail.clone(), pokes.clone());
        let reader = Patched { inner: counted, len: file_len, tail, pokes, pos: 0 };
        let mut limits = Limits::default();
        limits.decoding_buffer_size = 1 << 28;
        let mut d = Decoder::new(reader)
            .map_err(|e| match e {
                tiff::TiffError::IoError(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
                    bad("truncated: its first directory ends past the file".into())
                }
                e => bad(format!("not a readable TIFF file: {e}")),
            })?
            .with_limits(limits);
        let format = tag_text(&mut d, TAG_TEXTUREFORMAT).map_err(&bad)?.unwrap_or_default();
        let kind = MapKind::from_format(&format);
        let wrap_text = tag_text(&mut d, TAG_WRAPMODES).map_err(&bad)?.unwrap_or_default();
        let words: Vec<&str> =
            wrap_text.split([',', ' ']).filter(|w| !w.trim().is_empty()).collect();
        let wrap = match words.as_slice() {
            [s, t] => wrap_of(s).zip(wrap_of(t)).map(|(s, t)| [s, t]),
            [both] => wrap_of(both).map(|w| [w, w]),
            _ => None,
        };
        let fov_cot = tag_f32s(&mut d, TAG_FOVCOT, 1).map_err(&bad)?.map(|v| v[0]);
        let mut world_to_screen = tag_f32s(&mut d, TAG_WORLDTOSCREEN, 16).map_err(&bad)?;
        if format.to_ascii_lowercase().starts_with("pixie") {
            world_to_screen = world_to_screen.map(|m| ndc_to_screen(&m).to_vec());
        }
        let world_to_camera = tag_f32s(&mut d, TAG_WORLDTOCAMERA, 16).map_err(&bad)?;
        let to16 = |v: Vec<f32>| -> [f32; 16] { std::array::from_fn(|k| v[k]) };
        let (first, channels, sample) = directory(&mut d, file_len).map_err(&bad)?;
        let mut levels = vec![first];
        let mut directories = 1;
        while d.more_images() {
            d.next_image().map_err(|e| bad(format!("directory {directories}: {e}")))?;
            let (info, c, s) = directory(&mut d, file_len)
                .map_err(|e| bad(format!("directory {directories}: {e}")))?;
            directories += 1;
            let last = levels[levels.len() - 1];
            let halves = |a: u32, b: u32| b == a / 2 || b == a.div_ceil(2);
            let next_level = levels.len() == directories as usize - 1
                && (last.width > 1 || last.height > 1)
                && halves(last.width, info.width)
                && halves(last.height, info.height);
            if next_level && c == channels && s == sample {
                levels.push(info);
            }
            if directories > 64 {
                return Err(bad("more than 64 directories".into()));
            }
        }
        d.seek_to_image(0).map_err(|e| bad(e.to_string()))?;
        let header = Header {
            format,
            kind,
            wrap,
            wrap_text,
            fov_cot,
            world_to_screen: world_to_screen.map(to16),
            world_to_camera: world_to_camera.map(to16),
            channels,
            sample,
            levels,
            directories,
        };
        let mut decoders: Vec<Mutex<Option<TiffReader>>> =
            (0..header.levels.len()).map(|_| Mutex::new(None)).collect();
        decoders[0] = Mutex::new(Some(d));
        Ok(PreparedFile {
            path: path.to_path_buf(),
            header,
            decoders,
            patch,
            len: file_len,
            bytes_read,
        })
    }

    /// A decoder on directory `level`, over the file opened again.
    fn open_level(&self, level: usize) -> std::io::Result<TiffReader> {
        let bad = |e: tiff::TiffError| {
            std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string())
        };
        let file = File::open(&self.path)?;
        let counted = Counting { inner: BufReader::new(file), count: self.bytes_read.clone() };
        let (tail, pokes) = self.patch.clone();
        let reader = Patched { inner: counted, len: self.len, tail, pokes, pos: 0 };
        let mut limits = Limits::default();
        limits.decoding_buffer_size = 1 << 28;
        let mut d = Decoder::new(reader).map_err(bad)?.with_limits(limits);
        d.seek_to_image(level).map_err(bad)?;
        Ok(d)
    }

    /// Bytes read from the file so far (header and chunks).
    pub fn bytes_read(&self) -> u64 {
        self.bytes_read.load(Ordering::Relaxed)
    }

    /// Chunk `index` of level `level` as RGBA floats, `chunk_w x chunk_h` texels row by row
    /// (past the image's edge: 0).
    ///
    /// # Errors
    ///
    /// The decoder's error (a corrupt chunk) as an I/O error naming nothing (the caller names
    /// the file).
    pub fn read_chunk(&self, level: usize, index: u32) -> std::io::Result<Vec<f32>> {
        let bad = |e: String| std::io::Error::new(std::io::ErrorKind::InvalidData, e);
        let info = *self.header.levels.get(level).ok_or_else(|| bad("no such level".into()))?;
        let chunks_y = info.height.div_ceil(info.chunk_h);
        self.header.check_chunks().map_err(bad)?;
        if index >= info.chunks_x * chunks_y {
            return Err(bad(format!("no chunk {index}")));
        }
        let mut guard = self.decoders[level].lock().unwrap_or_else(PoisonError::into_inner);
        if guard.is_none() {
            *guard = Some(self.open_level(level)?);
        }
        let Some(d) = guard.as_mut() else { return Err(bad("no decoder".into())) };
        let (dw, dh) = (
            info.chunk_w.min(info.width - (index % info.chunks_x) * info.chunk_w),
            info.chunk_h.min(info.height - (index / info.chunks_x) * info.chunk_h),
        );
        let c = self.header.channels as usize;
        let planes = if info.planar { c } else { 1 };
        let per_plane = info.chunks_x * chunks_y;
        let mut read = Vec::with_capacity(planes);
        for p in 0..planes {
            let data =
                d.read_chunk(index + p as u32 * per_plane).map_err(|e| bad(e.to_string()))?;
            read.push(samples(data)?);
        }
        drop(guard);
        let values = if planes == 1 {
            read.swap_remove(0)
        } else {
            let n = read.iter().map(Vec::len).min().unwrap_or(0);
            (0..n).flat_map(|k| read.iter().map(move |plane| plane[k])).collect()
        };
        // The decoder returns the chunk's data without padding, or with (a strip's width is
        // the image's): take the row length from the data itself.
        let rows = dh as usize;
        let row_len = values.len().checked_div(rows).unwrap_or(0) / c;
        if row_len < dw as usize {
            return Err(bad(format!("a chunk of {} samples, short of {dw} x {dh}", values.len())));
        }
        let (cw, ch) = (info.chunk_w as usize, info.chunk_h as usize);
        let mut out = vec![0.0f32; cw * ch * 4];
        for y in 0..rows {
            for x in 0..dw as usize {
                let src = &values[(y * row_len + x) * c..(y * row_len + x) * c + c];
                let px = match c {
                    1 => [src[0], src[0], src[0], 1.0],
                    2 => [src[0], src[0], src[0], src[1]],
                    3 => [src[0], src[1], src[2], 1.0],
                    _ => [src[0], src[1], src[2], src[3]],
                };
                let k = 4 * (y * cw + x);
                for (o, v) in out[k..k + 4].iter_mut().zip(px) {
                    *o = if v.is_finite() { v } else { 0.0 };
                }
            }
        }
        Ok(out)
    }
}

/// A decoded chunk's samples as floats (integers scaled to [0, 1] or [-1, 1]).
fn samples(data: DecodingResult) -> std::io::Result<Vec<f32>> {
    let bad = |e: &str| std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string());
    Ok(match data {
        DecodingResult::U8(v) => v.iter().map(|&x| f32::from(x) / 255.0).collect(),
        DecodingResult::U16(v) => v.iter().map(|&x| f32::from(x) / 65535.0).collect(),
        DecodingResult::U32(v) => v.iter().map(|&x| (f64::from(x) / 4294967295.0) as f32).collect(),
        DecodingResult::I8(v) => v.iter().map(|&x| f32::from(x) / 127.0).collect(),
        DecodingResult::I16(v) => v.iter().map(|&x| f32::from(x) / 32767.0).collect(),
        DecodingResult::I32(v) => v.iter().map(|&x| (f64::from(x) / 2147483647.0) as f32).collect(),
        DecodingResult::F16(v) => v.iter().map(|x| x.to_f32()).collect(),
        DecodingResult::F32(v) => v,
        DecodingResult::F64(v) => v.iter().map(|&x| x as f32).collect(),
        _ => return Err(bad("unsupported sample type")),
    })
}
