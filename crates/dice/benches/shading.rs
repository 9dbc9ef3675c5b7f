//! Criterion benchmark (issue #30): RenderMan's `plastic` on a 16 x 16 grid under one
//! ambient and one distant light, shaded natively (`reyes_dice::Shader`, vertex by vertex, as
//! the REYES path shades a native Plastic) and on the shading-language machine (the built-in
//! `plastic.sl`, the lights given to `illuminance` as the dicer gives native lights: `L` and
//! `Cl` per point). Throughput is in points, so criterion's "elem/s" is points shaded per
//! second. Run with `cargo bench -p reyes-dice --bench shading`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use reyes_dice::{Shader, Viewer};
use reyes_scene::sl::exec::{ExecError, GridContext, LightQuery, LightSample, Lights, Num, Value};
use reyes_scene::{Light, Material};

const N: usize = 16;

/// The scene's native lights as the machine asks for them (as the dicer's `GridLights`).
struct Native<'s>(&'s Shader);

impl Lights for Native<'_> {
    fn lights(&mut self, q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError> {
        let n = q.nu * q.nv;
        let zeros = || Num::zeros(3, true, n);
        let mut out = vec![LightSample {
            ambient: true,
            l: zeros(),
            cl: Num::uniform(&self.0.ambient().to_array()).to_varying(n),
            ol: zeros(),
            lit: q.mask.on.clone(),
            outputs: Vec::new(),
        }];
        let mut s = LightSample {
            ambient: false,
            l: zeros(),
            cl: zeros(),
            ol: zeros(),
            lit: vec![false; n],
            outputs: Vec::new(),
        };
        for &i in &q.mask.idx {
            let i = i as usize;
            if let Some(Some((l, cl))) = self.0.light_vectors(Vec3::from(q.p.v3(i))).next() {
                s.l.lane_mut(i).copy_from_slice(&l.to_array());
                s.cl.lane_mut(i).copy_from_slice(&cl.to_array());
                s.lit[i] = true;
            }
        }
        out.push(s);
        Ok(out)
    }
}

fn shading(c: &mut Criterion) {
    let material = Material::Plastic {
        color: [0.8, 0.5, 0.3],
        opacity: [1.0; 3],
        ka: 1.0,
        kd: 0.5,
        ks: 0.5,
        roughness: 0.1,
        specular_color: [1.0; 3],
    };
    let lights = [
        Light::Ambient { color: [1.0; 3], intensity: 0.15 },
        Light::Distant {
            from: [-1.0, 1.0, -1.0],
            to: [0.0; 3],
            color: [1.0; 3],
            intensity: 1.0,
            shadows: false,
        },
    ];
    let object = reyes_scene::Object::new(
        reyes_scene::Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 },
        material,
    );
    let native = Shader::for_object(&object, &lights, Viewer::Eye(Vec3::ZERO));
    // A patch of a unit sphere at z = 5 seen from the origin (camera space = world here).
    let (mut p, mut nn) = (Vec::new(), Vec::new());
    for j in 0..N {
        for i in 0..N {
            let (a, b) = (0.6 * i as f32 / N as f32 - 0.3, 0.6 * j as f32 / N as f32 - 0.3);
            let n = Vec3::new(a, b, -(1.0 - a * a - b * b).sqrt());
            p.push(Vec3::new(0.0, 0.0, 5.0) + n);
            nn.push(n);
        }
    }
    let mut group = c.benchmark_group("plastic_16x16");
    group.throughput(Throughput::Elements((N * N) as u64));
    group.bench_function("native", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for k in 0..N * N {
                sum += native.shade(p[k], nn[k], Vec3::ONE).0[0];
            }
            black_box(sum)
        })
    });
    let source = reyes_scene::sl::shaders::standard("plastic").unwrap();
    let sh = reyes_scene::sl::compile_str("plastic.sl", source, &[]).unwrap();
    let flat = |v: &[Vec3]| v.iter().flat_map(|x| x.to_array()).collect::<Vec<f32>>();
    let (fp, fnn) = (flat(&p), flat(&nn));
    group.bench_function("shading language", |b| {
        b.iter(|| {
            let mut lights = Native(&native);
            let mut g = GridContext::new(&sh, N, N);
            g.set_varying("P", &fp).unwrap();
            g.set_varying("N", &fnn).unwrap();
            g.set_varying("Ng", &fnn).unwrap();
            g.set_varying("I", &fp).unwrap();
            g.set_uniform("E", &[0.0; 3]).unwrap();
            g.set_uniform("Cs", &[0.8, 0.5, 0.3]).unwrap();
            g.set_uniform("Os", &[1.0; 3]).unwrap();
            for (name, v) in [("Ka", 1.0), ("Kd", 0.5), ("Ks", 0.5), ("roughness", 0.1)] {
                g.set_param(name, Value::Num(Num::scalar(v))).unwrap();
            }
            g.set_lights(&mut lights);
            g.run().unwrap();
            black_box(g.get_v3("Ci", 0))
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = shading
}
criterion_main!(benches);
