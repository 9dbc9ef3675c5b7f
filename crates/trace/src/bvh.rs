//! Bounding volume hierarchy: binned SAH build into a flat node array, and the ray-box test
//! used by the iterative traversal in `lib.rs`.
//!
//! Invariants: nodes are stored depth first, so an interior node's left child is the next
//! node and its right child is at `right`; each leaf owns the slots `first..first + count`
//! of the primitive order returned by the build; every primitive appears in exactly one
//! leaf; a node's box encloses the boxes of everything under it; the tree is at most
//! `MAX_DEPTH` deep, so a traversal stack of `STACK` entries cannot overflow. The build is
//! deterministic (ties go to the lowest axis and bin) and iterative.

use glam::Vec3;

/// Deepest node level; deeper ranges become (large) leaves.
pub(crate) const MAX_DEPTH: usize = 56;
/// Traversal stack size; depth-first traversal holds at most one entry per level plus one.
pub(crate) const STACK: usize = 64;
/// Number of SAH bins per axis.
const BINS: usize = 16;
/// Largest leaf the SAH may choose to keep; larger ranges are always split when possible.
const MAX_LEAF: usize = 8;
/// Cost of visiting a node relative to one primitive test.
const TRAVERSAL_COST: f32 = 1.0;

/// An axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aabb {
    /// Least corner.
    pub min: Vec3,
    /// Greatest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The empty box (the identity of `union`).
    pub const EMPTY: Aabb = Aabb { min: Vec3::INFINITY, max: Vec3::NEG_INFINITY };

    /// The smallest box holding both.
    #[inline]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// Half the surface area (the SAH only compares areas).
    #[inline]
    fn half_area(self) -> f32 {
        let e = (self.max - self.min).max(Vec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    #[inline]
    fn centre(self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Is every coordinate finite and `min <= max`?
    pub fn is_valid(self) -> bool {
        self.min.is_finite() && self.max.is_finite() && self.min.cmple(self.max).all()
    }

    /// Entry and exit parameters of the ray `origin + t dir` (`inv_dir = 1 / dir`, every
    /// component finite), the interval widened by a few ulps so that a box is never missed
    /// through rounding; entry > exit means a miss. Branch-free.
    #[inline]
    pub fn slab(&self, origin: Vec3, inv_dir: Vec3) -> (f32, f32) {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let near = t0.min(t1).max_element();
        let far = t0.max(t1).min_element();
        widen(near, far)
    }

    /// As [`Aabb::slab`] for any `inv_dir`: an axis with infinite `inv_dir` (direction
    /// parallel to it) constrains nothing when the origin lies within that slab and misses
    /// otherwise, so the `0 * inf` NaN of the textbook test never arises.
    #[inline]
    pub fn slab_parallel(&self, origin: Vec3, inv_dir: Vec3) -> (f32, f32) {
        let mut t_near = f32::NEG_INFINITY;
        let mut t_far = f32::INFINITY;
        for k in 0..3 {
            let inv = inv_dir[k];
            if inv.is_infinite() {
                if origin[k] < self.min[k] || origin[k] > self.max[k] {
                    return (f32::INFINITY, f32::NEG_INFINITY);
                }
                continue;
            }
            let t0 = (self.min[k] - origin[k]) * inv;
            let t1 = (self.max[k] - origin[k]) * inv;
            let (lo, hi) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
            t_near = t_near.max(lo);
            t_far = t_far.min(hi);
        }
        widen(t_near, t_far)
    }
}

/// Widens `[near, far]` by a few ulps of each end.
#[inline]
fn widen(near: f32, far: f32) -> (f32, f32) {
    let slack = 4.0 * f32::EPSILON;
    (near - near.abs() * slack, far + far.abs() * slack)
}

/// What a node is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum NodeKind {
    /// Primitives at slots `first..first + count` of the order.
    Leaf {
        /// First slot.
        first: u32,
        /// Number of slots.
        count: u32,
    },
    /// Left child is the next node.
    Interior {
        /// Index of the right child.
        right: u32,
    },
}

/// A flattened node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Node {
    /// Box of everything below.
    pub bounds: Aabb,
    /// Leaf or interior.
    pub kind: NodeKind,
}

/// A built hierarchy.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Bvh {
    /// Nodes, root first (empty when there are no primitives).
    pub nodes: Vec<Node>,
    /// Slot -> primitive index into the input.
    pub order: Vec<u32>,
}

#[derive(Clone, Copy)]
struct Bin {
    bounds: Aabb,
    count: usize,
}

/// A pending range of slots and the interior node waiting for it as its right child.
struct Task {
    start: usize,
    end: usize,
    depth: usize,
    parent: Option<usize>,
}

/// Builds the hierarchy over `bounds` (all valid boxes).
pub(crate) fn build(bounds: &[Aabb]) -> Bvh {
    let mut order: Vec<u32> = (0..bounds.len() as u32).collect();
    let mut nodes: Vec<Node> = Vec::with_capacity(bounds.len().max(1) * 2);
    if bounds.is_empty() {
        return Bvh { nodes, order };
    }
    let centre: Vec<Vec3> = bounds.iter().map(|b| b.centre()).collect();
    let mut tasks = vec![Task { start: 0, end: bounds.len(), depth: 0, parent: None }];
    while let Some(task) = tasks.pop() {
        let index = nodes.len();
        if let Some(parent) = task.parent
            && let Some(node) = nodes.get_mut(parent)
            && let NodeKind::Interior { right, .. } = &mut node.kind
        {
            *right = index as u32;
        }
        let slots = &mut order[task.start..task.end];
        let node_bounds = slots.iter().fold(Aabb::EMPTY, |b, &i| b.union(bounds[i as usize]));
        let leaf = Node {
            bounds: node_bounds,
            kind: NodeKind::Leaf { first: task.start as u32, count: slots.len() as u32 },
        };
        if slots.len() <= 1 || task.depth >= MAX_DEPTH {
            nodes.push(leaf);
            continue;
        }
        let Some(mid) = split(slots, bounds, &centre, node_bounds) else {
            nodes.push(leaf);
            continue;
        };
        nodes.push(Node { bounds: node_bounds, kind: NodeKind::Interior { right: 0 } });
        let mid = task.start + mid;
        // Left is built next (it must follow its parent); the right waits on the stack.
        tasks.push(Task { start: mid, end: task.end, depth: task.depth + 1, parent: Some(index) });
        tasks.push(Task { start: task.start, end: mid, depth: task.depth + 1, parent: None });
    }
    Bvh { nodes, order }
}

/// Chooses a split of `slots` and partitions them: the left count, or `None` to make a
/// leaf. Binned SAH over the centroid bounds on all three axes; a range too large for a
/// leaf whose centroids all coincide is halved by count.
fn split(slots: &mut [u32], bounds: &[Aabb], centre: &[Vec3], node: Aabb) -> Option<usize> {
    let n = slots.len();
    let cb = slots.iter().fold(Aabb::EMPTY, |b, &i| {
        let c = centre[i as usize];
        b.union(Aabb { min: c, max: c })
    });
    let extent = cb.max - cb.min;
    let leaf_cost = n as f32;
    let parent_area = node.half_area();
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, bins on the left)
    for axis in 0..3 {
        if extent[axis].is_nan() || extent[axis] <= 0.0 {
            continue;
        }
        let scale = BINS as f32 / extent[axis];
        let bin_of = |i: u32| {
            let k = ((centre[i as usize][axis] - cb.min[axis]) * scale) as usize;
            k.min(BINS - 1)
        };
        let mut bins = [Bin { bounds: Aabb::EMPTY, count: 0 }; BINS];
        for &i in slots.iter() {
            let bin = &mut bins[bin_of(i)];
            bin.bounds = bin.bounds.union(bounds[i as usize]);
            bin.count += 1;
        }
        // Suffix areas and counts from the right.
        let mut right_area = [0.0_f32; BINS];
        let mut right_count = [0usize; BINS];
        let mut acc = Aabb::EMPTY;
        let mut cnt = 0;
        for k in (1..BINS).rev() {
            acc = acc.union(bins[k].bounds);
            cnt += bins[k].count;
            right_area[k] = acc.half_area();
            right_count[k] = cnt;
        }
        let mut acc = Aabb::EMPTY;
        let mut cnt = 0;
        for k in 0..BINS - 1 {
            acc = acc.union(bins[k].bounds);
            cnt += bins[k].count;
            let rc = right_count[k + 1];
            if cnt == 0 || rc == 0 {
                continue;
            }
            let cost = TRAVERSAL_COST
                + (acc.half_area() * cnt as f32 + right_area[k + 1] * rc as f32)
                    / parent_area.max(f32::MIN_POSITIVE);
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, k + 1));
            }
        }
    }
    match best {
        Some((cost, axis, left_bins)) if cost < leaf_cost || n > MAX_LEAF => {
            let scale = BINS as f32 / extent[axis];
            let goes_left = |i: u32| {
                let k = ((centre[i as usize][axis] - cb.min[axis]) * scale) as usize;
                k.min(BINS - 1) < left_bins
            };
            let mid = partition(slots, goes_left);
            (mid > 0 && mid < n).then_some(mid)
        }
        Some(_) => None,
        None if n > MAX_LEAF => Some(n / 2),
        None => None,
    }
}

/// Moves the slots for which `left` holds to the front, keeping each side's relative order;
/// returns how many there are.
fn partition(slots: &mut [u32], left: impl Fn(u32) -> bool) -> usize {
    let (l, r): (Vec<u32>, Vec<u32>) = slots.iter().partition(|&&i| left(i));
    let mid = l.len();
    for (slot, i) in slots.iter_mut().zip(l.into_iter().chain(r)) {
        *slot = i;
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(x: f32, y: f32, z: f32) -> Aabb {
        let c = Vec3::new(x, y, z);
        Aabb { min: c - 0.1, max: c + 0.1 }
    }

    #[test]
    fn every_primitive_is_in_exactly_one_leaf_and_boxes_nest() {
        let mut boxes = Vec::new();
        for i in 0..500 {
            let f = i as f32;
            boxes.push(cube((f * 0.37).sin() * 10.0, (f * 0.11).cos() * 5.0, f * 0.01));
        }
        // Many coincident boxes force the count split.
        boxes.extend(std::iter::repeat_n(cube(1.0, 1.0, 1.0), 40));
        let bvh = build(&boxes);
        let mut seen = vec![0; boxes.len()];
        for (index, node) in bvh.nodes.iter().enumerate() {
            match node.kind {
                NodeKind::Leaf { first, count } => {
                    for slot in first..first + count {
                        let prim = bvh.order[slot as usize] as usize;
                        seen[prim] += 1;
                        assert_eq!(node.bounds.union(boxes[prim]), node.bounds);
                    }
                }
                NodeKind::Interior { right } => {
                    for child in [index + 1, right as usize] {
                        let cb = bvh.nodes[child].bounds;
                        assert_eq!(node.bounds.union(cb), node.bounds);
                    }
                }
            }
        }
        assert!(seen.iter().all(|&c| c == 1));
        assert!(bvh.nodes.len() < 2 * boxes.len());
    }

    #[test]
    fn slab_handles_axis_parallel_rays() {
        let b = Aabb { min: Vec3::ZERO, max: Vec3::ONE };
        let inv = Vec3::new(1.0, 0.0, 0.0).recip();
        let (n, f) = b.slab_parallel(Vec3::new(-1.0, 0.5, 0.5), inv);
        assert!(n <= 1.0 && f >= 2.0 && n <= f);
        let (n, f) = b.slab_parallel(Vec3::new(-1.0, 1.5, 0.5), inv);
        assert!(n > f, "parallel and outside misses");
        // On the slab plane: 0 * inf is NaN and must not reject.
        let (n, f) = b.slab_parallel(Vec3::new(-1.0, 0.0, 0.5), inv);
        assert!(n <= f);
        let (n2, f2) = b.slab_parallel(Vec3::new(-1.0, 0.0, 1.0), -inv);
        assert!(n2 > f2 || f2 < 0.0, "going away");
        // The fast test agrees where the direction has no zero component.
        let inv = Vec3::new(1.0, 0.5, -0.25).recip();
        let o = Vec3::new(-1.0, 0.2, 1.5);
        assert_eq!(b.slab(o, inv), b.slab_parallel(o, inv));
    }
}
