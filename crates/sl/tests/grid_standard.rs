//! The rest of the standard shaders on the grid machine against their formulas: metal,
//! shinymetal, paintedplastic, fog, background, clamptoalpha, ambientlight, pointlight.

mod common;

use common::*;
use reyes_sl::exec::{
    ExecError, GridContext, LightQuery, LightSample, Lights, LookupKind, Num, TextureQuery,
    Textures, Value,
};
use reyes_sl::shaders::standard;

fn std_shader(name: &str) -> reyes_sl::CheckedShader {
    compile(standard(name).unwrap())
}

/// One light from straight in front of the eye (travelling +z, as the eye looks), colour 1,
/// and an ambient light of 0.25.
struct Front;

impl Lights for Front {
    fn lights(&mut self, q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError> {
        let n = q.nu * q.nv;
        let sample = |ambient: bool, cl: f32| LightSample {
            ambient,
            l: Num::uniform(&[0.0, 0.0, 1.0]),
            cl: Num::uniform(&[cl; 3]),
            ol: Num::zeros(3, false, n),
            lit: vec![true; n],
            outputs: vec![],
        };
        Ok(vec![sample(true, 0.25), sample(false, 1.0)])
    }
}

/// A map reading (0.5, 1, 2) everywhere, for texture and environment.
struct Flat;

impl Textures for Flat {
    fn lookup(&mut self, q: &TextureQuery<'_>) -> Result<Num, ExecError> {
        assert!(matches!(q.kind, LookupKind::Texture | LookupKind::Environment));
        assert_eq!(q.channels, 3);
        Ok(Num::uniform(&[0.5, 1.0, 2.0]))
    }
}

/// The specular term at point `i` of the plane for the `Front` light: Nf = -z, L = -z, V from
/// P towards the eye at (0, 0, -5).
fn spec(i: usize, nu: usize, nv: usize, roughness: f32) -> f32 {
    let (u, v) = uv(i, nu, nv);
    let e = [-W * u, -H * v, -5.0];
    let len = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
    let vv = e.map(|x| x / len);
    let h = [vv[0], vv[1], vv[2] - 1.0];
    let hl = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
    (-h[2] / hl).max(0.0).powf(8.0 / roughness)
}

#[test]
fn metal_and_shinymetal() {
    // metal: Cs (Ka amb + Ks spec); shinymetal adds Kr times the environment. pow(x, 10) of a
    // cosine near 1 keeps the relative error near 1e-6.
    let (nu, nv) = (3, 3);
    for name in ["metal", "shinymetal"] {
        let sh = std_shader(name);
        let mut lights = Front;
        let mut maps = Flat;
        let mut g = plane(&sh, nu, nv);
        g.set_lights(&mut lights);
        g.set_textures(&mut maps);
        g.set_uniform("Cs", &[1.0, 0.5, 0.25]).unwrap();
        if name == "shinymetal" {
            g.set_param("texturename", Value::Str("env".into())).unwrap();
        }
        g.run().unwrap();
        for i in 0..nu * nv {
            let s = spec(i, nu, nv, 0.1);
            let refl = if name == "shinymetal" { [0.5, 1.0, 2.0] } else { [0.0; 3] };
            let c = g.get_v3("Ci", i).unwrap();
            for (k, cs) in [1.0f32, 0.5, 0.25].iter().enumerate() {
                let want = cs * (0.25 + s + refl[k]);
                assert!(close(c[k], want, 1e-5), "{name} {i} {k}: {c:?} vs {want}");
            }
        }
    }
}

#[test]
fn paintedplastic_multiplies_the_map() {
    let (nu, nv) = (3, 3);
    let sh = std_shader("paintedplastic");
    let mut lights = Front;
    let mut maps = Flat;
    let mut g = plane(&sh, nu, nv);
    g.set_lights(&mut lights);
    g.set_textures(&mut maps);
    g.set_param("texturename", Value::Str("paint".into())).unwrap();
    g.run().unwrap();
    for i in 0..nu * nv {
        let s = spec(i, nu, nv, 0.1);
        let c = g.get_v3("Ci", i).unwrap();
        for (k, map) in [0.5f32, 1.0, 2.0].iter().enumerate() {
            // Cs = 1 times the map, (Ka amb + Kd N.L) = 0.25 + 0.5, plus Ks spec.
            let want = map * 0.75 + 0.5 * s;
            assert!(close(c[k], want, 1e-5), "{i} {k}: {c:?} vs {want}");
        }
    }
}

#[test]
fn fog_background_clamptoalpha() {
    // fog: d = 1 - exp(-|I| / distance); |I| = 5 on the axis point of a 1-point grid.
    let sh = std_shader("fog");
    let mut g = GridContext::new(&sh, 1, 1);
    g.set_uniform("I", &[0.0, 3.0, 4.0]).unwrap();
    g.set_uniform("Ci", &[1.0; 3]).unwrap();
    g.set_uniform("Oi", &[0.0; 3]).unwrap();
    g.set_param("distance", Value::Num(Num::scalar(5.0))).unwrap();
    g.run().unwrap();
    let d = 1.0 - (-1.0f32).exp();
    assert!(close(g.get_v3("Ci", 0).unwrap()[0], 1.0 - d, 1e-6));
    assert!(close(g.get_v3("Oi", 0).unwrap()[0], d, 1e-6));
    // background: Ci += (1 - alpha) bg; Oi = alpha = 1.
    let sh = std_shader("background");
    let mut g = GridContext::new(&sh, 2, 1);
    g.set_varying("alpha", &[0.25, 1.0]).unwrap();
    g.set_uniform("Ci", &[0.1; 3]).unwrap();
    g.set_param("background", Value::Num(Num::uniform(&[0.0, 0.5, 1.0]))).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [0.1, 0.1 + 0.375, 0.1 + 0.75]);
    assert_eq!(g.get_v3("Ci", 1).unwrap(), [0.1; 3]);
    assert_eq!(g.get_f("alpha", 0).unwrap(), 1.0);
    // clamptoalpha: each channel into [0, alpha].
    let sh = std_shader("clamptoalpha");
    let mut g = GridContext::new(&sh, 1, 1);
    g.set_uniform("alpha", &[0.5]).unwrap();
    g.set_uniform("Ci", &[-1.0, 0.25, 2.0]).unwrap();
    g.set_uniform("Oi", &[1.0; 3]).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [0.0, 0.25, 0.5]);
    assert_eq!(g.get_v3("Oi", 0).unwrap(), [0.5; 3]);
}

#[test]
fn light_shaders_alone() {
    // pointlight run directly: L = Ps - from, Cl = intensity lightcolor / (L . L).
    let sh = std_shader("pointlight");
    let mut g = GridContext::new(&sh, 2, 1);
    g.set_varying("Ps", &[0.0, 0.0, 2.0, 0.0, 3.0, 4.0]).unwrap();
    g.set_param("intensity", Value::Num(Num::scalar(10.0))).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("L", 1).unwrap(), [0.0, 3.0, 4.0]);
    assert_eq!(g.get_v3("Cl", 0).unwrap(), [2.5; 3]);
    assert_eq!(g.get_v3("Cl", 1).unwrap(), [0.4; 3]);
    // ambientlight: Cl = intensity lightcolor.
    let sh = std_shader("ambientlight");
    let mut g = GridContext::new(&sh, 1, 1);
    g.set_param("lightcolor", Value::Num(Num::uniform(&[1.0, 0.5, 0.0]))).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Cl", 0).unwrap(), [1.0, 0.5, 0.0]);
}
