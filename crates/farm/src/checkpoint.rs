//! Checkpoints: every finished bucket written to disk as it completes, and read back so that
//! a run with the same arguments renders only the rest (docs/farm.md).
//!
//! Layout: `ROOT/FINGERPRINT/bucket.N.exr`, one bucket file ([`reyes_film::tiles`]) per
//! finished bucket, in a folder named by the render's [`fingerprint`](crate::fingerprint()),
//! so a checkpoint of other arguments or another scene lies in another folder and is never
//! read. Every file's header is checked again on reading: one that names another render is
//! refused (exit 2), never mixed in. The folder is removed once the frame's output is
//! written ([`Checkpoint::finish`]).
//!
//! Invariant: bucket files are written atomically (a temporary file renamed into place), so
//! the folder only ever holds complete bucket files, whenever the process is killed; a
//! resumed frame adds the stored windows in their raster places, so its output is the
//! uninterrupted render's, byte for byte.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use reyes_film::WriteOptions;
use reyes_render::BucketResult;

use crate::piece::{Header, read_piece, write_piece};
use crate::{FarmError, one_line};

/// An open checkpoint of one frame.
#[derive(Debug)]
pub struct Checkpoint {
    dir: PathBuf,
    header: Header,
    done: BTreeMap<usize, BucketResult>,
    /// The first failure to write a bucket file (the render is then cancelled).
    failure: Mutex<Option<String>>,
}

impl Checkpoint {
    /// Open (creating it if need be) the checkpoint under `root` of the render `header`
    /// describes (a checkpoint's header: tile `(0, 0)`), and read the buckets already done
    /// ([`Checkpoint::done`]). An unreadable bucket file is left to be rendered again, with
    /// a line to `warn`.
    pub fn open(
        root: &Path,
        header: Header,
        warn: &mut dyn FnMut(String),
    ) -> Result<Checkpoint, FarmError> {
        let dir = root.join(&header.fingerprint);
        let shown = one_line(dir.display());
        std::fs::create_dir_all(&dir).map_err(|e| {
            FarmError::failed(format_args!("{shown}: --checkpoint: cannot create: {e}"))
        })?;
        reyes_film::remove_stale_temporaries(&dir);
        let entries = std::fs::read_dir(&dir).map_err(|e| {
            FarmError::failed(format_args!("{shown}: --checkpoint: cannot read: {e}"))
        })?;
        let mut done = BTreeMap::new();
        let mut names: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        names.sort();
        for path in names {
            let Some(b) = bucket_of(&path) else { continue };
            let file = one_line(path.display());
            let Ok(piece) = read_piece(&path) else {
                warn(format!(
                    "{file}: warning: --checkpoint: unreadable bucket file, rendering it again"
                ));
                continue;
            };
            let h = &piece.header;
            if h.fingerprint != header.fingerprint
                || h.version != header.version
                || h.tile != (0, 0)
            {
                return Err(FarmError::invalid(format_args!(
                    "{file}: --checkpoint: a bucket of another render (fingerprint {}, version {}); \
                     remove {shown} or choose another directory",
                    one_line(&h.fingerprint),
                    one_line(&h.version),
                )));
            }
            let result = match piece.buckets.as_slice() {
                [] => BucketResult::default(),
                [(k, r)] if *k == b => r.clone(),
                _ => {
                    return Err(FarmError::invalid(format_args!(
                        "{file}: --checkpoint: does not hold bucket {b} alone"
                    )));
                }
            };
            done.insert(b, result);
        }
        Ok(Checkpoint { dir, header, done, failure: Mutex::new(None) })
    }

    /// The buckets read back, by index.
    pub fn done(&self) -> &BTreeMap<usize, BucketResult> {
        &self.done
    }

    /// Write bucket `b`'s result (from a worker thread). A failure is kept
    /// ([`Checkpoint::failure`]) and cancels the render ([`reyes_render::cancel::request`]).
    pub fn save(&self, b: usize, result: &BucketResult) {
        let path = self.dir.join(format!("bucket.{b}.exr"));
        let results = [(b, result.clone())];
        if let Err(e) = write_piece(&path, &self.header, &results, &WriteOptions::default()) {
            let mut f = self.failure.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            if f.is_none() {
                *f = Some(format!("--checkpoint: {}", one_line(e)));
            }
            reyes_render::cancel::request();
        }
    }

    /// Why a bucket file could not be written, if one could not.
    pub fn failure(&self) -> Option<String> {
        self.failure.lock().unwrap_or_else(std::sync::PoisonError::into_inner).clone()
    }

    /// The frame's output is written: the checkpoint is no longer needed. A folder that
    /// cannot be removed is a line to `warn`.
    pub fn finish(self, warn: &mut dyn FnMut(String)) {
        if let Err(e) = std::fs::remove_dir_all(&self.dir) {
            warn(format!(
                "{}: warning: --checkpoint: cannot remove: {e}",
                one_line(self.dir.display())
            ));
        }
    }
}

/// `N` of a file named `bucket.N.exr`.
fn bucket_of(path: &Path) -> Option<usize> {
    let name = path.file_name()?.to_str()?;
    name.strip_prefix("bucket.")?.strip_suffix(".exr")?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_warning(w: String) {
        panic!("unexpected warning: {w}");
    }

    #[test]
    fn buckets_saved_are_read_back_and_another_renders_are_refused() {
        let tmp = tempfile::tempdir().expect("tempdir");
        let root = tmp.path();
        let scene = crate::test_scene();
        let header = Header::new(&scene, "t.ron", None, None);
        let ck = Checkpoint::open(root, header.clone(), &mut no_warning).expect("open");
        assert!(ck.done().is_empty());
        ck.save(3, &BucketResult::default());
        assert_eq!(ck.failure(), None);
        let again = Checkpoint::open(root, header.clone(), &mut no_warning).expect("reopen");
        assert_eq!(again.done().keys().collect::<Vec<_>>(), [&3]);
        // Another seed is another render: its own folder, empty.
        let mut seeded = scene.clone();
        seeded.hider.seed += 1;
        let other = Header::new(&seeded, "t.ron", None, None);
        assert_ne!(other.fingerprint, header.fingerprint);
        let fresh = Checkpoint::open(root, other.clone(), &mut no_warning).expect("other");
        assert!(fresh.done().is_empty());
        // A bucket file of the first put into its folder is refused, never mixed in.
        let (mine, theirs) = (root.join(&header.fingerprint), root.join(&other.fingerprint));
        std::fs::copy(mine.join("bucket.3.exr"), theirs.join("bucket.3.exr")).expect("copy");
        let e = Checkpoint::open(root, other, &mut no_warning).expect_err("refused");
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--checkpoint: a bucket of another render"), "{e}");
        // An unreadable bucket file is rendered again, with a warning.
        std::fs::write(mine.join("bucket.5.exr"), b"half a file").expect("write");
        let mut warnings = Vec::new();
        let again = Checkpoint::open(root, header, &mut |w| warnings.push(w)).expect("reopen");
        assert_eq!(again.done().keys().collect::<Vec<_>>(), [&3]);
        assert_eq!(warnings.len(), 1);
        assert!(warnings[0].ends_with("unreadable bucket file, rendering it again"));
        again.finish(&mut no_warning);
        assert!(!mine.exists(), "the folder is removed once the frame is written");
    }

    #[test]
    fn bucket_files_are_named_by_their_bucket() {
        assert_eq!(bucket_of(Path::new("ck/0123/bucket.17.exr")), Some(17));
        assert_eq!(bucket_of(Path::new("ck/0123/bucket.x.exr")), None);
        assert_eq!(bucket_of(Path::new("ck/0123/.reyes-film-1.tmp")), None);
    }
}
