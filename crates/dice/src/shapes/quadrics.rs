//! The hyperboloid (`RiHyperboloid`): the segment `p1 -> p2` turned about z.
//!
//! Invariants: `P(u, v) = Rz(u theta_max) lerp(p1, p2, v)`; the normal is
//! `dP/du x dP/dv = theta_max Rz(theta) ((-y, x, 0) x D)` with `(x, y, z)` the point of the
//! segment and `D = p2 - p1`, so a cylinder-like hyperboloid faces out of the axis exactly as
//! the cylinder does, and a cone-like one as the cone.

use glam::Vec3;

/// The point at `(u, v)`.
#[inline]
pub(super) fn hyperboloid_position(p1: Vec3, p2: Vec3, theta_max: f32, u: f32, v: f32) -> Vec3 {
    let (st, ct) = super::sweep(u, theta_max);
    let l = p1.lerp(p2, v);
    Vec3::new(l.x * ct - l.y * st, l.x * st + l.y * ct, l.z)
}

/// `(-y, x, 0) x D` at `v`, before the turn by theta.
#[inline]
fn unturned_normal(p1: Vec3, p2: Vec3, v: f32) -> Vec3 {
    let l = p1.lerp(p2, v);
    let d = p2 - p1;
    Vec3::new(l.x * d.z, l.y * d.z, -(l.x * d.x + l.y * d.y))
}

/// The unit normal at `(u, v)`. Where `dP/du x dP/dv` vanishes (a point on the axis, such as
/// a cone's apex, or where the segment runs along its circle) the normal a little way along
/// the segment is used, else +z.
pub(super) fn hyperboloid_normal(p1: Vec3, p2: Vec3, theta_max: f32, u: f32, v: f32) -> Vec3 {
    let scale = (p1.abs().max_element() + p2.abs().max_element()).max(f32::MIN_POSITIVE);
    let mut n = unturned_normal(p1, p2, v);
    if n.length() <= 1e-6 * scale * scale {
        n = unturned_normal(p1, p2, if v < 0.5 { v + 1e-3 } else { v - 1e-3 });
    }
    let (st, ct) = super::sweep(u, theta_max);
    let turned = Vec3::new(n.x * ct - n.y * st, n.x * st + n.y * ct, n.z);
    turned.try_normalize().unwrap_or(Vec3::Z)
}
