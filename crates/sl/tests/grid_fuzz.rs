//! Robustness law of the grid machine: no shader the checker accepts, and no input values
//! (NaN, infinities, huge numbers), make a run panic; a run ends (the budget) with results or
//! with an error naming the shader.

mod common;

use common::*;
use proptest::prelude::*;
use reyes_sl::exec::{GridContext, Num, ShaderLight, ShaderLights, Spaces, Value};
use reyes_sl::shaders::STANDARD;
use reyes_sl::{ShaderKind, compile_str};

/// A shader touching most of the machine: user functions with outputs and returns under
/// varying control, every loop form, arrays, the library, lighting.
const VALID: &str = r#"
float helper(float a; output color c) { c = color(a, a, a); if (a > 0.5) return a * a; return -a; }
surface test(float Ka = 1, Kd = .5; varying color tint = 1; float arr[3] = {1, 2, 3};
             output varying float extra = 0;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color Ct = tint, C = 0;
    float i, j, x = helper(s, Ct);
    for (i = 0; i < 4; i += 1) { for (j = 0; j < 3; j += 1) { if (j > t * 3) continue 2; if (i * j > s * 4) break 2; x += arr[i]; } }
    while (x > 10) x /= 2;
    illuminance(P, Nf, PI / 2) { C += Cl * (normalize(L) . Nf); }
    point Pw = point "world" (1, 2, 3); color h = color "hsv" (0.5, 1, 1);
    matrix m = matrix "shader" 1; vector cr = (Pw - P) ^ V;
    extra = noise(P * 4) + pnoise(s * 8, 4) + cellnoise(t * 5) + spline(s, 0, 1, 4, 9) + Du(s) + area(P);
    Ci = Os * Ct * (Ka * ambient() + Kd * diffuse(Nf)) + specular(Nf, V, 0.2) + C + h * mod(x, 3);
    Ci += (x > 1 ? 0 : 1) * arr[s * 5] + filterstep(0.5, s) + mix(color 0, color 1, smoothstep(0, 1, t));
    Oi = Os * clamp(length(cr), 0, 1) + determinant(m) * 0;
}
"#;

const SNIPPETS: &[&str] = &[
    "(",
    ")",
    "{",
    "}",
    ";",
    ",",
    "+",
    "-",
    "*",
    "/",
    ".",
    "^",
    "?",
    ":",
    "=",
    "+=",
    "0",
    "1e38",
    "-1",
    "s",
    "t",
    "P",
    "x",
    "break;",
    "continue;",
    "return 1;",
    "if (s > 0.5)",
    "else",
    "while (x < 1e30) x *= 2;",
    "while (s > 0)",
    "for (;;)",
    "sqrt(-1)",
    "1/0",
    "arr[9]",
    "noise(",
    "Du(",
    "log(0)",
    "pow(-2, 0.5)",
];

fn lights() -> ShaderLights {
    let light = |name: &str, params: Vec<(String, Value)>| ShaderLight {
        shader: std::sync::Arc::new(compile(reyes_sl::shaders::standard(name).unwrap())),
        params,
        spaces: Spaces::default(),
        categories: vec![],
    };
    ShaderLights {
        lights: vec![
            light("ambientlight", vec![]),
            light("pointlight", vec![("from".into(), Value::Num(Num::uniform(&[1.0, 1.0, -1.0])))]),
            light("spotlight", vec![("from".into(), Value::Num(Num::uniform(&[1.0, 1.0, -1.0])))]),
            light("distantlight", vec![]),
        ],
    }
}

/// Compiles and runs; a compile error is fine, a run error must name the shader.
fn run(src: &str, nu: usize, nv: usize, poison: Option<f32>) {
    let Ok(sh) = compile_str("fuzz.sl", src, &[]) else { return };
    let mut ls = lights();
    let mut g = plane(&sh, nu, nv);
    g.set_budget(200_000);
    g.set_lights(&mut ls);
    if let Some(x) = poison {
        let n = nu * nv;
        let mut p: Vec<f32> = (0..3 * n).map(|i| if i % 7 == 3 { x } else { i as f32 }).collect();
        p[0] = x;
        g.set_varying("P", &p).unwrap();
        g.set_varying("s", &p[..n]).unwrap();
        g.set_uniform("du", &[x]).unwrap();
    }
    if let Err(e) = g.run() {
        let m = e.to_string();
        assert!(m.starts_with(&format!("shader \"{}\"", sh.name)) && !m.contains('\n'), "{m}");
    }
}

#[test]
fn the_valid_shader_runs() {
    let sh = compile(VALID);
    let mut ls = lights();
    let mut g = plane(&sh, 6, 5);
    g.set_lights(&mut ls);
    let st = g.run().unwrap();
    assert!(st.instructions > 100);
    assert!(g.param("extra").unwrap().varying());
}

#[test]
fn every_standard_shader_runs() {
    for (name, src) in STANDARD {
        let sh = compile(src);
        let mut ls = lights();
        let mut g = plane(&sh, 4, 3);
        if sh.kind == ShaderKind::Light {
            g.set_varying("Ps", &[0.5; 36]).unwrap();
        }
        g.set_lights(&mut ls);
        g.run().unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn poisoned_inputs() {
    for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 1e38, -1e38, 0.0, f32::MIN_POSITIVE] {
        run(VALID, 5, 4, Some(x));
        for (_, src) in STANDARD {
            run(src, 3, 3, Some(x));
        }
    }
}

#[test]
fn one_point_and_one_row_grids() {
    for (nu, nv) in [(1, 1), (1, 7), (7, 1)] {
        let sh = compile(VALID);
        let mut g = GridContext::new(&sh, nu, nv);
        g.run().unwrap();
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutations_run_without_panic(
        edits in proptest::collection::vec((0usize..2400, proptest::sample::select(SNIPPETS), 0usize..4), 1..5)
    ) {
        let src = mutate(VALID, &edits);
        run(&src, 4, 3, None);
    }

    #[test]
    fn random_inputs_run_without_panic(x in any::<f32>(), nu in 1usize..6, nv in 2usize..5) {
        run(VALID, nu.max(2), nv, Some(x));
    }
}

#[test]
fn huge_arrays_are_refused() {
    let sh = compile("surface big() { float a[1000000]; a[s] = 1; Ci = a[0]; }");
    let e = plane(&sh, 16, 16).run().unwrap_err().to_string();
    assert!(
        e.starts_with("shader \"big\": its variables need") && e.contains("over the limit"),
        "{e}"
    );
}

#[test]
fn doubling_strings_are_capped() {
    let sh = compile(
        "surface s() { string x = \"ab\"; float i; for (i = 0; i < 40; i += 1) x = concat(x, x); Ci = match(\"b$\", x); }",
    );
    let mut g = GridContext::new(&sh, 2, 2);
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [1.0; 3]);
}

#[test]
fn long_patterns_do_not_overflow() {
    let sh = compile(
        "surface s() { string x = \"a\"; float i; for (i = 0; i < 20; i += 1) x = concat(x, x); Ci = match(x, x) + match(\"a*a*a*a*a*a*a*a*a*a*a*b\", x); }",
    );
    let mut g = GridContext::new(&sh, 1, 1);
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [0.0; 3]);
}

#[test]
fn deep_nesting_runs_within_the_stack() {
    // As deep as the checker allows: expressions 120 parentheses deep, varying ifs 200 deep, run on a
    // test thread's small stack.
    let e = format!("{}s{}", "(1 + ".repeat(120), ")".repeat(120));
    let ifs = format!("{} Ci = 1;", "if (s > 0.1) ".repeat(200));
    for body in [format!("Ci = {e};"), ifs] {
        let src = format!("surface d() {{ {body} }}");
        let sh = compile_str("d.sl", &src, &[]).unwrap_or_else(|e| panic!("{e}"));
        let mut g = plane(&sh, 3, 3);
        g.run().unwrap();
    }
}

/// A random float expression over s and t from the library.
fn expr_strategy() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        Just("s".to_string()),
        Just("t".to_string()),
        Just("u".to_string()),
        (-1e3f32..1e3).prop_map(|x| format!("{x:?}")),
        Just("0".to_string()),
        Just("1e38".to_string()),
    ];
    leaf.prop_recursive(5, 40, 4, |inner| {
        let f1 = proptest::sample::select(vec![
            "sin",
            "cos",
            "tan",
            "asin",
            "acos",
            "atan",
            "sqrt",
            "exp",
            "log",
            "abs",
            "sign",
            "floor",
            "ceil",
            "round",
            "inversesqrt",
            "radians",
            "degrees",
            "noise",
            "cellnoise",
            "Du",
            "Dv",
            "filterwidth",
            "-",
        ]);
        let f2 = proptest::sample::select(vec![
            "pow",
            "mod",
            "min",
            "max",
            "step",
            "atan",
            "log",
            "pnoise",
            "filterstep",
            "noise",
            "Deriv",
        ]);
        let f3 = proptest::sample::select(vec!["clamp", "mix", "smoothstep"]);
        let ops = proptest::sample::select(vec!["+", "-", "*", "/"]);
        prop_oneof![
            (f1, inner.clone()).prop_map(|(f, a)| format!("{f}({a})")),
            (f2, inner.clone(), inner.clone()).prop_map(|(f, a, b)| format!("{f}({a}, {b})")),
            (f3, inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(f, a, b, c)| format!("{f}({a}, {b}, {c})")),
            (inner.clone(), ops, inner.clone()).prop_map(|(a, o, b)| format!("({a} {o} {b})")),
            (inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(c, a, b)| format!("({c} > 0.5 ? {a} : {b})")),
            (inner.clone(), inner.clone(), inner.clone())
                .prop_map(|(x, a, b)| format!("spline({x}, {a}, {b}, {a}, {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!(
                "length(vector({a}, {b}, 1) ^ vector(noise(point({b}, {a}, 0))))"
            )),
            (inner.clone(), inner)
                .prop_map(|(a, b)| format!("comp(ctransform(\"hsv\", color({a}, {b}, 0.5)), 0)")),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn random_library_expressions_never_panic(e in expr_strategy()) {
        let src = format!(
            "surface r() {{ float x = {e}; float k = 0; while (k < 3 && x > 0) {{ k += 1; x = x / 2; }} Ci = color(x, k, {e}); }}"
        );
        let sh = compile_str("r.sl", &src, &[]).unwrap_or_else(|err| panic!("{err}\n{src}"));
        let mut g = plane(&sh, 4, 3);
        g.set_budget(1_000_000);
        g.run().unwrap_or_else(|err| panic!("{err}\n{src}"));
    }
}
