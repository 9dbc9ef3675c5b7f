//! Robustness law: no source makes the front end panic or loop. Random bytes, random token
//! soups and random mutations of valid shaders are compiled; every error displays as one line
//! with a position (or a path, for I/O).

mod common;

use common::mutate;
use proptest::prelude::*;
use reyes_sl::compile_str;

/// A valid shader touching most constructs.
const VALID: &str = r#"#define SQ(x) ((x) * (x))
#define CAT(a, b) a ## b
#define STR(x) #x
#if defined(SQ) && 1 + 1 == 2
float helper(float a; output color c) { c = color (a, a, a); return SQ(a); }
#else
#error no
#endif
surface test(float Ka = 1, Kd = .5; varying color tint = 1; string map = "m.tex"; float arr[2] = {1, 2};
             output varying float extra = 0;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color Ct = tint, C = 0;
    float i, x = helper(s, Ct);
    uniform float CAT(un, iq) = 1;
    for (i = 0; i < 3; i += 1) { if (i > 1) break; else continue; }
    while (x > 10) x /= 2;
    if (map != "") Ct *= color texture(map[0], s, t, "blur", 0.01);
    illuminance("cat", P, Nf, PI / 2) { C += Cl * (normalize(L) . Nf); }
    point Pw = point "world" (1, 2, 3); color h = color "hsv" (0.5, 1, 1);
    matrix m = matrix "shader" 1; vector cr = (Pw - P) ^ V;
    printf(STR(done %f\n), x);
    Oi = Os; Ci = Os * Ct * (Ka * ambient() + Kd * diffuse(Nf)) + C + (x > 1 ? 0 : 1) * arr[1];
}
"#;

const SNIPPETS: &[&str] = &[
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    ";",
    ",",
    ".",
    "^",
    "?",
    ":",
    "=",
    "+=",
    "#",
    "##",
    "\n#if 1\n",
    "\n#endif\n",
    "\n#define X(",
    "\\\n",
    "\"",
    "/*",
    "*/",
    "//",
    "1e",
    "1e99",
    "surface",
    "light",
    "float",
    "uniform",
    "varying",
    "output",
    "extern",
    "return",
    "break 2;",
    "illuminance(",
    "texture(",
    "noise(",
    "P",
    "Ci",
    "L",
    "point \"world\"",
    "color",
    "matrix",
    "@",
    "\u{1}",
    "é",
    "0.5f",
    "x++",
    "{1,2}",
    "(1,2,3)",
    "if (",
    "else",
    "while(s>0)",
    "for(;;)",
    "SQ(",
    "CAT(,)",
];

fn check(src: &str) {
    match compile_str("fuzz.sl", src, &[]) {
        Ok(_) => {}
        Err(e) => {
            let msg = e.to_string();
            assert!(!msg.contains('\n'), "not one line: {msg}");
            assert!(
                msg.starts_with("fuzz.sl:") || msg.starts_with("<command line>:"),
                "no position: {msg}"
            );
        }
    }
}

#[test]
fn the_valid_shader_compiles() {
    compile_str("fuzz.sl", VALID, &[]).unwrap();
}

#[test]
fn deep_nesting_is_refused_not_overflowed() {
    let deep =
        format!("surface s() {{ float x = {}1{}; }}", "(".repeat(20_000), ")".repeat(20_000));
    check(&deep);
    let ifs = format!("surface s() {{ {} Ci = 1; }}", "if (s > 0) ".repeat(20_000));
    check(&ifs);
    let blocks = format!("surface s() {{ {} }}", "{".repeat(20_000));
    check(&blocks);
    let neg = format!("surface s() {{ float x = {}1; }}", "-".repeat(20_000));
    check(&neg);
    let chain = format!("surface s() {{ float x = 1{}; }}", " + 1".repeat(50_000));
    check(&chain);
    let assigns = format!("surface s() {{ float x; x{} 1; }}", " = x".repeat(50_000));
    check(&assigns);
    let conds = format!("surface s() {{ float x = {} 1; }}", "s > 0 ? 1 :".repeat(50_000));
    check(&conds);
    let macros = format!(
        "#define F(x) x\nsurface s() {{ float x = {}1{}; }}",
        "F(".repeat(1_000),
        ")".repeat(1_000)
    );
    check(&macros);
    // Exponential macro expansion is stopped.
    let mut bomb = String::from("#define A0 x x\n");
    for i in 1..40 {
        bomb.push_str(&format!("#define A{i} A{} A{}\n", i - 1, i - 1));
    }
    bomb.push_str("surface s() { A39 }");
    check(&bomb);
    // Moderate nesting is fine.
    let ok = format!("surface s() {{ float x = {}1{}; }}", "(".repeat(150), ")".repeat(150));
    compile_str("fuzz.sl", &ok, &[]).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn token_soup_never_panics(parts in proptest::collection::vec(proptest::sample::select(SNIPPETS), 0..60)) {
        check(&parts.join(" "));
    }

    #[test]
    fn mutations_of_valid_source_never_panic(
        edits in proptest::collection::vec((0usize..2000, proptest::sample::select(SNIPPETS), 0usize..4), 1..6)
    ) {
        let src = mutate(VALID, &edits);
        check(&src);
    }

    #[test]
    fn standard_shaders_mutated_never_panic(
        which in 0usize..15, at in 0usize..1500, snippet in proptest::sample::select(SNIPPETS)
    ) {
        let mut src = reyes_sl::shaders::STANDARD[which].1.to_string();
        let mut i = at % (src.len() + 1);
        while !src.is_char_boundary(i) { i -= 1; }
        src.insert_str(i, snippet);
        check(&src);
    }
}
