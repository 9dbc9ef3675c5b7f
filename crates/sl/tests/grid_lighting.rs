//! `ambient`, `diffuse`, `specular` and `phong` on the grid machine (computed a block of
//! points at a time) give, to the bit, what the point-by-point formulas give: random
//! normals, viewing vectors, light directions and colours, lights that reach some points
//! only, a light kept out of the highlights at some points, under a varying `if`, on a grid
//! whose size is not a multiple of the block.

use reyes_sl::exec::light::specularbrdf;
use reyes_sl::exec::{ExecError, GridContext, LightQuery, LightSample, Lights, Num, Value};

type V3 = [f32; 3];

/// A small deterministic generator (xorshift), floats in [-1, 1).
struct Rng(u64);

impl Rng {
    fn f(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    }

    fn v(&mut self, n: usize) -> Vec<f32> {
        (0..n).map(|_| self.f()).collect()
    }
}

fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn scale(a: V3, k: f32) -> V3 {
    a.map(|x| x * k)
}

fn normalize(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    if l > 0.0 { scale(a, 1.0 / l) } else { a }
}

fn at(d: &[f32], i: usize) -> V3 {
    [d[3 * i], d[3 * i + 1], d[3 * i + 2]]
}

/// Two directional lights (varying `L` and `Cl`, each reaching a random part of the grid,
/// the second kept out of the highlights where its `__nonspecular` is 1) and an ambient one.
struct Random {
    lights: Vec<LightSample>,
}

impl Lights for Random {
    fn lights(&mut self, _q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError> {
        Ok(self.lights.clone())
    }
}

fn random_lights(n: usize, rng: &mut Rng) -> Vec<LightSample> {
    let mut out = Vec::new();
    for k in 0..2 {
        let lit = (0..n).map(|_| rng.f() > -0.6).collect();
        let nonspec = (0..n).map(|_| if rng.f() > 0.3 { 1.0 } else { 0.0 }).collect();
        let mut l = rng.v(3 * n);
        // A zero direction at one point: the normalisation leaves it alone.
        l[..3].fill(0.0);
        out.push(LightSample {
            ambient: false,
            l: Num { w: 3, varying: true, data: l },
            cl: Num { w: 3, varying: true, data: rng.v(3 * n).iter().map(|x| x + 1.0).collect() },
            ol: Num::zeros(3, false, n),
            lit,
            outputs: if k == 1 {
                vec![(
                    "__nonspecular".into(),
                    Value::Num(Num { w: 1, varying: true, data: nonspec }),
                )]
            } else {
                Vec::new()
            },
        });
    }
    out.push(LightSample {
        ambient: true,
        l: Num::zeros(3, false, n),
        cl: Num::uniform(&[0.25, 0.5, 0.75]),
        ol: Num::zeros(3, false, n),
        lit: vec![true; n],
        outputs: Vec::new(),
    });
    out
}

const SHADER: &str = "
surface lit(varying vector V = 0; varying float r = 0.1; float e = 20;
            output varying color cd = 0; output varying color cs = 0;
            output varying color cp = 0; output varying color ca = 0)
{
    if (s > -0.3) {
        cd = diffuse(N);
        cs = specular(N, V, r);
        cp = phong(N, V, e);
        ca = ambient();
    }
}";

/// The point-by-point sums, as the lighting functions are defined.
fn reference(model: &str, s: &[LightSample], nn: V3, v: V3, x: f32, i: usize) -> V3 {
    let mut out = [0.0f32; 3];
    for s in s {
        if (model == "ambient") != s.ambient || !s.lit[i] {
            continue;
        }
        let nonspec = s.outputs.first().is_some_and(|(_, f)| f.num().f(i) != 0.0);
        if nonspec && model != "diffuse" {
            continue;
        }
        let cl = s.cl.v3(i);
        let k = if model == "ambient" {
            1.0
        } else {
            let ls = normalize(scale(s.l.v3(i), -1.0));
            let nf = normalize(nn);
            let cos = dot(nf, ls);
            if cos <= 0.0 {
                continue;
            }
            match model {
                "diffuse" => cos,
                "specular" => specularbrdf(ls, nf, v, x),
                _ => {
                    let vv = normalize(v);
                    let r = scale(vv, -1.0);
                    let r = [0, 1, 2].map(|c| r[c] - nf[c] * (2.0 * dot(r, nf)));
                    dot(r, ls).max(0.0).powf(x)
                }
            }
        };
        for c in 0..3 {
            out[c] += cl[c] * k;
        }
    }
    out
}

#[test]
fn lighting_functions_match_the_formulas_to_the_bit() {
    let sh = reyes_sl::compile_str("lit.sl", SHADER, &[]).unwrap_or_else(|e| panic!("{e}"));
    for (nu, nv) in [(13, 7), (1, 1), (8, 2), (5, 3)] {
        let n = nu * nv;
        let mut rng = Rng(0x2545_f491_4f6c_dd1d ^ n as u64);
        let (svals, nn, vv) = (rng.v(n), rng.v(3 * n), rng.v(3 * n));
        let rough: Vec<f32> = rng.v(n).iter().map(|x| 0.05 + 0.2 * (x + 1.0)).collect();
        let mut lights = Random { lights: random_lights(n, &mut rng) };
        let samples = lights.lights.clone();
        let mut g = GridContext::new(&sh, nu, nv);
        g.set_varying("s", &svals).unwrap();
        g.set_varying("N", &nn).unwrap();
        g.set_varying("P", &rng.v(3 * n)).unwrap();
        g.set_param("V", Value::Num(Num { w: 3, varying: true, data: vv.clone() })).unwrap();
        g.set_param("r", Value::Num(Num { w: 1, varying: true, data: rough.clone() })).unwrap();
        g.set_lights(&mut lights);
        g.run().unwrap();
        for (name, model) in
            [("cd", "diffuse"), ("cs", "specular"), ("cp", "phong"), ("ca", "ambient")]
        {
            let got = g.param(name).unwrap().num().clone();
            let lit = (0..n).filter(|&i| got.v3(i) != [0.0; 3]).count();
            assert!(n < 20 || lit > n / 8, "{nu}x{nv} {model}: lit at {lit} of {n} points only");
            for i in 0..n {
                let want = if svals[i] > -0.3 {
                    let x = if model == "phong" { 20.0 } else { rough[i] };
                    reference(model, &samples, at(&nn, i), at(&vv, i), x, i)
                } else {
                    [0.0; 3]
                };
                assert_eq!(
                    got.v3(i).map(f32::to_bits),
                    want.map(f32::to_bits),
                    "{nu}x{nv} {model} at {i}: {:?} vs {want:?}",
                    got.v3(i)
                );
            }
        }
    }
}

#[test]
fn normalize_matches_the_formula_to_the_bit() {
    // Blocks of consecutive points run together; the rest (and partial masks) point by point.
    let src = "surface nz(output varying vector o = 0; output varying vector h = 0) {
        o = normalize(N);
        if (s > 0) { h = normalize(N); }
    }";
    let sh = reyes_sl::compile_str("nz.sl", src, &[]).unwrap_or_else(|e| panic!("{e}"));
    for (nu, nv) in [(13, 7), (8, 1), (3, 1)] {
        let n = nu * nv;
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ n as u64);
        let mut nn = rng.v(3 * n);
        nn[3..6].fill(0.0);
        let svals = rng.v(n);
        let mut g = GridContext::new(&sh, nu, nv);
        g.set_varying("N", &nn).unwrap();
        g.set_varying("s", &svals).unwrap();
        g.run().unwrap();
        let (o, h) = (g.param("o").unwrap().num().clone(), g.param("h").unwrap().num().clone());
        for (i, sv) in svals.iter().enumerate() {
            let want = normalize(at(&nn, i)).map(f32::to_bits);
            assert_eq!(o.v3(i).map(f32::to_bits), want, "{nu}x{nv} at {i}");
            let want_h = if *sv > 0.0 { want } else { [0; 3] };
            assert_eq!(h.v3(i).map(f32::to_bits), want_h, "{nu}x{nv} masked at {i}");
        }
    }
}
