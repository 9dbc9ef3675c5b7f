//! The rules of an object's surface and placement: each [`Shape`] variant's fields in order,
//! and each [`Transform`] step.
//!
//! Invariant: no check can panic; the matrix determinant is computed in `f64`.

use glam::DMat4;

use super::primitives::{
    Check, above, each, fail, finite, finite_all, finite_each, nonzero_vector, positive, sweep,
};
use crate::model::{Shape, Transform};

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
        Shape::Mesh { points, faces, colors } => {
            finite_each(&field("points"), points)?;
            if faces.is_empty() {
                return fail(field("faces"), "must hold at least one face");
            }
            for (f, face) in faces.iter().enumerate() {
                if !(3..=4).contains(&face.len()) {
                    return fail(
                        format!("{at}.faces[{f}]"),
                        format!("a face must have 3 or 4 indices, got {}", face.len()),
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
            Ok(())
        }
    }
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
