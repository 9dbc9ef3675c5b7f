//! Which render a piece belongs to (docs/farm.md): the fingerprint every tile and checkpoint
//! file carries, and which names a checkpoint's folder.
//!
//! Invariant: the fingerprint is a function of the scene as it will be rendered (after every
//! override) and of the renderer's version alone: never of the thread count, the tile or
//! the output name, which change no bucket.

use reyes_scene::Scene;

use crate::VERSION;

/// Which render a piece belongs to: a hash of everything that decides the pixels (the whole
/// scene after the front end's overrides, the crop window and the seed among them,
/// serialised as RON) and the renderer's version, as 16 hex digits.
pub fn fingerprint(scene: &Scene) -> String {
    let text = ron::to_string(scene).unwrap_or_default();
    let words: Vec<u64> = text
        .as_bytes()
        .chunks(8)
        .map(|c| c.iter().rev().fold(0u64, |w, &b| w << 8 | u64::from(b)))
        .chain([text.len() as u64])
        .collect();
    let version = VERSION.bytes().fold(0u64, |w, b| w.rotate_left(8) ^ u64::from(b));
    format!("{:016x}", reyes_sampling::hash(version, &words))
}
