//! Constructive solid geometry: a [`Solid`] and its [`Csg`] expression over named objects.
//!
//! Invariant: leaves name objects of the scene's `objects`; validation makes them closed and
//! each used by one leaf only.

use serde::{Deserialize, Serialize};

/// One CSG solid (Appendix A's CSG tree).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solid {
    /// Name, for messages.
    #[serde(default)]
    pub name: String,
    /// The expression.
    pub tree: Csg,
}

/// A CSG expression. Operands must be closed: full spheres and tori, cylinders, cones and
/// paraboloids (closed by their end caps when used here), closed meshes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Csg {
    /// A closed object, by name.
    Object(String),
    /// Everything inside any operand (two or more).
    Union(Vec<Csg>),
    /// Everything inside every operand (two or more).
    Intersection(Vec<Csg>),
    /// Inside the first operand and outside the second.
    Difference(Box<Csg>, Box<Csg>),
}
