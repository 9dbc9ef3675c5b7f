//! The beauty's EXR blocks, compressed while the frame is still rendering (stage: film, moved
//! ahead of the write): a scanline block whose lines no later bucket adds to can be encoded
//! as soon as its lines are final, in the render's worker pool, beside the buckets still
//! being rendered; the write then stores the chunks it finds ready and compresses only the
//! rest.
//!
//! Invariant (same bytes): a block's chunk is a function of the block's pixels and the
//! layer's header alone ([`exr::block::UncompressedBlock::compress_to_chunk`]), and blocks are
//! stored in the file in the same order whichever of them were ready, so a file written with
//! [`EarlyBlocks`] is byte for byte the file written without. The write uses the chunks only
//! when its own beauty header agrees with the one they were made for (size, channels,
//! compression, block layout; [`EarlyBlocks::fits`]); otherwise it compresses everything.

use std::ops::Range;
use std::sync::Mutex;

use exr::block::chunk::Chunk;
use exr::block::{BlockIndex, UncompressedBlock};
use exr::meta::header::Header;
use exr::prelude::*;
use rayon::prelude::*;
use reyes_scene::{Outputs, PixelType};

use crate::Film;

/// Compressed scanline blocks of a frame's beauty layer (R, G, B, A and Z), made from the
/// film's final lines as they come ([`EarlyBlocks::encode`]).
#[derive(Debug)]
pub struct EarlyBlocks {
    /// The beauty layer's header, as the write infers it for a whole (uncropped) frame.
    header: Header,
    width: usize,
    height: usize,
    /// Lines per block (1, 16 or 32 by compression).
    lines: usize,
    /// RGBA stored as half floats (Z is always float).
    half: bool,
    /// What `+inf` depth is stored as.
    zbackground: f32,
    /// Per block: its chunk, once made.
    chunks: Mutex<Vec<Option<Chunk>>>,
}

impl EarlyBlocks {
    /// The blocks of a `width x height` frame written with `outputs`; `named` when the beauty
    /// is one layer among AOV layers (it is then called `rgba`).
    /// None only if the encoder infers no header (it infers one per layer).
    pub fn new(width: u32, height: u32, outputs: &Outputs, named: bool) -> Option<EarlyBlocks> {
        let (w, h) = (width as usize, height as usize);
        let header = beauty_header((w, h), outputs, named)?;
        let lines = header.compression.scan_lines_per_block();
        let count = h.div_ceil(lines.max(1));
        Some(EarlyBlocks {
            header,
            width: w,
            height: h,
            lines: lines.max(1),
            half: outputs.pixel_type == PixelType::Half,
            zbackground: outputs.zbackground.value(),
            chunks: Mutex::new(vec![None; count]),
        })
    }

    /// Lines `lines` of `film` have just become final (no bucket still to come adds to
    /// them), and every line above them was final before: compress, in parallel in the
    /// current rayon pool, every block not yet made whose lines are all final. A range
    /// starting at line 0 starts again (a restarted render): the blocks made before are
    /// dropped.
    pub fn encode(&self, film: &Film, lines: Range<u32>) {
        if (film.width() as usize, film.height() as usize) != (self.width, self.height) {
            return;
        }
        let end = (lines.end as usize).min(self.height);
        let todo: Vec<usize> = {
            let Ok(mut chunks) = self.chunks.lock() else { return };
            if lines.start == 0 {
                chunks.iter_mut().for_each(|c| *c = None);
            }
            (0..chunks.len())
                .filter(|&k| chunks[k].is_none() && self.block_lines(k).end <= end)
                .collect()
        };
        let made: Vec<(usize, Chunk)> = todo
            .into_par_iter()
            .filter_map(|k| self.compress(film, k).ok().map(|c| (k, c)))
            .collect();
        if let Ok(mut chunks) = self.chunks.lock() {
            for (k, c) in made {
                chunks[k] = Some(c);
            }
        }
    }

    /// Whether chunks made for this header can stand in for the write's: the header of the
    /// beauty layer the write infers, `written`, stores the same pixels in the same blocks.
    pub(crate) fn fits(&self, written: &Header) -> bool {
        let (a, b) = (&self.header, written);
        a.channels == b.channels
            && a.compression == b.compression
            && a.blocks == b.blocks
            && a.line_order == b.line_order
            && a.layer_size == b.layer_size
            && a.own_attributes.layer_position == b.own_attributes.layer_position
    }

    /// Block `k`'s chunk: the one made early, moved out (a write holds every chunk at once
    /// as it is, and a copy kept here would double that), or made now from `film`. A second
    /// write of the same frame recompresses: same bytes, more time.
    pub(crate) fn chunk(&self, film: &Film, k: usize) -> exr::error::Result<Chunk> {
        let ready = self.chunks.lock().ok().and_then(|mut c| c.get_mut(k).and_then(Option::take));
        match ready {
            Some(c) => Ok(c),
            None => self.compress(film, k),
        }
    }

    /// Blocks made so far (for tests).
    pub fn ready(&self) -> usize {
        self.chunks.lock().map_or(0, |c| c.iter().flatten().count())
    }

    /// The lines of block `k`.
    fn block_lines(&self, k: usize) -> Range<usize> {
        let y0 = k * self.lines;
        y0..(y0 + self.lines).min(self.height)
    }

    /// Compress block `k` of `film`.
    fn compress(&self, film: &Film, k: usize) -> exr::error::Result<Chunk> {
        let ys = self.block_lines(k);
        let index = BlockIndex {
            layer: 0,
            pixel_position: Vec2(0, ys.start),
            pixel_size: Vec2(self.width, ys.len()),
            level: Vec2(0, 0),
        };
        let block = UncompressedBlock { index, data: self.block_bytes(film, ys) };
        let mut chunk = block.compress_to_chunk(std::slice::from_ref(&self.header))?;
        // The compressor's output keeps the capacity of its uncompressed input: a frame's
        // chunks held until the write would otherwise take the frame's raw size, not its
        // compressed one (3.1 MB against 1.8 MB at 640 x 480, half RGBA and float Z). A fresh
        // exact copy, not a shrink in place: the shrunk buffers' freed tails fragmented the
        // heap (heavy-motion peaks 1.3 MB lower this way).
        if let exr::block::chunk::CompressedBlock::ScanLine(b) = &mut chunk.compressed_block {
            b.compressed_pixels_le = b.compressed_pixels_le.as_slice().to_vec();
        }
        Ok(chunk)
    }

    /// The uncompressed bytes of lines `ys`, as OpenEXR lays out a scanline block: line by
    /// line, and within a line channel by channel in the header's (alphabetical) order A, B,
    /// G, R, Z, each a run of little-endian samples.
    fn block_bytes(&self, film: &Film, ys: Range<usize>) -> Vec<u8> {
        let w = self.width;
        let size = if self.half { 2 } else { 4 };
        let mut out = Vec::with_capacity(ys.len() * w * (4 * size + 4));
        let (rgba, z) = (film.rgba(), film.z());
        for y in ys {
            let row = &rgba[y * w..(y + 1) * w];
            for k in [3, 2, 1, 0] {
                if self.half {
                    out.extend(row.iter().flat_map(|p| f16::from_f32(p[k]).to_le_bytes()));
                } else {
                    out.extend(row.iter().flat_map(|p| p[k].to_le_bytes()));
                }
            }
            let zbg = self.zbackground;
            let depth =
                z[y * w..(y + 1) * w].iter().map(|&d| if d == f32::INFINITY { zbg } else { d });
            out.extend(depth.flat_map(f32::to_le_bytes));
        }
        out
    }
}

/// The header the write gives a whole frame's beauty layer (see `layers::encode_picture`),
/// inferred by the encoder itself from a layer of the same channels, size and encoding.
fn beauty_header((w, h): (usize, usize), outputs: &Outputs, named: bool) -> Option<Header> {
    let plane = |ty: PixelType| match ty {
        PixelType::Float => FlatSamples::F32(Vec::new()),
        PixelType::Half => FlatSamples::F16(Vec::new()),
    };
    let ty = outputs.pixel_type;
    let channels = vec![
        AnyChannel::new("R", plane(ty)),
        AnyChannel::new("G", plane(ty)),
        AnyChannel::new("B", plane(ty)),
        AnyChannel::new("A", plane(ty)),
        AnyChannel::new("Z", plane(PixelType::Float)),
    ];
    let attributes = match named {
        true => LayerAttributes::named("rgba"),
        false => LayerAttributes::default(),
    };
    let layer = Layer::new(
        (w, h),
        attributes,
        crate::layers::encoding(outputs.compression),
        AnyChannels::sort(SmallVec::from_vec(channels)),
    );
    let image =
        Image::from_layers(ImageAttributes::new(IntegerBounds::new((0, 0), (w, h))), vec![layer]);
    image.write().infer_meta_data().into_iter().next()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{AovFilm, AovLayer, Metadata, Picture, WriteOptions, write_picture};
    use reyes_scene::Compression as Comp;

    /// A film with varied values: infinite depth, zero alpha, values that round in half.
    fn film(width: u32, height: u32, seed: u32) -> Film {
        let n = (width * height) as usize;
        let rgba = (0..n)
            .map(|k| {
                let t = ((k as u32).wrapping_mul(2_654_435_761) ^ seed) as f32 / u32::MAX as f32;
                let a = if k % 7 == 3 { 0.0 } else { 0.1 + 0.9 * t };
                [a * t, a * (1.0 - t), a * (0.3 + 0.7 * t * t), a]
            })
            .collect();
        let z = (0..n).map(|k| if k % 5 == 0 { f32::INFINITY } else { 1.0 + k as f32 / 3.0 });
        Film::from_pixels(width, height, rgba, z.collect()).unwrap_or_else(|| Film::new(1, 1))
    }

    fn metadata() -> Metadata {
        Metadata {
            world_to_camera: [0.0; 16],
            world_to_ndc: [1.0; 16],
            screen_window: [-1.0, 1.0, -0.75, 0.75],
            software: "test".into(),
            scene: "t.ron".into(),
            seed: 3,
            samples: (2, 2),
            filter: "Gaussian 2x2".into(),
            render_time: None,
        }
    }

    /// The file `picture` makes (with `early`, or without).
    fn bytes(picture: &Picture, early: Option<&EarlyBlocks>) -> Vec<u8> {
        let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
        let path = dir.path().join("t.exr");
        let p = Picture { early, ..*picture };
        write_picture(&path, &p, &WriteOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn files_with_early_blocks_are_the_files_without() {
        // 37 lines: a last block of 5 (ZIP, 16 lines) or 5 (PIZ/DWAA, 32); odd width.
        let (w, h) = (23, 37);
        let f = film(w, h, 1);
        // The AOV layer's own blocks are compressed by the write either way.
        let aov = AovFilm::new(w, h, 2);
        let layers = [AovLayer {
            name: "uv".into(),
            channels: vec!["X", "Y"],
            start: 0,
            integer: false,
            pixel_type: PixelType::Float,
            compression: Comp::Zip,
        }];
        let m = metadata();
        for ty in [PixelType::Float, PixelType::Half] {
            for comp in [Comp::None, Comp::Zip, Comp::Piz, Comp::Dwaa] {
                for with_aovs in [false, true] {
                    let outputs =
                        Outputs { pixel_type: ty, compression: comp, ..Outputs::default() };
                    let aovs = with_aovs.then_some((&aov, &layers[..]));
                    let picture = Picture {
                        film: &f,
                        aovs,
                        outputs: &outputs,
                        metadata: &m,
                        placement: None,
                        early: None,
                    };
                    let want = bytes(&picture, None);
                    let what = format!("{ty:?} {comp:?} aovs {with_aovs}");
                    let early = EarlyBlocks::new(w, h, &outputs, with_aovs)
                        .unwrap_or_else(|| panic!("{what}: no header"));
                    // None ready, then the lines of a first bucket row, then all of them.
                    assert_eq!(bytes(&picture, Some(&early)), want, "{what}: none ready");
                    early.encode(&f, 0..13);
                    let lines = early.lines;
                    assert_eq!(early.ready(), 13 / lines, "{what}");
                    assert_eq!(bytes(&picture, Some(&early)), want, "{what}: some ready");
                    // The write took the chunks it used: none are left to it.
                    assert_eq!(early.ready(), 0, "{what}: taken");
                    early.encode(&f, 0..h);
                    assert_eq!(early.ready(), (h as usize).div_ceil(lines), "{what}");
                    assert_eq!(bytes(&picture, Some(&early)), want, "{what}: all ready");
                }
            }
        }
    }

    #[test]
    fn a_range_from_line_0_starts_again() {
        let (w, h) = (16, 40);
        let (old, new) = (film(w, h, 1), film(w, h, 2));
        let outputs = Outputs::default();
        let m = metadata();
        let picture = Picture {
            film: &new,
            aovs: None,
            outputs: &outputs,
            metadata: &m,
            placement: None,
            early: None,
        };
        let early = EarlyBlocks::new(w, h, &outputs, false).unwrap_or_else(|| panic!("header"));
        early.encode(&old, 0..32);
        assert_eq!(early.ready(), 2);
        // The render started again: the old blocks go, the new ones come as their lines do.
        early.encode(&new, 0..16);
        assert_eq!(early.ready(), 1);
        assert_eq!(bytes(&picture, Some(&early)), bytes(&picture, None));
    }

    #[test]
    fn chunks_for_another_header_are_not_used() {
        let (w, h) = (16, 20);
        let f = film(w, h, 4);
        let zip = Outputs::default();
        let piz = Outputs { compression: Comp::Piz, ..Outputs::default() };
        let m = metadata();
        let picture = Picture {
            film: &f,
            aovs: None,
            outputs: &piz,
            metadata: &m,
            placement: None,
            early: None,
        };
        let early = EarlyBlocks::new(w, h, &zip, false).unwrap_or_else(|| panic!("header"));
        early.encode(&f, 0..h);
        assert_eq!(bytes(&picture, Some(&early)), bytes(&picture, None));
        // A crop window's file (placed in a larger frame) never takes them either.
        let placed = Picture {
            placement: Some(crate::Placement { full: (40, 40), origin: (3, 5) }),
            outputs: &zip,
            ..picture
        };
        assert_eq!(bytes(&placed, Some(&early)), bytes(&placed, None));
    }
}
