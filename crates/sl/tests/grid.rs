//! The grid machine against formulas: globals, derivatives, control flow under masks,
//! parameters, robustness.

mod common;

use common::*;
use reyes_sl::exec::{ExecError, GridContext, Num, Value};

#[test]
fn ci_is_s_t() {
    // No arithmetic: the values are copied, so they are exact.
    let (nu, nv) = (5, 4);
    let ci = run_ci("surface st() { Ci = color(s, t, 0); }", nu, nv);
    for (i, c) in ci.iter().enumerate() {
        let (u, v) = uv(i, nu, nv);
        assert_eq!(*c, [u, v, 0.0], "point {i}");
    }
}

#[test]
fn u_v_du_dv_and_derivatives_on_a_bilinear_grid() {
    let (nu, nv) = (9, 7);
    let ci = run_ci("surface d() { Ci = color(u, v, du); Oi = color(dv, Du(s), Dv(t)); }", nu, nv);
    let sh = common::compile("surface d() { Oi = color(dv, Du(s), Dv(t)); Ci = color(u, v, du); }");
    let mut g = plane(&sh, nu, nv);
    g.run().unwrap();
    for (i, c) in ci.iter().enumerate() {
        let (u, v) = uv(i, nu, nv);
        assert_eq!(*c, [u, v, 1.0 / 8.0]);
        let o = g.get_v3("Oi", i).unwrap();
        // s = u is linear, so every difference quotient is 1 up to the rounding of s (f32,
        // relative 6e-8, divided by du = 1/8: about 1e-6).
        assert!(close(o[0], 1.0 / 6.0, 0.0), "{o:?}");
        assert!(close(o[1], 1.0, 1e-5) && close(o[2], 1.0, 1e-5), "{i}: {o:?}");
    }
}

#[test]
fn centred_inside_one_sided_at_the_edges() {
    // Du(s*s): the centred difference of a quadratic is exact (2s); the one-sided one at the
    // edges is off by du (s=0: (du^2 - 0)/du = du; s=1: (1 - (1-du)^2)/du = 2 - du).
    let nu = 11;
    let ci = run_ci("surface d() { Ci = Du(s * s); }", nu, 3);
    let du = 0.1f32;
    for (i, c) in ci.iter().enumerate().take(nu) {
        let s = i as f32 * du;
        let want = match i {
            0 => du,
            10 => 2.0 - du,
            _ => 2.0 * s,
        };
        assert!(close(c[0], want, 1e-4), "{i}: {} vs {want}", c[0]);
    }
}

#[test]
fn area_sums_to_the_plane() {
    // area(P) is the area of the micropolygon du x dv at each point; the (nu-1)(nv-1)
    // points that start a micropolygon tile the plane W x H = 6. Each term is exact to f32
    // rounding (1e-7 relative), so the sum of 80 is good to 1e-4.
    let (nu, nv) = (9, 11);
    let sh = common::compile(
        "surface a() { Ci = area(P); normal nn = calculatenormal(P); Oi = color(xcomp(nn), ycomp(nn), zcomp(nn)); }",
    );
    let mut g = plane(&sh, nu, nv);
    g.run().unwrap();
    let mut sum = 0.0;
    for j in 0..nv - 1 {
        for i in 0..nu - 1 {
            sum += g.get_v3("Ci", j * nu + i).unwrap()[0];
        }
    }
    assert!(close(sum, W * H, 1e-4), "{sum}");
    // calculatenormal = Du(P) ^ Dv(P) = (W,0,0) ^ (0,H,0) = (0,0,W H).
    let n = g.get_v3("Oi", 12).unwrap();
    assert!(close(n[2], W * H, 1e-4) && n[0].abs() < 1e-5, "{n:?}");
}

/// The nest below, computed directly.
fn nest(s: f32, t: f32) -> (f32, f32) {
    let (mut x, mut k) = (0.0f32, 0.0f32);
    while k < 10.0 {
        k += 1.0;
        if s > 0.5 {
            if k > 3.0 {
                break;
            }
            x += 1.0;
        } else {
            x += 2.0;
            if k >= 5.0 + t * 4.0 {
                break;
            }
            if t > 0.5 {
                continue;
            }
            x += 10.0;
        }
    }
    (x, k)
}

#[test]
fn varying_if_while_break_continue() {
    let src = "surface nest() {
        float x = 0, k = 0;
        while (k < 10) {
            k += 1;
            if (s > 0.5) { if (k > 3) break; x += 1; }
            else { x += 2; if (k >= 5 + t * 4) break; if (t > 0.5) continue; x += 10; }
        }
        Ci = color(x, k, 0);
    }";
    let (nu, nv) = (6, 5);
    for (i, c) in run_ci(src, nu, nv).iter().enumerate() {
        let (s, t) = uv(i, nu, nv);
        let (x, k) = nest(s, t);
        assert_eq!((c[0], c[1]), (x, k), "s {s} t {t}");
    }
}

#[test]
fn break_two_levels_for_loops_and_return() {
    let src = "
    float f(float a) { if (a > 0.5) return a * 10; return -a; }
    surface nest() {
        float x = 0, i, j;
        for (i = 0; i < 5; i += 1) {
            for (j = 0; j < 5; j += 1) {
                if (i * 5 + j >= s * 20) break 2;
                if (j > t * 4) continue 2;
                x += 1;
            }
        }
        Ci = color(x, f(s), i);
    }";
    let (nu, nv) = (5, 5);
    for (i, c) in run_ci(src, nu, nv).iter().enumerate() {
        let (s, t) = uv(i, nu, nv);
        let (mut x, mut ii) = (0.0f32, 0.0f32);
        'outer: while ii < 5.0 {
            let mut j = 0.0f32;
            while j < 5.0 {
                if ii * 5.0 + j >= s * 20.0 {
                    break 'outer;
                }
                if j > t * 4.0 {
                    ii += 1.0;
                    continue 'outer;
                }
                x += 1.0;
                j += 1.0;
            }
            ii += 1.0;
        }
        let f = if s > 0.5 { s * 10.0 } else { -s };
        assert_eq!(*c, [x, f, ii], "s {s} t {t}");
    }
}

#[test]
fn checkerboard_from_mod() {
    let (nu, nv) = (17, 13);
    let ci = run_ci(
        "surface checker(float freq = 4) {
            float c = mod(floor(s * freq) + floor(t * freq), 2);
            if (c < 0.5) Ci = color(1, 0, 0); else Ci = color(0, 0, 1);
        }",
        nu,
        nv,
    );
    for (i, c) in ci.iter().enumerate() {
        let (s, t) = uv(i, nu, nv);
        let even = ((s * 4.0).floor() + (t * 4.0).floor()) as i32 % 2 == 0;
        assert_eq!(*c, if even { [1.0, 0.0, 0.0] } else { [0.0, 0.0, 1.0] }, "{i}");
    }
}

#[test]
fn parameters_defaults_outputs() {
    let sh = common::compile(
        "surface p(float Kd = 2; float Ks = Kd * 3; output varying float r = 0;) {
            r = s * Ks; Ci = Kd;
        }",
    );
    let mut g = plane(&sh, 3, 3);
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [2.0; 3]);
    assert_eq!(g.param("r").unwrap().num().f(2), 6.0);
    g.set_param("Kd", Value::Num(Num::scalar(1.0))).unwrap();
    g.run().unwrap();
    // Ks's default sees the Kd set: 3; r = s * 3 at s = 1.
    assert_eq!(g.param("r").unwrap().num().f(2), 3.0);
    assert!(g.set_param("nope", Value::Num(Num::scalar(1.0))).is_err());
}

#[test]
fn uniform_work_runs_once() {
    // A uniform loop of 1000 iterations over a 1000-point grid: the count of instructions
    // does not scale with the grid.
    let sh = common::compile(
        "surface u() { uniform float k = 0, x = 0; while (k < 1000) { k += 1; x += k; } Ci = x; }",
    );
    let mut g = GridContext::new(&sh, 40, 25);
    let stats = g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 999).unwrap()[0], 500_500.0);
    assert!(stats.instructions < 20_000, "{}", stats.instructions);
}

#[test]
fn budget_stops_a_runaway_loop() {
    let sh = common::compile("surface spin() { float x = 0; while (1) { x += s; } Ci = x; }");
    let mut g = plane(&sh, 4, 4);
    g.set_budget(100_000);
    let e = g.run().unwrap_err();
    assert!(matches!(e, ExecError::Budget { .. }));
    assert!(e.to_string().starts_with("shader \"spin\": instruction budget of 100000"), "{e}");
}

#[test]
fn ieee_results_counted_never_a_panic() {
    let sh = common::compile(
        "surface bad() {
            float a[3] = {1, 2, 3};
            float z = 0;
            float x = 1 / z + sqrt(-1) + log(0);
            float m = -1; float y = a[s * 10] + a[m];
            Ci = color(x, y, inversesqrt(0));
        }",
    );
    let mut g = plane(&sh, 3, 3);
    let st = g.run().unwrap();
    assert!(g.get_v3("Ci", 0).unwrap()[0].is_nan());
    // y: a[s*10] clamps to a[2] where s*10 > 2, a[-1] to a[0]: 3 + 1 at s = 1.
    assert_eq!(g.get_v3("Ci", 2).unwrap()[1], 4.0);
    assert!(st.nonfinite >= 9, "{st:?}");
    assert!(st.index_clamped >= 2, "{st:?}");
}

#[test]
fn input_errors() {
    let sh = common::compile("surface c() { Ci = Cs; }");
    let mut g = GridContext::new(&sh, 2, 2);
    assert!(g.set_varying("Cs", &[1.0; 3]).is_err());
    assert!(g.set_uniform("nope", &[1.0]).is_err());
    g.set_uniform("Cs", &[0.5, 0.25, 1.0]).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 3).unwrap(), [0.5, 0.25, 1.0]);
}

#[test]
fn deriv_and_derivatives_under_a_mask() {
    // Deriv(s*s, s) = Du(s^2)/Du(s) + Dv(s^2)/Dv(s); Dv(s) = 0 drops the second term: 2s
    // inside (centred differences exact for quadratics), to rounding (1e-5).
    let (nu, nv) = (11, 3);
    let ci = run_ci(
        "surface d() {
            Ci = color(Deriv(s * s, s), 0, 0);
            if (s > 0.45) Ci = color(Deriv(s * s, s), Du(s), 1);
        }",
        nu,
        nv,
    );
    for (i, c) in ci.iter().enumerate().take(nu) {
        let s = i as f32 / 10.0;
        if (1..10).contains(&i) && i != 5 {
            assert!(close(c[0], 2.0 * s, 1e-4), "{i}: {c:?}");
        }
        // Under the mask, s = 0.5 has no active left neighbour: one-sided, (0.36-0.25)/0.1.
        if i == 5 {
            assert!(close(c[0], 1.1, 1e-4), "{c:?}");
            assert!(close(c[1], 1.0, 1e-4), "{c:?}");
        }
    }
}

#[test]
fn random_is_in_range_and_varies() {
    let sh = common::compile("surface r() { Ci = color(random(), random(), 0); }");
    let mut g = plane(&sh, 16, 16);
    g.run().unwrap();
    let v: Vec<[f32; 3]> = (0..256).map(|i| g.get_v3("Ci", i).unwrap()).collect();
    assert!(v.iter().all(|c| (0.0..1.0).contains(&c[0]) && (0.0..1.0).contains(&c[1])));
    // Uniform in [0, 1): mean 0.5, sd of the mean of 256 is 0.29/16 = 0.018; 0.08 is 4 sd.
    let mean = v.iter().map(|c| c[0]).sum::<f32>() / 256.0;
    assert!((mean - 0.5).abs() < 0.08, "{mean}");
    assert!(v.iter().any(|c| c[0] != c[1]));
}

#[test]
fn returns_under_different_masks() {
    let ci = run_ci(
        "float f(float a) { if (a < 0.3) return 1; if (a < 0.6) return a; return 3; }
         surface r() { Ci = f(s); }",
        11,
        2,
    );
    for (i, c) in ci.iter().enumerate().take(11) {
        let s = i as f32 / 10.0;
        let want = if s < 0.3 {
            1.0
        } else if s < 0.6 {
            s
        } else {
            3.0
        };
        assert_eq!(c[0], want, "{i}");
    }
}

#[test]
fn parameter_values_are_checked() {
    let sh = common::compile(
        "surface p(color c = 1; float a[2] = {1, 2}; string m = \"\"; varying color vc = 0;) {
            Ci = c + vc;
        }",
    );
    let mut g = GridContext::new(&sh, 2, 2);
    assert!(g.set_param("c", Value::Num(Num::uniform(&[1.0, 2.0]))).is_err());
    assert!(g.set_param("c", Value::Num(Num { w: 3, varying: true, data: vec![0.0; 9] })).is_err());
    assert!(g.set_param("c", Value::Str("x".into())).is_err());
    assert!(g.set_param("a", Value::Num(Num::scalar(1.0))).is_err());
    // c is uniform (the default): a value per point is refused, not silently cut to one.
    let e = g.set_param("c", Value::Num(Num { w: 3, varying: true, data: vec![0.5; 12] }));
    assert!(e.unwrap_err().to_string().contains("declared varying"));
    assert!(g.set_param("m", Value::Str("x".into())).is_ok());
    let two = Value::Array(vec![Value::Num(Num::scalar(3.0)), Value::Num(Num::scalar(4.0))]);
    assert!(g.set_param("a", two).is_ok());
    g.set_param("vc", Value::Num(Num { w: 3, varying: true, data: vec![0.5; 12] })).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 3).unwrap(), [1.5; 3]);
    let mut big = GridContext::new(&sh, 1 << 13, 1 << 13);
    assert!(big.run().unwrap_err().to_string().contains("over the limit"));
}

#[test]
fn set_parametric_is_the_dicer_grid() {
    // u from 0.5 to 1 over 5 columns (du = 0.125), v from 0 to 2 over 3 rows (dv = 1); the
    // last column and row land exactly on the ends.
    let sh =
        common::compile("surface p() { Ci = color(u, v, Du(s) * du); Oi = color(du, dv, t); }");
    let mut g = GridContext::new(&sh, 5, 3);
    g.set_parametric(0.5, 1.0, 0.0, 2.0).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 4).unwrap(), [1.0, 0.0, 0.125]);
    assert_eq!(g.get_v3("Ci", 14).unwrap(), [1.0, 2.0, 0.125]);
    assert_eq!(g.get_v3("Ci", 6).unwrap(), [0.625, 1.0, 0.125]);
    assert_eq!(g.get_v3("Oi", 7).unwrap(), [0.125, 1.0, 1.0]);
}
