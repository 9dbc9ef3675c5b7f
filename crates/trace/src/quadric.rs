//! Ray intersection with the RenderMan quadrics and the torus, in object space, in `f64`.
//!
//! Invariants: each shape describes exactly the surface the dicer (`reyes_dice`'s shapes
//! stage) evaluates: it sweeps around object z with `theta = atan2(y, x)` in
//! `[0, thetamax]` and `u = theta / thetamax`; `v` and the outward normal follow the
//! dicer's parametrisation of each shape (sphere latitude between the clamped z cuts,
//! cylinder height, cone `z = v height`, paraboloid `z = zmin + v (zmax - zmin)`, disk
//! `r = radius (1 - v)`, torus tube angle in `[phimin, phimax]`, hyperboloid `v` along its
//! segment with `theta` measured from the segment's own angle). `intersect` returns the nearest hit with object parameter `s > 0`,
//! whatever the caller's `t_max`, so the same ray always gives the same answer.

use std::f64::consts::TAU;

use glam::DVec3;
use reyes_scene::Shape;

use crate::placement::LocalRay;
use crate::poly::{quadratic, roots_in};

/// A hit in object space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalHit {
    /// Object-space ray parameter (> 0).
    pub s: f64,
    /// Object-space point.
    pub p: DVec3,
    /// Object-space outward normal (not necessarily unit).
    pub n: DVec3,
    /// Surface parameters as the dicer defines them.
    pub u: f64,
    /// See `u`.
    pub v: f64,
}

/// The sweep around z: `theta` in `[0, theta_max]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Sweep {
    theta_max: f64,
    full: bool,
}

impl Sweep {
    fn new(degrees: f32) -> Sweep {
        let d = f64::from(degrees);
        Sweep { theta_max: d.to_radians(), full: d >= 360.0 }
    }

    /// `theta` of the point `(x, y)` in `[0, 2 pi)` if it lies in the sweep.
    #[inline]
    fn angle(self, x: f64, y: f64) -> Option<f64> {
        let mut theta = y.atan2(x);
        if theta < 0.0 {
            theta += TAU;
        }
        (self.full || theta <= self.theta_max).then_some(theta)
    }

    #[inline]
    fn u(self, theta: f64) -> f64 {
        theta / self.theta_max
    }
}

/// A quadric or torus, with its parameters in `f64` and angles in radians.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Quadric {
    /// Sphere cut to `zmin..=zmax` (already clamped to the radius).
    Sphere {
        radius: f64,
        zmin: f64,
        zmax: f64,
        /// Is the cut at `zmin` above the south pole?
        cut_low: bool,
        /// Is the cut at `zmax` below the north pole?
        cut_high: bool,
        phi_min: f64,
        phi_max: f64,
        sweep: Sweep,
    },
    /// Open cylinder.
    Cylinder { radius: f64, zmin: f64, zmax: f64, sweep: Sweep },
    /// Cone from the base circle at z = 0 to the apex at z = height.
    Cone { height: f64, radius: f64, sweep: Sweep },
    /// Paraboloid `x^2 + y^2 = (rmax^2 / zmax) z`, cut to `zmin..=zmax` (`0 <= zmin < zmax`).
    Paraboloid { rmax: f64, zmin: f64, zmax: f64, sweep: Sweep },
    /// Disk in the plane z = height.
    Disk { height: f64, radius: f64, sweep: Sweep },
    /// Torus; the tube angle runs over `phi_min..=phi_max`.
    Torus { major: f64, minor: f64, phi_min: f64, phi_max: f64, full_tube: bool, sweep: Sweep },
    /// Hyperboloid: the segment `p1 -> p2` (`v` along it) turned about z through the sweep.
    Hyperboloid { p1: DVec3, p2: DVec3, sweep: Sweep },
}

impl Quadric {
    /// The quadric of a shape, or `None` for patches and meshes.
    pub fn from_shape(shape: &Shape) -> Option<Quadric> {
        Some(match shape {
            Shape::Sphere { radius, zmin, zmax, thetamax } => {
                let r = f64::from(*radius);
                let z0 = zmin.map_or(-r, f64::from).clamp(-r, r);
                let z1 = zmax.map_or(r, f64::from).clamp(-r, r);
                Quadric::Sphere {
                    radius: r,
                    zmin: z0,
                    zmax: z1,
                    cut_low: z0 > -r,
                    cut_high: z1 < r,
                    phi_min: (z0 / r).clamp(-1.0, 1.0).asin(),
                    phi_max: (z1 / r).clamp(-1.0, 1.0).asin(),
                    sweep: Sweep::new(*thetamax),
                }
            }
            Shape::Cylinder { radius, zmin, zmax, thetamax } => Quadric::Cylinder {
                radius: f64::from(*radius),
                zmin: f64::from(*zmin),
                zmax: f64::from(*zmax),
                sweep: Sweep::new(*thetamax),
            },
            Shape::Cone { height, radius, thetamax } => Quadric::Cone {
                height: f64::from(*height),
                radius: f64::from(*radius),
                sweep: Sweep::new(*thetamax),
            },
            Shape::Paraboloid { rmax, zmin, zmax, thetamax } => Quadric::Paraboloid {
                rmax: f64::from(*rmax),
                zmin: f64::from(*zmin),
                zmax: f64::from(*zmax),
                sweep: Sweep::new(*thetamax),
            },
            Shape::Disk { height, radius, thetamax } => Quadric::Disk {
                height: f64::from(*height),
                radius: f64::from(*radius),
                sweep: Sweep::new(*thetamax),
            },
            Shape::Torus { major_radius, minor_radius, phimin, phimax, thetamax } => {
                let (lo, hi) = (f64::from(*phimin), f64::from(*phimax));
                Quadric::Torus {
                    major: f64::from(*major_radius),
                    minor: f64::from(*minor_radius),
                    phi_min: lo.to_radians(),
                    phi_max: hi.to_radians(),
                    full_tube: hi - lo >= 360.0,
                    sweep: Sweep::new(*thetamax),
                }
            }
            Shape::Hyperboloid { point1, point2, thetamax } => Quadric::Hyperboloid {
                p1: DVec3::from(point1.map(f64::from)),
                p2: DVec3::from(point2.map(f64::from)),
                sweep: Sweep::new(*thetamax),
            },
            Shape::BilinearPatch { .. }
            | Shape::Mesh { .. }
            | Shape::PatchMesh { .. }
            | Shape::NuPatch { .. }
            | Shape::SubdivisionMesh { .. }
            | Shape::Curves { .. }
            | Shape::Points { .. }
            | Shape::Blobby { .. }
            | Shape::MeshFile { .. } => return None,
        })
    }

    /// An object-space box `(min, max)` enclosing the surface.
    pub fn object_bounds(&self) -> (DVec3, DVec3) {
        let box_of = |r: f64, z0: f64, z1: f64| {
            (DVec3::new(-r, -r, z0.min(z1)), DVec3::new(r, r, z0.max(z1)))
        };
        match self {
            Quadric::Sphere { radius, zmin, zmax, .. } => box_of(*radius, *zmin, *zmax),
            Quadric::Cylinder { radius, zmin, zmax, .. } => box_of(*radius, *zmin, *zmax),
            Quadric::Cone { height, radius, .. } => box_of(*radius, 0.0, *height),
            // The widest circle is the one at zmax (zmax > 0 for a valid paraboloid; the box
            // still encloses the surface otherwise, as |r| <= rmax on the cut).
            Quadric::Paraboloid { rmax, zmin, zmax, .. } => box_of(*rmax, *zmin, *zmax),
            Quadric::Disk { height, radius, .. } => box_of(*radius, *height, *height),
            Quadric::Torus { major, minor, .. } => box_of(major + minor, -minor, *minor),
            // |L_xy(v)| is convex along the segment: largest at an end.
            Quadric::Hyperboloid { p1, p2, .. } => {
                let r = p1.truncate().length().max(p2.truncate().length());
                box_of(r, p1.z, p2.z)
            }
        }
    }

    /// The nearest hit with `s > 0`.
    pub fn intersect(&self, ray: &LocalRay) -> Option<LocalHit> {
        match self {
            Quadric::Sphere { radius, zmin, zmax, cut_low, cut_high, phi_min, phi_max, sweep } => {
                let r = *radius;
                for s in sphere_roots(ray, r) {
                    let p = ray.o + ray.d * s;
                    if (*cut_low && p.z < *zmin) || (*cut_high && p.z > *zmax) {
                        continue;
                    }
                    let Some(theta) = sweep.angle(p.x, p.y) else { continue };
                    let phi = (p.z / r).clamp(-1.0, 1.0).asin();
                    let v = (phi - phi_min) / (phi_max - phi_min);
                    return Some(LocalHit { s, p, n: p / r, u: sweep.u(theta), v });
                }
                None
            }
            Quadric::Cylinder { radius, zmin, zmax, sweep } => {
                let (o, d) = (ray.o, ray.d);
                let a = d.x * d.x + d.y * d.y;
                let b = 2.0 * (o.x * d.x + o.y * d.y);
                let c = o.x * o.x + o.y * o.y - radius * radius;
                first_root(ray, a, b, c, |s, p| {
                    if p.z < *zmin || p.z > *zmax {
                        return None;
                    }
                    let theta = sweep.angle(p.x, p.y)?;
                    let n = DVec3::new(p.x, p.y, 0.0) / *radius;
                    let v = (p.z - zmin) / (zmax - zmin);
                    Some(LocalHit { s, p, n, u: sweep.u(theta), v })
                })
            }
            Quadric::Cone { height, radius, sweep } => {
                let (o, d, h, r) = (ray.o, ray.d, *height, *radius);
                let k = r / h;
                let m = r - k * o.z;
                let a = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
                let b = 2.0 * (o.x * d.x + o.y * d.y + m * k * d.z);
                let c = o.x * o.x + o.y * o.y - m * m;
                first_root(ray, a, b, c, |s, p| {
                    let v = p.z / h;
                    if !(0.0..=1.0).contains(&v) {
                        return None;
                    }
                    let theta = sweep.angle(p.x, p.y)?;
                    let rho = p.x.hypot(p.y);
                    let (cx, cy) = if rho > 0.0 { (p.x / rho, p.y / rho) } else { (1.0, 0.0) };
                    let n = DVec3::new(h.abs() * cx, h.abs() * cy, r.copysign(h));
                    Some(LocalHit { s, p, n, u: sweep.u(theta), v })
                })
            }
            Quadric::Paraboloid { rmax, zmin, zmax, sweep } => {
                // x^2 + y^2 - k z = 0 with k = rmax^2 / zmax: a quadratic in s.
                let (o, d) = (ray.o, ray.d);
                let k = rmax * rmax / zmax;
                let a = d.x * d.x + d.y * d.y;
                let b = 2.0 * (o.x * d.x + o.y * d.y) - k * d.z;
                let c = o.x * o.x + o.y * o.y - k * o.z;
                first_root(ray, a, b, c, |s, p| {
                    if p.z < *zmin || p.z > *zmax {
                        return None;
                    }
                    let theta = sweep.angle(p.x, p.y)?;
                    // The gradient: away from the axis and down, out of the solid bowl.
                    let n = DVec3::new(2.0 * p.x, 2.0 * p.y, -k);
                    let v = (p.z - zmin) / (zmax - zmin);
                    Some(LocalHit { s, p, n, u: sweep.u(theta), v })
                })
            }
            Quadric::Disk { height, radius, sweep } => {
                let (o, d) = (ray.o, ray.d);
                if d.z == 0.0 {
                    return None;
                }
                let s = (height - o.z) / d.z;
                if s.is_nan() || s <= 0.0 {
                    return None;
                }
                let p = DVec3::new(o.x + d.x * s, o.y + d.y * s, *height);
                let rho = p.x.hypot(p.y);
                if rho > *radius {
                    return None;
                }
                let theta = sweep.angle(p.x, p.y)?;
                Some(LocalHit { s, p, n: DVec3::Z, u: sweep.u(theta), v: 1.0 - rho / radius })
            }
            Quadric::Torus { major, minor, phi_min, phi_max, full_tube, sweep } => {
                torus(ray, *major, *minor, *phi_min, *phi_max, *full_tube, *sweep)
            }
            Quadric::Hyperboloid { p1, p2, sweep } => hyperboloid(ray, *p1, *p2, *sweep),
        }
    }
}

/// Tolerance on a hyperboloid's `v` outside `[0, 1]` before clamping.
const V_EDGE: f64 = 1e-9;

/// The hyperboloid's hit at segment parameter `v` and point `p`, if its angle from the
/// segment's own point lies in the sweep. The normal is `dP/du x dP/dv` (see the dicer's
/// shapes stage): `Rz(theta) ((-y, x, 0) x D)` for the segment point `(x, y, z)`, taken a
/// little way along the segment where it vanishes (a point on the axis).
fn hyperboloid_hit(
    s: f64,
    p: DVec3,
    v: f64,
    p1: DVec3,
    p2: DVec3,
    sweep: Sweep,
) -> Option<LocalHit> {
    if !(-V_EDGE..=1.0 + V_EDGE).contains(&v) {
        return None;
    }
    let v = v.clamp(0.0, 1.0);
    let d = p2 - p1;
    let l = p1.lerp(p2, v);
    // The angle from the segment's point to the hit: arg(p) - arg(l), via p * conj(l).
    let theta = if l.x == 0.0 && l.y == 0.0 {
        0.0
    } else {
        sweep.angle(p.x * l.x + p.y * l.y, p.y * l.x - p.x * l.y)?
    };
    let unturned = |l: DVec3| DVec3::new(l.x * d.z, l.y * d.z, -(l.x * d.x + l.y * d.y));
    let scale = p1.abs().max_element() + p2.abs().max_element();
    let mut n = unturned(l);
    if n.length() <= 1e-12 * scale * scale {
        n = unturned(p1.lerp(p2, if v < 0.5 { v + 1e-3 } else { v - 1e-3 }));
    }
    let (st, ct) = theta.sin_cos();
    let n = DVec3::new(n.x * ct - n.y * st, n.x * st + n.y * ct, n.z);
    let n = if n == DVec3::ZERO { DVec3::Z } else { n };
    Some(LocalHit { s, p, n, u: sweep.u(theta), v })
}

/// The hyperboloid: where the segment is not horizontal, `v` is linear in the ray's `s`
/// (through z) and `|p_xy|^2 = |L_xy(v)|^2` is a quadratic in `s`; a horizontal segment sweeps
/// a flat ring in its plane, where `|L_xy(v)|^2 = rho^2` is a quadratic in `v`.
fn hyperboloid(ray: &LocalRay, p1: DVec3, p2: DVec3, sweep: Sweep) -> Option<LocalHit> {
    let (o, d) = (ray.o, ray.d);
    let seg = p2 - p1;
    if seg.z != 0.0 {
        let (v0, v1) = ((o.z - p1.z) / seg.z, d.z / seg.z);
        let c0 = p1.truncate() + seg.truncate() * v0;
        let c1 = seg.truncate() * v1;
        let (oxy, dxy) = (o.truncate(), d.truncate());
        let a = dxy.length_squared() - c1.length_squared();
        let b = 2.0 * (oxy.dot(dxy) - c0.dot(c1));
        let c = oxy.length_squared() - c0.length_squared();
        return first_root(ray, a, b, c, |s, p| hyperboloid_hit(s, p, v0 + s * v1, p1, p2, sweep));
    }
    if d.z == 0.0 {
        return None;
    }
    let s = (p1.z - o.z) / d.z;
    if s.is_nan() || s <= 0.0 {
        return None;
    }
    let p = DVec3::new(o.x + d.x * s, o.y + d.y * s, p1.z);
    let (l0, dl) = (p1.truncate(), seg.truncate());
    let roots = quadratic(
        dl.length_squared(),
        2.0 * l0.dot(dl),
        l0.length_squared() - p.truncate().length_squared(),
    );
    roots.as_slice().iter().find_map(|&v| hyperboloid_hit(s, p, v, p1, p2, sweep))
}

/// The hit at the first root `s > 0` of `a s^2 + b s + c` (ascending) whose point
/// `o + d s` the shape's `hit` accepts (within its cuts and sweep).
#[inline]
fn first_root(
    ray: &LocalRay,
    a: f64,
    b: f64,
    c: f64,
    hit: impl Fn(f64, DVec3) -> Option<LocalHit>,
) -> Option<LocalHit> {
    for &s in quadratic(a, b, c).as_slice() {
        if s.is_nan() || s <= 0.0 {
            continue;
        }
        if let Some(h) = hit(s, ray.o + ray.d * s) {
            return Some(h);
        }
    }
    None
}

/// Parameters `s > 0` where the ray meets the sphere of radius `r` about the origin,
/// ascending. The discriminant is formed from the ray's closest approach to the centre,
/// which keeps it accurate for far-away origins.
fn sphere_roots(ray: &LocalRay, r: f64) -> impl Iterator<Item = f64> {
    let (o, d) = (ray.o, ray.d);
    let a = d.length_squared();
    let mut out = [f64::NAN; 2];
    if a > 0.0 {
        let h = o.dot(d);
        let closest = o - d * (h / a);
        let disc = r * r - closest.length_squared();
        if disc >= 0.0 {
            let sq = (a * disc).sqrt();
            let q = -(h + sq.copysign(h));
            let c = o.length_squared() - r * r;
            let (r0, r1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
            out = if r0 <= r1 { [r0, r1] } else { [r1, r0] };
        }
    }
    out.into_iter().filter(|s| *s > 0.0)
}

/// The torus `(|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2)`: the quartic in the distance
/// along the unit direction, measured from the ray's closest approach to the centre,
/// solved on the stretch inside the bounding sphere of radius `R + r`.
fn torus(
    ray: &LocalRay,
    major: f64,
    minor: f64,
    phi_min: f64,
    phi_max: f64,
    full_tube: bool,
    sweep: Sweep,
) -> Option<LocalHit> {
    let len = ray.d.length();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let dn = ray.d / len;
    let b = ray.o.dot(dn);
    let oc = ray.o - dn * b;
    let bound = (major + minor) * (1.0 + 1e-9);
    let cc = oc.length_squared();
    if cc > bound * bound {
        return None;
    }
    let half = (bound * bound - cc).sqrt();
    // In tau = sigma + b (sigma = distance from the origin): [max(-half, b), half].
    let (lo, hi) = (b.max(-half), half);
    if lo.is_nan() || hi.is_nan() || lo >= hi {
        return None;
    }
    let (r2, rr2) = (major * major, minor * minor);
    let e = oc.dot(dn);
    let g = cc + r2 - rr2;
    let alpha = dn.x * dn.x + dn.y * dn.y;
    let beta = 2.0 * (oc.x * dn.x + oc.y * dn.y);
    let gamma = oc.x * oc.x + oc.y * oc.y;
    let coeffs = [
        g * g - 4.0 * r2 * gamma,
        4.0 * e * g - 4.0 * r2 * beta,
        4.0 * e * e + 2.0 * g - 4.0 * r2 * alpha,
        4.0 * e,
        1.0,
    ];
    for &tau in roots_in(&coeffs, lo, hi).as_slice() {
        let sigma = tau - b;
        if sigma.is_nan() || sigma <= 0.0 {
            continue;
        }
        let p = oc + dn * tau;
        let rho = p.x.hypot(p.y);
        // The point lies on the tube around the circle of radius R either on its own side
        // of the axis (ring = rho) or, for a spindle torus, on the opposite side (ring = -rho).
        let near = ((rho - major).powi(2) + p.z * p.z - rr2).abs();
        let far = ((rho + major).powi(2) + p.z * p.z - rr2).abs();
        let (ring, cx, cy) = match (rho > 0.0, far < near) {
            (true, false) => (rho, p.x / rho, p.y / rho),
            (true, true) => (-rho, -p.x / rho, -p.y / rho),
            (false, _) => (0.0, 1.0, 0.0),
        };
        let Some(theta) = sweep.angle(cx, cy) else { continue };
        let phi = p.z.atan2(ring - major);
        let phi = phi_min + (phi - phi_min).rem_euclid(TAU);
        if !full_tube && phi > phi_max {
            continue;
        }
        let (sp, cp) = phi.sin_cos();
        let n = DVec3::new(cp * cx, cp * cy, sp);
        let v = (phi - phi_min) / (phi_max - phi_min);
        return Some(LocalHit { s: sigma / len, p, n, u: sweep.u(theta), v });
    }
    None
}
