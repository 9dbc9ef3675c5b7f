//! The patch machinery against the RenderMan Interface Specification, written out here
//! independently: every basis evaluated as `P(u, v) = U M G M^T V^T` from the spec's
//! matrices, the sub-patch counts of `RiPatchMesh`, a B-spline mesh as the uniform bicubic
//! B-spline, periodic wrap without a seam, and NURBS with Bezier knots as the Bezier patch.

use glam::DVec3;
use reyes_sampling::SplitMix64;
use reyes_scene::patches::{self, bezier_patches, patch_count};
use reyes_scene::{Basis, PatchType, Shape, Wrap};
use reyes_testkit::fixtures::nurbs_cylinder;

/// The spec's basis matrices (RenderMan Interface 3.2, `RiBasis`), typed in again.
fn spec_matrix(basis: Basis) -> [[f64; 4]; 4] {
    match basis {
        Basis::Bezier => {
            [[-1., 3., -3., 1.], [3., -6., 3., 0.], [-3., 3., 0., 0.], [1., 0., 0., 0.]]
        }
        Basis::BSpline => [
            [-1. / 6., 3. / 6., -3. / 6., 1. / 6.],
            [3. / 6., -6. / 6., 3. / 6., 0.],
            [-3. / 6., 0., 3. / 6., 0.],
            [1. / 6., 4. / 6., 1. / 6., 0.],
        ],
        // The spec's 1/2 (-1 3 -3 1; 2 -5 4 -1; -1 0 1 0; 0 2 0 0).
        Basis::CatmullRom => [
            [-1. / 2., 3. / 2., -3. / 2., 1. / 2.],
            [1., -5. / 2., 4. / 2., -1. / 2.],
            [-1. / 2., 0., 1. / 2., 0.],
            [0., 1., 0., 0.],
        ],
        Basis::Hermite => {
            [[2., 1., -2., 1.], [-3., -2., 3., -1.], [0., 1., 0., 0.], [1., 0., 0., 0.]]
        }
        Basis::Power => [[1., 0., 0., 0.], [0., 1., 0., 0.], [0., 0., 1., 0.], [0., 0., 0., 1.]],
        Basis::Matrix(m) => m.map(|r| r.map(f64::from)),
    }
}

/// `U M G M^T V^T` for one 4 x 4 geometry `g[a][b]` (a along u, b along v).
fn direct(mu: [[f64; 4]; 4], mv: [[f64; 4]; 4], g: &[[DVec3; 4]; 4], u: f64, v: f64) -> DVec3 {
    let uu = [u * u * u, u * u, u, 1.0];
    let vv = [v * v * v, v * v, v, 1.0];
    // (U M)_a and (V M)_b.
    let um: Vec<f64> = (0..4).map(|a| (0..4).map(|i| uu[i] * mu[i][a]).sum()).collect();
    let vm: Vec<f64> = (0..4).map(|b| (0..4).map(|i| vv[i] * mv[i][b]).sum()).collect();
    let mut p = DVec3::ZERO;
    for a in 0..4 {
        for b in 0..4 {
            p += g[a][b] * (um[a] * vm[b]);
        }
    }
    p
}

fn rng_points(rng: &mut SplitMix64, n: usize) -> Vec<[f32; 3]> {
    (0..n).map(|_| [0; 3].map(|_| rng.next_f32() * 4.0 - 2.0)).collect()
}

fn bicubic(
    nu: u32,
    nv: u32,
    wrap: (Wrap, Wrap),
    bases: (Basis, Basis),
    steps: (Option<u32>, Option<u32>),
    points: Vec<[f32; 3]>,
) -> Shape {
    Shape::PatchMesh {
        kind: PatchType::Bicubic,
        nu,
        nv,
        uwrap: wrap.0,
        vwrap: wrap.1,
        points,
        ubasis: bases.0,
        ustep: steps.0,
        vbasis: bases.1,
        vstep: steps.1,
    }
}

const ALL: [Basis; 6] = [
    Basis::Bezier,
    Basis::BSpline,
    Basis::CatmullRom,
    Basis::Hermite,
    Basis::Power,
    // An arbitrary explicit matrix.
    Basis::Matrix([
        [0.5, -1.0, 2.0, 0.25],
        [1.5, 0.0, -0.5, 1.0],
        [-2.0, 1.0, 0.0, 0.5],
        [0.3, 0.2, 0.1, 0.4],
    ]),
];

#[test]
fn every_basis_is_u_m_g_mt_vt() {
    let mut rng = SplitMix64::from_state(17);
    for ub in ALL {
        for vb in ALL {
            let points = rng_points(&mut rng, 16);
            let step = |b: Basis| if matches!(b, Basis::Matrix(_)) { Some(4) } else { None };
            let shape = bicubic(
                4,
                4,
                (Wrap::Nonperiodic, Wrap::Nonperiodic),
                (ub, vb),
                (step(ub), step(vb)),
                points.clone(),
            );
            let patches = bezier_patches(&shape, None);
            assert_eq!(patches.len(), 1);
            let g: [[DVec3; 4]; 4] = std::array::from_fn(|a| {
                std::array::from_fn(|b| DVec3::from(points[b * 4 + a].map(f64::from)))
            });
            for _ in 0..50 {
                let (u, v) = (f64::from(rng.next_f32()), f64::from(rng.next_f32()));
                let want = direct(spec_matrix(ub), spec_matrix(vb), &g, u, v);
                let got = patches[0].eval(u, v).p;
                let scale = 1.0 + want.length();
                assert!(
                    (want - got).length() < 1e-9 * scale * 100.0,
                    "{ub:?} x {vb:?} at ({u}, {v}): {want} vs {got}"
                );
            }
        }
    }
}

#[test]
fn the_standard_steps_are_renderman_s() {
    let steps: Vec<Option<u32>> = ALL.iter().map(|b| b.standard_step()).collect();
    assert_eq!(steps, [Some(3), Some(1), Some(1), Some(2), Some(4), None]);
    assert_eq!(Basis::default(), Basis::Bezier, "RenderMan's default basis");
}

#[test]
fn sub_patch_counts_follow_the_spec() {
    use PatchType::{Bicubic, Bilinear};
    use Wrap::{Nonperiodic as N, Periodic as P};
    // (kind, n, wrap, step) -> count; nupatches = nonperiodic ? (nu - 4) / ustep + 1 : nu / ustep.
    for (kind, n, wrap, step, want) in [
        (Bicubic, 4, N, 3, Ok(1)),
        (Bicubic, 7, N, 3, Ok(2)),
        (Bicubic, 13, N, 3, Ok(4)),
        (Bicubic, 6, N, 3, Err(())),
        (Bicubic, 3, N, 3, Err(())),
        (Bicubic, 9, P, 3, Ok(3)),
        (Bicubic, 8, P, 3, Err(())),
        (Bicubic, 4, N, 1, Ok(1)),
        (Bicubic, 10, N, 1, Ok(7)),
        (Bicubic, 8, P, 1, Ok(8)),
        (Bicubic, 3, P, 1, Ok(3)),
        (Bicubic, 4, N, 2, Ok(1)),
        (Bicubic, 8, N, 2, Ok(3)),
        (Bicubic, 7, N, 2, Err(())),
        (Bicubic, 6, P, 2, Ok(3)),
        (Bicubic, 4, N, 4, Ok(1)),
        (Bicubic, 12, N, 4, Ok(3)),
        (Bicubic, 8, P, 4, Ok(2)),
        (Bicubic, 0, P, 1, Err(())),
        (Bicubic, 4, N, 0, Err(())),
        (Bilinear, 2, N, 1, Ok(1)),
        (Bilinear, 5, N, 1, Ok(4)),
        (Bilinear, 5, P, 1, Ok(5)),
        (Bilinear, 1, N, 1, Err(())),
        (Bilinear, 1, P, 1, Err(())),
    ] {
        let got = patch_count(kind, n, wrap, step).map_err(|_| ());
        assert_eq!(got, want, "{kind:?} n {n} {wrap:?} step {step}");
    }
    // And the mesh lays them out: a 7 x 10 Bezier-by-B-spline mesh has 2 x 7 sub-patches.
    let mut rng = SplitMix64::from_state(2);
    let shape = bicubic(
        7,
        10,
        (Wrap::Nonperiodic, Wrap::Nonperiodic),
        (Basis::Bezier, Basis::BSpline),
        (None, None),
        rng_points(&mut rng, 70),
    );
    assert_eq!(bezier_patches(&shape, None).len(), 14);
    assert_eq!(patches::bezier_grid(&shape), Some((2, 7)));
}

/// The uniform cubic B-spline basis functions, from the knot-interval formula.
fn uniform_bspline(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

#[test]
fn a_b_spline_mesh_of_a_grid_is_the_uniform_bicubic_b_spline() {
    // A 6 x 5 grid of heights: 3 x 2 sub-patches, each the uniform B-spline of its 4 x 4 window.
    let (nu, nv) = (6usize, 5usize);
    let points: Vec<[f32; 3]> = (0..nu * nv)
        .map(|k| {
            let (i, j) = ((k % nu) as f32, (k / nu) as f32);
            [i, j, (i * 0.7).sin() * (j * 0.4).cos()]
        })
        .collect();
    let shape = bicubic(
        nu as u32,
        nv as u32,
        (Wrap::Nonperiodic, Wrap::Nonperiodic),
        (Basis::BSpline, Basis::BSpline),
        (None, None),
        points.clone(),
    );
    let patches = bezier_patches(&shape, None);
    assert_eq!(patches.len(), 3 * 2);
    for (k, b) in patches.iter().enumerate() {
        let (pu, pv) = (k % 3, k / 3);
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.5, 1.0)] {
            let (bu, bv) = (uniform_bspline(u), uniform_bspline(v));
            let mut want = DVec3::ZERO;
            for (b_, wv) in bv.iter().enumerate() {
                for (a, wu) in bu.iter().enumerate() {
                    want += DVec3::from(points[(pv + b_) * nu + pu + a].map(f64::from)) * (wu * wv);
                }
            }
            let got = b.eval(u, v).p;
            assert!((want - got).length() < 1e-12, "sub-patch {k} ({u}, {v}): {want} vs {got}");
            // On a regular grid the B-spline reproduces x and y linearly.
            assert!((got.x - (pu as f64 + 1.0 + u)).abs() < 1e-12);
            assert!((got.y - (pv as f64 + 1.0 + v)).abs() < 1e-12);
        }
    }
}

#[test]
fn periodic_wrap_closes_the_surface_without_a_seam() {
    let mut rng = SplitMix64::from_state(5);
    for (basis, nu) in
        [(Basis::BSpline, 7u32), (Basis::CatmullRom, 5), (Basis::Bezier, 6), (Basis::Hermite, 6)]
    {
        let shape = bicubic(
            nu,
            4,
            (Wrap::Periodic, Wrap::Nonperiodic),
            (basis, Basis::Bezier),
            (None, None),
            rng_points(&mut rng, nu as usize * 4),
        );
        let patches = bezier_patches(&shape, None);
        let n = patches.len();
        for v in [0.0, 0.25, 0.6, 1.0] {
            for k in 0..n {
                // The end of each sub-patch is the start of the next, and the last wraps to the first.
                let (a, b) = (patches[k].eval(1.0, v), patches[(k + 1) % n].eval(0.0, v));
                assert!((a.p - b.p).length() < 1e-12, "{basis:?}: gap after sub-patch {k}");
                if basis != Basis::Bezier {
                    // B-spline, Catmull-Rom and Hermite meshes are C1 across the seam.
                    assert!(
                        (a.dpdu - b.dpdu).length() < 1e-9,
                        "{basis:?}: kink after sub-patch {k}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_nurbs_with_bezier_knots_is_the_bezier_patch() {
    let mut rng = SplitMix64::from_state(9);
    let points = rng_points(&mut rng, 16);
    let bezier = bicubic(
        4,
        4,
        (Wrap::Nonperiodic, Wrap::Nonperiodic),
        (Basis::Bezier, Basis::Bezier),
        (None, None),
        points.clone(),
    );
    let nurbs = Shape::NuPatch {
        nu: 4,
        uorder: 4,
        uknot: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        umin: 0.0,
        umax: 1.0,
        nv: 4,
        vorder: 4,
        vknot: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vmin: 0.0,
        vmax: 1.0,
        points: points.iter().map(|p| [p[0], p[1], p[2], 1.0]).collect(),
        trim: Vec::new(),
        trim_outside: false,
    };
    let (a, b) = (bezier_patches(&bezier, None), bezier_patches(&nurbs, None));
    assert_eq!(a, b, "the same control net, exactly");
}

#[test]
fn the_nine_point_circle_is_exactly_round() {
    let shape = nurbs_cylinder();
    let patches = bezier_patches(&shape, None);
    assert_eq!(patches.len(), 4);
    let mut rng = SplitMix64::from_state(1);
    for b in &patches {
        for _ in 0..200 {
            let (u, v) = (f64::from(rng.next_f32()), f64::from(rng.next_f32()));
            let p = b.eval(u, v).p;
            // Exact but for the f32 weight 1/sqrt(2) (relative error 3e-8).
            assert!((p.truncate().length() - 1.0).abs() < 1e-7, "radius {}", p.truncate().length());
            assert!((p.z - (2.0 * v - 1.0)).abs() < 1e-7);
        }
    }
}
