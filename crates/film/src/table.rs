//! The per-frame filter table (stage: film, built once per frame before any bucket is splatted).
//!
//! Invariants: `weights().len() == ns() * footprint()²`, laid out `[(s * fw + j) * fw + i]`
//! (sample-major, then row `j`, then column `i`), all finite, and summing to 1 (up to float
//! rounding). Every interior output pixel therefore receives each entry exactly once from its
//! neighbourhood: unit gain for full opaque coverage (Appendix A 3.16).

use reyes_scene::filter::{self, FilterProblem};
use reyes_scene::{Filter, FilterKind, Original};

use crate::FilmError;

pub use reyes_scene::filter::border_for_width;

/// Filter weights of every sample stratum for every pixel of its `fw x fw` neighbourhood.
///
/// Port of the filter part of `tablesinit` (Appendix A 2.11), with `BoxFilterFlag` (2.8).
#[derive(Debug, Clone, PartialEq)]
pub struct FilterTable {
    kind: FilterKind,
    width: f32,
    height: f32,
    border: u32,
    footprint: u32,
    ns: usize,
    weights: Vec<f32>,
    box_fast: bool,
    /// The sum the weights were divided by, and the kernel's switches: what a sample away
    /// from its stratum centre needs to be weighed alike ([`crate::splat_points`]).
    sum: f64,
    original: Original,
}

impl FilterTable {
    /// Build the normalised table for kernel `kind` of full width `width` (in x and y), an
    /// `nx x ny` stratum grid, and `location[s]` = Appendix A's `Location[s]`: the lower-left
    /// corner of sample `s`'s stratum in `[0,1)²` (`nx * ny` entries).
    ///
    /// The same as [`FilterTable::for_filter`] with [`Filter::new`]`(kind, width)`.
    ///
    /// # Errors
    ///
    /// As [`FilterTable::for_filter`].
    pub fn new(
        kind: FilterKind,
        width: f32,
        nx: u32,
        ny: u32,
        location: &[[f32; 2]],
        original: &Original,
    ) -> Result<FilterTable, FilmError> {
        FilterTable::for_filter(&Filter::new(kind, width), nx, ny, location, original)
    }

    /// Build the normalised table for `filter` (its kernel and full widths in x and y) over an
    /// `nx x ny` stratum grid whose stratum `s` has lower-left corner `location[s]`.
    ///
    /// Port of `tablesinit` (Appendix A 2.11, "Create filter table" and "Normalize filter"):
    /// `w[s][j][i] = kernel(dx, dy)` with `dx = location[s].x + 0.5/nx - (i - border + 0.5)`,
    /// `dy = location[s].y + 0.5/ny - (j - border + 0.5)`, divided by the sum of all entries.
    /// The offsets use the stratum centre, never the jittered sample position. The sum is
    /// accumulated in `f64` (the C used `float`). The footprint is square, its `border` that of
    /// the larger width ([`Filter::max_width`]); the kernel cuts itself to each width. Weights
    /// may be negative (RenderMan's catmull-rom and sinc): only their sum must be positive.
    /// The weights and their sum are [`reyes_scene::filter::weigh`]'s, the function scene
    /// validation runs on the scene's filter, so a validated scene's filter always has a table.
    ///
    /// # Errors
    ///
    /// [`FilmError::DegenerateFilter`] if a width is not finite and positive, `nx` or `ny` is 0,
    /// `location.len() != nx * ny`, the table would be unreasonably large, or the weights sum
    /// to zero or less, or to a non-finite value.
    pub fn for_filter(
        filter: &Filter,
        nx: u32,
        ny: u32,
        location: &[[f32; 2]],
        original: &Original,
    ) -> Result<FilterTable, FilmError> {
        let (kind, width, height) = (filter.kind, filter.width, filter.y_width());
        let degenerate = |problem: FilterProblem| FilmError::DegenerateFilter {
            kind,
            width,
            height,
            reason: problem.to_string(),
        };
        let shape = filter::footprint(filter, nx, ny, location.len()).map_err(degenerate)?;
        let mut weights = Vec::with_capacity(shape.entries);
        let (_, sum) = filter::weigh(filter, nx, ny, location, original, |w| weights.push(w))
            .map_err(degenerate)?;
        for w in &mut weights {
            *w = (f64::from(*w) / sum) as f32;
        }
        // Both boxes of width 1 weigh every stratum of the own pixel alike (RenderMan's cut is
        // inclusive, stratum centres lie strictly inside the pixel).
        let unit_box = matches!(kind, FilterKind::Box | FilterKind::RiBox);
        Ok(FilterTable {
            kind,
            width,
            height,
            border: shape.border,
            footprint: shape.side,
            ns: shape.ns,
            weights,
            box_fast: unit_box && width == 1.0 && height == 1.0,
            sum,
            original: *original,
        })
    }

    /// The weight, on the table's scale, of a sample that stands for the fraction `area` of a
    /// pixel, at offset `(dx, dy)` from a pixel's centre: `kernel(dx, dy) * area * NS / sum`.
    /// A sample of the table (area `1/NS`, at its stratum's centre) gets exactly its entry.
    pub fn weight_at(&self, dx: f32, dy: f32, area: f32) -> f64 {
        let k = reyes_scene::filter::kernel::weight(
            self.kind,
            self.width,
            self.height,
            dx,
            dy,
            &self.original,
        );
        f64::from(k) * f64::from(area) * self.ns as f64 / self.sum
    }

    /// The kernel.
    pub fn kind(&self) -> FilterKind {
        self.kind
    }

    /// The full filter width in x, in pixels.
    pub fn width(&self) -> f32 {
        self.width
    }

    /// The full filter width in y, in pixels (the x width unless the filter gave a height).
    pub fn height(&self) -> f32 {
        self.height
    }

    /// Appendix A's `Border`: how far (pixels) a sample's weights reach beyond its own pixel.
    pub fn border(&self) -> u32 {
        self.border
    }

    /// The footprint side `fw = 2 * border + 1` (Appendix A's `width` in `tablesinit`).
    pub fn footprint(&self) -> u32 {
        self.footprint
    }

    /// Samples per pixel, `NS = nx * ny`.
    pub fn ns(&self) -> usize {
        self.ns
    }

    /// All weights, `[(s * fw + j) * fw + i]`: sample `s`'s weight for the output pixel
    /// `(i - border, j - border)` relative to the sample's own pixel. Sums to 1.
    pub fn weights(&self) -> &[f32] {
        &self.weights
    }

    /// The `fw * fw` weights of sample stratum `s` (row-major, `[j * fw + i]`).
    ///
    /// # Panics
    ///
    /// If `s >= ns()`.
    pub fn sample_weights(&self, s: usize) -> &[f32] {
        let n = (self.footprint as usize).pow(2);
        &self.weights[s * n..(s + 1) * n]
    }

    /// Appendix A's `BoxFilterFlag`: box (Appendix A's or RenderMan's) of width exactly 1 in x
    /// and y (border 0), where the splat adds
    /// `1/NS` of each sample to its own pixel (`applyboxfilter`).
    pub fn box_fast(&self) -> bool {
        self.box_fast
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) const KINDS: [FilterKind; 5] = [
        FilterKind::Box,
        FilterKind::Gaussian,
        FilterKind::Sinc,
        FilterKind::Bartlett,
        FilterKind::Bessel,
    ];
    pub(crate) const WIDTHS: [f32; 5] = [1.0, 1.5, 2.0, 3.0, 4.0];
    pub(crate) const GRIDS: [u32; 5] = [1, 2, 3, 4, 8];

    pub(crate) fn all_original() -> Original {
        Original {
            box_filter: true,
            bartlett_filter: true,
            sinc_filter: true,
            ..Original::default()
        }
    }

    /// The regular stratum corners `(x/nx, y/ny)`, in a scrambled (but fixed) order: the
    /// x-major enumeration rotated by a third and reversed.
    pub(crate) fn grid_locations(nx: u32, ny: u32) -> Vec<[f32; 2]> {
        let mut cells: Vec<[f32; 2]> = (0..nx)
            .flat_map(|x| (0..ny).map(move |y| [x as f32 / nx as f32, y as f32 / ny as f32]))
            .collect();
        let third = cells.len() / 3;
        cells.rotate_left(third);
        cells.reverse();
        cells
    }

    #[test]
    fn tables_sum_to_one() {
        for original in [Original::default(), all_original()] {
            for kind in KINDS {
                for width in WIDTHS {
                    for n in GRIDS {
                        let loc = grid_locations(n, n);
                        let t = FilterTable::new(kind, width, n, n, &loc, &original)
                            .unwrap_or_else(|e| panic!("{e}"));
                        let fw = t.footprint() as usize;
                        assert_eq!(t.weights().len(), t.ns() * fw * fw);
                        assert!(t.weights().iter().all(|w| w.is_finite()));
                        let sum: f64 = t.weights().iter().map(|&w| f64::from(w)).sum();
                        assert!(
                            (sum - 1.0).abs() < 1e-5,
                            "{kind:?} W={width} {n}x{n} {original:?}: sum {sum}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn border_and_footprint() {
        // Appendix A 3.17: W = 1 -> 0, 1.5 -> 1, 2 -> 1, 3 -> 1, 3.01 -> 2, 4 -> 2.
        for (w, b) in [(1.0, 0), (1.5, 1), (2.0, 1), (3.0, 1), (3.01, 2), (4.0, 2)] {
            let t = FilterTable::new(
                FilterKind::Gaussian,
                w,
                2,
                2,
                &grid_locations(2, 2),
                &Original::default(),
            )
            .unwrap_or_else(|e| panic!("{e}"));
            assert_eq!((t.border(), t.footprint()), (b, 2 * b + 1), "width {w}");
        }
    }

    #[test]
    fn box_fast_flag() {
        let o = Original::default();
        let loc = grid_locations(4, 4);
        let fast = FilterTable::new(FilterKind::Box, 1.0, 4, 4, &loc, &o).unwrap();
        assert!(fast.box_fast());
        assert_eq!(fast.border(), 0);
        assert!(fast.weights().iter().all(|&w| w == 1.0 / 16.0));
        assert!(!FilterTable::new(FilterKind::Box, 1.5, 4, 4, &loc, &o).unwrap().box_fast());
        assert!(!FilterTable::new(FilterKind::Gaussian, 1.0, 4, 4, &loc, &o).unwrap().box_fast());
    }

    /// Index of the stratum whose corner mirrors `loc` through the pixel centre.
    fn mirror_index(loc: &[[f32; 2]], s: usize, nx: u32, ny: u32) -> usize {
        let mx = 1.0 - 1.0 / nx as f32 - loc[s][0];
        let my = 1.0 - 1.0 / ny as f32 - loc[s][1];
        loc.iter()
            .position(|l| (l[0] - mx).abs() < 1e-6 && (l[1] - my).abs() < 1e-6)
            .unwrap_or_else(|| panic!("no mirror for stratum {s}"))
    }

    /// Is the table point-symmetric: w[s][j][i] == w[mirror s][fw-1-j][fw-1-i]? Equality is up
    /// to 1e-6 of the largest weight, because corners such as 1/3 are not exact in f32.
    fn point_symmetric(t: &FilterTable, loc: &[[f32; 2]], nx: u32, ny: u32) -> bool {
        let fw = t.footprint() as usize;
        let tol = 1e-6 * t.weights().iter().fold(0.0_f32, |m, w| m.max(w.abs()));
        (0..t.ns()).all(|s| {
            let m = mirror_index(loc, s, nx, ny);
            (0..fw).all(|j| {
                (0..fw).all(|i| {
                    let a = t.sample_weights(s)[j * fw + i];
                    let b = t.sample_weights(m)[(fw - 1 - j) * fw + (fw - 1 - i)];
                    (a - b).abs() <= tol
                })
            })
        })
    }

    #[test]
    fn original_box_table_is_asymmetric_fixed_symmetric() {
        // Appendix A 3.16's example: W = 1.2, nx = 4 (border 1, offsets up to 1.375).
        let loc = grid_locations(4, 4);
        let fixed = FilterTable::new(FilterKind::Box, 1.2, 4, 4, &loc, &Original::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let orig = FilterTable::new(FilterKind::Box, 1.2, 4, 4, &loc, &all_original())
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(fixed.border(), 1);
        assert!(point_symmetric(&fixed, &loc, 4, 4));
        assert!(!point_symmetric(&orig, &loc, 4, 4));
        // The original cuts exactly the entries at a positive offset > 1.2, i.e. 1.375: the
        // stratum at x = 3/4 (or y = 3/4) towards the pixel on its left (or above), i = 0.
        let fw = 3;
        for (s, l) in loc.iter().enumerate() {
            for j in 0..fw {
                for i in 0..fw {
                    let dx = l[0] + 0.125 - (i as f32 - 0.5);
                    let dy = l[1] + 0.125 - (j as f32 - 0.5);
                    let cut = dx > 1.2 || dy > 1.2;
                    let w = orig.sample_weights(s)[j * fw + i];
                    assert_eq!(w == 0.0, cut, "s={s} i={i} j={j} dx={dx} dy={dy}");
                }
            }
        }
        // The fixed box keeps only the sample's own pixel at this width: |d| <= 0.6.
        for s in 0..16 {
            let w = fixed.sample_weights(s);
            for (k, &v) in w.iter().enumerate() {
                assert_eq!(v != 0.0, k == 4, "s={s} k={k}");
            }
        }
    }

    #[test]
    fn fixed_tables_are_symmetric() {
        for kind in KINDS {
            for width in WIDTHS {
                for n in GRIDS {
                    let loc = grid_locations(n, n);
                    let t = FilterTable::new(kind, width, n, n, &loc, &Original::default())
                        .unwrap_or_else(|e| panic!("{e}"));
                    assert!(point_symmetric(&t, &loc, n, n), "{kind:?} W={width} {n}x{n}");
                }
            }
        }
    }

    #[test]
    fn degenerate_inputs_are_errors() {
        let o = Original::default();
        let loc = grid_locations(2, 2);
        let is_degenerate = |r: Result<FilterTable, FilmError>| {
            matches!(r, Err(FilmError::DegenerateFilter { .. }))
        };
        assert!(is_degenerate(FilterTable::new(FilterKind::Box, 0.0, 2, 2, &loc, &o)));
        assert!(is_degenerate(FilterTable::new(FilterKind::Box, f32::NAN, 2, 2, &loc, &o)));
        assert!(is_degenerate(FilterTable::new(FilterKind::Box, 1.0, 0, 2, &[], &o)));
        assert!(is_degenerate(FilterTable::new(FilterKind::Box, 1.0, 2, 2, &loc[..3], &o)));
        assert!(is_degenerate(FilterTable::new(FilterKind::Box, 1e6, 2, 2, &loc, &o)));
        // Locations far outside [0,1)²: every fixed-box weight is 0.
        let far = [[5.0_f32, 5.0]; 4];
        let e = FilterTable::new(FilterKind::Box, 1.0, 2, 2, &far, &o);
        assert!(is_degenerate(e));
        // A NaN location makes the sum NaN.
        let nan = [[f32::NAN, 0.0], [0.5, 0.0], [0.0, 0.5], [0.5, 0.5]];
        assert!(is_degenerate(FilterTable::new(FilterKind::Gaussian, 2.0, 2, 2, &nan, &o)));
        // One line, naming the kernel.
        let msg = FilterTable::new(FilterKind::Box, 1.0, 2, 2, &far, &o)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(msg.contains("Box") && !msg.contains('\n'), "{msg}");
    }

    fn table(kind: FilterKind, width: f32, height: Option<f32>, n: u32) -> FilterTable {
        let filter = Filter { kind, width, height };
        FilterTable::for_filter(&filter, n, n, &grid_locations(n, n), &Original::default())
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// The stratum-centre offset `(dx, dy)` of entry `k` of sample `s`'s weights.
    fn offset(t: &FilterTable, loc: &[[f32; 2]], n: u32, s: usize, k: usize) -> (f32, f32) {
        let fw = t.footprint() as usize;
        let b = t.border() as f32;
        let half = 0.5 / n as f32;
        let (i, j) = ((k % fw) as f32, (k / fw) as f32);
        (loc[s][0] + half - (i - b + 0.5), loc[s][1] + half - (j - b + 0.5))
    }

    proptest::proptest! {
        #[test]
        fn renderman_tables_sum_to_one(
            kind in proptest::sample::select(FilterKind::RENDERMAN),
            width in 1.0_f32..6.0,
            height in 1.0_f32..6.0,
            n in 1_u32..6,
        ) {
            // From a pixel wide up: a narrower filter can miss every stratum centre (see
            // `a_filter_between_the_stratum_centres_is_degenerate`).
            let t = table(kind, width, Some(height), n);
            let fw = t.footprint() as usize;
            proptest::prop_assert_eq!(t.border(), border_for_width(width.max(height)));
            proptest::prop_assert_eq!(t.weights().len(), t.ns() * fw * fw);
            proptest::prop_assert!(t.weights().iter().all(|w| w.is_finite()));
            let sum: f64 = t.weights().iter().map(|&w| f64::from(w)).sum();
            proptest::prop_assert!((sum - 1.0).abs() < 1e-5, "{:?} {}x{} {}: sum {}", kind, width, height, n, sum);
        }
    }

    #[test]
    fn a_filter_between_the_stratum_centres_is_degenerate() {
        // A disk 0.6 wide on a 2x2 grid: the stratum centres lie 0.25 from the pixel centre
        // in x and y, outside the disk, and every other pixel's are further: nothing to weigh.
        let f = Filter { kind: FilterKind::RiDisk, width: 0.6, height: None };
        let e = FilterTable::for_filter(&f, 2, 2, &grid_locations(2, 2), &Original::default());
        assert!(matches!(e, Err(FilmError::DegenerateFilter { .. })));
        // On a 3x3 grid the centre stratum lies on the pixel centre.
        assert_eq!(table(FilterKind::RiDisk, 0.6, None, 3).ns(), 9);
    }

    #[test]
    fn renderman_tables_are_symmetric() {
        for &kind in FilterKind::RENDERMAN {
            for (width, height) in [(2.0, 2.0), (4.0, 1.0), (1.5, 3.0)] {
                for n in GRIDS {
                    let loc = grid_locations(n, n);
                    let t = table(kind, width, Some(height), n);
                    assert!(point_symmetric(&t, &loc, n, n), "{kind:?} {width}x{height} {n}x{n}");
                }
            }
        }
    }

    #[test]
    fn the_footprint_reaches_the_larger_width_and_the_kernel_cuts_each() {
        let n = 4;
        let loc = grid_locations(n, n);
        for (width, height) in [(4.0_f32, 1.0_f32), (1.0, 4.0)] {
            let t = table(FilterKind::RiBox, width, Some(height), n);
            assert_eq!((t.border(), t.footprint()), (2, 5), "{width}x{height}");
            assert_eq!((t.width(), t.height()), (width, height));
            for s in 0..t.ns() {
                for (k, &w) in t.sample_weights(s).iter().enumerate() {
                    let (dx, dy) = offset(&t, &loc, n, s, k);
                    let inside = dx.abs() <= 0.5 * width && dy.abs() <= 0.5 * height;
                    assert_eq!(w != 0.0, inside, "{width}x{height} s={s} k={k} ({dx}, {dy})");
                }
            }
        }
    }

    #[test]
    fn appendix_a_kernels_stretch_to_a_height() {
        // Appendix A's box of width 2 and height 1 is RenderMan's 2 x 1 box; without a height,
        // or with the height equal to the width, it is exactly the width-only table.
        let o = Original::default();
        let loc = grid_locations(4, 4);
        let stretched = table(FilterKind::Box, 2.0, Some(1.0), 4);
        assert_eq!(stretched.weights(), table(FilterKind::RiBox, 2.0, Some(1.0), 4).weights());
        let plain = FilterTable::new(FilterKind::Box, 2.0, 4, 4, &loc, &o).unwrap();
        assert_ne!(stretched.weights(), plain.weights());
        for kind in KINDS {
            for width in WIDTHS {
                let plain = FilterTable::new(kind, width, 4, 4, &loc, &o).unwrap();
                assert_eq!(table(kind, width, None, 4), plain, "{kind:?} {width}");
                assert_eq!(table(kind, width, Some(width), 4), plain, "{kind:?} {width}");
            }
        }
        // A height taller than the width widens the footprint.
        assert_eq!(table(FilterKind::Gaussian, 2.0, Some(4.0), 4).border(), 2);
    }

    #[test]
    fn the_renderman_gaussian_is_not_appendix_as() {
        // RenderMan's gaussian 2 x 2, exp(-2 ((x)^2 + (y)^2)) cut to the square, against
        // Appendix A's gaussian 2, exp(-r^2) - exp(-1) cut to the unit circle: the same
        // footprint, different weights (in the corners Appendix A's is 0, RenderMan's not).
        let ri = table(FilterKind::RiGaussian, 2.0, None, 4);
        let aa = table(FilterKind::Gaussian, 2.0, None, 4);
        assert_eq!((ri.border(), ri.footprint()), (aa.border(), aa.footprint()));
        let largest = ri
            .weights()
            .iter()
            .zip(aa.weights())
            .map(|(a, b)| (a - b).abs() / a.abs().max(b.abs()))
            .fold(0.0_f32, f32::max);
        assert!(largest > 0.5, "largest relative difference {largest}");
        let zeros = |t: &FilterTable| t.weights().iter().filter(|&&w| w == 0.0).count();
        assert!(zeros(&aa) > zeros(&ri), "{} vs {}", zeros(&aa), zeros(&ri));
    }

    #[test]
    fn a_unit_renderman_box_is_the_fast_box() {
        let loc = grid_locations(4, 4);
        let ri = table(FilterKind::RiBox, 1.0, None, 4);
        let aa = FilterTable::new(FilterKind::Box, 1.0, 4, 4, &loc, &Original::default()).unwrap();
        assert!(ri.box_fast());
        assert_eq!(ri.weights(), aa.weights());
        assert!(!table(FilterKind::RiBox, 1.0, Some(2.0), 4).box_fast());
        assert!(!table(FilterKind::Box, 1.0, Some(2.0), 4).box_fast());
    }

    #[test]
    fn degenerate_heights_are_errors() {
        let o = Original::default();
        let loc = grid_locations(2, 2);
        for height in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            let f = Filter { kind: FilterKind::RiGaussian, width: 2.0, height: Some(height) };
            let e = FilterTable::for_filter(&f, 2, 2, &loc, &o);
            assert!(matches!(e, Err(FilmError::DegenerateFilter { .. })), "height {height}");
        }
        // Every weight cut (locations far outside the pixel): the sum is 0.
        let far = [[5.0_f32, 5.0]; 4];
        let f = Filter { kind: FilterKind::RiSinc, width: 4.0, height: Some(1.0) };
        let msg = FilterTable::for_filter(&f, 2, 2, &far, &o)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(msg.contains("RiSinc filter of width 4 x 1"), "{msg}");
    }
}
