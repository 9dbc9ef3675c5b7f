//! Lights: the callback a surface's `illuminance` (and `ambient`, `diffuse`, `specular`,
//! `phong`) asks for the light reaching a grid, and light shaders run on this machine.
//!
//! The renderer implements [`Lights`]: given the grid's points (and normals) it returns one
//! [`LightSample`] per light: per point, the light's `L` (from the light to the point, as the
//! light shader sees it), `Cl`, `Ol`, and whether the light reached the point at all (outside
//! an `illuminate` cone it does not). A light with no `illuminate` or `solar` is ambient: it
//! reaches `ambient()` only. [`ShaderLights`] is the implementation that runs light shaders
//! ([`ShaderLight`]) over the same grid with `Ps` set to the surface's points.

use std::rc::Rc;

use crate::ir::{CheckedShader, Expr, Stmt};

use super::geom::{V3, dot, length, scale};
use super::space::Spaces;
use super::value::{Mask, Num, Value, map_n};
use super::{ExecError, GridContext};

/// What the surface asks: the points lit (and their normals), on an `nu` x `nv` grid.
pub struct LightQuery<'q> {
    /// The `illuminance` category (`""`: every light).
    pub category: &'q str,
    /// The points being lit (a triple per point, or uniform).
    pub p: &'q Num,
    /// The surface normals there.
    pub n: &'q Num,
    /// The points that need light.
    pub mask: &'q Mask,
    /// Grid width.
    pub nu: usize,
    /// Grid height.
    pub nv: usize,
}

/// One light's contribution to a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct LightSample {
    /// No direction: reaches `ambient()` only.
    pub ambient: bool,
    /// Per point, from the light to the point (the light shader's `L`).
    pub l: Num,
    /// Per point, the light's colour.
    pub cl: Num,
    /// Per point, the light's opacity.
    pub ol: Num,
    /// Per point, whether the light reached it.
    pub lit: Vec<bool>,
    /// The light's `output` parameters, for `lightsource("name", var)` in `illuminance`
    /// (`__nondiffuse` and `__nonspecular`, when non-zero, keep the light out of `diffuse`,
    /// and out of `specular` and `phong`).
    pub outputs: Vec<(String, Value)>,
}

/// The renderer's side: the lights reaching a grid.
pub trait Lights {
    /// One sample per light in `q.category`.
    fn lights(&mut self, q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError>;
}

#[derive(Clone)]
/// A light shader instance: the shader, its parameter values, its coordinate systems (its
/// "shader" space is where it was declared), and its categories.
pub struct ShaderLight {
    /// The compiled light shader (shared: one compile serves every instance).
    pub shader: std::sync::Arc<CheckedShader>,
    /// Parameter values by name (others take their defaults).
    pub params: Vec<(String, Value)>,
    /// Its coordinate systems.
    pub spaces: Spaces,
    /// The categories it belongs to (`__category`).
    pub categories: Vec<String>,
}

/// Light shaders run on the grid machine.
#[derive(Default)]
pub struct ShaderLights {
    /// The lights.
    pub lights: Vec<ShaderLight>,
}

/// Where a light shader's `illuminate`/`solar` record what they lit.
pub(crate) struct LightRecord {
    pub(crate) lit: Vec<bool>,
    pub(crate) directional: bool,
}

impl Lights for ShaderLights {
    fn lights(&mut self, q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError> {
        self.lights_with(q, None)
    }
}

impl ShaderLights {
    /// [`Lights::lights`] with the light shaders' `shadow`, `texture` and `environment`
    /// calls answered by `textures`.
    pub fn lights_with(
        &self,
        q: &LightQuery<'_>,
        mut textures: Option<&mut dyn super::Textures>,
    ) -> Result<Vec<LightSample>, ExecError> {
        let mut out = Vec::new();
        for light in &self.lights {
            if !q.category.is_empty() && !light.categories.iter().any(|c| c == q.category) {
                continue;
            }
            let mut g = GridContext::new(&light.shader, q.nu, q.nv);
            g.set_spaces(light.spaces.clone());
            if let Some(t) = textures.as_deref_mut() {
                g.set_textures(t);
            }
            g.set_global("Ps", q.p.to_varying(g.n))?;
            g.set_global("Ns", q.n.to_varying(g.n))?;
            for (name, v) in &light.params {
                g.set_param(name, v.clone())?;
            }
            g.light_out = Some(LightRecord { lit: vec![false; g.n], directional: false });
            g.run()?;
            let rec = g.light_out.take().unwrap_or(LightRecord { lit: vec![], directional: false });
            let ambient = !rec.directional;
            out.push(LightSample {
                ambient,
                l: g.global_num("L"),
                cl: g.global_num("Cl"),
                ol: g.global_num("Ol"),
                lit: if ambient { q.mask.on.clone() } else { rec.lit },
                outputs: light
                    .shader
                    .params
                    .iter()
                    .filter(|&&id| {
                        matches!(
                            light.shader.vars[id].kind,
                            crate::ir::VarKind::Param { output: true, .. }
                        ) || light.shader.vars[id].name.starts_with("__")
                    })
                    .filter_map(|&id| {
                        let name = &light.shader.vars[id].name;
                        Some((name.clone(), g.param(name)?.clone()))
                    })
                    .collect(),
            });
        }
        Ok(out)
    }
}

fn in_cone(l: V3, axis: V3, cos_angle: f32) -> bool {
    dot(l, axis) >= cos_angle * length(l) * length(axis)
}

impl GridContext<'_> {
    /// The lights reaching `position` (cached until `P` is assigned). Shared with the cache,
    /// so a second `diffuse` or `specular` at the same points copies nothing.
    pub(crate) fn light_samples(
        &mut self,
        category: &str,
        position: &Num,
    ) -> Result<Rc<[LightSample]>, ExecError> {
        if let Some(s) = self.cached_lights(category, position) {
            return Ok(s);
        }
        let normal = self.global_num("N");
        let (nu, nv) = (self.nu, self.nv);
        let all = Mask::all(self.n);
        let Some(lights) = self.lights.as_deref_mut() else { return Ok(Rc::from([])) };
        let q = LightQuery { category, p: position, n: &normal, mask: &all, nu, nv };
        let s = lights.lights(&q)?;
        let n = self.n;
        let fits = |x: &Num| x.w == 3 && x.data.len() == if x.varying { 3 * n } else { 3 };
        if let Some(bad) =
            s.iter().position(|l| !(fits(&l.l) && fits(&l.cl) && fits(&l.ol) && l.lit.len() == n))
        {
            return Err(self.err_at(format!(
                "light {bad} returned L, Cl, Ol not of 3 floats (per point, for {n} points) or lit not of {n} flags"
            )));
        }
        super::pool::give(normal.data);
        let s: Rc<[LightSample]> = Rc::from(s);
        let old = self.light_cache.replace((position.clone(), category.to_string(), Rc::clone(&s)));
        self.light_cache_at_p = false;
        super::pool::recycle_lights(old);
        Ok(s)
    }

    /// The cached lights, if they were asked for at `position` in `category`.
    fn cached_lights(&self, category: &str, position: &Num) -> Option<Rc<[LightSample]>> {
        match &*self.light_cache {
            Some((p, c, s)) if p == position && c == category => Some(Rc::clone(s)),
            _ => None,
        }
    }

    /// The lights of every category at the global `P` (read in place when cached).
    pub(crate) fn light_samples_at_p(&mut self) -> Result<Rc<[LightSample]>, ExecError> {
        if self.light_cache_at_p
            && let Some((_, c, s)) = &*self.light_cache
            && c.is_empty()
        {
            return Ok(Rc::clone(s));
        }
        let k = Self::global_index("P");
        let s = match self.global_value(k) {
            Some(Value::Num(p)) => self.cached_lights("", p),
            _ => None,
        };
        let s = match s {
            Some(s) => s,
            None => {
                let p = self.global_num("P");
                self.light_samples("", &p)?
            }
        };
        self.light_cache_at_p = true;
        Ok(s)
    }

    /// `illuminance`: the body once per non-ambient light, at the points it reaches inside
    /// the cone, with `L` (from the point to the light), `Cl`, `Ol` set.
    pub(crate) fn illuminance(
        &mut self,
        category: Option<&Expr>,
        position: &Expr,
        cone: Option<&(Expr, Expr)>,
        body: &[Stmt],
        mask: &Mask,
    ) -> Result<(), ExecError> {
        let cat = match category {
            Some(c) => self.eval(c, mask)?.str().to_string(),
            None => String::new(),
        };
        let p = self.eval(position, mask)?.num().clone();
        let cone = match cone {
            Some((a, b)) => {
                let axis = self.eval(a, mask)?.num().clone();
                let angle = self.eval(b, mask)?.num().clone();
                Some((axis, angle))
            }
            None => None,
        };
        let samples = self.light_samples(&cat, &p)?;
        for s in samples.iter().filter(|s| !s.ambient) {
            self.tick()?;
            // Points that left (a `break` or `return` in the body for an earlier light) stay out.
            let alive = self.narrow(mask);
            let m = alive.filter(|i| {
                s.lit.get(i).copied().unwrap_or(false)
                    && cone.as_ref().is_none_or(|(axis, angle)| {
                        let a = angle.f(i);
                        a >= std::f32::consts::PI
                            || in_cone(scale(s.l.v3(i), -1.0), axis.v3(i), a.cos())
                    })
            });
            if m.is_empty() {
                continue;
            }
            let l = map_n(self.n, &m, &[&s.l], 3, |x, o| {
                o.copy_from_slice(&[-x[0][0], -x[0][1], -x[0][2]]);
            });
            self.set_global_masked("L", &l, &m);
            self.set_global_masked("Cl", &s.cl, &m);
            self.set_global_masked("Ol", &s.ol, &m);
            let outer = self.current_light.replace(s.outputs.clone());
            let r = self.exec_block(body, &m);
            self.current_light = outer;
            r?;
        }
        Ok(())
    }

    /// `illuminate(position[, axis, angle])` (`position` given) or `solar([axis, angle])`:
    /// sets `L` (from the light to `Ps`) and runs the body where it is in the cone.
    pub(crate) fn illuminate(
        &mut self,
        position: Option<&Expr>,
        cone: Option<&(Expr, Expr)>,
        body: &[Stmt],
        mask: &Mask,
    ) -> Result<(), ExecError> {
        let n = self.n;
        let ps = self.global_num("Ps");
        let l = match position {
            Some(e) => {
                let from = self.eval(e, mask)?.num().clone();
                map_n(n, mask, &[&ps.to_varying(n), &from], 3, |x, o| {
                    for c in 0..3 {
                        o[c] = x[0][c] - x[1][c];
                    }
                })
            }
            None => match cone {
                Some((a, _)) => self.eval(a, mask)?.num().to_varying(n),
                // solar() with no direction: light straight down onto the surface.
                None => {
                    let ns = self.global_num("Ns");
                    map_n(n, mask, &[&ns.to_varying(n)], 3, |x, o| {
                        o.copy_from_slice(&[-x[0][0], -x[0][1], -x[0][2]]);
                    })
                }
            },
        };
        let m = match (position, cone) {
            (Some(_), Some((a, b))) => {
                let axis = self.eval(a, mask)?.num().clone();
                let angle = self.eval(b, mask)?.num().clone();
                mask.filter(|i| {
                    angle.f(i) >= std::f32::consts::PI
                        || in_cone(l.v3(i), axis.v3(i), angle.f(i).cos())
                })
            }
            _ => mask.clone(),
        };
        self.set_global_masked("L", &l, &m);
        if let Some(rec) = self.light_out.as_mut() {
            rec.directional = true;
            for i in m.iter() {
                rec.lit[i] = true;
            }
        }
        if !m.is_empty() {
            self.exec_block(body, &m)?;
        }
        Ok(())
    }

    /// `lightsource("name", var)` inside `illuminance`: the current light's output parameter
    /// `name` into `var`; 1 if it has one, else 0 (and `var` unchanged).
    pub(crate) fn lightsource(
        &mut self,
        args: &[Expr],
        vals: &[Value],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let key = vals.first().map(Value::str).unwrap_or("");
        let found = self
            .current_light
            .as_ref()
            .and_then(|o| o.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone()));
        self.deliver(found, args, vals, mask)
    }

    /// `surface`, `displacement`, `atmosphere`, `incident`, `opposite`, `attribute`, `option`,
    /// `rendererinfo`, `textureinfo`: the value the renderer gave with
    /// [`GridContext::set_message`] under this function's name (`textureinfo`: the map's
    /// name and the field, joined by `:`), into the output argument; 1 if found, else 0.
    pub(crate) fn message(
        &mut self,
        name: &str,
        args: &[Expr],
        vals: &[Value],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let key = if name == "textureinfo" {
            format!("{}:{}", vals[0].str(), vals.get(1).map_or("", Value::str))
        } else {
            vals.first().map(Value::str).unwrap_or("").to_string()
        };
        let found = self.messages.get(&(name.to_string(), key)).cloned();
        let (args, vals) =
            if name == "textureinfo" { (&args[1..], &vals[1..]) } else { (args, vals) };
        self.deliver(found, args, vals, mask)
    }

    fn deliver(
        &mut self,
        found: Option<Value>,
        args: &[Expr],
        vals: &[Value],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let hit = match (found, args.get(1)) {
            (Some(v), Some(place)) if vals.get(1).is_some_and(|w| same_shape(&v, w)) => {
                self.write_place(place, &v, mask)?;
                1.0
            }
            _ => 0.0,
        };
        Ok(Value::Num(Num::scalar(hit)))
    }
}

/// The specular term for one light: `pow(max(0, N . H), 8 / roughness)` with `H` the half-way
/// vector of `L` and `V` (all normalised here). The Specification's listing writes the
/// exponent `1 / roughness`; PRMan, BMRT, Aqsis and Pixie all use `1 / (roughness / 8)`, which
/// is what the standard shaders' pictures are (the native plastic has it too, and matches
/// Aqsis's at 47.7 dB where 1 / roughness gave 25 dB: a highlight eight times as wide).
pub fn specularbrdf(l: V3, n: V3, v: V3, roughness: f32) -> f32 {
    let h = super::geom::normalize(super::geom::add(
        super::geom::normalize(l),
        super::geom::normalize(v),
    ));
    dot(super::geom::normalize(n), h).max(0.0).powf(8.0 / roughness)
}

/// Whether a message's value fits the variable it is read into (same kind and width).
fn same_shape(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Num(x), Value::Num(y)) => x.w == y.w,
        (Value::Str(_), Value::Str(_)) => true,
        (Value::Array(x), Value::Array(y)) => x.len() == y.len(),
        _ => false,
    }
}
