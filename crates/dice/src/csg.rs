//! CSG set-up: the scene's solids as Appendix A CSG trees (`CSGNewTree`), and for every
//! object the `(tree, slot id)` its micropolygons carry.
//!
//! Invariant: the dicer labels micropolygons and the hider resolves them from the same
//! [`CsgSetup`], so slot ids always match their tree. n-ary unions and intersections fold
//! left into binary nodes, as Appendix A's trees are binary.

use glam::Vec3;
use reyes_hider::{CsgExpr, CsgOp, CsgTree};
use reyes_scene::{Csg, Scene};

use crate::motion::{CameraMotion, ObjectMotion, ShutterTime};
use crate::split::{MARGIN_FRACTION, Patch, Splitter};

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

/// Camera-space bounds of every CSG operand over the shutter, for the dicer's depth rule
/// ([`Splitter::with_csg_depth`]): `(tree, object, lo, hi)`.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct OperandBounds(Vec<(u16, u32, Vec3, Vec3)>);

impl OperandBounds {
    /// The bounds of the operands of `csg` in `scene`: the test points of every surface's
    /// whole parameter range (and its control hull) at every breakpoint, grown by a quarter of
    /// their extent, as the split decisions' margin; infinite where a point is not finite.
    pub fn new(
        scene: &Scene,
        csg: &CsgSetup,
        (camera, shutter): (&CameraMotion, &ShutterTime),
        splitter: &Splitter,
    ) -> std::sync::Arc<OperandBounds> {
        let mut out = Vec::new();
        for (i, object) in scene.objects.iter().enumerate() {
            let Some((tree, _)) = csg.leaf.get(i).copied().flatten() else { continue };
            let motion = ObjectMotion::new(object, camera, shutter, true);
            let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
            for surface in 0..motion.surface_count() {
                for pose in &motion.poses(surface) {
                    let grid = splitter.test_grid(pose, &Patch::root());
                    let hull = splitter.hull_points(pose, &Patch::root()).unwrap_or_default();
                    for p in grid.iter().flatten().chain(&hull) {
                        (lo, hi) = (lo.min(*p), hi.max(*p));
                    }
                }
            }
            let grow = Vec3::splat(MARGIN_FRACTION * (hi - lo).max_element());
            let finite = lo.is_finite() && hi.is_finite();
            let (lo, hi) = if finite { (lo - grow, hi + grow) } else { (Vec3::MIN, Vec3::MAX) };
            out.push((tree, i as u32, lo, hi));
        }
        std::sync::Arc::new(OperandBounds(out))
    }

    /// Whether the box `lo..hi` meets the bound of an operand of `tree` other than `object`.
    pub fn meet_another(&self, tree: u16, object: u32, lo: Vec3, hi: Vec3) -> bool {
        self.0
            .iter()
            .any(|&(t, o, a, b)| t == tree && o != object && lo.cmple(b).all() && a.cmple(hi).all())
    }
}
