//! Helpers shared by the integration tests: scene files under cargo's per-target temporary
//! directory, and loading a bad one.
//!
//! Invariant: every file lives in `CARGO_TARGET_TMPDIR/reyes-scene-tests` under a name the
//! caller chooses, so tests running in parallel must use different names.

use std::path::{Path, PathBuf};

use reyes_scene::LoadError;

/// Writes `bytes` to the file `name` under cargo's per-target temporary directory.
pub fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("reyes-scene-tests");
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap_or_else(|e| panic!("{e}"));
    path
}

/// Loads the bad scene file at `path`: the error must be a bad scene (exit code 2) that
/// displays on one line.
pub fn load_bad(path: &Path) -> LoadError {
    let err = reyes_scene::load(path).err().unwrap_or_else(|| panic!("loaded a bad scene"));
    assert_eq!(err.exit_code(), 2);
    let shown = err.to_string();
    assert!(!shown.contains('\n'), "{shown}");
    err
}
