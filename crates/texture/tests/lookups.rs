//! The shading language's lookups against analytic truth (issue #32): environment maps that
//! encode their own directions return the reflected direction of a mirror sphere, latlong and
//! cube; a shadow map of a half-plane occluder puts the shadow's edge where the edge projects
//! and widens its penumbra by the blur; a prepared checkerboard filters as its PNG does and
//! keeps the map's mean.

use std::path::Path;

use reyes_texture::lookup::Options;
use reyes_texture::make::{
    MakeOptions, make_cube, make_latlong, make_shadow, make_texture, write_depth,
};
use reyes_texture::prepared::MapKind;
use reyes_texture::write::Depth;
use reyes_texture::{ColorSpace, TextureSystem};

fn ok<T, E: std::fmt::Display>(r: Result<T, E>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

fn norm(d: [f32; 3]) -> [f32; 3] {
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    [d[0] / l, d[1] / l, d[2] / l]
}

/// A direction as a colour: `(d + 1) / 2`.
fn colour(d: [f32; 3]) -> (f32, f32, f32, f32) {
    let d = norm(d);
    ((d[0] + 1.0) / 2.0, (d[1] + 1.0) / 2.0, (d[2] + 1.0) / 2.0, 1.0)
}

/// Reflected directions of a mirror sphere at the origin seen from (0, 0, -5) along +z: at
/// points over its visible cap, `R = I - 2 (N . I) N`.
fn mirror_directions() -> Vec<[f32; 3]> {
    let mut out = Vec::new();
    for a in 0..12 {
        for b in 1..10 {
            let phi = a as f32 / 12.0 * std::f32::consts::TAU;
            let theta = b as f32 / 10.0 * 1.4;
            let n = [theta.sin() * phi.cos(), theta.sin() * phi.sin(), -theta.cos()];
            let p = n;
            let i = norm([p[0], p[1], p[2] + 5.0]);
            let d = 2.0 * (n[0] * i[0] + n[1] * i[1] + n[2] * i[2]);
            out.push([i[0] - d * n[0], i[1] - d * n[1], i[2] - d * n[2]]);
        }
    }
    out
}

fn check_mirror(sys: &TextureSystem, id: reyes_texture::TextureId, tol: f32, what: &str) {
    for r in mirror_directions() {
        let got = sys.environment(id, &[r], &Options::default());
        let want = colour(r);
        let want = [want.0, want.1, want.2];
        for c in 0..3 {
            assert!((got[c] - want[c]).abs() <= tol, "{what}: R {r:?}: {got:?} vs {want:?}");
        }
    }
}

#[test]
fn latlong_map_returns_the_mirror_sphere_reflected_direction() {
    let dir = ok(tempfile::tempdir());
    let (src, out) = (dir.path().join("dirs.exr"), dir.path().join("dirs.env"));
    let (w, h) = (256usize, 128usize);
    // Texel (x, y) centre: longitude s = (x + 1/2) / w, colatitude t = (y + 1/2) / h, with
    // s = 1/2 + atan2(y, x) / 2 pi, t = acos(z) / pi.
    ok(exr::prelude::write_rgba_file(&src, w, h, |x, y| {
        let phi = ((x as f32 + 0.5) / w as f32 - 0.5) * std::f32::consts::TAU;
        let theta = (y as f32 + 0.5) / h as f32 * std::f32::consts::PI;
        colour([theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()])
    }));
    ok(make_latlong(
        &src,
        &out,
        &MakeOptions { depth: Some(Depth::Float), ..MakeOptions::default() },
    ));
    let mut sys = ok(TextureSystem::new(1 << 22));
    let id = ok(sys.load(&out, ColorSpace::Linear));
    assert_eq!(sys.texture(id).kind, MapKind::LatLong);
    // A single direction reads level 0 bilinearly between the four texel centres around it,
    // each at most a texel's diagonal away in angle: sqrt(2) * 2 pi / 256 radians. The colour
    // (d + 1) / 2 changes by at most half the angle, so the error is within
    // sqrt(2) * pi / 256.
    check_mirror(&sys, id, 2f32.sqrt() * std::f32::consts::PI / w as f32, "latlong");
}

#[test]
fn cube_face_map_returns_the_mirror_sphere_reflected_direction() {
    let dir = ok(tempfile::tempdir());
    let n = 64usize;
    // Each face's texel centre direction: forward + a right + b up, a = 2s - 1, b = 1 - 2t,
    // with PRMan's faces (px: right -z, up +y; nx: +z, +y; py: +x, -z; ny: +x, +z;
    // pz: +x, +y; nz: -x, +y).
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1., 0., 0.], [0., 0., -1.], [0., 1., 0.]),
        ([-1., 0., 0.], [0., 0., 1.], [0., 1., 0.]),
        ([0., 1., 0.], [1., 0., 0.], [0., 0., -1.]),
        ([0., -1., 0.], [1., 0., 0.], [0., 0., 1.]),
        ([0., 0., 1.], [1., 0., 0.], [0., 1., 0.]),
        ([0., 0., -1.], [-1., 0., 0.], [0., 1., 0.]),
    ];
    let mut files = Vec::new();
    for (k, (f, r, u)) in faces.iter().enumerate() {
        let file = dir.path().join(format!("face{k}.exr"));
        ok(exr::prelude::write_rgba_file(&file, n, n, |x, y| {
            let a = 2.0 * (x as f32 + 0.5) / n as f32 - 1.0;
            let b = 1.0 - 2.0 * (y as f32 + 0.5) / n as f32;
            colour([0, 1, 2].map(|c| f[c] + a * r[c] + b * u[c]))
        }));
        files.push(file);
    }
    let out = dir.path().join("cube.env");
    let faces: [&Path; 6] = std::array::from_fn(|k| files[k].as_path());
    ok(make_cube(
        faces,
        &out,
        &MakeOptions { depth: Some(Depth::Float), ..MakeOptions::default() },
    ));
    let mut sys = ok(TextureSystem::new(1 << 22));
    let id = ok(sys.load(&out, ColorSpace::Linear));
    assert_eq!(sys.texture(id).kind, MapKind::CubeFace);
    // A texel spans at most 2 / n radians (at a face's centre); bilinear reading within a
    // texel diagonal, and the clamp half a texel inside a face's edge, keep the direction
    // within sqrt(2) * 2 / n radians: the colour within half that.
    check_mirror(&sys, id, 2f32.sqrt() / n as f32, "cube");
}

/// A shadow map `w x w` of an orthographic light at the origin looking along +z over
/// x, y in [-1, 1]: depth 1 where the texel's centre has x < x0 (the occluder), far elsewhere.
fn half_plane_shadow(dir: &Path, w: u32, x0: f32) -> std::path::PathBuf {
    let z: Vec<f32> = (0..w * w)
        .map(|k| {
            let x = ((k % w) as f32 + 0.5) / w as f32 * 2.0 - 1.0;
            if x < x0 { 1.0 } else { 1e30 }
        })
        .collect();
    let screen = [1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.];
    let depth = dir.join("depth.z");
    ok(write_depth(&depth, w, w, &z, screen, screen, MapKind::Shadow));
    let out = dir.join("half.shd");
    ok(make_shadow(&depth, &out));
    out
}

#[test]
fn shadow_edge_sits_where_the_occluder_projects_and_the_penumbra_grows_with_blur() {
    let dir = ok(tempfile::tempdir());
    let w = 256u32;
    let x0 = 0.25; // on a texel boundary: 160 / 256 * 2 - 1
    let map = half_plane_shadow(dir.path(), w, x0);
    let mut sys = ok(TextureSystem::new(1 << 22));
    let id = ok(sys.load(&map, ColorSpace::Linear));
    assert_eq!(sys.texture(id).kind, MapKind::Shadow);
    let at = |x: f32, o: &Options| sys.shadow(id, &[[x, 0.1, 2.0]], o);
    let texel = 2.0 / w as f32; // in x
    // Far from the edge: fully shadowed, fully lit.
    let o = Options { samples: 256, ..Options::default() };
    assert_eq!(at(-0.5, &o), 1.0);
    assert_eq!(at(0.8, &o), 0.0);
    // A point at the occluder's depth or in front of it is lit (no self-shadowing).
    assert_eq!(sys.shadow(id, &[[-0.5, 0.1, 1.0]], &o), 0.0);
    // The edge: the 0.5 crossing of the shadow along x, without blur, lies within one texel
    // of x0 (the filter region is one texel wide, centred on the point).
    let crossing = |o: &Options| {
        let (mut a, mut b) = (-0.9f32, 0.9f32);
        for _ in 0..40 {
            let m = 0.5 * (a + b);
            if at(m, o) >= 0.5 { a = m } else { b = m }
        }
        0.5 * (a + b)
    };
    let edge = crossing(&o);
    assert!((edge - x0).abs() <= texel, "edge at {edge}, want {x0} within {texel}");
    // Penumbra: with blur b (in s, which spans x over 2), the region is b wide in s, 2b in x:
    // the shadow falls linearly from 1 to 0 over 2b around the edge, so its 10%-90% width is
    // 0.8 * 2b. Error terms: 16 strata across the region give the fraction within 1/16, i.e.
    // positions within 2b / 16 at each end; the map's texel adds one texel at each end.
    for b in [0.05f32, 0.1, 0.2] {
        let o = Options { samples: 256, blur: [b, b], ..Options::default() };
        let level = |v: f32| {
            let (mut lo, mut hi) = (-0.9f32, 0.9f32);
            for _ in 0..40 {
                let m = 0.5 * (lo + hi);
                if at(m, &o) >= v { lo = m } else { hi = m }
            }
            0.5 * (lo + hi)
        };
        let width = level(0.1) - level(0.9);
        let want = 0.8 * 2.0 * b;
        let tol = 2.0 * (2.0 * b / 16.0 + texel);
        assert!((width - want).abs() <= tol, "blur {b}: penumbra {width}, want {want} +- {tol}");
        assert!((crossing(&o) - x0).abs() <= texel + 2.0 * b / 16.0, "blur {b}: edge moved");
    }
}

#[test]
fn a_prepared_checkerboard_filters_as_its_png_and_keeps_the_mean() {
    let dir = ok(tempfile::tempdir());
    let (png, tex) = (dir.path().join("c.png"), dir.path().join("c.tex"));
    let n = 64u32;
    ok(image::GrayImage::from_fn(n, n, |x, y| {
        image::Luma([if (x / 4 + y / 4) % 2 == 0 { 220 } else { 30 }])
    })
    .save(&png));
    ok(make_texture(
        &png,
        &tex,
        &MakeOptions { depth: Some(Depth::Float), ..MakeOptions::default() },
    ));
    let mut sys = ok(TextureSystem::new(1 << 22));
    let a = ok(sys.load(&png, ColorSpace::Linear));
    let b = ok(sys.load(&tex, ColorSpace::Linear));
    let mean = (220.0 + 30.0) / 2.0 / 255.0;
    // A grazing view: footprints ever longer along t, one texel across.
    for k in 0..200 {
        let t = k as f32 / 200.0;
        let st = [0.3 + 0.001 * k as f32, t];
        let corners = |len: f32| {
            [
                [st[0], st[1]],
                [st[0] + 1.0 / 64.0, st[1]],
                [st[0], st[1] + len],
                [st[0] + 1.0 / 64.0, st[1] + len],
            ]
        };
        let len = 0.002 * (1.0 + k as f32);
        let o = Options::default();
        let (pa, pb) =
            (sys.texture_corners(a, corners(len), &o), sys.texture_corners(b, corners(len), &o));
        // The same levels (both are 2 x 2 box reductions in f32, the prepared one stored in
        // float) read by the same filter: equal up to float rounding of the level sums.
        assert!((pa[0] - pb[0]).abs() <= 1e-6, "k {k}: png {} vs prepared {}", pa[0], pb[0]);
    }
    // The whole map: the mean (every level's texel averages whole checks).
    let all = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
    let v = sys.texture_corners(b, all, &Options::default());
    assert!((v[0] - mean).abs() < 1e-5, "{} vs {mean}", v[0]);
    // Blur of a whole period (8 texels) about any point averages the checks.
    let tiny = [[0.51, 0.52], [0.51, 0.52], [0.51, 0.52], [0.51, 0.52]];
    let o = Options { blur: [8.0 / 64.0, 8.0 / 64.0], ..Options::default() };
    assert!((sys.texture_corners(b, tiny, &o)[0] - mean).abs() < 0.02 * mean);
    // Width 0 reads the texel: (0.51, 0.52) is texel (32, 33): check (8, 8), even, 220.
    let o = Options { width: [0.0, 0.0], ..Options::default() };
    let v = sys.texture_corners(b, tiny, &o)[0];
    assert!((v - 220.0 / 255.0).abs() < 1e-6, "{v}");
}
