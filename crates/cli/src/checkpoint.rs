//! `--checkpoint DIR`: every finished bucket is written to disk as it completes, and a run
//! with the same arguments skips the buckets already there (docs/farm.md).
//!
//! Layout: `DIR/FINGERPRINT/bucket.N.exr`, one bucket file ([`reyes_film::tiles`]) per
//! finished bucket, in a folder named by the render's [`fingerprint`](crate::pieces), so a
//! checkpoint of other arguments or another scene lies in another folder and is never
//! read. Every file's header is checked again on reading: one that names another render
//! is refused (exit 2), never mixed in. The folder is removed once the frame's output is
//! written.
//!
//! Invariant: bucket files are written atomically (a temporary file renamed into place), so
//! the folder only ever holds complete bucket files, whenever the render is killed; a
//! resumed frame adds the stored windows in their raster places, so its output is the
//! uninterrupted render's, byte for byte.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use reyes_film::WriteOptions;
use reyes_render::BucketResult;

use crate::Exit;
use crate::pieces::{Header, read_piece, write_piece};
use crate::term::say;

/// An open checkpoint of one frame.
pub(crate) struct Checkpoint {
    dir: PathBuf,
    header: Header,
    /// The first failure to write a bucket file (the render is then cancelled).
    failure: Mutex<Option<String>>,
}

impl Checkpoint {
    /// Open (creating it if need be) the checkpoint under `root` of the render `header`
    /// describes, and read the buckets already done.
    pub(crate) fn open(
        root: &Path,
        header: Header,
    ) -> Result<(Checkpoint, BTreeMap<usize, BucketResult>), Exit> {
        let dir = root.join(&header.fingerprint);
        std::fs::create_dir_all(&dir).map_err(|e| {
            Exit::error(1, format_args!("{}: --checkpoint: cannot create: {e}", dir.display()))
        })?;
        reyes_film::remove_stale_temporaries(&dir);
        let entries = std::fs::read_dir(&dir).map_err(|e| {
            Exit::error(1, format_args!("{}: --checkpoint: cannot read: {e}", dir.display()))
        })?;
        let mut done = BTreeMap::new();
        let mut names: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        names.sort();
        for path in names {
            let Some(b) = bucket_of(&path) else { continue };
            let piece = match read_piece(&path) {
                Ok(p) => p,
                Err(_) => {
                    say(format_args!(
                        "{}: warning: --checkpoint: unreadable bucket file, rendering it again",
                        path.display()
                    ));
                    continue;
                }
            };
            let h = &piece.header;
            if h.fingerprint != header.fingerprint
                || h.version != header.version
                || h.tile != (0, 0)
            {
                return Err(Exit::error(
                    2,
                    format_args!(
                        "{}: --checkpoint: a bucket of another render (fingerprint {}, version {}); \
                         remove {} or choose another directory",
                        path.display(),
                        h.fingerprint,
                        h.version,
                        dir.display()
                    ),
                ));
            }
            let result = match piece.buckets.as_slice() {
                [] => BucketResult::default(),
                [(k, r)] if *k == b => r.clone(),
                _ => {
                    return Err(Exit::error(
                        2,
                        format_args!(
                            "{}: --checkpoint: does not hold bucket {b} alone",
                            path.display()
                        ),
                    ));
                }
            };
            done.insert(b, result);
        }
        Ok((Checkpoint { dir, header, failure: Mutex::new(None) }, done))
    }

    /// Write bucket `b`'s result (from a worker thread). A failure cancels the render.
    pub(crate) fn save(&self, b: usize, result: &BucketResult) {
        let path = self.dir.join(format!("bucket.{b}.exr"));
        let results = [(b, result.clone())];
        if let Err(e) = write_piece(&path, &self.header, &results, &WriteOptions::default()) {
            let mut f = self.failure.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            if f.is_none() {
                *f = Some(format!("--checkpoint: {e}"));
            }
            reyes_render::cancel::request();
        }
    }

    /// Why a bucket file could not be written, if one could not.
    pub(crate) fn failure(&self) -> Option<String> {
        self.failure.lock().unwrap_or_else(std::sync::PoisonError::into_inner).clone()
    }

    /// The frame's output is written: the checkpoint is no longer needed.
    pub(crate) fn finish(self) {
        if let Err(e) = std::fs::remove_dir_all(&self.dir) {
            say(format_args!("{}: warning: --checkpoint: cannot remove: {e}", self.dir.display()));
        }
    }
}

/// `N` of a file named `bucket.N.exr`.
fn bucket_of(path: &Path) -> Option<usize> {
    let name = path.file_name()?.to_str()?;
    name.strip_prefix("bucket.")?.strip_suffix(".exr")?.parse().ok()
}
