//! The CSG rules: the number of solids, then each solid's tree in pre-order, each leaf
//! resolved to one closed object not used by any other leaf.
//!
//! Invariant: runs after every object is valid, so an operand's shape can be judged closed;
//! iterative, so no tree depth can exhaust the stack.

use std::collections::HashMap;

use super::primitives::{Check, fail};
use crate::closure::{Closure, closure};
use crate::error::clip;
use crate::model::{Csg, MAX_CSG_DEPTH, Scene};

/// Most solids in a scene: the renderer numbers CSG trees with `u16`.
const MAX_SOLIDS: usize = 65535;
/// Most leaves (objects) in one solid. The renderer's trees are binary and give every node
/// but the root a `u16` slot id in 1..=65535; a solid of `n` leaves has `2n - 2` slots.
const MAX_LEAVES: usize = 32768;

/// Object name -> the first object with it, and the second if any.
type Names<'a> = HashMap<&'a str, (usize, Option<usize>)>;
/// Object index -> the solid and the path of the leaf that uses it.
type Used = HashMap<usize, (usize, String)>;

/// An object name for a message: quoted, escaped and clipped.
fn quoted(name: &str) -> String {
    format!("{:?}", clip(name, 64))
}

/// The CSG rules: at most [`MAX_SOLIDS`] solids; each solid's tree by [`solid`]; every
/// object used by at most one leaf of all the trees.
pub(super) fn solids(scene: &Scene) -> Check {
    if scene.solids.is_empty() {
        return Ok(());
    }
    if scene.solids.len() > MAX_SOLIDS {
        return fail(
            "solids",
            format!("at most {MAX_SOLIDS} solids are allowed, got {}", scene.solids.len()),
        );
    }
    // Name -> the first two objects carrying it.
    let mut names: Names = HashMap::new();
    for (i, object) in scene.objects.iter().enumerate() {
        names
            .entry(object.name.as_str())
            .and_modify(|e| {
                e.1.get_or_insert(i);
            })
            .or_insert((i, None));
    }
    // Object index -> the leaf that uses it.
    let mut used: Used = HashMap::new();
    for (s, solid) in scene.solids.iter().enumerate() {
        self::solid(s, &solid.tree, scene, &names, &mut used)?;
    }
    Ok(())
}

/// Solid `s`: an operator at the root, at most [`MAX_LEAVES`] leaves, then every node in
/// pre-order, each operator at most [`MAX_CSG_DEPTH`] deep. Iterative, so no tree depth can
/// exhaust the stack.
fn solid(s: usize, tree: &Csg, scene: &Scene, names: &Names, used: &mut Used) -> Check {
    let at = format!("solids[{s}].tree");
    if matches!(tree, Csg::Object(_)) {
        return fail(at, "a solid needs an operator: Union, Intersection or Difference");
    }
    let mut leaves = 0usize;
    let mut stack = vec![tree];
    while let Some(node) = stack.pop() {
        match node {
            Csg::Object(_) => leaves += 1,
            Csg::Union(items) | Csg::Intersection(items) => stack.extend(items),
            Csg::Difference(a, b) => stack.extend([a.as_ref(), b.as_ref()]),
        }
    }
    if leaves > MAX_LEAVES {
        return fail(at, format!("a solid may use at most {MAX_LEAVES} objects, got {leaves}"));
    }
    // Each entry: a node, its path and how many operators it lies under.
    let mut stack: Vec<(&Csg, String, usize)> = vec![(tree, at, 0)];
    while let Some((node, path, above)) = stack.pop() {
        if !matches!(node, Csg::Object(_)) && above >= MAX_CSG_DEPTH {
            return fail(
                path,
                format!(
                    "CSG operators may nest at most {MAX_CSG_DEPTH} deep, this one is {} deep",
                    above + 1
                ),
            );
        }
        let (op, items) = match node {
            Csg::Object(name) => {
                leaf(&path, s, name, scene, names, used)?;
                continue;
            }
            Csg::Difference(a, b) => {
                stack.push((b, format!("{path}[1]"), above + 1));
                stack.push((a, format!("{path}[0]"), above + 1));
                continue;
            }
            Csg::Union(items) => ("Union", items),
            Csg::Intersection(items) => ("Intersection", items),
        };
        if items.len() < 2 {
            return fail(path, format!("{op} needs at least 2 operands, got {}", items.len()));
        }
        for (k, item) in items.iter().enumerate().rev() {
            stack.push((item, format!("{path}[{k}]"), above + 1));
        }
    }
    Ok(())
}

/// A leaf `Object(name)` at `path` in solid `s`: the name resolves to exactly one object,
/// not used by any leaf before, whose surface is closed.
fn leaf(path: &str, s: usize, name: &str, scene: &Scene, names: &Names, used: &mut Used) -> Check {
    if name.is_empty() {
        return fail(
            path,
            "an operand must name an object: unnamed objects cannot be used in solids",
        );
    }
    let index = match names.get(name) {
        None => return fail(path, format!("no object is named {}", quoted(name))),
        Some((first, Some(second))) => {
            return fail(
                path,
                format!(
                    "object name {0} is ambiguous: objects[{first}] and objects[{second}] are \
                     both named {0}",
                    quoted(name)
                ),
            );
        }
        Some((index, None)) => *index,
    };
    if let Some((other, at)) = used.get(&index) {
        return fail(
            path,
            format!("object {} is already used by solids[{other}] (at {at})", quoted(name)),
        );
    }
    let Some(object) = scene.objects.get(index) else {
        return fail(path, format!("no object is named {}", quoted(name)));
    };
    match closure(&object.shape) {
        Closure::Closed => {}
        Closure::Open(why) => {
            return fail(
                path,
                format!(
                    "object {} is not closed ({why}); CSG operands must be closed solids",
                    quoted(name)
                ),
            );
        }
        Closure::Misoriented(why) => {
            return fail(
                path,
                format!(
                    "object {} is not consistently oriented ({why}); the two faces at every \
                     edge of a closed mesh must run along it in opposite directions",
                    quoted(name)
                ),
            );
        }
    }
    used.insert(index, (s, path.to_string()));
    Ok(())
}
