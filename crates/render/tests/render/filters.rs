//! Pixel filters through the whole pipeline: the Appendix A kernels render bit for bit as
//! they did before the RenderMan kernels and the y width were added, an anisotropic filter
//! blurs only along its wide axis, and RenderMan's gaussian is not Appendix A's.

use reyes_film::Film;
use reyes_render::{RenderOptions, render};

/// A 3 x 3 image of a lit sphere whose silhouette crosses every pixel, so every kernel weight
/// of the footprint shows in the result.
fn three_by_three(filter: &str, original: bool) -> Film {
    let text = format!(
        "Scene(image: (width: 3, height: 3),
           camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 20.0),
           hider: (pixel_samples: (4, 4), filter: {filter}, seed: 7,
                   original: (box_filter: {original}, bartlett_filter: {original},
                              sinc_filter: {original})),
           lights: [Ambient(intensity: 0.2), Distant(from: (1.0, 1.0, -1.0))],
           objects: [(shape: Sphere(radius: 0.45), transform: [Translate((0.1, -0.05, 0.0))],
                      material: Matte(color: (0.9, 0.5, 0.2)))])"
    );
    let scene = reyes_scene::parse(&text, std::path::Path::new("three.ron")).unwrap();
    render(&scene, &RenderOptions { threads: Some(1), ..RenderOptions::default() }).unwrap().film
}

/// FNV-1a over the bits of every channel and depth of `film`, in raster order.
fn bits_hash(film: &Film, mut h: u64) -> u64 {
    let mut eat = |v: f32| {
        for b in v.to_bits().to_le_bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for (px, z) in film.rgba().iter().zip(film.z()) {
        px.iter().copied().for_each(&mut eat);
        eat(*z);
    }
    h
}

/// The Appendix A kernels at widths 1, 2 and 3.5 (border 0, 1 and 2), with the fixed and the
/// original shapes, hashed per kernel.
fn appendix_a_hashes() -> Vec<(&'static str, u64)> {
    ["Box", "Gaussian", "Sinc", "Bartlett", "Bessel"]
        .into_iter()
        .map(|kind| {
            let mut h = 0xcbf2_9ce4_8422_2325;
            for width in ["1.0", "2.0", "3.5"] {
                for original in [false, true] {
                    let filter = format!("(kind: {kind}, width: {width})");
                    h = bits_hash(&three_by_three(&filter, original), h);
                }
            }
            (kind, h)
        })
        .collect()
}

/// Hashes of [`appendix_a_hashes`] recorded before the RenderMan kernels were added (commit
/// 1b30040): the width-only path must compute exactly as it did.
const BEFORE: [(&str, u64); 5] = [
    ("Box", 0x2c42_31c3_6e43_c60f),
    ("Gaussian", 0x7c76_5132_681f_1725),
    ("Sinc", 0x7609_b199_3550_87d1),
    ("Bartlett", 0xf9c5_c445_5dae_2d10),
    ("Bessel", 0x2488_38b4_d864_21e5),
];

#[test]
fn appendix_a_kernels_render_bit_for_bit_as_before() {
    let now = appendix_a_hashes();
    for ((kind, got), (name, want)) in now.iter().zip(BEFORE) {
        assert_eq!(*kind, name);
        assert_eq!(*got, want, "{kind}: 3x3 renders changed (hash {got:#x})");
    }
}
