//! Front-to-back compositing of one sample's visible points: the body of Appendix A
//! `CSGResolve` for surfaces that are not in a CSG tree.
//!
//! Invariant: colours are premultiplied by opacity and `trans` is per-channel transmittance,
//! so compositing a point behind an accumulated `(C, T)` is `C += T*c`, `T *= t`.

use crate::tree::{CsgOrder, CsgTree, resolve_tree_at_sample};
use crate::visible::{LERP_DONE, NIL, VisPoint, lerpz, sortfront};

/// Flag bits read here; they are the micropolygon's (`reyes_hider::flags`), repeated so this
/// crate does not depend on the hider.
const OPAQUE: u32 = 1 << 1;
const MATTE: u32 = 1 << 3;
const GLASS: u32 = 1 << 9;

/// How a matte (holdout) surface is composited.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MatteRule {
    /// A matte surface adds no colour and no alpha and attenuates everything behind it by its
    /// transmittance; surfaces in front of it composite normally.
    #[default]
    Holdout,
    /// Appendix A as printed (appendix-a.md 3.14): the sample takes its `matte` and `opaque`
    /// flags from the deepest composited surface, so a matte behind a transparent surface
    /// drops the whole sample, and a non-opaque matte surface adds its colour like any other.
    Original,
}

/// What resolution needs besides the points: the matte rule and the CSG trees.
#[derive(Debug, Clone, Copy, Default)]
pub struct Resolver<'a> {
    /// Matte compositing rule.
    pub matte: MatteRule,
    /// The scene's CSG trees, indexed by `VisPoint::csg_tree`.
    pub trees: &'a [CsgTree],
    /// Depth comparison across CSG operands.
    pub order: CsgOrder,
}

/// The resolved value of one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Composite {
    /// Premultiplied colour.
    pub rgb: [f32; 3],
    /// Coverage.
    pub alpha: f32,
    /// Exact depth of the opaque surface that ended the composite, or +inf.
    pub z: f32,
}

impl Composite {
    /// Nothing visible.
    pub const EMPTY: Composite = Composite { rgb: [0.0; 3], alpha: 0.0, z: f32::INFINITY };
}

/// Port of `CSGResolve` for one sample: repeatedly take the nearest remaining point
/// (`sortfront`); if it belongs to a CSG tree, resolve that whole tree at this sample (its
/// boundary points go back into the list as ordinary points, the rest are dropped) and look
/// again; otherwise composite it behind what is already accumulated, stopping at the first
/// opaque surface. `lerps` counts exact-depth interpolations.
///
/// Appendix A's `glasshack`: right after compositing a glass surface, if another surface
/// remains, the accumulated colour is tinted by the raw colour directly behind,
/// `C *= a + (1 - a) * c_behind` with `a` the glass's `glasshackopacity`.
pub fn resolve_sample(
    points: &mut [VisPoint],
    head: u32,
    resolver: &Resolver,
    lerps: &mut u64,
) -> Composite {
    resolve_sample_traced(points, head, resolver, lerps, &mut ())
}

/// What [`resolve_sample_traced`] reports of the composite it computes, so that other values
/// of the same points (AOVs) can be composited with exactly the same weights.
pub trait Trace {
    /// Point `point` was composited behind per-channel transmittance `weight` (its colour
    /// added as `weight * color` unless `holdout`, a matte under the holdout rule).
    fn add(&mut self, point: u32, weight: [f32; 3], holdout: bool);
    /// Everything accumulated so far was multiplied by `factor` (Appendix A's glass hack).
    fn scale(&mut self, factor: [f32; 3]);
    /// The sample's colour was dropped (a matte at the back under the original rule).
    fn zero(&mut self);
}

/// No trace: [`resolve_sample`].
impl Trace for () {
    #[inline(always)]
    fn add(&mut self, _: u32, _: [f32; 3], _: bool) {}
    #[inline(always)]
    fn scale(&mut self, _: [f32; 3]) {}
    #[inline(always)]
    fn zero(&mut self) {}
}

/// [`resolve_sample`], reporting each compositing step to `trace` in the order it is done.
/// The composite is the same, bit for bit.
pub fn resolve_sample_traced<T: Trace>(
    points: &mut [VisPoint],
    mut head: u32,
    resolver: &Resolver,
    lerps: &mut u64,
    trace: &mut T,
) -> Composite {
    let rule = resolver.matte;
    let mut c = [0.0f32; 3];
    let mut t = [1.0f32; 3];
    // Coverage accumulated from non-matte surfaces, per channel (Holdout rule).
    let mut a = [0.0f32; 3];
    let mut any = false;
    let mut last_flags = 0;
    let mut z = f32::INFINITY;
    loop {
        let front = sortfront(points, &mut head, lerps);
        if front == NIL {
            break;
        }
        let p = points[front as usize];
        if p.csg_node != 0 {
            resolve_tree_at_sample(
                points,
                resolver.trees,
                p.csg_tree,
                &mut head,
                resolver.order,
                lerps,
            );
            continue;
        }
        head = p.next;
        any = true;
        last_flags = p.flags;
        let holdout = rule == MatteRule::Holdout && p.flags & MATTE != 0;
        trace.add(front, t, holdout);
        for k in 0..3 {
            if !holdout {
                c[k] += t[k] * p.color[k];
                a[k] += t[k] * (1.0 - p.trans[k]);
            }
            t[k] *= p.trans[k];
        }
        if p.flags & GLASS != 0 && head != NIL {
            let behind = sortfront(points, &mut head, lerps);
            let g = p.glass_opacity;
            let cb = points[behind as usize].color;
            let mut factor = [0.0; 3];
            for k in 0..3 {
                factor[k] = g + (1.0 - g) * cb[k];
                c[k] *= factor[k];
            }
            trace.scale(factor);
        }
        if p.flags & OPAQUE != 0 {
            z = if p.flags & LERP_DONE != 0 {
                p.minz
            } else {
                *lerps += 1;
                lerpz(&p.v)
            };
            break;
        }
    }
    if !any {
        return Composite::EMPTY;
    }
    match rule {
        MatteRule::Original => {
            if last_flags & MATTE != 0 {
                trace.zero();
                return Composite { rgb: [0.0; 3], alpha: 0.0, z };
            }
            let alpha =
                if last_flags & OPAQUE != 0 { 1.0 } else { 1.0 - (t[0] + t[1] + t[2]) / 3.0 };
            Composite { rgb: c, alpha, z }
        }
        MatteRule::Holdout => {
            let alpha = if last_flags & OPAQUE != 0 && last_flags & MATTE == 0 {
                1.0
            } else {
                (a[0] + a[1] + a[2]) / 3.0
            };
            Composite { rgb: c, alpha, z }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn surface(z: f32, color: [f32; 3], opacity: f32, flags: u32) -> VisPoint {
        let v = [[-0.5, -0.5, z], [0.5, -0.5, z], [0.5, 0.5, z], [-0.5, 0.5, z]];
        let o = opacity;
        VisPoint {
            v,
            minz: z,
            maxz: z,
            color: [color[0] * o, color[1] * o, color[2] * o],
            trans: [1.0 - o; 3],
            flags: flags | if o == 1.0 { OPAQUE } else { 0 },
            csg_tree: 0,
            csg_node: 0,
            glass_opacity: 0.0,
            next: NIL,
        }
    }

    fn list(mut pts: Vec<VisPoint>) -> (Vec<VisPoint>, u32) {
        let n = pts.len();
        for (i, p) in pts.iter_mut().enumerate() {
            p.next = if i + 1 < n { (i + 1) as u32 } else { NIL };
        }
        (pts, if n == 0 { NIL } else { 0 })
    }

    #[test]
    fn empty_sample() {
        let mut lerps = 0;
        assert_eq!(
            resolve_sample(&mut [], NIL, &Resolver::default(), &mut lerps),
            Composite::EMPTY
        );
    }

    #[test]
    fn half_transparent_over_opaque_in_any_insertion_order() {
        let red = surface(2.0, [1.0, 0.0, 0.0], 0.5, 0);
        let blue = surface(5.0, [0.0, 0.0, 1.0], 1.0, 0);
        let far = surface(9.0, [0.0, 1.0, 0.0], 1.0, 0);
        for order in [[0, 1, 2], [2, 1, 0], [1, 2, 0]] {
            let all = [red, blue, far];
            let (mut pts, head) = list(order.iter().map(|&i| all[i]).collect());
            let mut lerps = 0;
            let r = resolve_sample(&mut pts, head, &Resolver::default(), &mut lerps);
            assert_eq!(r.rgb, [0.5, 0.0, 0.5], "order {order:?}");
            assert_eq!(r.alpha, 1.0);
            assert_eq!(r.z, 5.0);
        }
    }

    #[test]
    fn transparent_alone_has_partial_alpha() {
        let (mut pts, head) = list(vec![surface(2.0, [1.0, 1.0, 1.0], 0.25, 0)]);
        let mut lerps = 0;
        let r = resolve_sample(&mut pts, head, &Resolver::default(), &mut lerps);
        assert_eq!(r.alpha, 0.25);
        assert_eq!(r.z, f32::INFINITY);
    }

    #[test]
    fn matte_holdout_keeps_what_is_in_front() {
        let glass = surface(2.0, [1.0, 0.0, 0.0], 0.5, 0);
        let matte = surface(4.0, [0.0, 1.0, 0.0], 1.0, MATTE);
        let behind = surface(6.0, [0.0, 0.0, 1.0], 1.0, 0);
        let (mut pts, head) = list(vec![behind, matte, glass]);
        let mut lerps = 0;
        let r = resolve_sample(&mut pts.clone(), head, &Resolver::default(), &mut lerps);
        assert_eq!(r.rgb, [0.5, 0.0, 0.0]);
        assert_eq!(r.alpha, 0.5);
        // The original drops the whole sample because its deepest surface is matte.
        let o = resolve_sample(
            &mut pts,
            head,
            &Resolver { matte: MatteRule::Original, ..Resolver::default() },
            &mut lerps,
        );
        assert_eq!((o.rgb, o.alpha), ([0.0; 3], 0.0));
    }

    #[test]
    fn glass_tints_by_the_colour_behind() {
        let mut glass = surface(1.0, [1.0, 1.0, 1.0], 1.0, GLASS);
        glass.glass_opacity = 0.25;
        let behind = surface(3.0, [0.0, 1.0, 0.5], 1.0, 0);
        let (mut pts, head) = list(vec![behind, glass]);
        let mut lerps = 0;
        let r = resolve_sample(&mut pts, head, &Resolver::default(), &mut lerps);
        // C = 1 * (0.25 + 0.75 * c_behind); the opaque glass then ends the sample.
        assert_eq!(r.rgb, [0.25, 1.0, 0.625]);
        assert_eq!(r.z, 1.0);
    }
}
