//! The report of a measurement: what `reyes-render measure` prints, each estimate with its
//! standard error, rounded to the digits the error leaves meaningful.

use std::fmt;

use glam::DVec3;

use crate::{Measurement, Target, quoted};

/// `x` with `decimals` decimals, without the sign of a negative value that rounds to zero.
fn fixed(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => s,
    }
}

/// `value ± se` with the error to two significant figures and the value to match.
fn plus_minus(value: f64, se: f64) -> String {
    if se > 0.0 && se.is_finite() {
        let decimals = (1 - se.log10().floor() as i64).clamp(0, 15) as usize;
        format!("{} ± {se:.decimals$}", fixed(value, decimals))
    } else {
        format!("{} ± 0", significant(value, 7))
    }
}

/// `x` to `digits` significant figures (no exponent).
fn significant(x: f64, digits: i64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (digits - 1 - x.abs().log10().floor() as i64).clamp(0, 15) as usize;
    fixed(x, decimals)
}

impl fmt::Display for Measurement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match &self.target {
            Target::Object { index, shape } => format!("objects[{index}], {shape}"),
            Target::Solid { index } => format!("solids[{index}], CSG"),
        };
        writeln!(f, "measure  {} ({what}), at shutter open", quoted(&self.name))?;
        if self.box_is_empty() {
            writeln!(f, "box      empty: the solid's operands do not overlap")?;
            writeln!(f, "volume   0")?;
            return writeln!(f, "centre   none: nothing is inside");
        }
        let (lo, hi) = self.bounds;
        let ext = hi - lo;
        let decimals = (5 - ext.max_element().log10().floor() as i64).clamp(0, 15) as usize;
        let v = |p: DVec3| {
            let [x, y, z] = p.to_array().map(|c| fixed(c, decimals));
            format!("({x}, {y}, {z})")
        };
        writeln!(
            f,
            "box      {} to {}, volume {}",
            v(lo),
            v(hi),
            significant(ext.x * ext.y * ext.z, 7)
        )?;
        let [nx, ny, nz] = self.grid;
        writeln!(
            f,
            "samples  {} points: {nx} x {ny} x {nz} strata, one jittered point each, seed {}",
            self.points(),
            self.seed
        )?;
        writeln!(f, "inside   {} points", self.inside)?;
        writeln!(f, "volume   {}", plus_minus(self.volume, self.volume_se))?;
        match &self.centre {
            Some(c) => writeln!(
                f,
                "centre   ({}, {}, {})",
                plus_minus(c.at.x, c.se.x),
                plus_minus(c.at.y, c.se.y),
                plus_minus(c.at.z, c.se.z)
            )?,
            None => writeln!(f, "centre   none: no sample point is inside")?,
        }
        writeln!(
            f,
            "± is one standard error, estimated from neighbouring strata paired (collapsed \
             strata), which errs on the large side"
        )
    }
}
