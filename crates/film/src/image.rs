//! The final image (stage: film, last before output): the sum of every bucket's window.
//!
//! Invariants: `rgba.len() == z.len() == width * height`, row-major from the top-left pixel;
//! rgba is premultiplied linear light, starting at 0; z starts at `+inf` and only ever
//! decreases. Floating-point addition is not associative, so the pixel values are
//! deterministic only if the caller adds the windows in a fixed order (for example bucket
//! index order), never in the order parallel workers happen to finish.

use crate::Window;

/// The output image: accumulated filtered colour and nearest opaque depth.
///
/// Port of the accumulation behind Appendix A's `DisplayWindow` (3.17), which must **add** the
/// overlapping bordered windows of adjacent buckets.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    rgba: Vec<[f32; 4]>,
    z: Vec<f32>,
}

impl Film {
    /// A `width x height` image: rgba all 0, z all `+inf`.
    pub fn new(width: u32, height: u32) -> Film {
        let n = width as usize * height as usize;
        Film { width, height, rgba: vec![[0.0; 4]; n], z: vec![f32::INFINITY; n] }
    }

    /// An image from its pixels (row-major from the top-left), or `None` if a length is not
    /// `width * height`.
    pub fn from_pixels(width: u32, height: u32, rgba: Vec<[f32; 4]>, z: Vec<f32>) -> Option<Film> {
        let n = (width as usize).checked_mul(height as usize)?;
        (rgba.len() == n && z.len() == n).then_some(Film { width, height, rgba, z })
    }

    /// Add one bucket's window: its rgba is added to the image pixels it overlaps (the part
    /// outside the image, i.e. the extended screen's margin, is cropped) and z keeps the
    /// minimum.
    ///
    /// Port of the `DisplayWindow` accumulation (Appendix A 3.17). Call it for the windows in
    /// a fixed order (e.g. bucket index order) so the floating-point sums are reproducible.
    ///
    /// # Panics
    ///
    /// If `win.rgba` or `win.z` does not hold `win.w * win.h` pixels.
    pub fn add(&mut self, win: &Window) {
        let (ww, wh) = (i64::from(win.w), i64::from(win.h));
        assert!(
            win.rgba.len() as i64 == ww * wh && win.z.len() as i64 == ww * wh,
            "Film::add: the window's buffers do not match its size"
        );
        let (x0, y0) = (i64::from(win.x0), i64::from(win.y0));
        // Overlap in raster coordinates, half-open.
        let xa = x0.max(0);
        let xb = (x0 + ww).min(i64::from(self.width));
        let ya = y0.max(0);
        let yb = (y0 + wh).min(i64::from(self.height));
        if xa >= xb || ya >= yb {
            return;
        }
        let iw = self.width as usize;
        let len = (xb - xa) as usize;
        for y in ya..yb {
            let src = ((y - y0) * ww + (xa - x0)) as usize;
            let dst = y as usize * iw + xa as usize;
            let (s_rgba, s_z) = (&win.rgba[src..src + len], &win.z[src..src + len]);
            for (d, s) in self.rgba[dst..dst + len].iter_mut().zip(s_rgba) {
                for k in 0..4 {
                    d[k] += s[k];
                }
            }
            for (d, &s) in self.z[dst..dst + len].iter_mut().zip(s_z) {
                *d = d.min(s);
            }
        }
    }

    /// The pixels `[x0, x1) x [y0, y1)` (`rect = [x0, x1, y0, y1]`, within the image) as an
    /// image of their own.
    pub fn crop(&self, [x0, x1, y0, y1]: [u32; 4]) -> Film {
        let (w, h) = (x1 - x0, y1 - y0);
        let mut rgba = Vec::with_capacity(w as usize * h as usize);
        let mut z = Vec::with_capacity(w as usize * h as usize);
        for y in y0..y1 {
            let row = y as usize * self.width as usize;
            rgba.extend_from_slice(&self.rgba[row + x0 as usize..row + x1 as usize]);
            z.extend_from_slice(&self.z[row + x0 as usize..row + x1 as usize]);
        }
        Film { width: w, height: h, rgba, z }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// All pixels' premultiplied rgba, row-major from the top-left.
    pub fn rgba(&self) -> &[[f32; 4]] {
        &self.rgba
    }

    /// All pixels' depth (`+inf` where no opaque surface), row-major from the top-left.
    pub fn z(&self) -> &[f32] {
        &self.z
    }

    /// The premultiplied rgba of pixel `(x, y)`, or `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        self.index(x, y).map(|k| self.rgba[k])
    }

    /// The depth of pixel `(x, y)`, or `None` outside the image.
    pub fn depth(&self, x: u32, y: u32) -> Option<f32> {
        self.index(x, y).map(|k| self.z[k])
    }

    fn index(&self, x: u32, y: u32) -> Option<usize> {
        (x < self.width && y < self.height).then(|| y as usize * self.width as usize + x as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn window(x0: i32, y0: i32, w: u32, h: u32, v: f32, z: f32) -> Window {
        let n = (w * h) as usize;
        Window { x0, y0, w, h, rgba: vec![[v; 4]; n], z: vec![z; n] }
    }

    #[test]
    fn new_film_is_empty() {
        let f = Film::new(3, 2);
        assert_eq!((f.width(), f.height()), (3, 2));
        assert!(f.rgba().iter().all(|p| *p == [0.0; 4]));
        assert!(f.z().iter().all(|z| *z == f32::INFINITY));
        assert_eq!(f.pixel(3, 0), None);
        assert_eq!(f.depth(0, 2), None);
    }

    #[test]
    fn add_crops_sums_and_keeps_min_z() {
        let mut f = Film::new(4, 3);
        // Hangs off the top-left corner: covers raster (-1..=1, -1..=1).
        f.add(&window(-1, -1, 3, 3, 1.0, 5.0));
        // Overlaps the first at (1, 0..=1), hangs off the right edge.
        f.add(&window(1, 0, 4, 2, 0.5, 2.0));
        // Entirely outside: ignored.
        f.add(&window(10, 10, 2, 2, 100.0, 0.0));
        f.add(&window(-5, 0, 2, 2, 100.0, 0.0));
        let expect = |x: u32, y: u32| -> (f32, f32) {
            let a = x <= 1 && y <= 1;
            let b = x >= 1 && y <= 1;
            let v = if a { 1.0 } else { 0.0 } + if b { 0.5 } else { 0.0 };
            let z = if b {
                2.0
            } else if a {
                5.0
            } else {
                f32::INFINITY
            };
            (v, z)
        };
        for y in 0..3 {
            for x in 0..4 {
                let (v, z) = expect(x, y);
                assert_eq!(f.pixel(x, y), Some([v; 4]), "({x},{y})");
                assert_eq!(f.depth(x, y), Some(z), "({x},{y})");
            }
        }
    }

    #[test]
    fn from_pixels_checks_lengths() {
        assert!(Film::from_pixels(2, 2, vec![[0.0; 4]; 4], vec![0.0; 4]).is_some());
        assert!(Film::from_pixels(2, 2, vec![[0.0; 4]; 3], vec![0.0; 4]).is_none());
        assert!(Film::from_pixels(2, 2, vec![[0.0; 4]; 4], vec![0.0; 5]).is_none());
    }
}
