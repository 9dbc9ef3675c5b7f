//! CSG set-up: the scene's solids as Appendix A CSG trees (`CSGNewTree`), and for every
//! object the `(tree, slot id)` its micropolygons carry.
//!
//! Invariant: the dicer labels micropolygons and the hider resolves them from the same
//! [`CsgSetup`], so slot ids always match their tree. n-ary unions and intersections fold
//! left into binary nodes, as Appendix A's trees are binary.

use reyes_hider::{CsgExpr, CsgOp, CsgTree};
use reyes_scene::{Csg, Scene};

/// Trees and leaf labels for a scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CsgSetup {
    /// One tree per solid, in scene order (tree index = `csg_tree`).
    pub trees: Vec<CsgTree>,
    /// Per object: `Some((tree, slot id))` if the object is a CSG operand.
    pub leaf: Vec<Option<(u16, u16)>>,
}

impl CsgSetup {
    /// Build the trees of `scene.solids`. The scene is validated, so names resolve; a solid
    /// that still cannot be built (e.g. a bare object) is skipped, and its objects render as
    /// ordinary surfaces.
    pub fn new(scene: &Scene) -> CsgSetup {
        let mut setup = CsgSetup { trees: Vec::new(), leaf: vec![None; scene.objects.len()] };
        for solid in &scene.solids {
            let Some(expr) = expr(&solid.tree, scene) else { continue };
            let Some((tree, leaves)) = CsgTree::build(&expr) else { continue };
            let Ok(index) = u16::try_from(setup.trees.len()) else { break };
            for (object, slot) in leaves {
                if let Some(l) = setup.leaf.get_mut(object as usize) {
                    *l = Some((index, slot));
                }
            }
            setup.trees.push(tree);
        }
        setup
    }

    /// True if object `i` is a CSG operand (and so must be closed, with end caps).
    pub fn is_operand(&self, i: usize) -> bool {
        self.leaf.get(i).is_some_and(Option::is_some)
    }
}

fn expr(c: &Csg, scene: &Scene) -> Option<CsgExpr> {
    let fold = |op: CsgOp, items: &[Csg]| -> Option<CsgExpr> {
        let mut it = items.iter();
        let mut acc = expr(it.next()?, scene)?;
        for item in it {
            acc = CsgExpr::Op(op, Box::new(acc), Box::new(expr(item, scene)?));
        }
        Some(acc)
    };
    match c {
        Csg::Object(name) => {
            let i = scene.objects.iter().position(|o| &o.name == name)?;
            Some(CsgExpr::Leaf(u32::try_from(i).ok()?))
        }
        Csg::Union(items) => fold(CsgOp::Union, items),
        Csg::Intersection(items) => fold(CsgOp::Intersection, items),
        Csg::Difference(a, b) => Some(CsgExpr::Op(
            CsgOp::Difference,
            Box::new(expr(a, scene)?),
            Box::new(expr(b, scene)?),
        )),
    }
}
