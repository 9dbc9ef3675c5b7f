//! Speed of the grid machine (ignored by default; run with
//! `cargo test --release -p reyes-sl --test grid_speed -- --ignored --nocapture`).

mod common;

use std::time::Instant;

use common::*;
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

fn time(label: &str, src: &str) {
    let sh = compile(src);
    let (nu, nv) = (32, 32);
    let mut lights = OneLight;
    let mut g = plane(&sh, nu, nv);
    g.set_lights(&mut lights);
    g.run().unwrap();
    let reps = 200;
    let t = Instant::now();
    let mut instr = 0;
    for _ in 0..reps {
        instr = g.run().unwrap().instructions;
    }
    let ns = t.elapsed().as_nanos() as f64 / (reps * nu * nv) as f64;
    println!("{label}: {ns:.0} ns per point ({instr} nodes per 32x32 grid)");
}

#[test]
#[ignore]
fn speed() {
    time("constant", reyes_sl::shaders::standard("constant").unwrap());
    time("plastic", reyes_sl::shaders::standard("plastic").unwrap());
    time(
        "noise fBm (4 octaves)",
        "surface f() { float i, a = 0, f = 1; for (i = 0; i < 4; i += 1) { a += noise(P * f) / f; f *= 2; } Ci = a; }",
    );
    time(
        "varying loop (mean 8 iterations)",
        "surface l() { float k = 0, x = 0; while (k < s * 16) { k += 1; x += k; } Ci = x; }",
    );
}
