//! A shading-language imager (issue #30): run once over the finished pixels, before they are
//! quantized or written. The pixels are one grid of `width x height` points (row by row from
//! the top-left): `Ci` the premultiplied colour, `alpha` the coverage (`Oi` is `alpha` in
//! every channel), `P` the raster position of the pixel centre (z = 0), `s`, `t` the NDC
//! position. The imager's `Ci` and `alpha` replace the pixel's; depth is untouched.
//!
//! Invariants: non-finite results become 0 and are counted; a failed run (its instruction
//! budget spent) is an error naming the imager, never a panic.

use reyes_film::Film;
use reyes_scene::sl::exec::GridContext;
use reyes_scene::{Scene, ShaderInstance};

use crate::RenderError;

/// `film` after the scene's imager, with the count of non-finite values zeroed; the film as
/// it was without one.
pub(crate) fn apply(scene: &Scene, film: Film, budget: u64) -> Result<(Film, u64), RenderError> {
    let Some(imager) = &scene.shaders.imager else { return Ok((film, 0)) };
    let info = reyes_dice::slinfo::Info::of_scene(scene);
    run(imager, film, budget, &info)
        .map_err(|e| RenderError::Shader { message: format!("imager: {e}") })
}

fn run(
    imager: &ShaderInstance,
    film: Film,
    budget: u64,
    info: &reyes_dice::slinfo::Info,
) -> Result<(Film, u64), reyes_scene::sl::exec::ExecError> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    let n = w * h;
    let mut g = GridContext::new(&imager.shader, w.max(1), h.max(1));
    g.set_budget(budget);
    // `option()`, `rendererinfo()`, `time` and `dtime`, as the other shaders see them.
    info.bind(&mut g);
    let rgba = film.rgba();
    let ci: Vec<f32> = rgba.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
    let oi: Vec<f32> = rgba.iter().flat_map(|p| [p[3]; 3]).collect();
    let alpha: Vec<f32> = rgba.iter().map(|p| p[3]).collect();
    let at = |k: usize| ((k % w) as f32 + 0.5, (k / w) as f32 + 0.5);
    let p: Vec<f32> = (0..n).flat_map(|k| [at(k).0, at(k).1, 0.0]).collect();
    let s: Vec<f32> = (0..n).map(|k| at(k).0 / w as f32).collect();
    let t: Vec<f32> = (0..n).map(|k| at(k).1 / h as f32).collect();
    g.set_varying("Ci", &ci)?;
    g.set_varying("Oi", &oi)?;
    g.set_varying("alpha", &alpha)?;
    g.set_varying("P", &p)?;
    g.set_varying("s", &s)?;
    g.set_varying("t", &t)?;
    for (name, v) in &imager.params {
        g.set_param(name, v.clone())?;
    }
    let stats = g.run()?;
    let mut nonfinite = stats.nonfinite;
    let mut clean = |x: f32| {
        if x.is_finite() {
            x
        } else {
            nonfinite += 1;
            0.0
        }
    };
    let out: Vec<[f32; 4]> = (0..n)
        .map(|k| {
            let c = g.get_v3("Ci", k).unwrap_or([0.0; 3]);
            let a = g.get_f("alpha", k).unwrap_or(0.0);
            [clean(c[0]), clean(c[1]), clean(c[2]), clean(a)]
        })
        .collect();
    let z = film.z().to_vec();
    let (fw, fh) = (film.width(), film.height());
    Ok((Film::from_pixels(fw, fh, out, z).unwrap_or(film), nonfinite))
}
