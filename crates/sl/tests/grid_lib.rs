//! The library on the grid machine against formulas: operators, math, geometry, colour
//! spaces, matrices, spaces, splines, strings, noise statistics.

mod common;

use common::*;
use reyes_sl::exec::{GridContext, Spaces};

/// Runs a surface body on a 1-point grid and returns Ci.
fn one(body: &str) -> [f32; 3] {
    let sh = compile(&format!("surface t() {{ {body} }}"));
    let mut g = GridContext::new(&sh, 1, 1);
    g.run().unwrap_or_else(|e| panic!("{e}"));
    g.get_v3("Ci", 0).unwrap()
}

fn near(a: [f32; 3], b: [f32; 3], tol: f32) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

#[test]
fn operators() {
    // dot, cross, colour/point arithmetic, promotion: small integers, exact.
    assert_eq!(one("Ci = color(vector(1, 2, 3) . vector(4, 5, 6));"), [32.0; 3]);
    let c = one(
        "vector c = vector(1, 0, 0) ^ vector(0, 1, 0); Ci = color(xcomp(c), ycomp(c), zcomp(c));",
    );
    assert_eq!(c, [0.0, 0.0, 1.0]);
    assert_eq!(one("Ci = color(1, 2, 3) * 2 + 1;"), [3.0, 5.0, 7.0]);
    assert_eq!(one("Ci = color(1, 2, 3) / color(2, 4, 8);"), [0.5, 0.5, 0.375]);
    let p = one(
        "vector d = point(3, 3, 3) - point(1, 2, 3); Ci = color(xcomp(d), ycomp(d), zcomp(d));",
    );
    assert_eq!(p, [2.0, 1.0, 0.0]);
    assert_eq!(one("Ci = (color(1,2,3) == color(1,2,3)) ? 1 : 0;"), [1.0; 3]);
    assert_eq!(one("Ci = (\"a\" != \"b\" && 2 > 1 || 0) ? 1 : 0;"), [1.0; 3]);
    assert_eq!(one("Ci = -color(1, 2, 3);"), [-1.0, -2.0, -3.0]);
}

#[test]
fn math_functions() {
    // Each against std's f32 function: the same operations, so equal (tolerance 1e-6 for
    // the ones this crate composes, like log with a base).
    let cases: &[(&str, f32)] = &[
        ("sin(0.5)", 0.5f32.sin()),
        ("cos(0.5)", 0.5f32.cos()),
        ("tan(0.5)", 0.5f32.tan()),
        ("asin(0.5)", 0.5f32.asin()),
        ("acos(0.5)", 0.5f32.acos()),
        ("atan(0.5)", 0.5f32.atan()),
        ("atan(1, -1)", 1f32.atan2(-1.0)),
        ("radians(180)", std::f32::consts::PI),
        ("degrees(PI)", 180.0),
        ("pow(2, 10)", 1024.0),
        ("exp(1)", 1f32.exp()),
        ("log(8)", 8f32.ln()),
        ("log(8, 2)", 3.0),
        ("sqrt(2)", 2f32.sqrt()),
        ("inversesqrt(4)", 0.5),
        ("abs(-3)", 3.0),
        ("sign(-3)", -1.0),
        ("floor(-1.5)", -2.0),
        ("ceil(-1.5)", -1.0),
        ("round(2.5)", 3.0),
        ("mod(-1, 3)", 2.0),
        ("min(3, 1, 2)", 1.0),
        ("max(3, 1, 2)", 3.0),
        ("clamp(5, 0, 2)", 2.0),
        ("mix(0, 10, 0.25)", 2.5),
        ("step(1, 0.5)", 0.0),
        ("step(1, 1)", 1.0),
        ("smoothstep(0, 2, 1)", 0.5),
        ("smoothstep(0, 1, 0.25)", 0.25 * 0.25 * (3.0 - 0.5)),
        ("filterstep(0.5, 0.4, 0.8)", 0.75),
    ];
    for (e, want) in cases {
        let got = one(&format!("Ci = {e};"))[0];
        assert!((got - want).abs() <= 1e-6, "{e}: {got} vs {want}");
    }
}

#[test]
fn geometric_functions() {
    let l = one("Ci = length(vector(3, 4, 0)) + distance(point(0, 0, 0), point(0, 0, 2));");
    assert_eq!(l[0], 7.0);
    let n = one("vector v = normalize(vector(0, 3, 4)); Ci = color(xcomp(v), ycomp(v), zcomp(v));");
    assert!(near(n, [0.0, 0.6, 0.8], 1e-6));
    let r = one(
        "vector r = reflect(vector(1, -1, 0), vector(0, 1, 0)); Ci = color(xcomp(r), ycomp(r), zcomp(r));",
    );
    assert_eq!(r, [1.0, 1.0, 0.0]);
    let f = one("normal nn = faceforward(normal(0, 0, 1), vector(0, 0, 1), vector(0, 0, 1));
         Ci = color(xcomp(nn), ycomp(nn), zcomp(nn));");
    assert_eq!(f, [0.0, 0.0, -1.0]);
    // Refraction into glass at normal incidence goes straight; Fresnel there is
    // ((1 - 1.5) / (1 + 1.5))^2 = 0.04 for eta = 1/1.5.
    let k = one("float kr, kt; fresnel(vector(0, 0, -1), normal(0, 0, 1), 1 / 1.5, kr, kt);
         vector t = refract(vector(0, 0, -1), vector(0, 0, 1), 1 / 1.5);
         Ci = color(kr, kt, zcomp(t));");
    assert!(near(k, [0.04, 0.96, -1.0], 1e-6), "{k:?}");
    let p =
        one("point p = point(1, 2, 3); setycomp(p, 7); Ci = color(xcomp(p), ycomp(p), zcomp(p));");
    assert_eq!(p, [1.0, 7.0, 3.0]);
    let rot = one(
        "point p = rotate(point(1, 0, 0), PI / 2, point(0, 0, 0), point(0, 0, 1)); Ci = color(xcomp(p), ycomp(p), zcomp(p));",
    );
    assert!(near(rot, [0.0, 1.0, 0.0], 1e-6), "{rot:?}");
}

#[test]
fn spaces_and_transforms() {
    // "world" is 2x bigger than current, moved by (1, 0, 0): a world point p is 2p + (1,0,0).
    let m = [2., 0., 0., 0., 0., 2., 0., 0., 0., 0., 2., 0., 1., 0., 0., 1.];
    let sh = compile(
        "surface t() {
            point a = point \"world\" (1, 1, 1);
            point b = transform(\"world\", point(3, 3, 3));
            vector c = vtransform(\"world\", \"current\", vector(1, 0, 0));
            normal d = ntransform(\"world\", normal(0, 0, 1));
            Ci = color(xcomp(a), xcomp(b), xcomp(c)); Oi = color(zcomp(d), ycomp(a), zcomp(b));
        }",
    );
    let mut g = GridContext::new(&sh, 1, 1);
    g.set_spaces(Spaces::default().with("world", m));
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [3.0, 1.0, 2.0]);
    assert_eq!(g.get_v3("Oi", 0).unwrap(), [2.0, 2.0, 1.5]);
    let sh = compile("surface t() { point a = point \"nowhere\" (1, 1, 1); }");
    let e = GridContext::new(&sh, 1, 1).run().unwrap_err();
    assert!(e.to_string().contains("unknown coordinate system \"nowhere\""), "{e}");
}

#[test]
fn colour_spaces_round_trip() {
    // hsv (0, 1, 1) is red; (1/3, 1, 1) green; hsl (2/3, 1, 0.5) blue; each space back to
    // rgb and again returns the colour (3x3 inverses in f32: 1e-5).
    assert!(near(one("Ci = color \"hsv\" (0, 1, 1);"), [1.0, 0.0, 0.0], 1e-6));
    assert!(near(one("Ci = color \"hsv\" (1.0/3, 1, 1);"), [0.0, 1.0, 0.0], 1e-6));
    assert!(near(one("Ci = color \"hsl\" (2.0/3, 1, 0.5);"), [0.0, 0.0, 1.0], 1e-6));
    for sp in ["hsv", "hsl", "xyz", "xyY", "YIQ"] {
        let c = one(&format!(
            "color c = color(0.2, 0.5, 0.7); Ci = ctransform(\"{sp}\", \"rgb\", ctransform(\"{sp}\", c));"
        ));
        assert!(near(c, [0.2, 0.5, 0.7], 1e-5), "{sp}: {c:?}");
    }
    // White has luminance Y = 1 (the rows of the XYZ matrix sum so).
    assert!(near(one("Ci = comp(ctransform(\"xyz\", color(1)), 1);"), [1.0; 3], 1e-4));
    let c = one("color c = 0; setcomp(c, 2, 5); Ci = c;");
    assert_eq!(c, [0.0, 0.0, 5.0]);
}

#[test]
fn matrices() {
    let d = one("matrix m = matrix(2,0,0,0, 0,3,0,0, 0,0,4,0, 0,0,0,1); Ci = determinant(m);");
    assert_eq!(d[0], 24.0);
    let t = one("matrix m = translate(matrix 1, vector(1, 2, 3));
         m = scale(m, point(2, 2, 2));
         point p = transform(m, point(1, 1, 1));
         Ci = color(xcomp(p), ycomp(p), zcomp(p));");
    // scale applies first (it is concatenated last, as RiScale does): 2p + (1, 2, 3).
    assert_eq!(t, [3.0, 4.0, 5.0]);
    let i = one("matrix m = rotate(matrix 1, 0.7, vector(1, 2, 3)); matrix k = m / m;
         Ci = color(comp(k, 0, 0), comp(k, 0, 1), comp(k, 3, 3));");
    assert!(near(i, [1.0, 0.0, 1.0], 1e-6), "{i:?}");
    // inverse (an extension; m / m is the Specification's way): m * inverse(m) = 1.
    let j = one("matrix m = translate(rotate(matrix 1, 0.3, vector(0, 1, 0)), vector(1, 2, 3));
         matrix k = m * inverse(m);
         Ci = color(comp(k, 1, 1), comp(k, 3, 0), comp(k, 2, 2));");
    assert!(near(j, [1.0, 0.0, 1.0], 1e-6), "{j:?}");
}

#[test]
fn splines() {
    // Catmull-Rom passes through its interior knots; linear interpolates them; B-spline of
    // constant knots is that constant (its basis sums to 1).
    assert!(near(one("Ci = spline(0, 9, 1, 2, 3, 9);"), [1.0; 3], 1e-6));
    assert!(near(one("Ci = spline(1, 9, 1, 2, 3, 9);"), [3.0; 3], 1e-6));
    assert!(near(one("Ci = spline(0.5, 0, 1, 2, 3, 4);"), [2.0; 3], 1e-6));
    assert!(near(one("Ci = spline(\"linear\", 0.25, 9, 0, 4, 8, 9);"), [2.0; 3], 1e-6));
    assert!(near(one("Ci = spline(\"bspline\", 0.3, 5, 5, 5, 5, 5);"), [5.0; 3], 1e-5));
    assert!(near(one("Ci = spline(\"bezier\", 0.5, 0, 0, 1, 1);"), [0.5; 3], 1e-6));
    let a = one("float k[5] = {0, 1, 2, 3, 4}; Ci = spline(0.5, k);");
    assert!(near(a, [2.0; 3], 1e-6));
    // One Catmull-Rom segment at its middle: (-k0 + 9 k1 + 9 k2 - k3) / 16 per component.
    let c = one("Ci = spline(0.5, color(0), color(1, 2, 3), color(2, 4, 6), color(3));");
    assert!(near(c, [24.0 / 16.0, 51.0 / 16.0, 78.0 / 16.0], 1e-6), "{c:?}");
}

#[test]
fn strings() {
    let sh = compile(
        "surface t() {
            string a = concat(\"ab\", \"cd\");
            string f = format(\"%s=%.2f %d[%5.1f|%-4d|%03d]\", a, 0.5, 7, 2.25, 3, -4);
            printf(\"%s|%f\\n\", f, s);
            Ci = color(match(\"^a.c+d$\", a), match(\"[x-z]\", a), match(\"b\", a));
        }",
    );
    let mut g = GridContext::new(&sh, 2, 1);
    g.set_varying("s", &[1.0, 2.0]).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [1.0, 0.0, 1.0]);
    assert_eq!(
        g.printed(),
        ["abcd=0.50 7[  2.2|3   |-04]|1.000000\n", "abcd=0.50 7[  2.2|3   |-04]|2.000000\n"]
    );
}

#[test]
fn noise_statistics() {
    // 64 x 64 points over 16 x 16 lattice cells. Range: [0, 1] by construction. Mean 0.5:
    // the noise is symmetric about 0.5; values are correlated within a cell, so there are
    // about 256 independent samples with sd about 0.1: the mean's sd is 0.006; 0.03 is 5 sd.
    let (nu, nv) = (64, 64);
    let sh = compile(
        "surface n() {
            point q = point(s * 16, t * 16, 0.37);
            Ci = color(noise(q), noise(s * 16), cellnoise(q));
            color c = noise(q, 0.5);
            Oi = c;
        }",
    );
    let mut g = plane(&sh, nu, nv);
    g.run().unwrap();
    for k in 0..3 {
        let vals: Vec<f32> = (0..nu * nv).map(|i| g.get_v3("Ci", i).unwrap()[k]).collect();
        let mean = vals.iter().sum::<f32>() / vals.len() as f32;
        assert!(vals.iter().all(|v| (0.0..=1.0).contains(v)), "range {k}");
        assert!((mean - 0.5).abs() < 0.03, "mean {k}: {mean}");
        let spread = vals.iter().fold(0.0f32, |m, v| m.max((v - 0.5).abs()));
        assert!(spread > 0.2, "{k}: the noise varies ({spread})");
    }
    // Colour noise: three different channels.
    let o = g.get_v3("Oi", 100).unwrap();
    assert!(o[0] != o[1] && o[1] != o[2]);
    // Continuity: neighbours 1/4 of a cell apart differ by at most the gradient bound (the
    // gradient of 0.75 n is below 3 per unit) times 0.25.
    for i in 0..nu * nv - 1 {
        if i % nu != nu - 1 {
            let (a, b) = (g.get_v3("Ci", i).unwrap()[0], g.get_v3("Ci", i + 1).unwrap()[0]);
            assert!((a - b).abs() < 0.75, "{i}");
        }
    }
    // Integer lattice points are 0.5 exactly (gradient noise is 0 there).
    assert_eq!(one("Ci = noise(point(3, 4, 5));")[0], 0.5);
}

#[test]
fn pnoise_is_periodic_and_continuous() {
    // pnoise(x, 4) at x and x + 4 hashes the same wrapped cells at the same offsets: equal
    // up to the rounding of x + 4 (f32, 5e-7 relative, times a gradient below 3).
    let sh = compile(
        "surface n() {
            float x = s * 7.3;
            Ci = color(pnoise(x, 4), pnoise(x + 4, 4), pnoise(point(x, t * 3, 0.5) + point(8, 6, 0), point(4, 3, 2)));
            Oi = color(pnoise(point(x, t * 3, 0.5), point(4, 3, 2)), noise(x), noise(x + 1e-3));
        }",
    );
    let mut g = plane(&sh, 50, 5);
    g.run().unwrap();
    for i in 0..250 {
        let c = g.get_v3("Ci", i).unwrap();
        let o = g.get_v3("Oi", i).unwrap();
        assert!((c[0] - c[1]).abs() < 1e-4, "{i}: {c:?}");
        assert!((c[2] - o[0]).abs() < 1e-4, "{i}: {c:?} {o:?}");
        assert!((o[1] - o[2]).abs() < 0.01, "{i}: continuity {o:?}");
    }
}

#[test]
fn open_array_formals_and_categories_of_noise() {
    // A function taking any length of array passes it whole to spline.
    let sh = compile(
        "float through(float x; float k[]) { return spline(\"linear\", x, k); }
         surface t() { float k[6] = {9, 0, 2, 4, 6, 9}; Ci = through(0.5, k); }",
    );
    let mut g = GridContext::new(&sh, 1, 1);
    g.run().unwrap();
    // Linear through the interior knots 0 2 4 6 at the middle: 3.
    let c = g.get_v3("Ci", 0).unwrap();
    assert!(near(c, [3.0; 3], 1e-6), "{c:?}");
    // 2D noise and vector/point results: in range, 0.5 on the lattice.
    let v = one(
        "vector v = noise(2.0, 3.0); point p = noise(0.25, 0.5); Ci = color(xcomp(v), ycomp(p), noise(4.0));",
    );
    assert!(near([v[0], v[2], 0.0], [0.5, 0.5, 0.0], 0.0), "{v:?}");
    assert!((0.0..=1.0).contains(&v[1]));
}

#[test]
fn message_passing_from_the_renderer() {
    let sh = compile(
        "surface m() {
            float kd = 0, fov = 0, missing = 5;
            string name = \"\";
            float a = surface(\"Kd\", kd) + option(\"fov\", fov) + attribute(\"none\", missing);
            float b = rendererinfo(\"renderer\", name) + textureinfo(\"map.tx\", \"channels\", fov);
            Ci = color(a, kd + missing, fov); Oi = color(b, match(\"reyes\", name), 0);
        }",
    );
    let mut g = GridContext::new(&sh, 1, 1);
    g.set_message("surface", "Kd", reyes_sl::exec::Value::Num(reyes_sl::exec::Num::scalar(0.5)));
    g.set_message("option", "fov", reyes_sl::exec::Value::Num(reyes_sl::exec::Num::scalar(45.0)));
    g.set_message("rendererinfo", "renderer", reyes_sl::exec::Value::Str("reyes-render".into()));
    g.set_message(
        "textureinfo",
        "map.tx:channels",
        reyes_sl::exec::Value::Num(reyes_sl::exec::Num::scalar(3.0)),
    );
    g.run().unwrap();
    // Two answers found (Kd, fov), one not (missing keeps 5); then renderer and channels.
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [2.0, 5.5, 3.0]);
    assert_eq!(g.get_v3("Oi", 0).unwrap(), [2.0, 1.0, 0.0]);
}
