//! `TrimCurve` (RI Spec 3.2, "Trim curves"): the current trim loops, an attribute that every
//! later `NuPatch` of the attribute block carries (other primitives ignore it); and
//! `Attribute "trimcurve" "sense"` (PRMan's), which keeps the inside instead.
//!
//! Invariants: the arrays are checked against each other before anything is built (one
//! error line per inconsistency, at the request), then each curve by the scene's own trim
//! rules ([`reyes_scene::validate_trim`]), so a `TrimCurve` that is accepted always builds a
//! patch that validates, but for the reach of its points, which needs the patch's domain
//! and is checked (and reported) at the `NuPatch`.

use std::sync::Arc;

use reyes_scene::{TrimCurve, TrimLoop};

use super::frame::Machine;
use crate::{Request, RibError};

impl Machine {
    /// `TrimCurve ncurves order knot min max n u v w`.
    pub(super) fn trim_curve(&mut self, r: &Request) -> Result<(), RibError> {
        let loops = trim_loops(r)?;
        if let Err(issue) = reyes_scene::validate_trim(&loops, None) {
            return Err(r.error(format!("{}: {}", issue.path, issue.message)));
        }
        self.attributes.trim = Arc::new(loops);
        Ok(())
    }
}

/// The loops of a `TrimCurve` request, its arrays checked for length and count.
fn trim_loops(r: &Request) -> Result<Vec<TrimLoop>, RibError> {
    let ints = |i: usize| r.ints(i).unwrap_or(&[]);
    let floats = |i: usize| r.floats(i).unwrap_or(&[]);
    let (ncurves, order, knot, min, max, n) =
        (ints(0), ints(1), floats(2), floats(3), floats(4), ints(5));
    let (u, v, w) = (floats(6), floats(7), floats(8));
    let mut total = 0usize;
    for (i, &c) in ncurves.iter().enumerate() {
        if c < 1 {
            return Err(r.error(format!("ncurves[{i}] must be >= 1 (a loop has curves), got {c}")));
        }
        total += c as usize;
    }
    // One order, min, max and n per curve.
    for (name, len) in
        [("order", order.len()), ("min", min.len()), ("max", max.len()), ("n", n.len())]
    {
        if len != total {
            return Err(r.error(format!(
                "{name} must have one value per curve, the sum of ncurves = {total}, got {len}"
            )));
        }
    }
    let (mut knots, mut points) = (0usize, 0usize);
    for k in 0..total {
        if order[k] < 2 {
            return Err(r.error(format!("order[{k}] must be >= 2, got {}", order[k])));
        }
        if n[k] < order[k] {
            return Err(
                r.error(format!("n[{k}] must be >= order[{k}] ({}), got {}", order[k], n[k]))
            );
        }
        knots += (n[k] + order[k]) as usize;
        points += n[k] as usize;
    }
    if knot.len() != knots {
        return Err(r.error(format!(
            "knot must have n[k] + order[k] values for every curve, {knots} in all, got {}",
            knot.len()
        )));
    }
    for (name, len) in [("u", u.len()), ("v", v.len()), ("w", w.len())] {
        if len != points {
            return Err(r.error(format!(
                "{name} must have n[k] values for every curve, {points} in all, got {len}"
            )));
        }
    }
    let (mut kk, mut pk, mut curve) = (0usize, 0usize, 0usize);
    let mut loops = Vec::with_capacity(ncurves.len());
    for &c in ncurves {
        let mut curves = Vec::with_capacity(c as usize);
        for _ in 0..c {
            let (o, m) = (order[curve] as usize, n[curve] as usize);
            curves.push(TrimCurve {
                order: o as u32,
                knot: knot[kk..kk + m + o].to_vec(),
                min: min[curve],
                max: max[curve],
                points: (pk..pk + m).map(|i| [u[i], v[i], w[i]]).collect(),
            });
            kk += m + o;
            pk += m;
            curve += 1;
        }
        loops.push(TrimLoop { curves });
    }
    Ok(loops)
}
