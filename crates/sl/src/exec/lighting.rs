//! `ambient`, `diffuse`, `specular`, `phong`: sums over the lights at the global `P`.
//!
//! The lights' terms are computed a block of points at a time, each triple held as three
//! arrays of components, so the normalisations (a square root and a division each) run on
//! several points at once instead of one dependent chain per point. Every operation is the
//! one the point-by-point formulas of `geom` and [`specularbrdf`] do, in the same order, so
//! the results are the same to the bit; only `powf` stays one point at a time.
//!
//! [`specularbrdf`]: super::light::specularbrdf

// Index loops over the blocks' lanes on purpose: fixed-length loops the compiler turns into
// vector instructions.
#![allow(clippy::needless_range_loop)]

use super::lanes::{B, Fs, Src, T3, add, dot, normalize, reflect, scale};
use super::value::{Mask, Num, Value, ZERO1};
use super::{ExecError, GridContext};

/// Which of the lighting functions.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Model {
    Ambient,
    Diffuse,
    Specular,
    Phong,
}

impl GridContext<'_> {
    /// `ambient`, `diffuse`, `specular`, `phong` (`args`: the normal, the viewing vector and
    /// the roughness or exponent, as given).
    pub(crate) fn lighting(
        &mut self,
        name: &str,
        args: &[Value],
        mask: &Mask,
    ) -> Result<Num, ExecError> {
        let samples = self.light_samples_at_p()?;
        let n = self.n;
        let model = match name {
            "ambient" => Model::Ambient,
            "diffuse" => Model::Diffuse,
            "specular" => Model::Specular,
            _ => Model::Phong,
        };
        let arg = |k: usize| args.get(k).map_or(&*ZERO1, Value::num);
        let (nn, v, x) = (arg(0), arg(1), arg(2));
        let (nn_at, v_at) = (Src::of(nn), Src::of(v));
        let mut out = Num::zeros(3, true, n);
        for s in samples.iter() {
            if (model == Model::Ambient) != s.ambient {
                continue;
            }
            let flag = |key: &str| s.outputs.iter().find(|(k, _)| k == key).map(|(_, v)| v.num());
            let skip = match model {
                Model::Diffuse => flag("__nondiffuse"),
                Model::Specular | Model::Phong => flag("__nonspecular"),
                Model::Ambient => None,
            };
            let (l_at, cl_at) = (Src::of(&s.l), Src::of(&s.cl));
            let lit = |i: usize| {
                s.lit.get(i).copied().unwrap_or(false) && !skip.is_some_and(|f| f.f(i) != 0.0)
            };
            if model == Model::Ambient {
                for i in mask.iter().filter(|&i| lit(i)) {
                    let cl = cl_at.at(i);
                    let o = out.lane_mut(i);
                    for c in 0..3 {
                        o[c] += cl[c] * 1.0;
                    }
                }
                continue;
            }
            for block in mask.idx.chunks(B) {
                // The block's points, its lanes past the last point copies of the first.
                let (mut idx, mut on) = ([0usize; B], [false; B]);
                for j in 0..B {
                    idx[j] = block[j.min(block.len() - 1)] as usize;
                    on[j] = j < block.len() && lit(idx[j]);
                }
                if !on.contains(&true) {
                    continue;
                }
                let run = block.len() == B && idx[B - 1] - idx[0] == B - 1;
                let gather = |src: &Src<'_>| {
                    let mut t = T3([[0.0; B]; 3]);
                    match *src {
                        // Consecutive points of a triple per point: one slice.
                        Src::Lanes { data, w: 3 } if run => {
                            let x = &data[3 * idx[0]..3 * (idx[0] + B)];
                            for j in 0..B {
                                for c in 0..3 {
                                    t.0[c][j] = x[3 * j + c];
                                }
                            }
                        }
                        _ => {
                            for j in 0..B {
                                let v = src.at(idx[j]);
                                for c in 0..3 {
                                    t.0[c][j] = v[c];
                                }
                            }
                        }
                    }
                    t
                };
                let ls = normalize(&scale(&gather(&l_at), &[-1.0; B]));
                let nf = normalize(&gather(&nn_at));
                let cos = dot(&nf, &ls);
                for j in 0..B {
                    // Only a cosine `<= 0` leaves the light out (a NaN one does not).
                    on[j] &= cos[j] > 0.0 || cos[j].is_nan();
                }
                let k: Fs = match model {
                    Model::Specular => {
                        let h = normalize(&add(&normalize(&ls), &normalize(&gather(&v_at))));
                        let mut base = dot(&normalize(&nf), &h);
                        base.iter_mut().for_each(|d| *d = d.max(0.0));
                        let mut k = [0.0; B];
                        for j in (0..B).filter(|&j| on[j]) {
                            k[j] = base[j].powf(8.0 / x.f(idx[j]));
                        }
                        k
                    }
                    Model::Phong => {
                        let vv = normalize(&gather(&v_at));
                        let r = reflect(&scale(&vv, &[-1.0; B]), &nf);
                        let mut base = dot(&r, &ls);
                        base.iter_mut().for_each(|d| *d = d.max(0.0));
                        let mut k = [0.0; B];
                        for j in (0..B).filter(|&j| on[j]) {
                            k[j] = base[j].powf(x.f(idx[j]));
                        }
                        k
                    }
                    _ => cos,
                };
                for j in (0..B).filter(|&j| on[j]) {
                    let cl = cl_at.at(idx[j]);
                    let o = out.lane_mut(idx[j]);
                    for c in 0..3 {
                        o[c] += cl[c] * k[j];
                    }
                }
            }
        }
        Ok(out)
    }
}
