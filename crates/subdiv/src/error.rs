//! The errors of a control mesh: one variant per way a mesh or its tags can be invalid, each
//! naming the face, vertex or tag index.

use std::fmt;

/// Invalid input, naming the face, vertex or tag index.
#[derive(Clone, Debug, PartialEq)]
pub enum SubdivError {
    /// A face with fewer than 3 vertices.
    FaceTooSmall {
        /// Face index.
        face: usize,
        /// Its count.
        count: usize,
    },
    /// `face_counts` does not sum to `faces.len()`.
    FaceCountSum {
        /// The sum of the counts.
        expected: usize,
        /// `faces.len()`.
        got: usize,
    },
    /// A vertex index out of range in a face.
    VertexIndex {
        /// Face index.
        face: usize,
        /// The bad index.
        index: usize,
    },
    /// Facevarying data of the wrong length.
    FacevaryingLength {
        /// `faces.len() * facevarying_width`.
        expected: usize,
        /// What was given.
        got: usize,
    },
    /// Vertex varying data of the wrong length.
    VaryingLength {
        /// `points.len() * width`.
        expected: usize,
        /// What was given.
        got: usize,
    },
    /// A face uses a vertex twice.
    RepeatedVertex {
        /// Face index.
        face: usize,
        /// The vertex.
        vertex: usize,
    },
    /// A non-finite control point.
    NonFinitePoint {
        /// Vertex index.
        vertex: usize,
    },
    /// An edge used twice in the same direction or by more than two faces.
    NonManifoldEdge {
        /// Face where it was found.
        face: usize,
        /// Edge end points.
        a: usize,
        /// Edge end points.
        b: usize,
    },
    /// A tag naming a vertex or face out of range, a bad sharpness, or a crease step that is not an edge.
    BadTag {
        /// Tag index.
        tag: usize,
        /// What is wrong.
        what: String,
    },
}

impl fmt::Display for SubdivError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::FaceTooSmall { face, count } => {
                write!(f, "face {face}: {count} vertices, need at least 3")
            }
            Self::FaceCountSum { expected, got } => {
                write!(f, "face counts sum to {expected} but {got} face indices given")
            }
            Self::VertexIndex { face, index } => {
                write!(f, "face {face}: vertex index {index} out of range")
            }
            Self::RepeatedVertex { face, vertex } => {
                write!(f, "face {face}: vertex {vertex} used twice")
            }
            Self::FacevaryingLength { expected, got } => {
                write!(f, "facevarying: {got} floats, expected {expected}")
            }
            Self::VaryingLength { expected, got } => {
                write!(f, "vertex varying: {got} floats, expected {expected}")
            }
            Self::NonFinitePoint { vertex } => write!(f, "vertex {vertex}: non-finite point"),
            Self::NonManifoldEdge { face, a, b } => {
                write!(f, "face {face}: edge {a}-{b} is non-manifold or inconsistently oriented")
            }
            Self::BadTag { tag, what } => write!(f, "tag {tag}: {what}"),
        }
    }
}

impl std::error::Error for SubdivError {}
