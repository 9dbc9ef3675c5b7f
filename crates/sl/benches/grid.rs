//! Criterion benchmark of the grid machine: standard and hand-written shaders run over a 32x32
//! grid with one light from a test callback. Throughput is in grid points, so criterion's
//! "elem/s" is points shaded per second. Run with `cargo bench -p reyes-sl --bench grid`.

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Duration;

use common::*;
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use reyes_sl::exec::{LightQuery, LightSample, Lights, Num};

struct OneLight;

impl Lights for OneLight {
    fn lights(
        &mut self,
        q: &LightQuery<'_>,
    ) -> Result<Vec<LightSample>, reyes_sl::exec::ExecError> {
        let n = q.nu * q.nv;
        Ok(vec![LightSample {
            ambient: false,
            l: Num::uniform(&[0.3, 0.2, 1.0]),
            cl: Num::uniform(&[1.0; 3]),
            ol: Num::zeros(3, false, n),
            lit: vec![true; n],
            outputs: vec![],
        }])
    }
}

const FBM: &str = "surface f() { float i, a = 0, f = 1; for (i = 0; i < 4; i += 1) { a += noise(P * f) / f; f *= 2; } Ci = a; }";
const LOOP: &str =
    "surface l() { float k = 0, x = 0; while (k < s * 16) { k += 1; x += k; } Ci = x; }";

fn grid(c: &mut Criterion) {
    let (nu, nv) = (32, 32);
    let mut group = c.benchmark_group("grid_machine");
    group.throughput(Throughput::Elements((nu * nv) as u64));
    let cases = [
        ("constant", reyes_sl::shaders::standard("constant").unwrap()),
        ("plastic", reyes_sl::shaders::standard("plastic").unwrap()),
        ("noise fBm 4 octaves", FBM),
        ("varying loop, mean 8 iterations", LOOP),
    ];
    for (name, src) in cases {
        let sh = compile(src);
        let mut lights = OneLight;
        let mut g = plane(&sh, nu, nv);
        g.set_lights(&mut lights);
        group.bench_function(name, |b| b.iter(|| black_box(g.run().unwrap().instructions)));
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = grid
}
criterion_main!(benches);
