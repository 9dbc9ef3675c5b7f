//! CSG trees and their per-sample resolution: Appendix A `CSGNewTree`, `csg_resolve_tree`,
//! `csg_resolve_surface`, `extract_csgtree`, `extract_csgnode`, `sortlist`, `mergelists`.
//!
//! A tree is binary, as Appendix A's `struct CSGnode { child[2], id[2], op }`. Every child
//! slot has an id, unique and non-zero within its tree; the root's own id is 0. A leaf
//! object's micropolygons carry `csg_tree` = the tree's index and `csg_node` = the id of the
//! slot the object occupies. Resolution relabels the points that lie on the boundary of each
//! combined solid with the id of the slot above, so after the root only points labelled 0
//! remain visible; the others keep a child id that is never extracted again.

use crate::bilinear_weights;
use crate::visible::{LERP_DONE, NIL, VisPoint, sortfront};

/// Appendix A's CSG operators (`CSGDifferenceOp` 1, `CSGIntersectionOp` 2, `CSGUnionOp` 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CsgOp {
    /// First operand minus second.
    Difference,
    /// Both.
    Intersection,
    /// Either.
    Union,
}

/// A CSG expression over leaf objects, as written in a scene.
///
/// An n-ary union folded into binary nodes is as deep as it has operands, so building a tree
/// from an expression ([`CsgTree::build`]) and dropping one never recurse; `Clone`, `Debug`
/// and `PartialEq` do, and are meant for the small expressions of tests.
#[derive(Debug, Clone, PartialEq)]
pub enum CsgExpr {
    /// A closed object, by index.
    Leaf(u32),
    /// An operator on two sub-expressions.
    Op(CsgOp, Box<CsgExpr>, Box<CsgExpr>),
}

impl Drop for CsgExpr {
    /// Drops the sub-expressions from an explicit stack: a chain of 32767 operators (a flat
    /// union of 32768 operands) would otherwise recurse once per operator.
    fn drop(&mut self) {
        fn take(e: &mut CsgExpr, into: &mut Vec<CsgExpr>) {
            if let CsgExpr::Op(..) = e {
                into.push(std::mem::replace(e, CsgExpr::Leaf(0)));
            }
        }
        let CsgExpr::Op(_, a, b) = self else { return };
        if matches!((a.as_ref(), b.as_ref()), (CsgExpr::Leaf(_), CsgExpr::Leaf(_))) {
            return;
        }
        let mut stack = Vec::new();
        take(a, &mut stack);
        take(b, &mut stack);
        while let Some(mut e) = stack.pop() {
            if let CsgExpr::Op(_, a, b) = &mut e {
                take(a, &mut stack);
                take(b, &mut stack);
            }
            // `e` drops here with leaves for operands: no recursion.
        }
    }
}

/// One node: port of `struct CSGnode`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CsgNode {
    /// Operator.
    pub op: CsgOp,
    /// Child nodes (index into the tree's nodes), `None` for a leaf slot.
    pub child: [Option<u16>; 2],
    /// Ids of the two child slots.
    pub id: [u16; 2],
}

/// A CSG tree (port of the `Tree[]` entry registered by `CSGNewTree`).
///
/// Invariant: `nodes` are in post-order, as [`CsgTree::build`] lays them out: every node after
/// the nodes of its subtrees, the first operand's before the second's, so a subtree's nodes are
/// contiguous and end at its root, and `root` is the last node. [`csg_resolve_tree`] walks
/// them in that order instead of recursing.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CsgTree {
    /// Nodes; `nodes[root]` is the root.
    pub nodes: Vec<CsgNode>,
    /// Root node index.
    pub root: u16,
    /// Per node, the id of the slot it fills in its parent's node (0 for the root).
    slots: Vec<u16>,
}

/// Largest number of slots in one tree (ids are `u16`, 0 is the root).
pub const MAX_SLOTS: usize = u16::MAX as usize;

impl CsgTree {
    /// Build a tree from an expression whose root is an operator. Returns the tree and, for
    /// every leaf, `(object index, slot id)`, in expression order; `None` if the expression is
    /// a bare leaf or has more slots than [`MAX_SLOTS`].
    ///
    /// Slot ids are given in pre-order (a node's first slot, the first operand's subtree, its
    /// second slot, the second operand's subtree) and nodes are laid out in post-order, as the
    /// recursive `CSGNewTree` did; the walk keeps its own stack, so no depth exhausts the
    /// thread's.
    pub fn build(expr: &CsgExpr) -> Option<(CsgTree, Vec<(u32, u16)>)> {
        /// An operator being built: its node, the id of its own slot, the next operand.
        struct Open<'a> {
            node: CsgNode,
            slot: u16,
            next: usize,
            operands: [&'a CsgExpr; 2],
        }
        fn open<'a>(op: CsgOp, a: &'a CsgExpr, b: &'a CsgExpr, slot: u16) -> Open<'a> {
            Open {
                node: CsgNode { op, child: [None, None], id: [0, 0] },
                slot,
                next: 0,
                operands: [a, b],
            }
        }
        let CsgExpr::Op(op, a, b) = expr else { return None };
        let mut nodes = Vec::new();
        let mut slots = Vec::new();
        let mut leaves = Vec::new();
        let mut next_id = 1usize;
        let mut root = 0u16;
        let mut stack = vec![open(*op, a, b, 0)];
        while let Some(top) = stack.last_mut() {
            let k = top.next;
            let Some(&operand) = top.operands.get(k) else {
                // Both operands done: the node follows its subtrees.
                let done = stack.pop()?;
                nodes.push(done.node);
                slots.push(done.slot);
                let index = u16::try_from(nodes.len() - 1).ok()?;
                match stack.last_mut() {
                    Some(parent) => parent.node.child[parent.next - 1] = Some(index),
                    None => root = index,
                }
                continue;
            };
            top.next += 1;
            if next_id > MAX_SLOTS {
                return None;
            }
            let id = next_id as u16;
            next_id += 1;
            top.node.id[k] = id;
            match operand {
                CsgExpr::Leaf(obj) => leaves.push((*obj, id)),
                CsgExpr::Op(op, a, b) => stack.push(open(*op, a, b, id)),
            }
        }
        Some((CsgTree { nodes, root, slots }, leaves))
    }
}

/// Port of `extract_csgtree`: unlink every point of tree `ntree` that is a CSG leaf point
/// (`csg_node != 0`) from `*list`; return them as a list (in reverse order, as the original).
/// Appendix A also pulls non-CSG points whose `csgtree` happens to match (3.15); harmless
/// there, and avoided here by testing `csg_node`.
pub fn extract_csgtree(points: &mut [VisPoint], ntree: u16, list: &mut u32) -> u32 {
    unlink_where(points, list, |p| p.csg_tree == ntree && p.csg_node != 0)
}

/// Port of `extract_csgnode`: unlink every point labelled `id` from `*list` and return them.
pub fn extract_csgnode(points: &mut [VisPoint], id: u16, list: &mut u32) -> u32 {
    unlink_where(points, list, |p| p.csg_node == id)
}

/// The loop both extractions share: unlink every point of `*list` that is `wanted` and
/// return them as a list, both lists in reverse order (as the original).
fn unlink_where(
    points: &mut [VisPoint],
    list: &mut u32,
    wanted: impl Fn(&VisPoint) -> bool,
) -> u32 {
    let (mut taken, mut kept) = (NIL, NIL);
    let mut i = *list;
    while i != NIL {
        let next = points[i as usize].next;
        let p = &mut points[i as usize];
        if wanted(p) {
            p.next = taken;
            taken = i;
        } else {
            p.next = kept;
            kept = i;
        }
        i = next;
    }
    *list = kept;
    taken
}

/// Port of `mergelists`: the concatenation `a ++ b` (not a sorted merge).
pub fn mergelists(points: &mut [VisPoint], a: u32, b: u32) -> u32 {
    if a == NIL {
        return b;
    }
    let mut p = a;
    while points[p as usize].next != NIL {
        p = points[p as usize].next;
    }
    points[p as usize].next = b;
    a
}

/// Port of `sortlist`: selection sort front to back by repeated `sortfront` (iterative here;
/// the original recursed once per point).
pub fn sortlist(points: &mut [VisPoint], head: &mut u32, lerps: &mut u64) {
    if *head == NIL {
        return;
    }
    sortfront(points, head, lerps);
    let mut prev = *head;
    loop {
        let mut rest = points[prev as usize].next;
        if rest == NIL {
            return;
        }
        sortfront(points, &mut rest, lerps);
        points[prev as usize].next = rest;
        prev = rest;
    }
}

/// Port of `csg_resolve_surface`: walk two front-to-back lists together; each point toggles
/// the inside/outside state of its own solid. A point of A lies on the combined boundary iff
/// `b` (the state gating A) is set; a point of B iff `a` is. Initial states: union a = b = 1
/// (outside both), intersection a = b = 0, difference A - B: a = 0, b = 1. Survivors are
/// relabelled `id`.
pub fn csg_resolve_surface(points: &mut [VisPoint], mut la: u32, mut lb: u32, id: u16, op: CsgOp) {
    let (mut a, mut b) = match op {
        CsgOp::Union => (true, true),
        CsgOp::Difference => (false, true),
        CsgOp::Intersection => (false, false),
    };
    while la != NIL && lb != NIL {
        if points[la as usize].minz < points[lb as usize].minz {
            if b {
                points[la as usize].csg_node = id;
            }
            la = points[la as usize].next;
            a = !a;
        } else {
            if a {
                points[lb as usize].csg_node = id;
            }
            lb = points[lb as usize].next;
            b = !b;
        }
    }
    if b {
        while la != NIL {
            points[la as usize].csg_node = id;
            la = points[la as usize].next;
        }
    }
    if a {
        while lb != NIL {
            points[lb as usize].csg_node = id;
            lb = points[lb as usize].next;
        }
    }
}

/// Port of `csg_resolve_tree`: post-order evaluation of `node` (whose own slot id is `id`)
/// on the tree's points in `*list`.
///
/// The original recursed into each child before resolving the node; the nodes of `node`'s
/// subtree are laid out in exactly that order (see [`CsgTree`]), so they are resolved here in a
/// loop from the subtree's first node, each with the id of the slot it fills, and no depth
/// exhausts the stack.
pub fn csg_resolve_tree(
    points: &mut [VisPoint],
    tree: &CsgTree,
    node: u16,
    id: u16,
    list: &mut u32,
    lerps: &mut u64,
) {
    // The subtree's first node in post-order: down the first operand that is an operator.
    let mut first = node;
    while let Some(c) = tree.nodes[first as usize].child.iter().flatten().next() {
        first = *c;
    }
    for i in first..=node {
        let own = if i == node { id } else { tree.slots[i as usize] };
        resolve_node(points, &tree.nodes[i as usize], own, list, lerps);
    }
}

/// One node of `csg_resolve_tree`, its operands already resolved: extract the points of its two
/// slots, resolve them against each other and relabel the survivors `id`.
fn resolve_node(points: &mut [VisPoint], n: &CsgNode, id: u16, list: &mut u32, lerps: &mut u64) {
    let mut l0 = extract_csgnode(points, n.id[0], list);
    let mut l1 = extract_csgnode(points, n.id[1], list);
    if l0 != NIL || l1 != NIL {
        sortlist(points, &mut l0, lerps);
        sortlist(points, &mut l1, lerps);
        csg_resolve_surface(points, l0, l1, id, n.op);
        *list = mergelists(points, l0, *list);
        *list = mergelists(points, l1, *list);
    }
}

/// How cross-list depth comparisons are made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CsgOrder {
    /// Every point of the tree is given its exact depth before resolution, so points of the
    /// two operands are compared by true depth: the depth of the micropolygon's bilinear
    /// surface at the sample ([`crate::bilinear_weights`]).
    #[default]
    Exact,
    /// Appendix A: compare by `minz`, which may still be a range minimum when the two points
    /// came from different lists (3.15), and can misorder overlapping surfaces.
    Original,
}

/// Resolve tree `ntree` for one sample: extract its points from `*head`, resolve, put the
/// survivors (relabelled as ordinary points, `csg_node = 0`) back, drop the rest.
pub fn resolve_tree_at_sample(
    points: &mut [VisPoint],
    trees: &[CsgTree],
    ntree: u16,
    head: &mut u32,
    order: CsgOrder,
    lerps: &mut u64,
) {
    let mut list = extract_csgtree(points, ntree, head);
    let Some(tree) = trees.get(ntree as usize) else {
        // Unknown tree: treat its points as ordinary surfaces rather than lose them.
        let mut i = list;
        while i != NIL {
            points[i as usize].csg_node = 0;
            i = points[i as usize].next;
        }
        *head = mergelists(points, list, *head);
        return;
    };
    if order == CsgOrder::Exact {
        // The depth of the micropolygon's bilinear surface at the sample, not Shepard's
        // (`lerpz`, which is not planar-exact): where an operand is seen at a grazing angle a
        // micropolygon a pixel wide spans many pixels in depth, and Shepard's error, a part of
        // that span, decided which operand was in front along the notch of a difference
        // (issue #36). Set even where Shepard's depth was taken to find the front.
        let mut i = list;
        while i != NIL {
            let p = &mut points[i as usize];
            let w = bilinear_weights(&p.v);
            let z = w[0] * p.v[0][2] + w[1] * p.v[1][2] + w[2] * p.v[2][2] + w[3] * p.v[3][2];
            *lerps += 1;
            p.minz = z;
            p.maxz = z;
            p.flags |= LERP_DONE;
            i = p.next;
        }
    }
    csg_resolve_tree(points, tree, tree.root, 0, &mut list, lerps);
    let resolved = extract_csgnode(points, 0, &mut list);
    // `list` now holds the points that are not on the solid's boundary: freed (dropped).
    *head = mergelists(points, resolved, *head);
}
