//! Fields of small shapes for measuring coverage against exact projected areas.
//!
//! A field is a square image of `cells x cells` cells of `cell` pixels, one copy of a shape
//! per cell at a pseudo-random sub-pixel offset from the cell's centre, white and
//! `Constant`, seen by an orthographic camera whose screen window makes one world unit one
//! pixel, with 8 x 8 samples and a 1-pixel box filter. With that filter every sample counts
//! in exactly one pixel with weight 1/64, so a cell's summed alpha is the fraction of its
//! samples that see the shape times the cell's area: an unbiased estimate of the shape's
//! projected area.
//!
//! Invariant: the same arguments give the same scene (the offsets come from a fixed key).

use reyes_film::Film;
use reyes_scene::Scene;

use crate::fixtures::parse;
use crate::random::Uniform;

/// A field of copies of a shape.
#[derive(Debug, Clone)]
pub struct Field<'a> {
    /// The shape, in RON.
    pub shape: &'a str,
    /// RON transforms applied before the move to the cell, each followed by a comma.
    pub transform: &'a str,
    /// RON object fields, each followed by a comma.
    pub fields: &'a str,
    /// RON hider fields, each followed by a comma (besides samples, filter and seed).
    pub hider: &'a str,
    /// Cells across and down.
    pub cells: u32,
    /// Cell side in pixels.
    pub cell: u32,
}

impl Field<'_> {
    /// The scene.
    pub fn scene(&self) -> Scene {
        let size = self.cells * self.cell;
        let half = size as f32 / 2.0;
        let mut rng = Uniform::new(0x5eed_0019);
        let mut objects = String::new();
        for j in 0..self.cells {
            for i in 0..self.cells {
                let c = self.cell as f32 / 2.0;
                let x = (i * self.cell) as f32 + c - half + rng.range(-0.5, 0.5);
                let y = half - (j * self.cell) as f32 - c + rng.range(-0.5, 0.5);
                objects.push_str(&format!(
                    "(shape: {}, transform: [{}Translate(({x}, {y}, 10.0))], {}
                      material: Constant(color: (1.0, 1.0, 1.0))),\n",
                    self.shape, self.transform, self.fields
                ));
            }
        }
        parse(&format!(
            "Scene(image: (width: {size}, height: {size}),
               camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                        screen_window: Some(({l}, {half}, {l}, {half})), hither: 0.1, yon: 100.0),
               hider: (pixel_samples: (8, 8), filter: (kind: Box, width: 1.0), seed: 19, {}),
               objects: [{objects}])",
            self.hider,
            l = -half
        ))
    }

    /// The summed alpha of each cell of a render of [`Field::scene`], in raster order.
    pub fn cell_sums(&self, film: &Film) -> Vec<f64> {
        let size = self.cells * self.cell;
        let mut cells = vec![0.0_f64; (self.cells * self.cells) as usize];
        for (k, p) in film.rgba().iter().enumerate() {
            let (x, y) = (k as u32 % size, k as u32 / size);
            cells[((y / self.cell) * self.cells + x / self.cell) as usize] += f64::from(p[3]);
        }
        cells
    }
}

/// Mean and standard error of the mean of `v` (at least two values).
pub fn mean_se(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}
