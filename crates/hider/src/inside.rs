//! The point-in-quadrilateral test of Appendix A `sample`, unrolled as the original.
//!
//! The vertices are already relative to the sample point, so the test asks whether the origin
//! is inside. It casts a ray from the origin towards +x and counts quad edges that cross the
//! x axis at positive x: odd means inside (even-odd rule, so convex, concave and bow-tie quads
//! all work). Vertices 0 and 2 are opposite corners; 1 and 3 are each adjacent to both, so
//! which edges can cross follows from the signs of the y coordinates (appendix-a.md 3.10).
//!
//! Zero handling, as the original: when `v0.y > 0` a vertex with `y == 0` counts as above;
//! otherwise as below. Consistent within one quad; two quads sharing a vertex exactly on the
//! sample's scan line may classify it differently (measure zero with jitter).

/// Port of the unrolled inside test of `sample`. `v` holds the 4 vertices relative to the
/// sample point, in cyclic order.
#[inline(always)]
pub fn inside(v: &[[f32; 3]; 4]) -> bool {
    let (x0, y0) = (v[0][0], v[0][1]);
    let (x1, y1) = (v[1][0], v[1][1]);
    let (x2, y2) = (v[2][0], v[2][1]);
    let (x3, y3) = (v[3][0], v[3][1]);
    let mut inside = false;
    if y0 > 0.0 {
        if y2 < 0.0 {
            // Exactly one of 1-0, 1-2 crosses (by v1's side), and one of 3-0, 3-2.
            if y1 < 0.0 {
                inside ^= x1 * y0 > y1 * x0;
            } else {
                inside ^= x2 * y1 > y2 * x1;
            }
            if y3 < 0.0 {
                inside ^= x3 * y0 > y3 * x0;
            } else {
                inside ^= x2 * y3 > y2 * x3;
            }
        } else {
            // v0 and v2 on the same side: both edges at v1 cross or neither (same for v3).
            if y1 < 0.0 {
                inside ^= x1 * y0 > y1 * x0;
                inside ^= x1 * y2 > y1 * x2;
            }
            if y3 < 0.0 {
                inside ^= x3 * y0 > y3 * x0;
                inside ^= x3 * y2 > y3 * x2;
            }
        }
    } else if y2 > 0.0 {
        if y1 > 0.0 {
            inside ^= x1 * y0 < y1 * x0;
        } else {
            inside ^= x2 * y1 < y2 * x1;
        }
        if y3 > 0.0 {
            inside ^= x3 * y0 < y3 * x0;
        } else {
            inside ^= x2 * y3 < y2 * x3;
        }
    } else {
        if y1 > 0.0 {
            inside ^= x1 * y0 < y1 * x0;
            inside ^= x1 * y2 < y1 * x2;
        }
        if y3 > 0.0 {
            inside ^= x3 * y0 < y3 * x0;
            inside ^= x3 * y2 < y3 * x2;
        }
    }
    inside
}

/// The same test as [`inside`], without data-dependent branches, on the vertices' x and y
/// (relative to the sample point). Returns exactly what [`inside`] returns for every input,
/// zeros, infinities and NaNs included (checked exhaustively in the tests); the hider's loops
/// use it because the sign branches of the unrolled form mispredict on jittered samples.
///
/// Derivation: in every branch of [`inside`] a vertex counts as "up" when `y > 0` if
/// `y0 <= 0` (or NaN), and when `!(y < 0)` if `y0 > 0`; the edges tested are exactly those
/// whose two ends differ, and each is tested as `x_lo * y_up > y_lo * x_up` (up and lo: its
/// two ends). For edge `i -> j` with `A = x_i * y_j`, `B = y_i * x_j` that is `A > B` when
/// `j` is up and `B > A` when `i` is up (products commute exactly). The result is the parity
/// of the edges that cross.
// `!(t < 0.0)` on purpose: a NaN counts as "up" there, as in the unrolled test's `else`.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
#[inline(always)]
pub fn inside_xy(x: [f32; 4], y: [f32; 4]) -> bool {
    let y0_up = y[0] > 0.0;
    let up = y.map(|t| if y0_up { !(t < 0.0) } else { t > 0.0 });
    let mut parity = false;
    for i in 0..4 {
        let j = (i + 1) & 3;
        let a = x[i] * y[j];
        let b = y[i] * x[j];
        let crosses = if up[j] { a > b } else { b > a };
        parity ^= (up[i] != up[j]) & crosses;
    }
    parity
}

/// Reference even-odd test by explicit edge crossings, in f64, for checking [`inside`].
pub fn inside_reference(v: &[[f32; 3]; 4]) -> bool {
    let mut inside = false;
    for k in 0..4 {
        let (ax, ay) = (v[k][0] as f64, v[k][1] as f64);
        let (bx, by) = (v[(k + 1) % 4][0] as f64, v[(k + 1) % 4][1] as f64);
        if (ay > 0.0) != (by > 0.0) {
            let x = ax + (0.0 - ay) * (bx - ax) / (by - ay);
            if x > 0.0 {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn quad(p: [(f32, f32); 4]) -> [[f32; 3]; 4] {
        p.map(|(x, y)| [x, y, 1.0])
    }

    #[test]
    fn unit_square_and_bow_tie() {
        let sq = quad([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]);
        assert!(inside(&sq));
        let off = quad([(1.0, -1.0), (3.0, -1.0), (3.0, 1.0), (1.0, 1.0)]);
        assert!(!inside(&off));
        // Bow-tie crossing at the origin's right: the origin lies in the left lobe.
        let bow = quad([(-1.0, -1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, 1.0)]);
        assert_eq!(inside(&bow), inside_reference(&bow));
    }

    /// Distance from the origin to the nearest edge, to skip points on edges (where the
    /// original's zero rule and the reference may legitimately differ in the last bit).
    fn edge_distance(v: &[[f32; 3]; 4]) -> f64 {
        (0..4)
            .map(|k| {
                let (ax, ay) = (v[k][0] as f64, v[k][1] as f64);
                let (bx, by) = (v[(k + 1) % 4][0] as f64, v[(k + 1) % 4][1] as f64);
                let (dx, dy) = (bx - ax, by - ay);
                let l2 = dx * dx + dy * dy;
                let t = if l2 > 0.0 { (-(ax * dx + ay * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
                (ax + t * dx).hypot(ay + t * dy)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// [`inside_xy`] equals [`inside`] on every quad whose coordinates come from a set with
    /// both zeros, ties, infinities and NaN (exhaustive: 8^8 quads, about 16.8 million).
    #[test]
    fn branchless_equals_unrolled_exhaustively() {
        const VALS: [f32; 8] = [-1.0, -0.0, 0.0, 0.5, 1.0, 2.0, f32::INFINITY, f32::NAN];
        let mut c = [0usize; 8];
        loop {
            let x = [VALS[c[0]], VALS[c[1]], VALS[c[2]], VALS[c[3]]];
            let y = [VALS[c[4]], VALS[c[5]], VALS[c[6]], VALS[c[7]]];
            let v = [0, 1, 2, 3].map(|k| [x[k], y[k], 1.0]);
            assert_eq!(inside_xy(x, y), inside(&v), "{x:?} {y:?}");
            let mut d = 0;
            while d < 8 {
                c[d] += 1;
                if c[d] < VALS.len() {
                    break;
                }
                c[d] = 0;
                d += 1;
            }
            if d == 8 {
                break;
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        /// Random convex, concave and self-intersecting quads around the origin.
        #[test]
        fn agrees_with_exact_test(c in prop::array::uniform8(-2.0f32..2.0)) {
            let v = quad([(c[0], c[1]), (c[2], c[3]), (c[4], c[5]), (c[6], c[7])]);
            prop_assume!(edge_distance(&v) > 1e-4);
            prop_assert_eq!(inside(&v), inside_reference(&v));
        }

        /// [`inside_xy`] equals [`inside`] on random quads, including coordinates that tie.
        #[test]
        fn branchless_equals_unrolled(c in prop::array::uniform8(-4i32..4), f in prop::array::uniform8(-2.0f32..2.0), tie in 0u32..256) {
            // Each coordinate is either a small integer (ties, zeros) or a random float.
            let k = |i: usize| if tie >> i & 1 == 1 { c[i] as f32 * 0.5 } else { f[i] };
            let x = [k(0), k(1), k(2), k(3)];
            let y = [k(4), k(5), k(6), k(7)];
            let v = [0, 1, 2, 3].map(|j| [x[j], y[j], 1.0]);
            prop_assert_eq!(inside_xy(x, y), inside(&v));
        }

        /// Two quads sharing an edge (a split convex quad) cover each point exactly once.
        #[test]
        fn shared_edge_covers_once(c in prop::array::uniform8(-2.0f32..2.0), m in 0.2f32..0.8) {
            // A convex quad: points on a circle in angular order, made relative to a random origin.
            let ang = [0.0f32, 1.6, 3.2, 4.7];
            let r = [1.0 + c[0].abs() * 0.2, 1.0 + c[1].abs() * 0.2, 1.0 + c[2].abs() * 0.2, 1.0 + c[3].abs() * 0.2];
            let p: Vec<(f32, f32)> = (0..4).map(|k| (r[k] * (ang[k] + c[4] * 0.1).cos() - c[5] * 0.5, r[k] * (ang[k] + c[4] * 0.1).sin() - c[6] * 0.5)).collect();
            let lerp = |a: (f32, f32), b: (f32, f32)| (a.0 + m * (b.0 - a.0), a.1 + m * (b.1 - a.1));
            let e01 = lerp(p[0], p[1]);
            let e32 = lerp(p[3], p[2]);
            let left = quad([p[0], e01, e32, p[3]]);
            let right = quad([e01, p[1], p[2], e32]);
            let whole = quad([p[0], p[1], p[2], p[3]]);
            prop_assume!(edge_distance(&left) > 1e-4 && edge_distance(&right) > 1e-4);
            prop_assert_eq!(inside(&left) as u32 + inside(&right) as u32, inside(&whole) as u32);
        }
    }
}
