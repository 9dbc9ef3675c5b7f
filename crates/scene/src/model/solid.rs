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

/// Most operators a CSG expression nests along any path from its root to a leaf (the root
/// counts 1). Validation refuses deeper trees, so the stages that walk a tree recursively
/// (the dicer's set-up, the measurement of solids, dropping and cloning a `Csg`) recurse at
/// most this deep. RON refuses deeper nesting anyway (its limit is 128 levels of brackets in
/// all); the RIB reader refuses `SolidBegin` blocks nested more than half this deep, since each
/// block makes at most two levels.
pub const MAX_CSG_DEPTH: usize = 128;

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
