//! A bilinear test grid: the plane P = (W u, H v, 0) over u, v in [0, 1], `nu` x `nv` vertices.
#![allow(dead_code)]

use reyes_sl::exec::GridContext;
use reyes_sl::{CheckedShader, compile_str};

pub const W: f32 = 2.0;
pub const H: f32 = 3.0;

pub fn compile(src: &str) -> CheckedShader {
    compile_str("test.sl", src, &[]).unwrap_or_else(|e| panic!("{e}"))
}

pub fn uv(i: usize, nu: usize, nv: usize) -> (f32, f32) {
    ((i % nu) as f32 / (nu - 1) as f32, (i / nu) as f32 / (nv - 1) as f32)
}

/// Sets u, v, du, dv, s, t, P, N, Ng, I, E for the plane.
pub fn plane<'a>(sh: &'a CheckedShader, nu: usize, nv: usize) -> GridContext<'a> {
    let mut g = GridContext::new(sh, nu, nv);
    let n = nu * nv;
    let (mut u, mut v, mut p, mut nn, mut inc) = (vec![], vec![], vec![], vec![], vec![]);
    for i in 0..n {
        let (a, b) = uv(i, nu, nv);
        u.push(a);
        v.push(b);
        p.extend([W * a, H * b, 0.0]);
        nn.extend([0.0, 0.0, 1.0]);
        inc.extend([W * a, H * b, 5.0]);
    }
    g.set_varying("u", &u).unwrap();
    g.set_varying("v", &v).unwrap();
    g.set_varying("s", &u).unwrap();
    g.set_varying("t", &v).unwrap();
    g.set_uniform("du", &[1.0 / (nu - 1) as f32]).unwrap();
    g.set_uniform("dv", &[1.0 / (nv - 1) as f32]).unwrap();
    g.set_varying("P", &p).unwrap();
    g.set_varying("N", &nn).unwrap();
    g.set_varying("Ng", &nn).unwrap();
    // The eye at z = -5: I from the eye to P.
    g.set_varying("I", &inc).unwrap();
    g.set_uniform("E", &[0.0, 0.0, -5.0]).unwrap();
    g
}

/// Runs `src` on the plane and returns Ci per point.
pub fn run_ci(src: &str, nu: usize, nv: usize) -> Vec<[f32; 3]> {
    let sh = compile(src);
    let mut g = plane(&sh, nu, nv);
    g.run().unwrap_or_else(|e| panic!("{e}"));
    (0..nu * nv).map(|i| g.get_v3("Ci", i).unwrap()).collect()
}

pub fn close(a: f32, b: f32, tol: f32) -> bool {
    (a - b).abs() <= tol
}

/// `valid` with each edit `(at, snippet, cut)` applied in turn: `cut` bytes from about byte
/// `at` (wrapped to the text, moved back to a character boundary) replaced by `snippet`.
pub fn mutate(valid: &str, edits: &[(usize, &str, usize)]) -> String {
    let mut src = valid.to_string();
    for &(at, snippet, cut) in edits {
        let mut i = at % (src.len() + 1);
        while !src.is_char_boundary(i) {
            i -= 1;
        }
        let mut j = (i + cut).min(src.len());
        while !src.is_char_boundary(j) {
            j -= 1;
        }
        src.replace_range(i..j, snippet);
    }
    src
}
