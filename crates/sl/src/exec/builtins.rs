//! The standard library: dispatch by name (and the argument types the checker resolved).
//! Mathematical, geometric, colour, matrix, noise, derivative and lighting functions are
//! here; strings and splines in `strings`. Results follow IEEE arithmetic (`sqrt(-1)` is NaN,
//! `1/0` infinite; stores count them in [`super::Stats::nonfinite`]).

use std::f32::consts::PI;

use crate::ir::Expr;
use crate::types::BaseType;

use super::geom::{self, V3};
use super::lanes::map_v3;
use super::space::{self, Mat, mat_det, mat_inverse, mat_mul, transform_num};
use super::value::{Mask, Num, Value, map_c, map_f, map_n};
use super::{ExecError, GridContext, noise};

fn v3(l: &[f32]) -> V3 {
    if l.len() >= 3 { [l[0], l[1], l[2]] } else { [l[0]; 3] }
}

impl GridContext<'_> {
    pub(crate) fn builtin(
        &mut self,
        name: &str,
        e: &Expr,
        args: &[Expr],
        _options: &[(String, Expr)],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let mut vals = Vec::with_capacity(args.len());
        for a in args {
            vals.push(self.eval(a, mask)?);
        }
        let r = self.builtin_of(name, e, args, &vals, mask);
        vals.into_iter().for_each(super::pool::recycle);
        r
    }

    /// [`Self::builtin`] on the arguments' values.
    fn builtin_of(
        &mut self,
        name: &str,
        e: &Expr,
        args: &[Expr],
        vals: &[Value],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        self.at = e.pos;
        let n = self.n;
        let nums: Vec<&Num> = vals.iter().map(Value::num).collect();
        let a = |k: usize| nums.get(k).copied().unwrap_or(&super::value::ZERO1);
        let w_out = super::value::width(e.ty.base);
        let f1 = |f: fn(f32) -> f32| super::value::map_c1(n, mask, a(0), f);
        let num = |x: Num| Ok(Value::Num(x));
        match name {
            "radians" => num(f1(|x| x * (PI / 180.0))),
            "degrees" => num(f1(|x| x * (180.0 / PI))),
            "sin" => num(f1(f32::sin)),
            "cos" => num(f1(f32::cos)),
            "tan" => num(f1(f32::tan)),
            "asin" => num(f1(f32::asin)),
            "acos" => num(f1(f32::acos)),
            "atan" if nums.len() == 2 => num(map_f(n, mask, &[a(0), a(1)], |x| x[0].atan2(x[1]))),
            "atan" => num(f1(f32::atan)),
            "pow" => num(super::value::map_c2(n, mask, a(0), a(1), f32::powf)),
            "exp" => num(f1(f32::exp)),
            "sqrt" => num(f1(f32::sqrt)),
            "inversesqrt" => num(f1(|x| 1.0 / x.sqrt())),
            "log" if nums.len() == 2 => {
                num(map_f(n, mask, &[a(0), a(1)], |x| x[0].ln() / x[1].ln()))
            }
            "log" => num(f1(f32::ln)),
            "mod" => num(map_f(n, mask, &[a(0), a(1)], |x| x[0] - x[1] * (x[0] / x[1]).floor())),
            "abs" => num(f1(f32::abs)),
            "sign" => num(f1(|x| {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            })),
            "floor" => num(f1(f32::floor)),
            "ceil" => num(f1(f32::ceil)),
            "round" => num(f1(f32::round)),
            "min" => {
                num(map_c(n, mask, &nums, |x| x.iter().copied().fold(f32::INFINITY, f32::min)))
            }
            "max" => {
                num(map_c(n, mask, &nums, |x| x.iter().copied().fold(f32::NEG_INFINITY, f32::max)))
            }
            "clamp" => num(map_c(n, mask, &nums, |x| x[0].max(x[1]).min(x[2]))),
            "mix" => num(map_c(n, mask, &nums, |x| x[0] * (1.0 - x[2]) + x[1] * x[2])),
            "step" => num(map_f(n, mask, &nums, |x| if x[1] < x[0] { 0.0 } else { 1.0 })),
            "smoothstep" => num(map_f(n, mask, &nums, |x| smoothstep(x[0], x[1], x[2]))),
            "filterstep" => {
                let w = if nums.len() >= 3 {
                    map_f(n, mask, &[a(1), a(2)], |x| (x[1] - x[0]).abs())
                } else {
                    self.filterwidth(a(1), mask)
                };
                let centre = if nums.len() >= 3 {
                    map_f(n, mask, &[a(1), a(2)], |x| 0.5 * (x[0] + x[1]))
                } else {
                    a(1).clone()
                };
                num(map_f(n, mask, &[a(0), &centre, &w], |x| {
                    if x[2] > 0.0 {
                        ((x[1] - x[0]) / x[2] + 0.5).clamp(0.0, 1.0)
                    } else if x[1] < x[0] {
                        0.0
                    } else {
                        1.0
                    }
                }))
            }
            "filterwidth" => num(self.filterwidth(a(0), mask)),
            "Du" => num(self.deriv(a(0), false, mask)),
            "Dv" => num(self.deriv(a(0), true, mask)),
            "Deriv" => num(self.deriv_by(a(0), a(1), mask)),
            "Dtime" => num(Num::zeros(a(0).w, false, n)),
            "area" => num(self.area(a(0), mask)),
            "calculatenormal" => num(self.calculatenormal(a(0), mask)),
            "xcomp" | "ycomp" | "zcomp" => {
                let c = (name.as_bytes()[0] - b'x') as usize;
                num(map_n(n, mask, &[a(0)], 1, |l, o| o[0] = l[0][c]))
            }
            "setxcomp" | "setycomp" | "setzcomp" => {
                let c = (name.as_bytes()[3] - b'x') as usize;
                let v = map_n(n, mask, &[a(0), a(1)], 3, |l, o| {
                    o.copy_from_slice(&l[0][..3]);
                    o[c] = l[1][0];
                });
                self.write_place(&args[0], &Value::Num(v), mask)?;
                num(Num::scalar(0.0))
            }
            "length" => num(map_n(n, mask, &[a(0)], 1, |l, o| o[0] = geom::length(v3(l[0])))),
            "normalize" => num(super::lanes::normalize_lanes(n, mask, a(0))),
            "distance" => num(map_n(n, mask, &[a(0), a(1)], 1, |l, o| {
                o[0] = geom::length(geom::sub(v3(l[0]), v3(l[1])))
            })),
            "ptlined" => num(map_n(n, mask, &nums, 1, |l, o| {
                o[0] = geom::ptlined(v3(l[0]), v3(l[1]), v3(l[2]))
            })),
            "faceforward" => {
                let nref = match self.global_value(Self::global_index("Ng")) {
                    _ if nums.len() >= 3 => a(2),
                    Some(Value::Num(ng)) => ng,
                    _ => &super::value::ZERO1,
                };
                num(map_v3(n, mask, [a(0), a(1), nref], |[x, i, r]| geom::faceforward(x, i, r)))
            }
            "reflect" => num(map_v3(n, mask, [a(0), a(1)], |[i, x]| geom::reflect(i, x))),
            "refract" => num(map_n(n, mask, &nums, 3, |l, o| {
                o.copy_from_slice(&geom::refract(v3(l[0]), v3(l[1]), l[2][0]))
            })),
            "fresnel" => {
                let r = map_n(n, mask, &[a(0), a(1), a(2)], 8, |l, o| {
                    let (kr, kt, rr, tt) = geom::fresnel(v3(l[0]), v3(l[1]), l[2][0]);
                    o[0] = kr;
                    o[1] = kt;
                    o[2..5].copy_from_slice(&rr);
                    o[5..8].copy_from_slice(&tt);
                });
                for (k, (lo, w)) in [(0, 1), (1, 1), (2, 3), (5, 3)].into_iter().enumerate() {
                    if let Some(place) = args.get(3 + k) {
                        let part =
                            map_n(n, mask, &[&r], w, |l, o| o.copy_from_slice(&l[0][lo..lo + w]));
                        self.write_place(place, &Value::Num(part), mask)?;
                    }
                }
                num(Num::scalar(0.0))
            }
            "rotate" if e.ty.base == BaseType::Point => num(map_n(n, mask, &nums, 3, |l, o| {
                let (p, ang, p0, p1) = (v3(l[0]), l[1][0], v3(l[2]), v3(l[3]));
                let m = geom::rotation(ang, geom::sub(p1, p0));
                o.copy_from_slice(&geom::add(space::xform_vector(&m, geom::sub(p, p0)), p0));
            })),
            "transform" | "vtransform" | "ntransform" => {
                self.transform(e.ty.base, args, vals, mask)
            }
            "depth" => {
                let to_cam = mat_inverse(&self.space("camera")?);
                let (near, far) = self.spaces.clipping.unwrap_or((0.0, 1.0));
                num(map_n(n, mask, &[a(0)], 1, |l, o| {
                    o[0] = (space::xform_point(&to_cam, v3(l[0]))[2] - near) / (far - near)
                }))
            }
            "comp" if nums.len() == 3 => num(map_n(n, mask, &nums, 1, |l, o| {
                o[0] = l[0][cidx(l[1][0], 4) * 4 + cidx(l[2][0], 4)]
            })),
            "comp" => num(map_n(n, mask, &nums, 1, |l, o| o[0] = l[0][cidx(l[1][0], 3)])),
            "setcomp" => {
                let w = a(0).w;
                let v = map_n(n, mask, &nums, w, |l, o| {
                    o.copy_from_slice(l[0]);
                    if w == 16 {
                        o[cidx(l[1][0], 4) * 4 + cidx(l[2][0], 4)] = l[3][0];
                    } else {
                        o[cidx(l[1][0], 3)] = l[2][0];
                    }
                });
                self.write_place(&args[0], &Value::Num(v), mask)?;
                num(Num::scalar(0.0))
            }
            "ctransform" => {
                let (from, to, c) = if vals.len() == 3 {
                    (vals[0].str(), vals[1].str(), a(2))
                } else {
                    ("rgb", vals[0].str(), a(1))
                };
                for s in [from, to] {
                    if space::color_to_rgb(s, [0.0; 3]).is_none() {
                        return Err(self.err_at(format!("unknown colour space \"{s}\"")));
                    }
                }
                num(map_n(n, mask, &[c], 3, |l, o| {
                    let rgb = space::color_to_rgb(from, v3(l[0])).unwrap_or([0.0; 3]);
                    o.copy_from_slice(&space::rgb_to_color(to, rgb).unwrap_or([0.0; 3]));
                }))
            }
            "inverse" => num(map_n(n, mask, &[a(0)], 16, |l, o| {
                o.copy_from_slice(&mat_inverse(&mat16(l[0])))
            })),
            "determinant" => num(map_n(n, mask, &[a(0)], 1, |l, o| o[0] = mat_det(&mat16(l[0])))),
            "translate" | "rotate" | "scale" => num(map_n(n, mask, &nums, 16, |l, o| {
                let m = mat16(l[0]);
                let mut t = space::IDENTITY;
                match name {
                    "translate" => t[12..15].copy_from_slice(&v3(l[1])),
                    "scale" => {
                        let s = v3(l[1]);
                        (t[0], t[5], t[10]) = (s[0], s[1], s[2]);
                    }
                    _ => t = geom::rotation(l[1][0], v3(l[2])),
                }
                o.copy_from_slice(&mat_mul(&t, &m));
            })),
            "noise" | "pnoise" | "cellnoise" => num(noise_fn(name, args, &nums, w_out, n, mask)),
            "random" => {
                let mut out = Num::zeros(w_out, true, n);
                let base = self.random_state;
                self.random_state = self.random_state.wrapping_add(0x9e37_79b9_7f4a_7c15);
                for i in mask.iter() {
                    for (c, o) in out.lane_mut(i).iter_mut().enumerate() {
                        *o = noise::random01(
                            base ^ ((i as u64) << 8 | c as u64).wrapping_mul(0xff51_afd7_ed55_8ccd),
                        );
                    }
                }
                num(out)
            }
            "ambient" | "diffuse" | "specular" | "phong" => num(self.lighting(name, vals, mask)?),
            "specularbrdf" => num(map_n(n, mask, &nums, 3, |l, o| {
                o.fill(super::light::specularbrdf(v3(l[0]), v3(l[1]), v3(l[2]), l[3][0]))
            })),
            "concat" | "format" | "printf" | "match" | "shadername" => {
                self.string_fn(name, args, vals, mask)
            }
            "spline" => Ok(self.spline(args, vals, w_out, mask)),
            "lightsource" => self.lightsource(args, vals, mask),
            "atmosphere" | "displacement" | "surface" | "incident" | "opposite" | "attribute"
            | "option" | "rendererinfo" | "textureinfo" => self.message(name, args, vals, mask),
            _ => Err(self.err_at(format!("\"{name}\" is not available in the grid machine yet"))),
        }
    }

    /// The change of `x` across one grid step: `|Du(x) du| + |Dv(x) dv|`.
    fn filterwidth(&self, x: &Num, mask: &Mask) -> Num {
        let (xu, xv) = (self.deriv(x, false, mask), self.deriv(x, true, mask));
        let (du, dv) = (self.global_num("du"), self.global_num("dv"));
        map_c(self.n, mask, &[&xu, &xv, &du, &dv], |l| (l[0] * l[2]).abs() + (l[1] * l[3]).abs())
    }

    fn transform(
        &mut self,
        base: BaseType,
        args: &[Expr],
        vals: &[Value],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let k = vals.len();
        let p = vals[k - 1].num();
        let to_matrix = |s: &Self, v: &Value, e: &Expr| -> Result<Option<Mat>, ExecError> {
            match (&e.kind, v) {
                (_, Value::Str(name)) => Ok(Some(mat_inverse(&s.space(name)?))),
                (_, Value::Num(m)) if m.w == 16 && !m.varying => Ok(Some(mat16(&m.data))),
                _ => Ok(None),
            }
        };
        let m = match k {
            2 => to_matrix(self, &vals[0], &args[0])?,
            _ => {
                let from = self.space(vals[0].str())?;
                let to = match &vals[1] {
                    Value::Str(s) => Some(mat_inverse(&self.space(s)?)),
                    _ => to_matrix(self, &vals[1], &args[1])?,
                };
                to.map(|t| mat_mul(&from, &t))
            }
        };
        let n = self.n;
        match m {
            Some(m) => Ok(Value::Num(transform_num(base, &m, p, n, mask))),
            // A varying matrix: point by point.
            None => {
                let mv = vals[k - 2].num();
                let from = if k == 3 { self.space(vals[0].str())? } else { space::IDENTITY };
                Ok(Value::Num(map_n(n, mask, &[mv, p], 3, |l, o| {
                    let m = mat_mul(&from, &mat16(l[0]));
                    let q = v3(l[1]);
                    o.copy_from_slice(&match base {
                        BaseType::Point => space::xform_point(&m, q),
                        BaseType::Normal => space::xform_normal(&m, q),
                        _ => space::xform_vector(&m, q),
                    });
                })))
            }
        }
    }
}

fn mat16(l: &[f32]) -> Mat {
    l.try_into().unwrap_or(space::IDENTITY)
}

/// A component index, clamped into `0..len`.
fn cidx(x: f32, len: usize) -> usize {
    if x >= 0.0 { (x as usize).min(len - 1) } else { 0 }
}

/// The Specification's smoothstep: 0 below `a`, 1 above `b`, the cubic `3t^2 - 2t^3` between.
pub fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    if x < a {
        0.0
    } else if x >= b {
        1.0
    } else {
        let t = (x - a) / (b - a);
        t * t * (3.0 - 2.0 * t)
    }
}

/// `noise`, `pnoise`, `cellnoise` of 1 to 4 coordinates, `w_out` results per point.
fn noise_fn(name: &str, args: &[Expr], nums: &[&Num], w_out: usize, n: usize, mask: &Mask) -> Num {
    let widths: Vec<usize> =
        args.iter().map(|a| if a.ty.base == BaseType::Float { 1 } else { 3 }).collect();
    let half = if name == "pnoise" { args.len() / 2 } else { args.len() };
    let name = name.to_string();
    map_n(n, mask, nums, w_out, move |l, o| {
        let mut x = [0.0f32; 4];
        let mut per = [0.0f32; 4];
        let mut d = 0;
        for k in 0..half {
            for c in 0..widths[k] {
                if d < 4 {
                    x[d] = l[k][c];
                    if name == "pnoise" {
                        per[d] = l[half + k][c.min(l[half + k].len() - 1)];
                    }
                    d += 1;
                }
            }
        }
        for (c, oc) in o.iter_mut().enumerate() {
            let seed = if w_out == 1 { 0 } else { c as u32 + 1 };
            *oc = match name.as_str() {
                "cellnoise" => noise::cellnoise(&x[..d], seed),
                "pnoise" => noise::noise01(&x[..d], Some(&per[..d]), seed),
                _ => noise::noise01(&x[..d], None, seed),
            };
        }
    })
}
