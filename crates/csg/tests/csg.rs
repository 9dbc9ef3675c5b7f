//! CSG resolution against set arithmetic along one sample's ray.
//!
//! Each primitive solid is convex, so a sample's ray enters it at depth e and leaves at x:
//! two visible points. A point of primitive i at depth d lies on the boundary of the combined
//! solid iff the solid's membership changes across d. The resolver must keep exactly those.

use proptest::prelude::*;
use reyes_csg::{CsgExpr, CsgOp, CsgOrder, CsgTree, NIL, VisPoint, resolve_tree_at_sample};

fn point(z: f32, slot: u16, tree: u16, next: u32) -> VisPoint {
    VisPoint {
        v: [[-0.5, -0.5, z], [0.5, -0.5, z], [0.5, 0.5, z], [-0.5, 0.5, z]],
        minz: z,
        maxz: z,
        color: [1.0; 3],
        trans: [0.0; 3],
        flags: 1 << 1,
        csg_tree: tree,
        csg_node: slot,
        glass_opacity: 0.0,
        next,
    }
}

fn member(e: &CsgExpr, z: f64, iv: &[(f32, f32)]) -> bool {
    match e {
        CsgExpr::Leaf(i) => {
            let (a, b) = iv[*i as usize];
            z > a as f64 && z < b as f64
        }
        CsgExpr::Op(op, a, b) => {
            let (p, q) = (member(a, z, iv), member(b, z, iv));
            match op {
                CsgOp::Union => p || q,
                CsgOp::Intersection => p && q,
                CsgOp::Difference => p && !q,
            }
        }
    }
}

/// Depths of the points that survive resolution of `expr` over the intervals `iv`.
fn survivors(expr: &CsgExpr, iv: &[(f32, f32)]) -> Vec<f32> {
    let (tree, leaves) = CsgTree::build(expr).expect("operator at the root");
    let mut pts = Vec::new();
    let mut head = NIL;
    for &(obj, slot) in &leaves {
        let (e, x) = iv[obj as usize];
        for z in [e, x] {
            pts.push(point(z, slot, 0, head));
            head = (pts.len() - 1) as u32;
        }
    }
    // An ordinary surface far behind, which must be untouched.
    pts.push(point(1000.0, 0, 0, head));
    head = (pts.len() - 1) as u32;
    let mut lerps = 0;
    resolve_tree_at_sample(&mut pts, &[tree], 0, &mut head, CsgOrder::Exact, &mut lerps);
    let mut out = Vec::new();
    let mut i = head;
    while i != NIL {
        assert_eq!(pts[i as usize].csg_node, 0, "only resolved points stay in the list");
        out.push(pts[i as usize].minz);
        i = pts[i as usize].next;
    }
    assert!(out.contains(&1000.0));
    out.retain(|&z| z != 1000.0);
    out.sort_by(f32::total_cmp);
    out
}

fn reference(expr: &CsgExpr, iv: &[(f32, f32)]) -> Vec<f32> {
    let mut out: Vec<f32> = iv
        .iter()
        .flat_map(|&(a, b)| [a, b])
        .filter(|&z| {
            let eps = 1e-3;
            member(expr, z as f64 - eps, iv) != member(expr, z as f64 + eps, iv)
        })
        .collect();
    out.sort_by(f32::total_cmp);
    out
}

fn leaf(i: u32) -> Box<CsgExpr> {
    Box::new(CsgExpr::Leaf(i))
}

fn op(o: CsgOp, a: Box<CsgExpr>, b: Box<CsgExpr>) -> Box<CsgExpr> {
    Box::new(CsgExpr::Op(o, a, b))
}

#[test]
fn the_three_operators_on_two_spheres() {
    use CsgOp::*;
    // A occupies 2..6 along the ray, B 4..8.
    let iv = [(2.0, 6.0), (4.0, 8.0)];
    assert_eq!(survivors(&op(Union, leaf(0), leaf(1)), &iv), [2.0, 8.0]);
    assert_eq!(survivors(&op(Intersection, leaf(0), leaf(1)), &iv), [4.0, 6.0]);
    // A - B: A's front, then B's front seen from inside A (the hole's wall).
    assert_eq!(survivors(&op(Difference, leaf(0), leaf(1)), &iv), [2.0, 4.0]);
    // B passing right through A: nothing of A - B remains on this ray.
    assert_eq!(
        survivors(&op(Difference, leaf(0), leaf(1)), &[(2.0, 6.0), (1.0, 7.0)]),
        Vec::<f32>::new()
    );
}

/// Random expression trees of depth <= 3 over distinct leaves.
fn expr_strategy() -> impl Strategy<Value = (CsgExpr, usize)> {
    let ops = prop_oneof![Just(CsgOp::Union), Just(CsgOp::Intersection), Just(CsgOp::Difference)];
    (prop::collection::vec(ops, 7), 0u8..4).prop_map(|(ops, shape)| {
        let e = match shape {
            0 => CsgExpr::Op(ops[0], leaf(0), leaf(1)),
            1 => CsgExpr::Op(ops[0], op(ops[1], leaf(0), leaf(1)), leaf(2)),
            2 => CsgExpr::Op(ops[0], leaf(0), op(ops[1], leaf(1), op(ops[2], leaf(2), leaf(3)))),
            _ => CsgExpr::Op(
                ops[0],
                op(ops[1], op(ops[3], leaf(0), leaf(1)), leaf(2)),
                op(ops[2], leaf(3), op(ops[4], leaf(4), leaf(5))),
            ),
        };
        let n = [2, 3, 4, 6][shape as usize];
        (e, n)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn resolution_keeps_exactly_the_boundary(
        (expr, n) in expr_strategy(),
        ends in prop::collection::vec((0u32..1000, 1u32..400), 6),
    ) {
        // Distinct depths (ties are a measure-zero case the original also leaves to chance).
        let iv: Vec<(f32, f32)> = ends.iter().enumerate().take(n)
            .map(|(i, &(a, l))| {
                let a = a as f32 + i as f32 * 0.001;
                (a, a + l as f32 + 0.5)
            })
            .collect();
        let mut all: Vec<f32> = iv.iter().flat_map(|&(a, b)| [a, b]).collect();
        all.sort_by(f32::total_cmp);
        prop_assume!(all.windows(2).all(|w| w[1] - w[0] > 0.01));
        prop_assert_eq!(survivors(&expr, &iv), reference(&expr, &iv));
    }

    /// Nested trees resolve the same as an equivalent re-associated (flattened) form.
    #[test]
    fn nesting_matches_the_flattened_tree(
        ends in prop::collection::vec((0u32..1000, 1u32..400), 4),
        which in 0u8..3,
    ) {
        use CsgOp::*;
        let iv: Vec<(f32, f32)> = ends.iter().enumerate()
            .map(|(i, &(a, l))| (a as f32 + i as f32 * 0.001, a as f32 + i as f32 * 0.001 + l as f32 + 0.5))
            .collect();
        let (nested, flat) = match which {
            // ((A u B) u C) u D  vs  A u (B u (C u D))
            0 => (op(Union, op(Union, op(Union, leaf(0), leaf(1)), leaf(2)), leaf(3)),
                  op(Union, leaf(0), op(Union, leaf(1), op(Union, leaf(2), leaf(3))))),
            // ((A n B) n C) n D  vs  (A n B) n (C n D)
            1 => (op(Intersection, op(Intersection, op(Intersection, leaf(0), leaf(1)), leaf(2)), leaf(3)),
                  op(Intersection, op(Intersection, leaf(0), leaf(1)), op(Intersection, leaf(2), leaf(3)))),
            // ((A - B) - C) - D  vs  A - (B u (C u D))
            _ => (op(Difference, op(Difference, op(Difference, leaf(0), leaf(1)), leaf(2)), leaf(3)),
                  op(Difference, leaf(0), op(Union, leaf(1), op(Union, leaf(2), leaf(3))))),
        };
        prop_assert_eq!(survivors(&nested, &iv), survivors(&flat, &iv));
    }
}
