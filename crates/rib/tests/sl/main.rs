//! Shading-language shaders rendered end to end (issue #30): RIB naming `.sl` files the test
//! writes into a temporary folder, loaded, compiled, bound and rendered, each picture checked
//! against a formula with a tolerance derived from the geometry and the sampling.
//!
//! Sampling used throughout unless a test says otherwise: `Hider "hidden" "jitter" [0]` puts
//! each pixel's 2 x 2 samples at its strata's centres (a quarter pixel from the pixel centre
//! along each axis, symmetrically), and `PixelFilter "box" 1 1` weighs the four equally and
//! nothing else, so a pixel is exactly the mean of the four samples' colours.

mod binding;
mod grid;
mod lights;
mod messages;
mod opacity;
mod outputs;
mod volume;

use reyes_film::Film;
use reyes_rib::{Loaded, RiOptions, Source};

/// A folder holding the test's shaders and RIB file.
pub struct Files(pub tempfile::TempDir);

impl Files {
    /// The shaders `(name, source)` written as `name.sl`.
    pub fn new(shaders: &[(&str, &str)]) -> Files {
        let dir = tempfile::tempdir().unwrap();
        for (name, text) in shaders {
            std::fs::write(dir.path().join(format!("{name}.sl")), text).unwrap();
        }
        Files(dir)
    }

    /// Loads `rib` written as `scene.rib` beside the shaders.
    pub fn load(&self, rib: &str) -> Result<Loaded, reyes_rib::RibError> {
        let path = self.0.path().join("scene.rib");
        std::fs::write(&path, rib).unwrap();
        reyes_rib::load(Source::open(&path).unwrap(), &RiOptions::default())
    }

    /// The one frame of `rib`, validated.
    pub fn scene(&self, rib: &str) -> reyes_scene::Scene {
        match self.load(rib) {
            Ok(mut l) => l.frames.remove(0).scene,
            Err(e) => panic!("{e}"),
        }
    }
}

/// Renders a scene.
pub fn render(scene: &reyes_scene::Scene) -> Film {
    reyes_render::render(scene, &reyes_render::RenderOptions::default()).unwrap().film
}

/// Renders `rib` with the shaders `(name, source)`.
pub fn render_rib(shaders: &[(&str, &str)], rib: &str) -> Film {
    render(&Files::new(shaders).scene(rib))
}

/// Pixel `(x, y)` of a film.
pub fn pixel(film: &Film, x: u32, y: u32) -> [f32; 4] {
    film.rgba()[(y * film.width() + x) as usize]
}

/// The options of every test picture: `size` pixels square, orthographic over the screen
/// window `[-w, w]^2`, samples at stratum centres, box filter one pixel wide.
pub fn ortho(size: u32, w: f32) -> String {
    format!(
        "Format {size} {size} 1\nProjection \"orthographic\"\nScreenWindow {} {w} {} {w}\n\
         PixelSamples 2 2\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n",
        -w, -w
    )
}

/// The screen position of the centre of pixel `(x, y)` of a `size`-pixel square picture of
/// the screen window `[-w, w]^2` (y up), offset by `(dx, dy)` pixels.
pub fn screen(size: u32, w: f32, x: u32, y: u32, (dx, dy): (f32, f32)) -> (f32, f32) {
    let px = 2.0 * w / size as f32;
    (-w + (x as f32 + 0.5 + dx) * px, w - (y as f32 + 0.5 + dy) * px)
}

/// The four sample offsets of a pixel (stratum centres of 2 x 2), in pixels.
pub const SAMPLES: [(f32, f32); 4] = [(-0.25, -0.25), (0.25, -0.25), (-0.25, 0.25), (0.25, 0.25)];
