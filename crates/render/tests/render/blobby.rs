//! Blobby implicit surfaces render at their true shape (issue #34): a lone ellipsoid's
//! silhouette is the ellipse of its isosurface, and two equal blobs join in the waist the
//! field predicts.
//!
//! The field of a primitive is `F(R) = (1 - R^2)^3` and the surface is `F = 27/64`, so a
//! lone field's surface is at `R = 1/2`: an ellipsoid whose matrix scales the unit sphere by
//! `(a, b, c)` has the surface of semi-axes `(a/2, b/2, c/2)`. Seen orthographically along z
//! its silhouette is the ellipse of semi-axes `a/2` and `b/2` (turned with the ellipsoid).

use reyes_render::{RenderOptions, render};
use reyes_testkit::coverage::{Field, mean_se};
use reyes_testkit::fixtures::parse;

/// The threshold of the field.
const T: f64 = 27.0 / 64.0;

/// An ellipsoid's RIB matrix (unit sphere to ellipsoid): scale `(a, b, c)`, then a turn of
/// `angle` degrees about z, then a move to `(x, y, 0)`, as 16 floats in RON.
fn ellipsoid(a: f64, b: f64, c: f64, angle: f64, x: f64, y: f64) -> String {
    let (s, k) = angle.to_radians().sin_cos();
    // Row vector convention: p' = p M; rows are the images of the axes.
    let m =
        [[a * k, a * s, 0.0, 0.0], [-b * s, b * k, 0.0, 0.0], [0.0, 0.0, c, 0.0], [x, y, 0.0, 1.0]];
    m.iter().flatten().map(|v| format!("{v}")).collect::<Vec<_>>().join(", ")
}

/// A lone ellipsoid's silhouette is the ellipse of semi-axes `a/2` and `b/2`, turned as the
/// ellipsoid is: its area (the mean of 256 cells' summed alpha) is `pi a b / 4` within 2%
/// (noise below a third of that), and the principal second moments of the coverage about
/// its centroid are the ellipse's `A^2 / 4` and `B^2 / 4`, each within 2% (a pixel's alpha
/// stands at its centre, which adds the `1/12` square pixel of a uniform offset within it).
#[test]
fn a_lone_ellipsoid_is_the_ellipse_of_its_isosurface() {
    let (a, b, c, angle) = (12.0_f64, 7.0_f64, 5.0_f64, 30.0_f64);
    let shape =
        format!("Blobby(code: [1001, 0], floats: [{}])", ellipsoid(a, b, c, angle, 0.0, 0.0));
    let field = Field { shape: &shape, transform: "", fields: "", hider: "", cells: 16, cell: 16 };
    let film = render(&field.scene(), &RenderOptions::default()).unwrap().film;
    let exact = std::f64::consts::PI * a * b / 4.0;
    let (mean, se) = mean_se(&field.cell_sums(&film));
    eprintln!("ellipse area {mean:.4} of {exact:.4} (+- {se:.4})");
    assert!(se / exact < 0.02 / 3.0, "noise {se}");
    assert!((mean / exact - 1.0).abs() <= 0.02, "area {mean} of {exact}");
    // Second moments, per cell, then averaged.
    let size = (field.cells * field.cell) as usize;
    let rgba = film.rgba();
    let (mut big, mut small) = (Vec::new(), Vec::new());
    for cj in 0..field.cells as usize {
        for ci in 0..field.cells as usize {
            let mut m = [0.0_f64; 6];
            for y in cj * 16..(cj + 1) * 16 {
                for x in ci * 16..(ci + 1) * 16 {
                    let w = f64::from(rgba[y * size + x][3]);
                    let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                    m = [
                        m[0] + w,
                        m[1] + w * px,
                        m[2] + w * py,
                        m[3] + w * px * px,
                        m[4] + w * py * py,
                        m[5] + w * px * py,
                    ];
                }
            }
            let (cx, cy) = (m[1] / m[0], m[2] / m[0]);
            let sxx = m[3] / m[0] - cx * cx - 1.0 / 12.0;
            let syy = m[4] / m[0] - cy * cy - 1.0 / 12.0;
            let sxy = m[5] / m[0] - cx * cy;
            let (mid, half) = (0.5 * (sxx + syy), (0.25 * (sxx - syy).powi(2) + sxy * sxy).sqrt());
            big.push(mid + half);
            small.push(mid - half);
        }
    }
    let (big, se_big) = mean_se(&big);
    let (small, se_small) = mean_se(&small);
    let (want_big, want_small) = ((a / 2.0).powi(2) / 4.0, (b / 2.0).powi(2) / 4.0);
    eprintln!(
        "second moments {big:.4} (+- {se_big:.4}) of {want_big:.4}, {small:.4} (+- {se_small:.4}) of {want_small:.4}"
    );
    assert!((big / want_big - 1.0).abs() <= 0.02, "major {big} of {want_big}");
    assert!((small / want_small - 1.0).abs() <= 0.02, "minor {small} of {want_small}");
}

/// The height of the two-blob silhouette at `x`: the largest `y` with the field at `(x, y,
/// 0)` at least `T`, for blobs of scale `s` at `(-d/2, 0)` and `(d/2, 0)` (bisection).
fn height(x: f64, s: f64, d: f64) -> f64 {
    let f = |r2: f64| if r2 < 1.0 { (1.0 - r2).powi(3) } else { 0.0 };
    let field = |y: f64| {
        f(((x - d / 2.0).powi(2) + y * y) / (s * s)) + f(((x + d / 2.0).powi(2) + y * y) / (s * s))
    };
    if field(0.0) < T {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0, s);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if field(mid) >= T { lo = mid } else { hi = mid }
    }
    lo
}

/// Two equal blobs of scale `s` (each alone a sphere of radius `s/2`) `d` apart join in a
/// waist of radius `s sqrt(1 - (T/2)^(1/3) - d^2 / (4 s^2))`, where the two fields, each
/// `(1 - R^2)^3` at `R^2 = (d^2/4 + rho^2) / s^2`, sum to `T`. Measured as the summed alpha
/// of the one-pixel column through the waist (no random offset: the blobs are centred on
/// that column's middle), over 64 copies; the column's exact coverage is the silhouette's
/// height integrated over it (`2 rho` to within its curvature). The dicer's flatness rule
/// puts every silhouette point within `tol = min(flatness, relative_flatness * extent)` =
/// `min(0.05, extent / 512)` pixels of the true one, so the column is within `2 tol` of
/// exact (its two edges), plus three standard errors of the sampling.
#[test]
fn two_blobs_join_in_the_predicted_waist() {
    let s = 8.0_f64;
    for d in [6.0_f64, 8.0, 9.5] {
        let rho = s * (1.0 - (T / 2.0).cbrt() - d * d / (4.0 * s * s)).sqrt();
        let exact: f64 =
            (0..1000).map(|k| 2.0 * height(-0.5 + (k as f64 + 0.5) / 1000.0, s, d)).sum::<f64>()
                / 1000.0;
        let (copies, cell) = (8_usize, 24_usize);
        let size = copies * cell;
        let half = size as f64 / 2.0;
        let mut objects = String::new();
        for j in 0..copies {
            for i in 0..copies {
                // Cell centre, on a pixel's middle.
                let x = (i * cell) as f64 + 12.5 - half;
                let y = half - (j * cell) as f64 - 12.5;
                objects.push_str(&format!(
                    "(shape: Blobby(code: [1001, 0, 1001, 16, 0, 2, 0, 1], floats: [{}, {}]),
                      material: Constant(color: (1.0, 1.0, 1.0))),\n",
                    ellipsoid(s, s, s, 0.0, x - d / 2.0, y),
                    ellipsoid(s, s, s, 0.0, x + d / 2.0, y)
                ));
            }
        }
        let scene = parse(&format!(
            "Scene(image: (width: {size}, height: {size}),
               camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 1.0), projection: Orthographic,
                        screen_window: Some(({l}, {half}, {l}, {half})), hither: 0.1, yon: 100.0),
               hider: (pixel_samples: (8, 8), filter: (kind: Box, width: 1.0), seed: 34),
               objects: [{objects}])",
            l = -half
        ));
        let film = render(&scene, &RenderOptions::default()).unwrap().film;
        let rgba = film.rgba();
        let mut columns = Vec::new();
        for j in 0..copies {
            for i in 0..copies {
                let x = i * cell + 12;
                let sum: f64 =
                    (j * cell..(j + 1) * cell).map(|y| f64::from(rgba[y * size + x][3])).sum();
                columns.push(sum);
            }
        }
        let (mean, se) = mean_se(&columns);
        eprintln!(
            "d {d}: waist column {mean:.4} +- {se:.4}, exact {exact:.4}, 2 rho {:.4}",
            2.0 * rho
        );
        // The blobby's raster extent: its bound, d + 2s by 2s.
        let tol = 0.05_f64.min((d + 2.0 * s) / 512.0);
        let bound = 2.0 * tol + 3.0 * se;
        eprintln!("d {d}: error {:.4} px, bound {bound:.4} px", mean - exact);
        assert!(se / exact < 0.01, "d {d}: noise {se}");
        assert!((mean - exact).abs() <= bound, "d {d}: waist column {mean} of {exact}");
        // The column spans the waist to within its curvature.
        assert!((exact / (2.0 * rho) - 1.0).abs() < 0.02, "d {d}: the column is the waist");
    }
}
