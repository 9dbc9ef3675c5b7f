//! Level of detail (Spec 3.2, 4.2.5): `Detail` bounds what follows, `DetailRange` says for
//! which raster areas of that bound the primitives that follow are drawn, and
//! `RelativeDetail` scales every area.
//!
//! Invariants: the detail is the area in pixels of the screen-aligned rectangle around the
//! bound's eight corners projected to raster space (unbounded when a corner is at or behind
//! the eye of a perspective camera), times `RelativeDetail`. A level's weight ramps linearly
//! from 0 at `minvisible` to 1 at `lowertransition`, stays 1 to `uppertransition` and ramps
//! back to 0 at `maxvisible`. Levels blend by opacity: a primitive keeps `weight` of its
//! opacity, and is not drawn at weight 0.

use glam::DVec3;

use super::frame::Machine;
use super::state::{FrameOptions, Projection};
use crate::{Request, RibError};

/// The weight of the level `DetailRange [lo_off lo_on hi_on hi_off]` at `detail`.
pub(crate) fn weight(range: [f32; 4], detail: f64) -> f32 {
    let [off_low, on_low, on_high, off_high] = range.map(f64::from);
    let w = if detail < off_low || detail > off_high {
        0.0
    } else if detail < on_low {
        (detail - off_low) / (on_low - off_low)
    } else if detail > on_high {
        (off_high - detail) / (off_high - on_high)
    } else {
        1.0
    };
    w.clamp(0.0, 1.0) as f32
}

/// The raster area in pixels of the rectangle around `corners` (camera space) in the frame
/// of `o`; infinite when a corner is not in front of a perspective camera's eye.
pub(crate) fn raster_area(corners: &[[f64; 3]; 8], o: &FrameOptions) -> f64 {
    let (w, h) = (f64::from(o.width), f64::from(o.height));
    let aspect = o.frame_aspect.map_or(w * f64::from(o.pixel_aspect) / h, f64::from);
    let [l, r, b, t] = match o.screen_window {
        Some(s) => s.map(f64::from),
        None if aspect >= 1.0 => [-aspect, aspect, -1.0, 1.0],
        None => [-1.0, 1.0, -1.0 / aspect, 1.0 / aspect],
    };
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for c in corners {
        let (x, y) = match o.projection {
            Projection::Orthographic => (c[0], c[1]),
            Projection::Perspective { fov } => {
                if c[2] <= 0.0 {
                    return f64::INFINITY;
                }
                let k = 1.0 / (f64::from(fov).to_radians() / 2.0).tan() / c[2];
                (c[0] * k, c[1] * k)
            }
        };
        let p = DVec3::new((x - l) / (r - l) * w, (t - y) / (t - b) * h, 0.0);
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (hi.x - lo.x) * (hi.y - lo.y)
}

impl Machine {
    /// `RelativeDetail scale`: an option (>= 0).
    pub(super) fn relative_detail(&mut self, r: &Request) -> Result<(), RibError> {
        let v = r.float(0).ok_or_else(|| r.error("expected a number"))?;
        if !(v.is_finite() && v >= 0.0) {
            return Err(r.error(format!("the relative detail must be >= 0, got {v}")));
        }
        if self.in_world() {
            let w = r.warning("an option inside the world block: ignored for this frame");
            self.warnings.push(w);
            return Ok(());
        }
        self.frame_options.relative_detail = v;
        Ok(())
    }

    /// `Detail [xmin xmax ymin ymax zmin zmax]` in the current object space.
    pub(super) fn detail(&mut self, r: &Request) -> Result<(), RibError> {
        let b = match r.floats(0) {
            Some(b) if b.len() == 6 && b.iter().all(|v| v.is_finite()) => b,
            _ => return Err(r.error("expected a bound of 6 finite numbers")),
        };
        let m = self.to_world().at(f32::NEG_INFINITY);
        let corner = |i: usize| {
            let p = DVec3::new(
                f64::from(b[i & 1]),
                f64::from(b[2 + ((i >> 1) & 1)]),
                f64::from(b[4 + ((i >> 2) & 1)]),
            );
            m.project_point3(p).to_array()
        };
        self.attributes.detail = Some(std::array::from_fn(corner));
        Ok(())
    }

    /// `DetailRange minvisible lowertransition uppertransition maxvisible`: the weight of the
    /// primitives that follow, from the current `Detail` bound.
    pub(super) fn detail_range(&mut self, r: &Request) -> Result<(), RibError> {
        // The reader has checked the signature: four numbers, bare or as one array.
        let v: Vec<f32> = r
            .floats(0)
            .map(<[f32]>::to_vec)
            .unwrap_or_else(|| (0..4).map(|i| r.float(i).unwrap_or(0.0)).collect());
        let &[a, b, c, d] = v.as_slice() else {
            return Err(r.error(format!("expected 4 numbers, got {}", v.len())));
        };
        let range = [a, b, c, d];
        if range.iter().any(|v| v.is_nan()) || range.windows(2).any(|p| p[0] > p[1]) {
            return Err(r.error(format!(
                "the range must be in increasing order, got [{} {} {} {}]",
                range[0], range[1], range[2], range[3]
            )));
        }
        let Some(corners) = self.attributes.detail else {
            self.tolerate(
                &r.at,
                "DetailRange",
                "no Detail bound is set",
                "the level is drawn as if fully visible",
            )?;
            self.attributes.detail_weight = 1.0;
            return Ok(());
        };
        let detail = raster_area(&corners, &self.frame_options)
            * f64::from(self.frame_options.relative_detail);
        self.attributes.detail_weight = weight(range, detail);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_ramp_linearly_over_the_transitions() {
        let range = [10.0, 20.0, 100.0, 200.0];
        assert_eq!(weight(range, 5.0), 0.0);
        assert_eq!(weight(range, 15.0), 0.5);
        assert_eq!(weight(range, 50.0), 1.0);
        assert_eq!(weight(range, 175.0), 0.25);
        assert_eq!(weight(range, 250.0), 0.0);
        // Open ends: the last level to infinity, the first from 0.
        let last = [100.0, 200.0, f32::INFINITY, f32::INFINITY];
        assert_eq!(weight(last, f64::INFINITY), 1.0);
        assert_eq!(weight([0.0, 0.0, 10.0, 20.0], 0.0), 1.0);
    }
}
