//! A classic TIFF file seen with a PhotometricInterpretation tag added to every directory
//! that lacks one: Pixie's `texmake` writes none, and the `tiff` decoder requires it.
//!
//! Invariants: only the header's and the directories' bytes are read to make the patch; the
//! patched directories are appended past the file's end and the pointers to them redirected,
//! so every chunk reads through unchanged; a file that needs nothing is read as it is.

use std::io::{Read, Seek, SeekFrom};

/// The bytes appended past a file's end, and the single bytes replaced inside it.
pub(crate) type Patch = (Vec<u8>, Vec<(u64, u8)>);

/// A classic TIFF file seen with a PhotometricInterpretation tag added to every directory
/// that lacks one (Pixie's `texmake` writes none, and the decoder requires it): the patched
/// directories are appended past the file's end, and the header's and each directory's
/// pointer to the next are redirected to them. Everything else reads through unchanged.
pub(crate) struct Patched<R> {
    pub(crate) inner: R,
    pub(crate) len: u64,
    /// Bytes past the file's end.
    pub(crate) tail: Vec<u8>,
    /// Replacements of single bytes inside the file (the redirected pointers).
    pub(crate) pokes: Vec<(u64, u8)>,
    pub(crate) pos: u64,
}

impl<R: Read + Seek> Read for Patched<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.pos >= self.len {
            let at = ((self.pos - self.len) as usize).min(self.tail.len());
            let n = buf.len().min(self.tail.len() - at);
            buf[..n].copy_from_slice(&self.tail[at..at + n]);
            self.pos += n as u64;
            return Ok(n);
        }
        let want = buf.len().min((self.len - self.pos) as usize);
        self.inner.seek(SeekFrom::Start(self.pos))?;
        let n = self.inner.read(&mut buf[..want])?;
        for &(at, b) in &self.pokes {
            if at >= self.pos && at < self.pos + n as u64 {
                buf[(at - self.pos) as usize] = b;
            }
        }
        self.pos += n as u64;
        Ok(n)
    }
}

impl<R: Read + Seek> Seek for Patched<R> {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        let end = self.len + self.tail.len() as u64;
        let p = match to {
            SeekFrom::Start(p) => Some(p),
            SeekFrom::End(d) => end.checked_add_signed(d),
            SeekFrom::Current(d) => self.pos.checked_add_signed(d),
        };
        self.pos = p.ok_or_else(|| std::io::Error::other("seek before the start"))?;
        Ok(self.pos)
    }
}

/// The patch of [`Patched`] for `bytes` (the whole file; None when nothing needs it or the
/// file is not a classic TIFF it can walk).
fn photometric_patch(bytes: &[u8]) -> Option<Patch> {
    let le = bytes.starts_with(b"II*\0");
    if !le && !bytes.starts_with(b"MM\0*") {
        return None;
    }
    let u16_at = |o: usize| -> Option<u16> {
        let b: [u8; 2] = bytes.get(o..o + 2)?.try_into().ok()?;
        Some(if le { u16::from_le_bytes(b) } else { u16::from_be_bytes(b) })
    };
    let u32_at = |o: usize| -> Option<u32> {
        let b: [u8; 4] = bytes.get(o..o + 4)?.try_into().ok()?;
        Some(if le { u32::from_le_bytes(b) } else { u32::from_be_bytes(b) })
    };
    let w16 = |v: u16| if le { v.to_le_bytes() } else { v.to_be_bytes() };
    let w32 = |v: u32| if le { v.to_le_bytes() } else { v.to_be_bytes() };
    let mut tail = Vec::new();
    let mut pokes = Vec::new();
    let mut pointer_at = 4usize;
    let mut ifd = u32_at(4)? as usize;
    let mut any = false;
    for _ in 0..64 {
        if ifd == 0 {
            break;
        }
        let n = u16_at(ifd)? as usize;
        let entries: Vec<&[u8]> = (0..n)
            .map(|k| bytes.get(ifd + 2 + 12 * k..ifd + 14 + 12 * k))
            .collect::<Option<_>>()?;
        let tag = |e: &[u8]| {
            if le { u16::from_le_bytes([e[0], e[1]]) } else { u16::from_be_bytes([e[0], e[1]]) }
        };
        let next = u32_at(ifd + 2 + 12 * n)?;
        if entries.iter().all(|e| tag(e) != 262) {
            any = true;
            let samples = entries
                .iter()
                .find(|e| tag(e) == 277)
                .map(|e| {
                    if le {
                        u16::from_le_bytes([e[8], e[9]])
                    } else {
                        u16::from_be_bytes([e[8], e[9]])
                    }
                })
                .unwrap_or(1);
            let mut entry = Vec::with_capacity(12);
            entry.extend_from_slice(&w16(262));
            entry.extend_from_slice(&w16(3));
            entry.extend_from_slice(&w32(1));
            entry.extend_from_slice(&w16(if samples >= 3 { 2 } else { 1 }));
            entry.extend_from_slice(&[0, 0]);
            let new_at = (bytes.len() + tail.len()) as u32;
            tail.extend_from_slice(&w16(n as u16 + 1));
            let mut placed = false;
            for e in &entries {
                if !placed && tag(e) > 262 {
                    tail.extend_from_slice(&entry);
                    placed = true;
                }
                tail.extend_from_slice(e);
            }
            if !placed {
                tail.extend_from_slice(&entry);
            }
            let next_at = bytes.len() + tail.len();
            tail.extend_from_slice(&w32(next));
            if tail.len() % 2 == 1 {
                tail.push(0);
            }
            redirect(&mut tail, &mut pokes, bytes.len(), pointer_at, w32(new_at));
            pointer_at = next_at;
        } else {
            pointer_at = ifd + 2 + 12 * n;
        }
        ifd = next as usize;
    }
    any.then_some((tail, pokes))
}

/// Reads the directories' bytes (only the header and the directories) and makes the patch.
pub(crate) fn directories_needing_a_patch<R: Read + Seek>(
    r: &mut R,
    len: u64,
) -> std::io::Result<Patch> {
    // Read the file sparsely: the header, then each directory, into a buffer as long as
    // the file whose other bytes stay zero (only directories and the header are looked at).
    // Files are at most a few hundred MB; the buffer is allocated lazily by directory.
    let mut head = [0u8; 8];
    r.seek(SeekFrom::Start(0))?;
    if r.read_exact(&mut head).is_err() {
        return Ok((Vec::new(), Vec::new()));
    }
    let le = head.starts_with(b"II*\0");
    if !le && !head.starts_with(b"MM\0*") {
        return Ok((Vec::new(), Vec::new()));
    }
    let mut sparse = Sparse { bytes: std::collections::BTreeMap::new() };
    sparse.bytes.insert(0, head.to_vec());
    let u32v = |b: [u8; 4]| if le { u32::from_le_bytes(b) } else { u32::from_be_bytes(b) };
    let mut ifd = u64::from(u32v([head[4], head[5], head[6], head[7]]));
    for _ in 0..64 {
        if ifd == 0 || ifd + 2 > len {
            break;
        }
        let mut n = [0u8; 2];
        r.seek(SeekFrom::Start(ifd))?;
        r.read_exact(&mut n)?;
        let n = u64::from(if le { u16::from_le_bytes(n) } else { u16::from_be_bytes(n) });
        let size = 2 + 12 * n + 4;
        if ifd + size > len {
            break;
        }
        let mut dir = vec![0u8; size as usize];
        r.seek(SeekFrom::Start(ifd))?;
        r.read_exact(&mut dir)?;
        let next = &dir[dir.len() - 4..];
        let next = u64::from(u32v([next[0], next[1], next[2], next[3]]));
        sparse.bytes.insert(ifd, dir);
        ifd = next;
    }
    r.seek(SeekFrom::Start(0))?;
    Ok(sparse.patch(len).unwrap_or_default())
}

/// Some ranges of a file's bytes.
struct Sparse {
    bytes: std::collections::BTreeMap<u64, Vec<u8>>,
}

impl Sparse {
    /// [`photometric_patch`] over a buffer as long as the file with only the read ranges set.
    fn patch(&self, len: u64) -> Option<Patch> {
        let mut all = vec![0u8; usize::try_from(len).ok()?];
        for (&at, b) in &self.bytes {
            all[at as usize..at as usize + b.len()].copy_from_slice(b);
        }
        photometric_patch(&all)
    }
}

/// Writes `value` at `at`: inside the tail, or as pokes into the file.
fn redirect(tail: &mut [u8], pokes: &mut Vec<(u64, u8)>, len: usize, at: usize, value: [u8; 4]) {
    for (k, b) in value.into_iter().enumerate() {
        if at + k >= len {
            tail[at + k - len] = b;
        } else {
            pokes.push(((at + k) as u64, b));
        }
    }
}
