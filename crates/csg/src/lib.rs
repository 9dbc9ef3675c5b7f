//! reyes-csg: resolution of one sample's visible points (Appendix A `CSGResolve` and helpers).
//!
//! Stage: runs inside the hider, once per sample after every micropolygon of the bucket has
//! been tested. Input is a singly linked list of [`VisPoint`]s in an arena (indices, `NIL`
//! terminated, unsorted); output is the sample's front-to-back [`Composite`].
//! Invariants: a point's `[minz, maxz]` always contains its exact depth at the sample; once
//! [`LERP_DONE`] is set, `minz == maxz` is that exact depth.
#![deny(missing_docs)]

mod bilinear;
mod resolve;
mod tree;
mod visible;

pub use bilinear::bilinear_weights;
pub use resolve::{Composite, MatteRule, Resolver, Trace, resolve_sample, resolve_sample_traced};
pub use tree::{
    CsgExpr, CsgNode, CsgOp, CsgOrder, CsgTree, MAX_SLOTS, csg_resolve_surface, csg_resolve_tree,
    extract_csgnode, extract_csgtree, mergelists, resolve_tree_at_sample, sortlist,
};
pub use visible::{LERP_DONE, NIL, VisPoint, findfront, lerpz, shepard_weights, sortfront};
