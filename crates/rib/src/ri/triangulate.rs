//! Triangulation of RIB's general polygons: a planar outline with any number of holes, convex
//! or not, into triangles over the same vertices (ear clipping, after bridging each hole into
//! the outline; the method of Eberly's "Triangulation by Ear Clipping").
//!
//! Invariants: no vertex is added or moved; the triangles cover exactly the polygon's area
//! (outline minus holes) when the loops are simple and do not cross; a degenerate or crossing
//! input gives `None`, never a panic or an endless loop; triangles keep the outline's winding.

use reyes_scene::V3;

/// The polygon's loops projected onto its own plane: 2D points, with the index of the 3D
/// vertex each came from.
type Loop2 = Vec<([f64; 2], u32)>;

/// Triangles over `points` covering the face whose first loop is the outline and whose other
/// loops are holes. None if the face is degenerate (no plane) or cannot be triangulated.
pub(crate) fn face(points: &[V3], loops: &[Vec<u32>]) -> Option<Vec<[u32; 3]>> {
    let outline = loops.first()?;
    let normal = newell(points, outline)?;
    // Project onto the plane's two axes that keep the most area.
    let (a, b) = {
        let n = normal.map(f64::abs);
        if n[2] >= n[0] && n[2] >= n[1] {
            (0, 1)
        } else if n[0] >= n[1] {
            (1, 2)
        } else {
            (2, 0)
        }
    };
    let flat = |lp: &[u32]| -> Loop2 {
        lp.iter()
            .map(|&k| {
                let p = points[k as usize];
                ([f64::from(p[a]), f64::from(p[b])], k)
            })
            .collect()
    };
    let mut outer = flat(outline);
    let ccw = signed_area(&outer) > 0.0;
    if !ccw {
        outer.reverse();
    }
    let mut holes: Vec<Loop2> = loops[1..].iter().map(|l| flat(l)).collect();
    for h in &mut holes {
        if signed_area(h) > 0.0 {
            h.reverse();
        }
    }
    // Bridge holes in order of their rightmost vertex, rightmost first.
    holes.sort_by(|p, q| rightmost(q).total_cmp(&rightmost(p)));
    for h in holes {
        outer = bridge(outer, h)?;
    }
    let mut tris = ear_clip(&outer)?;
    if !ccw {
        for t in &mut tris {
            t.swap(1, 2);
        }
    }
    Some(tris)
}

/// Newell's normal of a loop (its vector area times 2); None if it is zero.
fn newell(points: &[V3], lp: &[u32]) -> Option<[f64; 3]> {
    let mut n = [0.0f64; 3];
    for i in 0..lp.len() {
        let p = points.get(lp[i] as usize)?;
        let q = points.get(lp[(i + 1) % lp.len()] as usize)?;
        let (p, q) = (p.map(f64::from), q.map(f64::from));
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (len > 0.0 && len.is_finite()).then_some(n)
}

fn signed_area(lp: &Loop2) -> f64 {
    let n = lp.len();
    (0..n).map(|i| cross(lp[i].0, lp[(i + 1) % n].0)).sum::<f64>() * 0.5
}

fn cross(p: [f64; 2], q: [f64; 2]) -> f64 {
    p[0] * q[1] - p[1] * q[0]
}

/// Twice the signed area of triangle `a b c`.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

fn rightmost(lp: &Loop2) -> f64 {
    lp.iter().map(|v| v.0[0]).fold(f64::NEG_INFINITY, f64::max)
}

/// `outer` (counter-clockwise) with hole `hole` (clockwise) joined in by a two-way bridge from
/// the hole's rightmost vertex to a visible vertex of `outer`.
fn bridge(outer: Loop2, hole: Loop2) -> Option<Loop2> {
    let (hi, m) = hole.iter().enumerate().max_by(|a, b| a.1.0[0].total_cmp(&b.1.0[0]))?;
    let m = m.0;
    // The nearest edge crossing the ray from m toward +x.
    let n = outer.len();
    let mut best: Option<(f64, usize)> = None;
    for i in 0..n {
        let (p, q) = (outer[i].0, outer[(i + 1) % n].0);
        if (p[1] - m[1]) * (q[1] - m[1]) > 0.0 || p[1] == q[1] {
            continue;
        }
        let t = (m[1] - p[1]) / (q[1] - p[1]);
        let x = p[0] + t * (q[0] - p[0]);
        if x >= m[0] && best.is_none_or(|(bx, _)| x < bx) {
            // The edge's endpoint with the larger x is the candidate.
            let k = if p[0] > q[0] { i } else { (i + 1) % n };
            best = Some((x, k));
        }
    }
    let (_, mut k) = best?;
    // Any reflex vertex inside the triangle (m, hit, candidate) is closer in angle: take the
    // one making the smallest angle with the ray.
    let cand = outer[k].0;
    let mut best_angle = f64::INFINITY;
    for (i, v) in outer.iter().enumerate() {
        let p = v.0;
        if i == k || p[0] < m[0] {
            continue;
        }
        let prev = outer[(i + n - 1) % n].0;
        let next = outer[(i + 1) % n].0;
        let reflex = orient(prev, p, next) < 0.0;
        if reflex && inside_triangle(p, m, [cand[0].max(m[0]), m[1]], cand) {
            let angle = (p[1] - m[1]).abs().atan2(p[0] - m[0]);
            if angle < best_angle {
                best_angle = angle;
                k = i;
            }
        }
    }
    let mut out = Vec::with_capacity(outer.len() + hole.len() + 2);
    out.extend_from_slice(&outer[..=k]);
    for j in 0..=hole.len() {
        out.push(hole[(hi + j) % hole.len()]);
    }
    out.push(outer[k]);
    out.extend_from_slice(&outer[k + 1..]);
    Some(out)
}

fn inside_triangle(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let (d1, d2, d3) = (orient(a, b, p), orient(b, c, p), orient(c, a, p));
    let neg = d1 < 0.0 || d2 < 0.0 || d3 < 0.0;
    let pos = d1 > 0.0 || d2 > 0.0 || d3 > 0.0;
    !(neg && pos)
}

/// Ear clipping of a counter-clockwise loop (bridges may repeat vertices).
fn ear_clip(lp: &Loop2) -> Option<Vec<[u32; 3]>> {
    let mut idx: Vec<usize> = (0..lp.len()).collect();
    let mut tris = Vec::with_capacity(lp.len().saturating_sub(2));
    let mut guard = 0usize;
    while idx.len() > 3 {
        let n = idx.len();
        let mut clipped = false;
        for i in 0..n {
            let (ia, ib, ic) = (idx[(i + n - 1) % n], idx[i], idx[(i + 1) % n]);
            let (a, b, c) = (lp[ia].0, lp[ib].0, lp[ic].0);
            if orient(a, b, c) <= 0.0 {
                continue;
            }
            let blocked = idx.iter().any(|&j| {
                let p = lp[j].0;
                j != ia
                    && j != ib
                    && j != ic
                    && p != a
                    && p != b
                    && p != c
                    && inside_triangle(p, a, b, c)
            });
            if blocked {
                continue;
            }
            tris.push([lp[ia].1, lp[ib].1, lp[ic].1]);
            idx.remove(i);
            clipped = true;
            break;
        }
        if !clipped {
            // Only collinear or degenerate corners are left: drop one with zero area.
            let n = idx.len();
            let flat = (0..n).find(|&i| {
                let (a, b, c) = (lp[idx[(i + n - 1) % n]].0, lp[idx[i]].0, lp[idx[(i + 1) % n]].0);
                orient(a, b, c).abs() <= 1e-12 * (1.0 + a[0].abs() + a[1].abs())
            })?;
            idx.remove(flat);
        }
        guard += 1;
        if guard > 4 * lp.len() + 8 {
            return None;
        }
    }
    if idx.len() == 3 {
        let (a, b, c) = (lp[idx[0]], lp[idx[1]], lp[idx[2]]);
        if orient(a.0, b.0, c.0) > 0.0 {
            tris.push([a.1, b.1, c.1]);
        }
    }
    (!tris.is_empty()).then_some(tris)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area3(points: &[V3], tris: &[[u32; 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|k| points[k as usize].map(f64::from));
                let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                let x = [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ];
                0.5 * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
            })
            .sum()
    }

    #[test]
    fn a_concave_l_shape_keeps_its_area() {
        // An L of area 3 in the xz plane, clockwise seen from +y.
        let pts: Vec<V3> = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
            .iter()
            .map(|&(x, z)| [x, 0.0, z])
            .collect();
        let tris = face(&pts, &[(0..6).collect()]).unwrap();
        assert_eq!(tris.len(), 4);
        assert!((area3(&pts, &tris) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn a_square_with_a_square_hole() {
        let mut pts: Vec<V3> =
            [(0., 0.), (4., 0.), (4., 4.), (0., 4.)].iter().map(|&(x, y)| [x, y, 1.0]).collect();
        pts.extend([(1., 1.), (1., 3.), (3., 3.), (3., 1.)].iter().map(|&(x, y)| [x, y, 1.0]));
        let tris = face(&pts, &[vec![0, 1, 2, 3], vec![4, 5, 6, 7]]).unwrap();
        assert!((area3(&pts, &tris) - 12.0).abs() < 1e-9, "{}", area3(&pts, &tris));
        // The winding of every triangle is the outline's.
        for t in &tris {
            let [a, b, c] = t.map(|k| pts[k as usize]);
            let z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
            assert!(z > 0.0, "{t:?}");
        }
    }

    #[test]
    fn degenerate_faces_give_none() {
        let pts: Vec<V3> = vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert!(face(&pts, &[vec![0, 1, 2]]).is_none());
        assert!(face(&pts, &[vec![0, 1, 7]]).is_none());
    }
}
