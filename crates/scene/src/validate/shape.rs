//! The rules of an object's surface and placement: each [`Shape`] variant's fields in order,
//! and each [`Transform`] step.
//!
//! Invariant: no check can panic; the matrix determinant is computed in `f64`.

use glam::DMat4;

use super::primitives::{
    Check, above, each, fail, finite, finite_all, finite_each, int_in, nonzero_vector, positive,
    sweep,
};
use crate::model::{Basis, PatchType, Shape, Transform, Wrap};
use crate::patches::{self, MAX_ORDER};

pub(super) fn shape(at: &str, shape: &Shape) -> Check {
    let field = |name: &str| format!("{at}.{name}");
    match shape {
        Shape::Sphere { radius, zmin, zmax, thetamax } => {
            positive(&field("radius"), *radius)?;
            if let Some(z) = zmin {
                finite(&field("zmin"), *z)?;
            }
            if let Some(z) = zmax {
                finite(&field("zmax"), *z)?;
            }
            let lo = zmin.unwrap_or(-radius).clamp(-radius, *radius);
            let hi = zmax.unwrap_or(*radius).clamp(-radius, *radius);
            if lo >= hi {
                let culprit = if zmax.is_some() { "zmax" } else { "zmin" };
                return fail(
                    field(culprit),
                    format!(
                        "zmin must be < zmax once both are clamped to [-radius, radius], \
                         got zmin {lo} and zmax {hi}"
                    ),
                );
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Cylinder { radius, zmin, zmax, thetamax } => {
            positive(&field("radius"), *radius)?;
            finite(&field("zmin"), *zmin)?;
            finite(&field("zmax"), *zmax)?;
            above(&field("zmax"), *zmax, "zmin", *zmin)?;
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Cone { height, radius, thetamax } => {
            finite(&field("height"), *height)?;
            if *height == 0.0 {
                return fail(field("height"), "must be non-zero, got 0");
            }
            positive(&field("radius"), *radius)?;
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Disk { height, radius, thetamax } => {
            finite(&field("height"), *height)?;
            positive(&field("radius"), *radius)?;
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Paraboloid { rmax, zmin, zmax, thetamax } => {
            positive(&field("rmax"), *rmax)?;
            finite(&field("zmin"), *zmin)?;
            finite(&field("zmax"), *zmax)?;
            if *zmin < 0.0 {
                return fail(field("zmin"), format!("must be >= 0, got {zmin}"));
            }
            above(&field("zmax"), *zmax, "zmin", *zmin)?;
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::Torus { major_radius, minor_radius, phimin, phimax, thetamax } => {
            positive(&field("major_radius"), *major_radius)?;
            positive(&field("minor_radius"), *minor_radius)?;
            finite(&field("phimin"), *phimin)?;
            finite(&field("phimax"), *phimax)?;
            above(&field("phimax"), *phimax, "phimin", *phimin)?;
            if f64::from(*phimax) - f64::from(*phimin) > 360.0 {
                return fail(
                    field("phimax"),
                    format!(
                        "must be at most phimin + 360 ({}), got {phimax}",
                        f64::from(*phimin) + 360.0
                    ),
                );
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::BilinearPatch { points } => finite_each(&field("points"), points),
        Shape::SubdivisionMesh { points, faces, tags, colors, st } => {
            super::subdivision::subdivision_mesh(
                at,
                points,
                faces,
                tags,
                colors.as_deref(),
                st.as_deref(),
            )
        }
        Shape::Curves { .. } => super::hair::curves(at, shape),
        Shape::Points { .. } => super::hair::points(at, shape),
        Shape::Blobby { .. } => super::hair::blobby(at, shape),
        Shape::MeshFile { path, .. } => fail(
            field("path"),
            format!(
                "the mesh file {path:?} was not read: MeshFile is read by parse or load, \
                 not by validate"
            ),
        ),
        Shape::Mesh { points, faces, colors, normals, st } => {
            finite_each(&field("points"), points)?;
            if faces.is_empty() {
                return fail(field("faces"), "must hold at least one face");
            }
            for (f, face) in faces.iter().enumerate() {
                if face.len() < 3 {
                    return fail(
                        format!("{at}.faces[{f}]"),
                        format!("a face must have at least 3 indices, got {}", face.len()),
                    );
                }
                for (k, &index) in face.iter().enumerate() {
                    if usize::try_from(index).unwrap_or(usize::MAX) >= points.len() {
                        return fail(
                            format!("{at}.faces[{f}][{k}]"),
                            format!(
                                "index {index} is out of range: the mesh has {} points",
                                points.len()
                            ),
                        );
                    }
                }
            }
            if let Some(colors) = colors {
                if colors.len() != points.len() {
                    return fail(
                        field("colors"),
                        format!(
                            "must have one colour per point ({}), got {}",
                            points.len(),
                            colors.len()
                        ),
                    );
                }
                finite_each(&field("colors"), colors)?;
            }
            if let Some(normals) = normals {
                per_point(&field("normals"), "normal", normals.len(), points.len())?;
                finite_each(&field("normals"), normals)?;
                for (i, n) in normals.iter().enumerate() {
                    if n.iter().all(|c| *c == 0.0) {
                        return fail(
                            format!("{at}.normals[{i}]"),
                            "must be non-zero, got [0, 0, 0]",
                        );
                    }
                }
            }
            if let Some(st) = st {
                per_point(&field("st"), "(s, t) pair", st.len(), points.len())?;
                finite_each(&field("st"), st)?;
            }
            Ok(())
        }
        Shape::Hyperboloid { point1, point2, thetamax } => {
            finite_all(&field("point1"), point1)?;
            finite_all(&field("point2"), point2)?;
            if point1 == point2 {
                return fail(
                    field("point2"),
                    "must differ from point1, or the segment sweeps nothing",
                );
            }
            let on_axis = |p: &[f32; 3]| p[0] == 0.0 && p[1] == 0.0;
            if on_axis(point1) && on_axis(point2) {
                return fail(
                    field("point2"),
                    "the segment lies on the z axis, so it sweeps no surface",
                );
            }
            sweep(&field("thetamax"), *thetamax)
        }
        Shape::PatchMesh { kind, nu, nv, uwrap, vwrap, points, ubasis, ustep, vbasis, vstep } => {
            let mut steps = [1, 1];
            for (k, (dir, basis, given)) in
                [("u", ubasis, ustep), ("v", vbasis, vstep)].into_iter().enumerate()
            {
                if let Basis::Matrix(m) = basis {
                    finite_each(&field(&format!("{dir}basis")), m)?;
                }
                if *kind == PatchType::Bicubic {
                    steps[k] = match patches::step(basis, *given) {
                        Some(0) => {
                            return fail(field(&format!("{dir}step")), "must be >= 1, got 0");
                        }
                        Some(s) => s,
                        None => {
                            return fail(
                                field(&format!("{dir}step")),
                                format!("a Matrix {dir}basis has no standard step: give {dir}step"),
                            );
                        }
                    };
                }
            }
            counts(&field("nu"), *kind, *nu, *uwrap, steps[0])?;
            counts(&field("nv"), *kind, *nv, *vwrap, steps[1])?;
            point_count(&field("points"), points.len(), *nu, *nv)?;
            finite_each(&field("points"), points)
        }
        Shape::NuPatch {
            nu,
            uorder,
            uknot,
            umin,
            umax,
            nv,
            vorder,
            vknot,
            vmin,
            vmax,
            points,
            trim,
            ..
        } => {
            knots(at, "u", *nu, *uorder, uknot, *umin, *umax)?;
            knots(at, "v", *nv, *vorder, vknot, *vmin, *vmax)?;
            point_count(&field("points"), points.len(), *nu, *nv)?;
            finite_each(&field("points"), points)?;
            for (i, p) in points.iter().enumerate() {
                if p[3] <= 0.0 {
                    return fail(
                        format!("{at}.points[{i}][3]"),
                        format!("the weight must be > 0, got {}", p[3]),
                    );
                }
            }
            let domain = [*umin, *umax, *vmin, *vmax];
            for (i, l) in trim.iter().enumerate() {
                super::trim::trim_loop(&format!("{at}.trim[{i}]"), l, Some(domain))?;
            }
            Ok(())
        }
    }
}

/// The sub-patch count of one direction of a patch mesh ([`patches::patch_count`]).
fn counts(path: &str, kind: PatchType, n: u32, wrap: Wrap, step: u32) -> Check {
    match patches::patch_count(kind, n, wrap, step) {
        Ok(_) => Ok(()),
        Err(why) => fail(path, why),
    }
}

/// `len` control points for an `nu x nv` grid.
fn point_count(path: &str, len: usize, nu: u32, nv: u32) -> Check {
    let want = u64::from(nu) * u64::from(nv);
    if len as u64 != want {
        return fail(path, format!("must have nu * nv = {want} points, got {len}"));
    }
    Ok(())
}

/// One direction of a NURBS patch (`dir` is `u` or `v`): the order in `2..=MAX_ORDER`, at
/// least `order` points, `n + order` finite non-decreasing knots, and a drawn range
/// `min < max` inside the valid range `[knot[order - 1], knot[n]]`.
pub(super) fn knots(
    at: &str,
    dir: &str,
    n: u32,
    order: u32,
    knot: &[f32],
    min: f32,
    max: f32,
) -> Check {
    let field = |name: &str| format!("{at}.{dir}{name}");
    int_in(&field("order"), order, 2, MAX_ORDER)?;
    if n < order {
        return fail(format!("{at}.n{dir}"), format!("must be >= {dir}order ({order}), got {n}"));
    }
    let want = u64::from(n) + u64::from(order);
    if knot.len() as u64 != want {
        return fail(
            field("knot"),
            format!("must have n{dir} + {dir}order = {want} knots, got {}", knot.len()),
        );
    }
    finite_all(&field("knot"), knot)?;
    for (i, w) in knot.windows(2).enumerate() {
        if w[1] < w[0] {
            return fail(
                format!("{at}.{dir}knot[{}]", i + 1),
                format!("must not decrease, got {} after {}", w[1], w[0]),
            );
        }
    }
    finite(&field("min"), min)?;
    finite(&field("max"), max)?;
    let (lo, hi) = (knot[order as usize - 1], knot[n as usize]);
    if min < lo {
        return fail(
            field("min"),
            format!(
                "must be >= {dir}knot[{}] ({lo}), the start of the valid range, got {min}",
                order - 1
            ),
        );
    }
    if max > hi {
        return fail(
            field("max"),
            format!("must be <= {dir}knot[{n}] ({hi}), the end of the valid range, got {max}"),
        );
    }
    above(&field("max"), max, &format!("{dir}min"), min)
}

/// Each step of a transform list at `at`, step `i` at `at[i]`.
pub(super) fn transforms(at: &str, list: &[Transform]) -> Check {
    for (i, t) in list.iter().enumerate() {
        transform(&format!("{at}[{i}]"), t)?;
    }
    Ok(())
}

fn transform(at: &str, t: &Transform) -> Check {
    match t {
        Transform::Translate(v) => finite_all(at, v),
        Transform::Rotate { angle, axis } => {
            finite(&format!("{at}.angle"), *angle)?;
            nonzero_vector(&format!("{at}.axis"), axis)
        }
        Transform::Scale(v) => {
            finite_all(at, v)?;
            each(at, v, |path, s| {
                if s == 0.0 { fail(path, "a scale factor must be non-zero, got 0") } else { Ok(()) }
            })
        }
        Transform::Matrix(rows) => {
            finite_each(at, rows)?;
            if rows[3] != [0.0, 0.0, 0.0, 1.0] {
                let [a, b, c, d] = rows[3];
                return fail(
                    format!("{at}[3]"),
                    format!(
                        "the last row must be (0, 0, 0, 1): projective transforms are not \
                         supported, got ({a}, {b}, {c}, {d})"
                    ),
                );
            }
            let det = DMat4::from_cols_array_2d(&rows.map(|r| r.map(f64::from))).determinant();
            if det.abs() <= 1e-12 {
                return fail(
                    at,
                    format!(
                        "the matrix must be invertible (|determinant| > 1e-12), got determinant {det}"
                    ),
                );
            }
            Ok(())
        }
    }
}

/// `len` values, one `what` per point of a mesh of `points` points.
fn per_point(path: &str, what: &str, len: usize, points: usize) -> Check {
    if len == points {
        Ok(())
    } else {
        fail(path, format!("must have one {what} per point ({points}), got {len}"))
    }
}
