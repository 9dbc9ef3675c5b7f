//! Visible points and lazy depth ordering: `struct visiblepoint`, `lerpz`, `findfront`,
//! `sortfront` of Appendix A.
//!
//! Visible points live in a per-bucket arena (`&mut [VisPoint]`) and are linked by `u32`
//! indices instead of Appendix A's malloc'd free list, so the hider's sample loop allocates
//! nothing once the arena has grown to the bucket's needs.

/// End-of-list marker for `VisPoint::next` and list heads.
pub const NIL: u32 = u32::MAX;

/// Flag bit (Appendix A `flag.lerpdone`, bit 5 of `struct visflags`): `minz == maxz` is exact.
pub const LERP_DONE: u32 = 1 << 5;

/// Port of `struct visiblepoint`: one micropolygon covering one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VisPoint {
    /// The micropolygon's vertices relative to the sample point (x, y in pixels) and their
    /// eye depths, as tested; kept for [`lerpz`].
    pub v: [[f32; 3]; 4],
    /// Smallest depth the point can have (micropolygon z range, or exact once lerped).
    pub minz: f32,
    /// Largest depth the point can have.
    pub maxz: f32,
    /// Premultiplied colour.
    pub color: [f32; 3],
    /// Per-channel transmittance (1 = clear).
    pub trans: [f32; 3],
    /// Micropolygon flag bits, plus [`LERP_DONE`].
    pub flags: u32,
    /// CSG tree id (0: none).
    pub csg_tree: u16,
    /// CSG node id (0: not CSG, or resolved).
    pub csg_node: u16,
    /// Appendix A `glasshackopacity`.
    pub glass_opacity: f32,
    /// Next point of the same sample's list, or [`NIL`].
    pub next: u32,
}

/// Shepard weights with Manhattan distances (the shared core of `lerpz` and `gouraud`).
///
/// With the sample at the origin and `d_k = |x_k| + |y_k|`, the weight of vertex k is
/// `prod_{j != k} d_j`, i.e. proportional to `1/d_k`: inverse-distance weighting of power 1.
/// Returns normalised weights summing to 1. Appendix A divides by the weight sum even when
/// two or more distances are zero (a degenerate quad), giving 0/0 = NaN (appendix-a.md 3.11);
/// here a vertex at distance zero takes all the weight instead.
#[inline]
pub fn shepard_weights(v: &[[f32; 3]; 4]) -> [f32; 4] {
    let d = [
        v[0][0].abs() + v[0][1].abs(),
        v[1][0].abs() + v[1][1].abs(),
        v[2][0].abs() + v[2][1].abs(),
        v[3][0].abs() + v[3][1].abs(),
    ];
    let d01 = d[0] * d[1];
    let d23 = d[2] * d[3];
    let w = [d23 * d[1], d23 * d[0], d01 * d[3], d01 * d[2]];
    let sum = w[0] + w[1] + w[2] + w[3];
    if sum > 0.0 && sum.is_finite() {
        let inv = 1.0 / sum;
        return [w[0] * inv, w[1] * inv, w[2] * inv, w[3] * inv];
    }
    // Two or more vertices on the sample (or an overflow): take the nearest vertex.
    let mut k = 0;
    for j in 1..4 {
        if d[j] < d[k] {
            k = j;
        }
    }
    let mut out = [0.0; 4];
    out[k] = 1.0;
    out
}

/// Port of `lerpz`: depth at the sample point by Shepard interpolation of the vertex depths.
///
/// Exact at the vertices and a convex combination of the vertex depths everywhere, so it never
/// leaves the micropolygon's z range. It is not planar-exact (appendix-a.md 3.11).
#[inline]
pub fn lerpz(v: &[[f32; 3]; 4]) -> f32 {
    let w = shepard_weights(v);
    w[0] * v[0][2] + w[1] * v[1][2] + w[2] * v[2][2] + w[3] * v[3][2]
}

#[inline]
fn make_exact(p: &mut VisPoint, lerps: &mut u64) {
    let z = lerpz(&p.v);
    *lerps += 1;
    p.minz = z;
    p.maxz = z;
    p.flags |= LERP_DONE;
}

/// Port of `findfront`: the frontmost point of the list starting at `head`, computing exact
/// depths (counted in `lerps`) only where z ranges overlap. Returns [`NIL`] for an empty list.
///
/// 1. Take the point with the smallest `minz`.
/// 2. If it is exact, or no other point's `minz` is below its `maxz`, it is the front.
/// 3. Otherwise make it exact; then every point whose `minz` is below the current front's
///    depth is made exact and becomes the front if nearer.
///
/// Points with `minz` at or beyond the front's exact depth can never be nearer, so the result
/// is exact. Ties keep the earlier point in list order, as the original's strict `<` does.
pub fn findfront(points: &mut [VisPoint], head: u32, lerps: &mut u64) -> u32 {
    if head == NIL {
        return NIL;
    }
    let mut front = head;
    let mut i = points[head as usize].next;
    while i != NIL {
        if points[i as usize].minz < points[front as usize].minz {
            front = i;
        }
        i = points[i as usize].next;
    }
    if points[front as usize].flags & LERP_DONE != 0 {
        return front;
    }
    let front_max = points[front as usize].maxz;
    let mut overlap = false;
    let mut i = head;
    while i != NIL {
        if i != front && points[i as usize].minz < front_max {
            overlap = true;
            break;
        }
        i = points[i as usize].next;
    }
    if !overlap {
        return front;
    }
    make_exact(&mut points[front as usize], lerps);
    let mut i = head;
    while i != NIL {
        let front_z = points[front as usize].minz;
        let p = &mut points[i as usize];
        if p.minz < front_z {
            if p.flags & LERP_DONE == 0 {
                make_exact(p, lerps);
            }
            if p.minz < front_z {
                front = i;
            }
        }
        i = points[i as usize].next;
    }
    front
}

/// Port of `sortfront`: unlink the frontmost point of `*head`'s list and make it the head.
/// Returns the (new) head, or [`NIL`] for an empty list.
pub fn sortfront(points: &mut [VisPoint], head: &mut u32, lerps: &mut u64) -> u32 {
    let front = findfront(points, *head, lerps);
    if front == NIL || front == *head {
        return front;
    }
    let mut prev = *head;
    loop {
        let next = points[prev as usize].next;
        if next == front {
            points[prev as usize].next = points[front as usize].next;
            points[front as usize].next = *head;
            *head = front;
            return front;
        }
        // `front` came from this list, so the walk reaches it before NIL.
        debug_assert_ne!(next, NIL);
        prev = next;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(minz: f32, maxz: f32, v: [[f32; 3]; 4]) -> VisPoint {
        VisPoint {
            v,
            minz,
            maxz,
            color: [0.0; 3],
            trans: [0.0; 3],
            flags: 0,
            csg_tree: 0,
            csg_node: 0,
            glass_opacity: 0.0,
            next: NIL,
        }
    }

    fn link(points: &mut [VisPoint]) -> u32 {
        for i in 0..points.len() {
            points[i].next = if i + 1 < points.len() { (i + 1) as u32 } else { NIL };
        }
        if points.is_empty() { NIL } else { 0 }
    }

    /// A unit square around the sample, tilted so that z = base + x.
    fn tilted(base: f32) -> [[f32; 3]; 4] {
        [
            [-0.5, -0.5, base - 0.5],
            [0.5, -0.5, base + 0.5],
            [0.5, 0.5, base + 0.5],
            [-0.5, 0.5, base - 0.5],
        ]
    }

    #[test]
    fn lerpz_exact_at_vertices_and_centre() {
        let v = tilted(3.0);
        for k in 0..4 {
            let mut rel = v;
            for p in rel.iter_mut() {
                p[0] -= v[k][0];
                p[1] -= v[k][1];
            }
            assert_eq!(lerpz(&rel), v[k][2]);
        }
        // Centre of a parallelogram: all distances equal, so the mean, which is the plane.
        assert!((lerpz(&v) - 3.0).abs() < 1e-6);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(5000))]
        /// On a planar quad (depth z = z0 + g.(x, y)) Shepard interpolation is a convex
        /// combination of the vertex depths, so its error against the plane at the sample is at
        /// most max_k |g.(v_k - p)| <= |g| * max_k |v_k - p| (Cauchy-Schwarz): the depth change
        /// across the micropolygon. For a one-pixel micropolygon that is the depth gradient per
        /// pixel, far below the gaps between distinct surfaces.
        #[test]
        fn lerpz_stays_near_the_plane(
            c in proptest::array::uniform8(-1.0f32..1.0),
            g in proptest::array::uniform2(-0.5f32..0.5),
            z0 in 1.0f32..100.0,
            p in proptest::array::uniform2(0.05f32..0.95),
        ) {
            // A convex quad: the unit square's corners jittered by up to 0.2, sample inside.
            let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
            let v: [[f32; 3]; 4] = std::array::from_fn(|k| {
                let x = corners[k].0 + 0.2 * c[2 * k] - p[0];
                let y = corners[k].1 + 0.2 * c[2 * k + 1] - p[1];
                [x, y, z0 + g[0] * x + g[1] * y]
            });
            let plane = z0; // the plane's depth at the sample (the origin)
            let reach = v.iter().map(|q| q[0].hypot(q[1])).fold(0.0f32, f32::max);
            let bound = g[0].hypot(g[1]) * reach;
            let err = (lerpz(&v) - plane).abs();
            // f32 rounding of depths near z0: a few ulps of z0.
            proptest::prop_assert!(err <= bound + 4.0 * f32::EPSILON * z0, "{err} > {bound}");
            // The closed form of appendix-a.md 3.11, inverse-distance weighting of power 1 with
            // Manhattan distances, evaluated independently in f64.
            let (mut num, mut den) = (0.0f64, 0.0f64);
            for q in &v {
                let d = (q[0].abs() + q[1].abs()) as f64;
                num += q[2] as f64 / d;
                den += 1.0 / d;
            }
            let reference = num / den;
            proptest::prop_assert!(((lerpz(&v) as f64) - reference).abs() <= 1e-5 * reference);
            let lo = v.iter().map(|q| q[2]).fold(f32::INFINITY, f32::min);
            let hi = v.iter().map(|q| q[2]).fold(f32::NEG_INFINITY, f32::max);
            let z = lerpz(&v);
            proptest::prop_assert!(z >= lo - 4.0 * f32::EPSILON * z0 && z <= hi + 4.0 * f32::EPSILON * z0);
        }
    }

    #[test]
    fn lerpz_degenerate_quad_is_finite() {
        // Two vertices on the sample: Appendix A gives 0/0 = NaN.
        let v = [[0.0, 0.0, 1.0], [0.0, 0.0, 2.0], [1.0, 0.0, 3.0], [1.0, 1.0, 4.0]];
        assert_eq!(lerpz(&v), 1.0);
    }

    #[test]
    fn findfront_skips_lerp_when_ranges_disjoint() {
        let mut pts = vec![point(5.0, 6.0, tilted(5.5)), point(1.0, 2.0, tilted(1.5))];
        let head = link(&mut pts);
        let mut lerps = 0;
        assert_eq!(findfront(&mut pts, head, &mut lerps), 1);
        assert_eq!(lerps, 0);
    }

    #[test]
    fn findfront_lerps_overlapping_ranges() {
        // Point 0's range starts nearer (1..10), but at the sample it lies at depth 5;
        // point 1 lies at depth 3. Both must be made exact, and point 1 is in front.
        let flat = |z: f32| [[-0.5, -0.5, z], [0.5, -0.5, z], [0.5, 0.5, z], [-0.5, 0.5, z]];
        let mut pts = vec![point(1.0, 10.0, flat(5.0)), point(3.0, 3.2, flat(3.0))];
        let head = link(&mut pts);
        let mut lerps = 0;
        assert_eq!(findfront(&mut pts, head, &mut lerps), 1);
        assert_eq!(lerps, 2);
        assert_eq!((pts[0].minz, pts[0].maxz), (5.0, 5.0));
        assert!(pts[0].flags & LERP_DONE != 0);
    }

    #[test]
    fn sortfront_moves_front_to_head() {
        let mut pts = vec![
            point(5.0, 5.0, tilted(5.0)),
            point(7.0, 7.0, tilted(7.0)),
            point(2.0, 2.0, tilted(2.0)),
            point(9.0, 9.0, tilted(9.0)),
        ];
        let mut head = link(&mut pts);
        let mut lerps = 0;
        let mut order = Vec::new();
        while head != NIL {
            let f = sortfront(&mut pts, &mut head, &mut lerps);
            order.push(f);
            head = pts[f as usize].next;
        }
        assert_eq!(order, vec![2, 0, 1, 3]);
    }
}
