//! The RI state machine through its public entry: RIB text to validated scenes (the mapping
//! of each supported request onto the model), its error catalogue, and whole renders of the
//! peers' benchmark files against the peers' own pictures and our RON ports.

mod area;
mod deep;
mod detail;
mod errors;
mod extensions;
mod frames;
mod hair;
mod lookdev;
mod mapping;
mod peers;
mod program;
mod renderman;
mod textures;
mod tolerance;
mod trim;

use reyes_rib::{Loaded, RiOptions, RibError, Source, load};

/// Loads RIB text (as `test.rib`).
pub fn rib(text: &str) -> Result<Loaded, RibError> {
    load(Source::from_bytes("test.rib", text.as_bytes().to_vec()), &RiOptions::default())
}

/// Loads RIB text that must be valid, with its one frame's scene.
pub fn scene(text: &str) -> reyes_scene::Scene {
    match rib(text) {
        Ok(mut l) => {
            assert_eq!(l.frames.len(), 1, "one frame expected");
            l.frames.remove(0).scene
        }
        Err(e) => panic!("{e}"),
    }
}

/// A world block of `body` after a small perspective camera.
pub fn world(body: &str) -> String {
    format!(
        "Format 64 48 1\nProjection \"perspective\" \"fov\" [40]\nWorldBegin\n{body}\nWorldEnd\n"
    )
}
