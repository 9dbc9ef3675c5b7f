//! The data of hair, particles and implicit surfaces (issue #34): the curve type of
//! [`super::Shape::Curves`] and the primitive variables of every storage class that curves,
//! points and blobbies carry.
//!
//! Invariant: a [`Primvar`] names its storage class, and its values are counted as RenderMan
//! counts that class for the primitive it belongs to (validation checks the count, see
//! `crate::curves` for the curves' rules).

use serde::{Deserialize, Serialize};

/// The kind of a [`super::Shape::Curves`]: RenderMan's `"linear"` or `"cubic"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum CurveType {
    /// Polylines through the control points.
    Linear,
    /// Cubic segments in the curve's basis, one per `step` control points.
    Cubic,
}

/// A primitive variable of one RenderMan storage class. The count each class holds depends
/// on the primitive: for curves, `Uniform` is one value per curve, `Varying` one per segment
/// end (per curve `segments + 1`, or `segments` when periodic), `Vertex` one per control
/// point (interpolated by the curve's basis on cubic curves); for points, `Uniform` is one
/// value for all, `Varying` and `Vertex` one per point; for a blobby, `Varying` and `Vertex`
/// one per primitive field (opcodes 1000 and above).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Primvar<T> {
    /// One value for the whole primitive.
    Constant(T),
    /// One value per curve (per primitive for points and blobbies).
    Uniform(Vec<T>),
    /// Linearly interpolated values (see the type's documentation for the count).
    Varying(Vec<T>),
    /// One value per control point.
    Vertex(Vec<T>),
}

impl<T> Primvar<T> {
    /// The storage class as RenderMan spells it, for messages.
    pub fn class(&self) -> &'static str {
        match self {
            Primvar::Constant(_) => "constant",
            Primvar::Uniform(_) => "uniform",
            Primvar::Varying(_) => "varying",
            Primvar::Vertex(_) => "vertex",
        }
    }

    /// The values, in order (one for a constant).
    pub fn values(&self) -> &[T] {
        match self {
            Primvar::Constant(v) => std::slice::from_ref(v),
            Primvar::Uniform(v) | Primvar::Varying(v) | Primvar::Vertex(v) => v,
        }
    }

    /// The values, mutable (the RIB reader scales widths).
    pub fn values_mut(&mut self) -> &mut [T] {
        match self {
            Primvar::Constant(v) => std::slice::from_mut(v),
            Primvar::Uniform(v) | Primvar::Varying(v) | Primvar::Vertex(v) => v,
        }
    }
}

impl<T: Copy> Primvar<T> {
    /// The value for element `i` of a primitive whose every element has one value per class
    /// (points, blobby leaves): the constant, the single uniform value, or value `i`.
    pub fn at(&self, i: usize) -> Option<T> {
        match self {
            Primvar::Constant(v) => Some(*v),
            Primvar::Uniform(v) => v.first().copied(),
            Primvar::Varying(v) | Primvar::Vertex(v) => v.get(i).copied(),
        }
    }
}

/// RenderMan's default width of curves and points: 1 in object space.
pub(crate) fn default_width() -> Primvar<f32> {
    Primvar::Constant(1.0)
}
