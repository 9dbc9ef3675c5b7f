//! The standard shaders on the grid machine against their formulas, lit by a test light
//! callback and by the standard light shaders run on the machine.

mod common;

use common::*;
use reyes_sl::exec::{
    ExecError, GridContext, LightQuery, LightSample, Lights, Num, ShaderLight, ShaderLights,
    Spaces, Value,
};
use reyes_sl::shaders::standard;

fn std_shader(name: &str) -> reyes_sl::CheckedShader {
    compile(standard(name).unwrap())
}

/// One ambient light (colour `amb`) and one distant light shining along `dir` (colour `col`).
struct TestLights {
    amb: [f32; 3],
    dir: [f32; 3],
    col: [f32; 3],
    calls: usize,
}

impl Lights for TestLights {
    fn lights(&mut self, q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError> {
        self.calls += 1;
        let n = q.nu * q.nv;
        let all = vec![true; n];
        Ok(vec![
            LightSample {
                ambient: true,
                l: Num::zeros(3, false, n),
                cl: Num::uniform(&self.amb),
                ol: Num::zeros(3, false, n),
                lit: all.clone(),
                outputs: vec![],
            },
            LightSample {
                ambient: false,
                l: Num::uniform(&self.dir),
                cl: Num::uniform(&self.col),
                ol: Num::zeros(3, false, n),
                lit: all,
                outputs: vec![],
            },
        ])
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f32; 3]) -> [f32; 3] {
    let l = dot(a, a).sqrt();
    a.map(|x| x / l)
}

#[test]
fn constant_is_os_cs() {
    let sh = std_shader("constant");
    let mut g = plane(&sh, 3, 3);
    g.set_uniform("Cs", &[0.2, 0.4, 0.6]).unwrap();
    g.set_uniform("Os", &[0.5, 0.5, 1.0]).unwrap();
    g.run().unwrap();
    // One product each: exact to f32 rounding (a product of two f32 is correctly rounded).
    assert_eq!(g.get_v3("Ci", 4).unwrap(), [0.2 * 0.5, 0.4 * 0.5, 0.6]);
    assert_eq!(g.get_v3("Oi", 4).unwrap(), [0.5, 0.5, 1.0]);
}

#[test]
fn matte_is_ambient_plus_lambert() {
    // The eye is at z = -5, so faceforward turns N = +z into Nf = -z. The light travels along
    // (-1, 0, 2): L (surface to light) = (1, 0, -2), and Nf . normalize(L) = 2/sqrt(5). Ci = Cs (Ka amb + Kd Cl N.L); a handful of f32 operations: 1e-6.
    let sh = std_shader("matte");
    let mut lights =
        TestLights { amb: [0.1, 0.1, 0.1], dir: [-1.0, 0.0, 2.0], col: [1.0, 0.5, 0.25], calls: 0 };
    let mut g = plane(&sh, 4, 4);
    g.set_lights(&mut lights);
    g.set_param("Kd", Value::Num(Num::scalar(0.8))).unwrap();
    g.set_uniform("Cs", &[1.0, 1.0, 0.5]).unwrap();
    g.run().unwrap();
    let ndl = 2.0 / 5f32.sqrt();
    let want = [0.1 + 0.8 * ndl, 0.1 + 0.8 * 0.5 * ndl, 0.5 * (0.1 + 0.8 * 0.25 * ndl)];
    for i in 0..16 {
        let c = g.get_v3("Ci", i).unwrap();
        for k in 0..3 {
            assert!(close(c[k], want[k], 1e-6), "{i}: {c:?} vs {want:?}");
        }
    }
    drop(g);
    // ambient() and diffuse() share one query of the lights per grid.
    assert_eq!(lights.calls, 1);
}

#[test]
fn plastic_adds_the_highlight() {
    // The eye at z = -5: I points +z, faceforward turns N into Nf = -z, V = -normalize(I).
    // The light travels +z from the eye's side: L = -z, so N.L = 1 and diffuse = Cl; the
    // highlight is pow(Nf . normalize(L + V), 8/roughness), as the peers compute it.
    let sh = std_shader("plastic");
    let mut lights = TestLights { amb: [0.0; 3], dir: [0.0, 0.0, 1.0], col: [1.0; 3], calls: 0 };
    let mut g = plane(&sh, 3, 3);
    g.set_lights(&mut lights);
    g.set_uniform("Cs", &[0.5, 0.25, 1.0]).unwrap();
    g.run().unwrap();
    // At the centre point (1, 1.5, 0) I = (1, 1.5, 5): V is off the axis, so compute.
    let i = 4;
    let inc = [1.0, 1.5, 5.0];
    let v = norm(inc.map(|x| -x));
    let nf = [0.0, 0.0, -1.0];
    let l = [0.0, 0.0, -1.0];
    let h = norm([l[0] + v[0], l[1] + v[1], l[2] + v[2]]);
    let spec = dot(nf, h).max(0.0).powf(8.0 / 0.1);
    let c = g.get_v3("Ci", i).unwrap();
    for (k, cs) in [0.5f32, 0.25, 1.0].iter().enumerate() {
        // Ka amb = 0; Kd = Ks = 0.5; N.L = 1. pow(x, 80) magnifies the relative error of
        // N.H (1e-7) eightyfold, 8e-6 at most: tolerance 1e-5.
        let want = cs * 0.5 + 0.5 * spec;
        assert!(close(c[k], want, 1e-5), "{k}: {c:?} vs {want}");
    }
}

#[test]
fn matte_under_the_standard_light_shaders() {
    // A pointlight 2 above the plane (z = -2, the side facing the eye, which faceforward
    // picks) and an ambientlight: Ci = Cs (amb + I / d^2 * N.L).
    let mut lights = ShaderLights {
        lights: vec![
            ShaderLight {
                shader: std::sync::Arc::new(std_shader("pointlight")),
                params: vec![
                    ("intensity".into(), Value::Num(Num::scalar(4.0))),
                    ("from".into(), Value::Num(Num::uniform(&[1.0, 1.5, -2.0]))),
                ],
                spaces: Spaces::default(),
                categories: vec![],
            },
            ShaderLight {
                shader: std::sync::Arc::new(std_shader("ambientlight")),
                params: vec![("intensity".into(), Value::Num(Num::scalar(0.25)))],
                spaces: Spaces::default(),
                categories: vec![],
            },
        ],
    };
    let sh = std_shader("matte");
    let mut g = plane(&sh, 5, 5);
    g.set_lights(&mut lights);
    g.run().unwrap();
    for i in 0..25 {
        let (u, v) = uv(i, 5, 5);
        let d = [1.0 - W * u, 1.5 - H * v, -2.0];
        let d2 = dot(d, d);
        let ndl = 2.0 / d2.sqrt();
        let want = 0.25 + 4.0 / d2 * ndl;
        let c = g.get_v3("Ci", i).unwrap();
        assert!(close(c[0], want, 1e-5), "{i}: {c:?} vs {want}");
    }
}

#[test]
fn spotlight_cone_and_illuminance_cone() {
    // A spotlight 1 above the centre pointing at the plane, cone 30 degrees: points farther
    // than tan(30 deg) from the centre get no light.
    let mut lights = ShaderLights {
        lights: vec![ShaderLight {
            shader: std::sync::Arc::new(std_shader("spotlight")),
            params: vec![
                ("from".into(), Value::Num(Num::uniform(&[1.0, 1.5, -1.0]))),
                ("to".into(), Value::Num(Num::uniform(&[1.0, 1.5, 0.0]))),
            ],
            spaces: Spaces::default(),
            categories: vec![],
        }],
    };
    let sh =
        compile("surface lit() { Ci = 0; illuminance(P, vector(0, 0, -1), PI / 2) { Ci += Cl; } }");
    let (nu, nv) = (9, 9);
    let mut g = plane(&sh, nu, nv);
    g.set_lights(&mut lights);
    g.run().unwrap();
    for i in 0..nu * nv {
        let (u, v) = uv(i, nu, nv);
        let r = ((W * u - 1.0).powi(2) + (H * v - 1.5).powi(2)).sqrt();
        let c = g.get_v3("Ci", i).unwrap()[0];
        if r > (30f32).to_radians().tan() + 1e-3 {
            assert_eq!(c, 0.0, "{i} r {r}");
        }
        if r < 1e-6 {
            // The axis: cos = 1, distance 1, smoothstep 1: Cl = 1.
            assert!(close(c, 1.0, 1e-5), "{c}");
        }
        // Everywhere the spotlight's formula: cos^2 / d^2 times the smooth edge (a dozen f32
        // operations on values near 1: 1e-5).
        let d2 = r * r + 1.0;
        let cos = 1.0 / d2.sqrt();
        let (c0, c1) = (30f32.to_radians().cos(), 25f32.to_radians().cos());
        let edge = if cos < c0 {
            0.0
        } else if cos >= c1 {
            1.0
        } else {
            let x = (cos - c0) / (c1 - c0);
            x * x * (3.0 - 2.0 * x)
        };
        assert!(close(c, cos * cos / d2 * edge, 1e-5), "{i}: {c} vs {}", cos * cos / d2 * edge);
    }
    // The illuminance cone: from +z nothing is lit.
    let sh2 =
        compile("surface lit() { Ci = 0; illuminance(P, vector(0, 0, 1), 0.5) { Ci += Cl; } }");
    let mut g = plane(&sh2, nu, nv);
    g.set_lights(&mut lights);
    g.run().unwrap();
    assert!((0..nu * nv).all(|i| g.get_v3("Ci", i).unwrap() == [0.0; 3]));
}

#[test]
fn distantlight_through_solar() {
    let mut lights = ShaderLights {
        lights: vec![ShaderLight {
            shader: std::sync::Arc::new(std_shader("distantlight")),
            params: vec![("to".into(), Value::Num(Num::uniform(&[0.0, 0.0, 1.0])))],
            spaces: Spaces::default(),
            categories: vec![],
        }],
    };
    let sh = compile("surface d() { Ci = diffuse(vector(0, 0, -1)); }");
    let mut g = GridContext::new(&sh, 2, 2);
    g.set_lights(&mut lights);
    g.run().unwrap();
    // Light travels +z, so it comes from -z: full strength on a normal facing -z.
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [1.0; 3]);
}

#[test]
fn illuminance_categories() {
    // Two distant lights, one in category "key": illuminance("key", ...) sees only it.
    let light = |intensity: f32, cats: Vec<String>| ShaderLight {
        shader: std::sync::Arc::new(std_shader("distantlight")),
        params: vec![("intensity".into(), Value::Num(Num::scalar(intensity)))],
        spaces: Spaces::default(),
        categories: cats,
    };
    let mut lights =
        ShaderLights { lights: vec![light(1.0, vec!["key".into()]), light(10.0, vec![])] };
    let sh = compile(
        "surface c() {
            Ci = 0;
            illuminance(\"key\", P) { Ci += Cl; }
            illuminance(P) { Oi += Cl; }
        }",
    );
    let mut g = GridContext::new(&sh, 2, 1);
    g.set_uniform("Os", &[0.0; 3]).unwrap();
    g.set_lights(&mut lights);
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 1).unwrap(), [1.0; 3]);
    assert_eq!(g.get_v3("Oi", 1).unwrap(), [11.0; 3]);
}

/// A procedural texture: the mean of the corners' s (texture), or a constant (others); it
/// records the channel and options it was asked for.
struct MeanS {
    seen: Vec<(String, usize, usize)>,
}

impl reyes_sl::exec::Textures for MeanS {
    fn lookup(&mut self, q: &reyes_sl::exec::TextureQuery<'_>) -> Result<Num, ExecError> {
        self.seen.push((q.name.to_string(), q.channel, q.options.len()));
        let n = q.coords[0].data.len().max(1);
        let mut out = Num::zeros(q.channels, true, n);
        for i in q.mask.iter() {
            let v = match q.kind {
                reyes_sl::exec::LookupKind::Texture => {
                    (0..4).map(|k| q.coords[2 * k].f(i)).sum::<f32>() / 4.0
                }
                _ => 1.0,
            };
            out.lane_mut(i).fill(v);
        }
        Ok(out)
    }
}

#[test]
fn texture_footprint_from_derivatives() {
    // Corners (s, t), (s + Du(s) du, ...), (s + Dv(s) dv, ...), (s + both): with s = u,
    // Du(s) du = du and Dv(s) = 0, the mean of the corners' s is s + du/2 (exact to rounding).
    let sh = compile(
        "surface tx() { Ci = color texture(\"map\"[1], s, t, \"blur\", 0.1); Oi = texture(\"map\"); }",
    );
    let (nu, nv) = (5, 3);
    let mut tex = MeanS { seen: vec![] };
    let mut g = plane(&sh, nu, nv);
    g.set_textures(&mut tex);
    g.run().unwrap();
    for i in 0..nu * nv {
        let (s, _) = uv(i, nu, nv);
        let c = g.get_v3("Ci", i).unwrap();
        assert!(close(c[0], s + 0.125, 1e-6), "{i}: {c:?}");
        assert!(close(g.get_v3("Oi", i).unwrap()[0], s + 0.125, 1e-6));
    }
    drop(g);
    assert_eq!(tex.seen[0], ("map".to_string(), 1, 1));
    assert_eq!(tex.seen[1], ("map".to_string(), 0, 0));
    // Without a callback, a lookup is an error of the run naming the shader.
    let mut g = plane(&sh, nu, nv);
    assert!(g.run().unwrap_err().to_string().contains("needs a texture callback"));
}

#[test]
fn bumpy_displaces_along_the_normal() {
    // The map is the mean of the footprint's s, so amp = Km (s + du/2), and P moves along
    // N = +z by it.
    let sh = std_shader("bumpy");
    let (nu, nv) = (5, 5);
    let mut tex = MeanS { seen: vec![] };
    let mut g = plane(&sh, nu, nv);
    g.set_textures(&mut tex);
    g.set_param("texturename", Value::Str("bumps".into())).unwrap();
    g.set_param("Km", Value::Num(Num::scalar(0.5))).unwrap();
    g.run().unwrap();
    for i in 0..nu * nv {
        let (u, v) = uv(i, nu, nv);
        let p = g.get_v3("P", i).unwrap();
        let amp = 0.5 * (u + 0.125);
        assert!(close(p[2], amp, 1e-6) && p[0] == W * u && p[1] == H * v, "{i}: {p:?}");
    }
    // Each run starts from the globals as set: a second run displaces the same amount.
    g.run().unwrap();
    assert!(close(g.get_v3("P", 24).unwrap()[2], 0.5 * 1.125, 1e-6));
    // N = calculatenormal(P) = Du(P) ^ Dv(P) with Du(P) = (W, 0, 0.5): N = (-0.5 H, 0, W H).
    let n = g.get_v3("N", 12).unwrap();
    assert!(close(n[0], -0.5 * H, 1e-4) && close(n[2], W * H, 1e-4) && n[1].abs() < 1e-5, "{n:?}");
}

#[test]
fn lightsource_messages_and_nonspecular() {
    // A light with an output parameter and __nonspecular: the surface reads the message in
    // illuminance, and specular() leaves the light out while diffuse() does not.
    let light = compile(
        "light msg(float __nonspecular = 1; output float tag = 7;) {
            solar(vector(0, 0, 1), 0) { Cl = 1; }
        }",
    );
    let mut lights = ShaderLights {
        lights: vec![ShaderLight {
            shader: std::sync::Arc::new(light),
            params: vec![],
            spaces: Spaces::default(),
            categories: vec![],
        }],
    };
    let sh = compile(
        "surface s() {
            float tag = 0, got = 0;
            illuminance(P) { got = lightsource(\"tag\", tag); }
            normal n = normal(0, 0, -1);
            Ci = color(tag, got, 0) + diffuse(n) * color(0, 0, 1);
            Oi = specular(n, vector(0, 0, -1), 0.1);
        }",
    );
    let mut g = GridContext::new(&sh, 2, 2);
    g.set_lights(&mut lights);
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap(), [7.0, 1.0, 1.0]);
    assert_eq!(g.get_v3("Oi", 0).unwrap(), [0.0; 3]);
}

#[test]
fn depthcue_blends_with_depth() {
    // "camera" is "current" here and the clipping range 0..10, so depth(P) = z / 10 = 0.5 at
    // z = 5; with the defaults (distances 0 and 1, background black) Ci = mix(Ci, 0, 0.5) and
    // Oi = mix(Oi, 1, 0.5): halves, exact.
    let sh = std_shader("depthcue");
    let mut g = GridContext::new(&sh, 2, 1);
    g.set_spaces(Spaces { clipping: Some((0.0, 10.0)), ..Spaces::default() });
    g.set_uniform("P", &[0.0, 0.0, 5.0]).unwrap();
    g.set_uniform("Ci", &[1.0, 0.5, 0.25]).unwrap();
    g.set_uniform("Oi", &[0.0; 3]).unwrap();
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 1).unwrap(), [0.5, 0.25, 0.125]);
    assert_eq!(g.get_v3("Oi", 1).unwrap(), [0.5; 3]);
}

#[test]
fn break_inside_illuminance_leaves_the_enclosing_loop() {
    // Two lights of 1 and 10; the loop runs once, and a point with s > 0.5 breaks out after
    // the first light, so it sums only 1; the others sum 11.
    let light = |intensity: f32| ShaderLight {
        shader: std::sync::Arc::new(std_shader("distantlight")),
        params: vec![("intensity".into(), Value::Num(Num::scalar(intensity)))],
        spaces: Spaces::default(),
        categories: vec![],
    };
    let mut lights = ShaderLights { lights: vec![light(1.0), light(10.0)] };
    let sh = compile(
        "surface b() {
            float k, sum = 0;
            for (k = 0; k < 1; k += 1) {
                illuminance(P) { sum += comp(Cl, 0); if (s > 0.5) break; }
            }
            Ci = sum;
        }",
    );
    let mut g = GridContext::new(&sh, 2, 1);
    g.set_varying("s", &[0.0, 1.0]).unwrap();
    g.set_lights(&mut lights);
    g.run().unwrap();
    assert_eq!(g.get_v3("Ci", 0).unwrap()[0], 11.0);
    assert_eq!(g.get_v3("Ci", 1).unwrap()[0], 1.0);
}
