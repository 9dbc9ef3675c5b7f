//! Analytic tests. Tolerances: evaluation is f64 inside and rounded to f32 once, so points of
//! size ~1 agree to a few f32 ulps (1e-6); 1e-5 leaves margin for the 20-level fallback.

use super::*;
use crate::patch::on_edge;
use proptest::prelude::*;

fn grid_mesh(n: usize, z: impl Fn(usize, usize) -> f32) -> Mesh {
    let mut m = Mesh::default();
    for j in 0..=n {
        for i in 0..=n {
            m.points.push(Vec3::new(i as f32, j as f32, z(i, j)));
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            m.face_counts.push(4);
            m.faces.extend([v, v + 1, v + n + 2, v + n + 1]);
        }
    }
    m
}

/// Cox-de Boor uniform cubic B-spline basis (independent of the matrix form in the crate).
fn cox(i: i32, k: usize, t: f64) -> f64 {
    let ti = i as f64;
    if k == 0 {
        return if t >= ti && t < ti + 1.0 { 1.0 } else { 0.0 };
    }
    let kf = k as f64;
    (t - ti) / kf * cox(i, k - 1, t) + (ti + kf + 1.0 - t) / kf * cox(i + 1, k - 1, t)
}

#[test]
fn regular_grid_is_bicubic_bspline() {
    let z = |i: usize, j: usize| ((i * 7 + j * 3) % 5) as f32 * 0.3;
    let m = grid_mesh(6, z);
    let patches = limit_patches(&m).unwrap();
    assert!(!patches.is_empty());
    for p in &patches {
        // Child 0 of level-0 face f covers (u/2, v/2) of that face; the others are rotated.
        let (fi, fj) = (p.face % 6, p.face / 6);
        if m.faces[p.face * 4] != p.corners[0] || !(1..=4).contains(&fi) || !(1..=4).contains(&fj) {
            continue;
        }
        for &(u, v) in &[(0.0f32, 0.0f32), (0.3, 0.7), (0.5, 0.5), (0.9, 0.1)] {
            let (x, y) = (fi as f64 + u as f64 / 2.0, fj as f64 + v as f64 / 2.0);
            let mut want = 0.0;
            for j in 0..=6 {
                for i in 0..=6 {
                    // Control point i sits at knot position i: basis centred there.
                    want += z(i, j) as f64 * cox(i as i32 - 2, 3, x) * cox(j as i32 - 2, 3, y);
                }
            }
            let (pp, _, _) = p.eval(u, v);
            assert!((pp.z as f64 - want).abs() < 1e-5, "{pp} vs {want}");
            assert!((pp.x as f64 - x).abs() < 1e-5 && (pp.y as f64 - y).abs() < 1e-5);
        }
        assert!(p.bspline().is_some());
    }
}

fn cube() -> Mesh {
    let mut m = Mesh::default();
    for i in 0..8 {
        m.points.push(Vec3::new(
            if i & 1 == 0 { -1.0 } else { 1.0 },
            if i & 2 == 0 { -1.0 } else { 1.0 },
            if i & 4 == 0 { -1.0 } else { 1.0 },
        ));
    }
    for f in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        m.face_counts.push(4);
        m.faces.extend(f);
    }
    m
}

/// The brief asked for "between the inscribed sphere and the cube", but that is false: the
/// Halstead mask at a cube corner (valence 3) gives (9v + 4 sum e + sum f)/24 = -(1,1,1)/2,
/// at distance sqrt(3)/2 < 1. So: strictly inside the cube, outside the sphere of radius 0.8,
/// and the corner is exactly the mask value.
#[test]
fn cube_limit_between_sphere_and_cube() {
    let patches = limit_patches(&cube()).unwrap();
    assert_eq!(patches.len(), 24);
    let c = patches.iter().find(|p| p.corners[0] == 0).unwrap().eval(0.0, 0.0).0;
    assert!((c + Vec3::splat(0.5)).length() < 1e-6, "{c}");
    for p in &patches {
        for j in 0..=8 {
            for i in 0..=8 {
                let (q, _, _) = p.eval(i as f32 / 8.0, j as f32 / 8.0);
                // The limit cube of half-side 1 lies strictly inside the cube and, contrary
                // to "between the inscribed sphere and the cube", inside the inscribed sphere
                // too: from 68/81 (face centres: the bicubic limit of a face's 4 x 4 net) to
                // sqrt(3)/2 (corners: (9 v + 4 sum e + sum f) / 24 = v / 2). Sampling at
                // 1/8 steps touches both ends, so 1e-5 is rounding only.
                let r = q.length();
                assert!(
                    r >= 68.0 / 81.0 - 1e-5
                        && r <= 3.0_f32.sqrt() / 2.0 + 1e-5
                        && q.abs().max_element() < 1.0,
                    "{q} {i} {j} {:?}",
                    p.corners
                );
            }
        }
    }
}

#[test]
fn valence_limit_masks() {
    for n in 3..=6usize {
        // Centre 0, ring of n edge neighbours and n diagonal points, bumpy.
        let mut m = Mesh { points: vec![Vec3::new(0.0, 0.0, 1.0)], ..Mesh::default() };
        for k in 0..2 * n {
            let a = k as f32 * std::f32::consts::PI / n as f32;
            let r = if k % 2 == 0 { 1.0 } else { 1.6 };
            m.points.push(Vec3::new(r * a.cos(), r * a.sin(), 0.1 * k as f32));
        }
        for k in 0..n {
            let e = 1 + 2 * k;
            let d = e + 1;
            let e2 = 1 + (2 * k + 2) % (2 * n);
            m.face_counts.push(4);
            m.faces.extend([0, e, d, e2]);
        }
        let patches = limit_patches(&m).unwrap();
        let p = patches.iter().find(|p| p.face == 0 && m.faces[0] == 0).unwrap();
        let (q, _, _) = p.eval(0.0, 0.0);
        // Halstead et al. 1993: (n^2 v + 4 sum e + sum f) / (n (n + 5)) on any quad mesh.
        let nf = n as f32;
        let es: Vec3 = (0..n).map(|k| m.points[1 + 2 * k]).sum();
        let fs: Vec3 = (0..n).map(|k| m.points[2 + 2 * k]).sum();
        let want = (m.points[0] * nf * nf + es * 4.0 + fs) / (nf * (nf + 5.0));
        assert!((q - want).length() < 1e-5, "valence {n}: {q} vs {want}");
    }
}

fn crease_mesh(s: f32) -> Mesh {
    let mut m = grid_mesh(6, |i, j| if j == 3 && i == 3 { 1.0 } else { 0.0 });
    m.tags.push(Tag::Crease { vertices: (0..=6).map(|i| 21 + i).collect(), sharpness: s });
    m
}

fn height_at_bump(m: &Mesh) -> f32 {
    let ps = limit_patches(m).unwrap();
    let p = ps.iter().find(|p| p.corners[0] == 24).unwrap();
    p.eval(0.0, 0.0).0.z
}

#[test]
fn sharp_crease_is_bspline_curve_and_semisharp_is_monotone() {
    // Infinitely sharp: the crease's limit at the bump vertex is the cubic B-spline of the
    // polyline there, (0 + 4*1 + 0)/6.
    let h = height_at_bump(&crease_mesh(f32::INFINITY));
    assert!((h - 4.0 / 6.0).abs() < 1e-5, "{h}");
    let hs: Vec<f32> = [0.0, 0.5, 1.0, 2.0, f32::INFINITY]
        .iter()
        .map(|&s| height_at_bump(&crease_mesh(s)))
        .collect();
    // Smooth: the bicubic limit at a lone unit bump is (4/9).
    assert!((hs[0] - 4.0 / 9.0).abs() < 1e-5, "{hs:?}");
    assert!(hs.windows(2).all(|w| w[0] < w[1]), "{hs:?}");
}

#[test]
fn holes_and_boundary_corners() {
    let mut m = grid_mesh(2, |_, _| 0.0);
    m.tags.push(Tag::InterpolateBoundary);
    let all = limit_patches(&m).unwrap();
    assert_eq!(all.len(), 16, "{:?}", all.iter().map(|p| p.corners).collect::<Vec<_>>());
    let c = all.iter().find(|p| p.corners[0] == 0).unwrap();
    assert_eq!(c.eval(0.0, 0.0).0, Vec3::ZERO);
    m.tags.push(Tag::Hole { faces: vec![1] });
    assert_eq!(limit_patches(&m).unwrap().len(), 12);
    let plain = grid_mesh(2, |_, _| 0.0);
    assert_eq!(limit_patches(&plain).unwrap().len(), 4);
}

#[test]
fn bad_input_errors() {
    let mut m = cube();
    m.faces[3] = 99;
    assert_eq!(limit_patches(&m).unwrap_err(), SubdivError::VertexIndex { face: 0, index: 99 });
    let mut m = cube();
    m.tags.push(Tag::Crease { vertices: vec![0, 7], sharpness: 1.0 });
    assert!(limit_patches(&m).unwrap_err().to_string().starts_with("tag 0:"));
    let mut m = cube();
    m.face_counts[0] = 2;
    assert!(limit_patches(&m).is_err());
    let mut m = cube();
    m.points[2].x = f32::NAN;
    assert_eq!(limit_patches(&m).unwrap_err(), SubdivError::NonFinitePoint { vertex: 2 });
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(8))]
    #[test]
    fn shared_edges_bit_identical(jit in proptest::collection::vec(-0.3f32..0.3, 24), k in 1u32..8) {
        let mut m = cube();
        for (i, p) in m.points.iter_mut().enumerate() {
            *p += Vec3::new(jit[3 * i], jit[3 * i + 1], jit[3 * i + 2]);
        }
        let ps = limit_patches(&m).unwrap();
        let t = k as f32 / 8.0;
        let mut seen: HashMap<(usize, usize, u32), Vec3> = HashMap::new();
        for p in &ps {
            for e in 0..4 {
                let (a, b) = (p.corners[e], p.corners[(e + 1) % 4]);
                let tc = if a < b { t } else { 1.0 - t };
                let (u, v) = on_edge(e, if a < b { t as f64 } else { 1.0 - t as f64 });
                let q = p.eval(u as f32, v as f32).0;
                let kk = (a.min(b), a.max(b), tc.to_bits());
                if let Some(o) = seen.insert(kk, q) {
                    prop_assert_eq!(o.to_array().map(f32::to_bits), q.to_array().map(f32::to_bits));
                }
            }
        }
    }
}

#[test]
fn facevarying_bilinear_and_derivatives() {
    let mut m = grid_mesh(4, |i, j| ((i * 3 + j) % 4) as f32 * 0.2);
    m.facevarying_width = 1;
    m.facevarying = (0..m.faces.len()).map(|k| (k % 4) as f32).collect();
    let ps = limit_patches(&m).unwrap();
    // Level-0 face corners carry 0,1,2,3; child 0 has 0 at (0,0), (0+1)/2 at (1,0),
    // 1.5 at the centre (1,1) and (3+0)/2 at (0,1); bilinear in between.
    let p = ps.iter().find(|p| p.face == 5 && p.corners[0] == m.faces[20]).unwrap();
    assert_eq!(p.eval_facevarying(1.0, 1.0), vec![1.5]);
    assert!((p.eval_facevarying(0.5, 0.0)[0] - 0.25).abs() < 1e-6);
    // Derivatives against central differences of the positions: h = 1e-3, error O(h^2)
    // times the third derivative (~1) plus f32 rounding 1e-7/h: 1e-3 tolerance.
    for p in &ps {
        let (u, v, h) = (0.4f32, 0.6f32, 1e-3f32);
        let (_, du, dv) = p.eval(u, v);
        let fu = (p.eval(u + h, v).0 - p.eval(u - h, v).0) / (2.0 * h);
        let fv = (p.eval(u, v + h).0 - p.eval(u, v - h).0) / (2.0 * h);
        assert!((du - fu).length() < 1e-3 && (dv - fv).length() < 1e-3, "{du} {fu} {dv} {fv}");
    }
    m.facevarying.pop();
    assert!(matches!(limit_patches(&m), Err(SubdivError::FacevaryingLength { .. })));
}

#[test]
fn vertex_varyings_follow_points() {
    // Varying = the points' own x and y (width 2): it must evaluate to the same x, y (exactly
    // the same arithmetic, so bit-identical).
    let m = cube();
    let data: Vec<f32> = m.points.iter().flat_map(|p| [p.x, p.y]).collect();
    let vs = varying_patches(&m, 2, &data).unwrap();
    let ps = limit_patches(&m).unwrap();
    assert_eq!(vs.len(), 1);
    for (p, q) in ps.iter().zip(&vs[0]) {
        let (a, b) = (p.eval(0.3, 0.8).0, q.eval(0.3, 0.8).0);
        assert_eq!((a.x, a.y, b.z), (b.x, b.y, 0.0));
    }
    assert!(varying_patches(&m, 2, &data[1..]).is_err());
}

#[test]
fn the_kept_descent_evaluates_as_the_adaptive_one_bit_for_bit() {
    // The cube's patches each have a valence-3 corner; one with a crease has irregular quads
    // along an edge too, beyond the kept levels' budget.
    let mut creased = cube();
    creased.tags.push(Tag::Crease { vertices: vec![0, 1, 3, 2, 0], sharpness: 2.5 });
    for mesh in [cube(), creased] {
        for p in limit_patches(&mesh).unwrap() {
            for j in 0..=16 {
                for i in 0..=16 {
                    let (u, v) = (f64::from(i) / 16.0, f64::from(j) / 16.0);
                    // Off the grid too, and close to the corners (below the kept levels).
                    for (u, v) in [(u, v), (u * 0.013 + 1e-4, v * 0.007), (0.999 - u * 1e-3, v)] {
                        assert_eq!(p.local.eval(u, v), eval_local(&p.local.local, u, v));
                    }
                }
            }
        }
    }
}
