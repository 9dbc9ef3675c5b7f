//! Pixel filters: the kernels (Appendix A's five in [`kernel`], RenderMan's in [`renderman`])
//! and the weights of a filter over the sample strata of a pixel ([`weigh`]), which the film
//! normalises into its filter table.
//!
//! They live here, beside the scene model, so that validation evaluates exactly the sum the
//! film divides by: [`check`] runs [`weigh`] over the stratum locations the hider uses
//! ([`reyes_sampling::permute::stratum_locations`]), so a filter that passes validation always
//! has a table, and one the film would refuse is a scene error with a position.
//!
//! Invariants: [`weigh`] never panics and never allocates; its weights come in the film
//! table's order, `[(s * fw + j) * fw + i]` (sample, then row `j`, then column `i` of the
//! `fw x fw` footprint), and their sum is accumulated in `f64` in that order.

pub mod kernel;
pub mod renderman;

use std::fmt;

use crate::{Filter, Hider, Original};

/// Most entries a filter table may hold (256 MiB of weights): a filter and sample grid that
/// would need more are a scene error, not something to allocate.
pub const MAX_TABLE_ENTRIES: usize = 1 << 26;

/// Appendix A's `Border` for a filter of full width `width`: `(int)(width/2 + 0.499)`, computed
/// exactly as the hider computes its extended screen (f32, truncation toward zero).
pub fn border_for_width(width: f32) -> u32 {
    (width / 2.0 + 0.499).max(0.0) as u32
}

/// Why a filter has no table.
#[derive(Debug, Clone, PartialEq)]
pub enum FilterProblem {
    /// A width is not finite and positive.
    Width,
    /// An empty sample grid.
    EmptyGrid {
        /// Strata across.
        nx: u32,
        /// Strata down.
        ny: u32,
    },
    /// A sample grid too large to count.
    GridTooLarge {
        /// Strata across.
        nx: u32,
        /// Strata down.
        ny: u32,
    },
    /// Not one stratum location per sample.
    Locations {
        /// Locations given.
        got: usize,
        /// Strata across.
        nx: u32,
        /// Strata down.
        ny: u32,
    },
    /// More than [`MAX_TABLE_ENTRIES`] weights.
    TooLarge {
        /// The footprint's side.
        footprint: usize,
        /// Samples per pixel.
        ns: usize,
    },
    /// The weights sum to zero or less, or to a non-finite value: the kernel misses every
    /// stratum centre (a filter narrower than the strata are apart), or cancels itself.
    Sum(f64),
}

impl fmt::Display for FilterProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FilterProblem::Width => f.write_str("the widths must be finite and positive"),
            FilterProblem::EmptyGrid { nx, ny } => write!(f, "empty {nx}x{ny} sample grid"),
            FilterProblem::GridTooLarge { nx, ny } => {
                write!(f, "{nx}x{ny} sample grid is too large")
            }
            FilterProblem::Locations { got, nx, ny } => write!(
                f,
                "{got} stratum locations for a {nx}x{ny} grid (expected {})",
                u64::from(*nx) * u64::from(*ny)
            ),
            FilterProblem::TooLarge { footprint, ns } => write!(
                f,
                "a {footprint}x{footprint} footprint with {ns} samples exceeds \
                 {MAX_TABLE_ENTRIES} weights"
            ),
            FilterProblem::Sum(sum) => write!(f, "the filter weights sum to {sum}"),
        }
    }
}

/// The shape of a filter table: Appendix A's `Border`, the footprint side `2 * border + 1`,
/// the samples per pixel and the number of weights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Footprint {
    /// How far (pixels) a sample's weights reach beyond its own pixel.
    pub border: u32,
    /// The side `fw` of the square of pixels a sample weighs.
    pub side: u32,
    /// Samples per pixel, `nx * ny`.
    pub ns: usize,
    /// Weights in all, `ns * fw * fw`.
    pub entries: usize,
}

/// The footprint of `filter` over an `nx x ny` stratum grid with `locations` stratum
/// locations, or why it has none (a width not finite and positive, an empty grid, not one
/// location per sample, more than [`MAX_TABLE_ENTRIES`] weights). The footprint is square,
/// its border that of the larger width ([`Filter::max_width`]).
pub fn footprint(
    filter: &Filter,
    nx: u32,
    ny: u32,
    locations: usize,
) -> Result<Footprint, FilterProblem> {
    let (width, height) = (filter.width, filter.y_width());
    if !(width.is_finite() && width > 0.0 && height.is_finite() && height > 0.0) {
        return Err(FilterProblem::Width);
    }
    if nx == 0 || ny == 0 {
        return Err(FilterProblem::EmptyGrid { nx, ny });
    }
    let ns =
        (nx as usize).checked_mul(ny as usize).ok_or(FilterProblem::GridTooLarge { nx, ny })?;
    if locations != ns {
        return Err(FilterProblem::Locations { got: locations, nx, ny });
    }
    let border = border_for_width(filter.max_width());
    let side = 2 * border + 1;
    let fw = side as usize;
    let entries = fw
        .checked_mul(fw)
        .and_then(|a| a.checked_mul(ns))
        .filter(|&n| n <= MAX_TABLE_ENTRIES)
        .ok_or(FilterProblem::TooLarge { footprint: fw, ns })?;
    Ok(Footprint { border, side, ns, entries })
}

/// The unnormalised weights of `filter` for every stratum of an `nx x ny` grid and every pixel
/// of its footprint, given in the table's order to `each`; returns the footprint and the sum of
/// the weights, which is finite and positive (else [`FilterProblem::Sum`]).
///
/// Port of `tablesinit` (Appendix A 2.11, "Create filter table"): the weight of stratum `s`
/// for pixel `(i, j)` of the footprint is `kernel(dx, dy)` with
/// `dx = location[s].x + 0.5/nx - (i - border + 0.5)` and
/// `dy = location[s].y + 0.5/ny - (j - border + 0.5)`: offsets from the stratum centre, never
/// the jittered sample position. The sum is accumulated in `f64` (the C used `float`). Weights
/// may be negative (RenderMan's catmull-rom and sinc): only their sum must be positive.
pub fn weigh(
    filter: &Filter,
    nx: u32,
    ny: u32,
    location: &[[f32; 2]],
    original: &Original,
    mut each: impl FnMut(f32),
) -> Result<(Footprint, f64), FilterProblem> {
    let shape = footprint(filter, nx, ny, location.len())?;
    let (kind, width, height) = (filter.kind, filter.width, filter.y_width());
    let half_x = 0.5 / f64::from(nx);
    let half_y = 0.5 / f64::from(ny);
    let b = f64::from(shape.border);
    let fw = shape.side as usize;
    let mut sum = 0.0_f64;
    for loc in location {
        let cx = f64::from(loc[0]) + half_x;
        let cy = f64::from(loc[1]) + half_y;
        for j in 0..fw {
            let dy = (cy - (j as f64 - b + 0.5)) as f32;
            for i in 0..fw {
                let dx = (cx - (i as f64 - b + 0.5)) as f32;
                let w = kernel::weight(kind, width, height, dx, dy, original);
                sum += f64::from(w);
                each(w);
            }
        }
    }
    if !sum.is_finite() || sum <= 0.0 {
        return Err(FilterProblem::Sum(sum));
    }
    Ok((shape, sum))
}

/// The rule validation applies to `hider`'s filter: its table over the hider's sample strata
/// (`pixel_samples`, paired as `original.permute` says) can be built, as [`weigh`] builds it.
/// `pixel_samples` must already be valid (each in 1..=64).
pub fn check(hider: &Hider) -> Result<(), FilterProblem> {
    let (nx, ny) = hider.pixel_samples;
    let location = reyes_sampling::permute::stratum_locations(nx, ny, hider.original.permute);
    weigh(&hider.filter, nx, ny, &location, &hider.original, |_| {}).map(|_| ())
}
