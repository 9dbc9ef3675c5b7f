//! Object transforms: the object-to-world matrix of an object and its normal matrix.
//!
//! Invariants: transforms apply in list order, first item first, so the matrix is
//! `T_last * ... * T_first` acting on column vectors; points go through the full 4x4
//! (with the homogeneous divide, so a projective `Matrix` works); normals go through the
//! inverse transpose of the upper 3x3, computed from cofactors so that a singular matrix
//! still gives finite (if meaningless) normals instead of NaN.

use crate::Transform;
use glam::{Mat3, Mat4, Vec3};

/// The matrix of one transform step.
pub fn transform_matrix(t: &Transform) -> Mat4 {
    match t {
        Transform::Translate(d) => Mat4::from_translation(Vec3::from(*d)),
        Transform::Rotate { angle, axis } => match Vec3::from(*axis).try_normalize() {
            Some(axis) => Mat4::from_axis_angle(axis, angle.to_radians()),
            None => Mat4::IDENTITY,
        },
        Transform::Scale(s) => Mat4::from_scale(Vec3::from(*s)),
        // Rows as written act on column vectors: glam is column-major, so transpose.
        Transform::Matrix(rows) => Mat4::from_cols_array_2d(rows).transpose(),
    }
}

/// Object-to-world matrix `T_last * ... * T_first` of a transform list.
pub fn object_to_world(transforms: &[Transform]) -> Mat4 {
    transforms.iter().fold(Mat4::IDENTITY, |m, t| transform_matrix(t) * m)
}

/// The matrix that carries object-space normals to world space for `object_to_world`:
/// the inverse transpose of its upper 3x3, up to a positive factor.
pub fn normal_matrix(object_to_world: &Mat4) -> Mat3 {
    let a = Mat3::from_mat4(*object_to_world);
    // Columns of det(A) * A^-T are the cross products of A's column pairs.
    let cofactor = Mat3::from_cols(
        a.y_axis.cross(a.z_axis),
        a.z_axis.cross(a.x_axis),
        a.x_axis.cross(a.y_axis),
    );
    if a.determinant() < 0.0 { -cofactor } else { cofactor }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn list_order_is_first_item_first() {
        // Translate then rotate 90 degrees about z: (1,0,0) -> (3,0,0) -> (0,3,0).
        let m = object_to_world(&[
            Transform::Translate([2.0, 0.0, 0.0]),
            Transform::Rotate { angle: 90.0, axis: [0.0, 0.0, 2.0] },
        ]);
        let p = m.project_point3(Vec3::X);
        assert!((p - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-5, "{p}");
        // The other order: (1,0,0) -> (0,1,0) -> (2,1,0).
        let m = object_to_world(&[
            Transform::Rotate { angle: 90.0, axis: [0.0, 0.0, 1.0] },
            Transform::Translate([2.0, 0.0, 0.0]),
        ]);
        let p = m.project_point3(Vec3::X);
        assert!((p - Vec3::new(2.0, 1.0, 0.0)).length() < 1e-5, "{p}");
    }

    #[test]
    fn matrix_rows_act_on_column_vectors() {
        let m = object_to_world(&[Transform::Matrix([
            [1.0, 0.0, 0.0, 5.0],
            [0.0, 2.0, 0.0, 6.0],
            [0.0, 0.0, 3.0, 7.0],
            [0.0, 0.0, 0.0, 1.0],
        ])]);
        let p = m.project_point3(Vec3::ONE);
        assert_eq!(p, Vec3::new(6.0, 8.0, 10.0));
    }

    #[test]
    fn normals_use_the_inverse_transpose() {
        // Non-uniform scale: the plane x + y = 1 becomes x/2 + y = 1, normal (1/2, 1, 0).
        let m = object_to_world(&[Transform::Scale([2.0, 1.0, 1.0])]);
        let n = (normal_matrix(&m) * Vec3::new(1.0, 1.0, 0.0)).normalize();
        let expect = Vec3::new(0.5, 1.0, 0.0).normalize();
        assert!((n - expect).length() < 1e-6, "{n}");
        // A mirror keeps an outward normal outward: the sphere point (1,0,0) maps to
        // (-1,0,0), whose outward normal is (-1,0,0).
        let m = object_to_world(&[Transform::Scale([-1.0, 1.0, 1.0])]);
        let n = (normal_matrix(&m) * Vec3::X).normalize();
        assert!((n - Vec3::NEG_X).length() < 1e-6, "{n}");
        // A singular matrix gives finite normals.
        let m = object_to_world(&[Transform::Matrix([
            [0.0; 4],
            [0.0; 4],
            [0.0; 4],
            [0.0, 0.0, 0.0, 1.0],
        ])]);
        assert!(normal_matrix(&m).is_finite());
    }
}
