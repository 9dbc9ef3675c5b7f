//! Deep CSG trees: building, resolving and dropping never recurse once per level.
//!
//! A flat union of 32768 operands folds into a chain of 32767 binary operators; a RIB solid of
//! nested differences makes a chain too. Both must build, resolve a sample and drop on a thread
//! with a small stack, and the iterative build must lay trees out exactly as the recursive
//! `CSGNewTree` did (the same slot ids, nodes and leaves), so resolution is unchanged.

use proptest::prelude::*;
use reyes_csg::resolve_tree_at_sample;
use reyes_csg::{CsgExpr, CsgNode, CsgOp, CsgOrder, CsgTree, MAX_SLOTS, NIL, VisPoint};

/// A tree's nodes, its root and its leaves' `(object, slot id)`.
type Layout = (Vec<CsgNode>, u16, Vec<(u32, u16)>);

/// The recursive `CSGNewTree` walk as it was before the build kept its own stack: the
/// reference layout.
fn recursive_build(expr: &CsgExpr) -> Option<Layout> {
    fn walk(
        e: &CsgExpr,
        nodes: &mut Vec<CsgNode>,
        leaves: &mut Vec<(u32, u16)>,
        next_id: &mut usize,
    ) -> Option<u16> {
        let CsgExpr::Op(op, a, b) = e else { return None };
        let mut node = CsgNode { op: *op, child: [None, None], id: [0, 0] };
        for (k, sub) in [a, b].into_iter().enumerate() {
            if *next_id > MAX_SLOTS {
                return None;
            }
            let id = *next_id as u16;
            *next_id += 1;
            node.id[k] = id;
            match sub.as_ref() {
                CsgExpr::Leaf(obj) => leaves.push((*obj, id)),
                inner => node.child[k] = Some(walk(inner, nodes, leaves, next_id)?),
            }
        }
        nodes.push(node);
        Some((nodes.len() - 1) as u16)
    }
    let (mut nodes, mut leaves, mut next_id) = (Vec::new(), Vec::new(), 1);
    let root = walk(expr, &mut nodes, &mut leaves, &mut next_id)?;
    Some((nodes, root, leaves))
}

fn op_strategy() -> impl Strategy<Value = CsgOp> {
    prop_oneof![Just(CsgOp::Union), Just(CsgOp::Intersection), Just(CsgOp::Difference)]
}

/// Random expressions of up to about 64 leaves, any shape.
fn expr_strategy() -> impl Strategy<Value = CsgExpr> {
    let leaf = (0u32..100).prop_map(CsgExpr::Leaf);
    leaf.prop_recursive(10, 64, 2, |inner| {
        (op_strategy(), inner.clone(), inner)
            .prop_map(|(o, a, b)| CsgExpr::Op(o, Box::new(a), Box::new(b)))
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn the_build_lays_trees_out_as_the_recursive_walk(expr in expr_strategy()) {
        let ours = CsgTree::build(&expr).map(|(t, leaves)| (t.nodes, t.root, leaves));
        prop_assert_eq!(ours, recursive_build(&expr));
    }
}

/// `n` leaves folded left into one operator each, `(((0 op 1) op 2) ... op n-1)`, as the dicer
/// folds an n-ary union; `right` folds to the right instead, as nested RIB differences nest.
fn chain(n: u32, op: CsgOp, right: bool) -> CsgExpr {
    let leaf = |i| Box::new(CsgExpr::Leaf(i));
    if right {
        let mut acc = CsgExpr::Leaf(n - 1);
        for i in (0..n - 1).rev() {
            acc = CsgExpr::Op(op, leaf(i), Box::new(acc));
        }
        acc
    } else {
        let mut acc = CsgExpr::Leaf(0);
        for i in 1..n {
            acc = CsgExpr::Op(op, Box::new(acc), leaf(i));
        }
        acc
    }
}

fn point(z: f32, slot: u16, next: u32) -> VisPoint {
    VisPoint {
        v: [[-0.5, -0.5, z], [0.5, -0.5, z], [0.5, 0.5, z], [-0.5, 0.5, z]],
        minz: z,
        maxz: z,
        color: [1.0; 3],
        trans: [0.0; 3],
        flags: 1 << 1,
        csg_tree: 0,
        csg_node: slot,
        glass_opacity: 0.0,
        next,
    }
}

/// Depths that survive resolving `tree` at a sample where only the first and the last
/// leaf are hit, the first over `a`, the last over `b`.
fn survivors(tree: &CsgTree, leaves: &[(u32, u16)], a: (f32, f32), b: (f32, f32)) -> Vec<f32> {
    let (first, last) = (leaves[0], leaves[leaves.len() - 1]);
    let mut pts = Vec::new();
    let mut head = NIL;
    for (slot, (e, x)) in [(first.1, a), (last.1, b)] {
        for z in [e, x] {
            pts.push(point(z, slot, head));
            head = (pts.len() - 1) as u32;
        }
    }
    let mut lerps = 0;
    resolve_tree_at_sample(
        &mut pts,
        std::slice::from_ref(tree),
        0,
        &mut head,
        CsgOrder::Exact,
        &mut lerps,
    );
    let mut out = Vec::new();
    while head != NIL {
        out.push(pts[head as usize].minz);
        head = pts[head as usize].next;
    }
    out.sort_by(f32::total_cmp);
    out
}

/// Runs `f` on a thread with a 256 KiB stack: a walk that recursed once per level of a
/// 32767-deep chain would need several MiB.
fn on_a_small_stack(f: impl FnOnce() + Send + 'static) {
    let worker = std::thread::Builder::new().stack_size(256 << 10).spawn(f);
    let joined = worker.map(|h| h.join());
    assert!(matches!(joined, Ok(Ok(()))), "the deep tree failed on a small stack");
}

#[test]
fn a_flat_union_of_32768_operands() {
    on_a_small_stack(|| {
        let expr = chain(32768, CsgOp::Union, false);
        let (tree, leaves) = CsgTree::build(&expr).expect("65534 slots fit");
        assert_eq!((tree.nodes.len(), leaves.len()), (32767, 32768));
        assert_eq!(tree.root as usize, tree.nodes.len() - 1);
        // Two overlapping spans along the ray: the union keeps the outer ends.
        assert_eq!(survivors(&tree, &leaves, (2.0, 6.0), (4.0, 8.0)), [2.0, 8.0]);
        drop(expr);
    });
}

#[test]
fn a_chain_of_32767_nested_differences() {
    on_a_small_stack(|| {
        let expr = chain(32768, CsgOp::Difference, true);
        let (tree, leaves) = CsgTree::build(&expr).expect("65534 slots fit");
        assert_eq!(leaves.len(), 32768);
        // 0 - (1 - (2 - ... - 32767)): leaf 1 is not on this ray, so the whole second operand
        // is empty here and leaf 0 keeps both its ends.
        assert_eq!(survivors(&tree, &leaves, (2.0, 6.0), (4.0, 8.0)), [2.0, 6.0]);
        drop(expr);
    });
}

#[test]
fn one_slot_too_many_is_refused() {
    on_a_small_stack(|| {
        // 32769 leaves need 65536 slots.
        assert!(CsgTree::build(&chain(32769, CsgOp::Union, false)).is_none());
    });
}
