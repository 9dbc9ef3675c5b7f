//! The grid machine: runs a [`CheckedShader`] over a whole grid of points at once.
//!
//! A grid is `nu` x `nv` vertices as a REYES dicer makes them; point `i` is at
//! `(i % nu, i / nu)`, u fastest. The machine interprets the checked IR directly, each node
//! computing its value for the whole grid: a uniform node once, a varying one for each active
//! point ([`value`]). Varying `if`, loops, `break`, `continue` and `return` narrow a [`Mask`];
//! uniform ones branch once. See `docs/shading.md`, "How a grid executes".
//!
//! ```
//! use reyes_sl::exec::GridContext;
//! let sh = reyes_sl::compile_str("st.sl", "surface st() { Ci = color(s, t, 0); }", &[]).unwrap();
//! let mut g = GridContext::new(&sh, 2, 2);
//! g.set_varying("s", &[0.0, 1.0, 0.0, 1.0]).unwrap();
//! g.set_varying("t", &[0.0, 0.0, 1.0, 1.0]).unwrap();
//! g.run().unwrap();
//! assert_eq!(g.get_v3("Ci", 3), Some([1.0, 1.0, 0.0]));
//! ```

mod builtins;
mod deriv;
mod expr;
mod geom;
mod lanes;
pub mod light;
mod lighting;
mod noise;
mod pool;
pub mod space;
mod stmt;
mod strings;
pub mod texture;
pub mod value;

use std::collections::HashMap;

use crate::globals::GLOBALS;
use crate::ir::{CheckedShader, VarKind};
use crate::types::{Detail, ShaderKind};

pub use light::{LightQuery, LightSample, Lights, ShaderLight, ShaderLights};
pub use space::Spaces;
pub use texture::{LookupKind, TextureQuery, Textures};
pub use value::{Mask, Num, Value};

/// The default instruction budget per grid: IR nodes evaluated (each counts once, whether
/// uniform or varying) plus loop iterations.
pub const DEFAULT_BUDGET: u64 = 50_000_000;

/// The most points a grid may have (a dicer makes grids of hundreds; this bounds memory).
pub const MAX_POINTS: usize = 1 << 24;

/// The most floats a run's variables may take (256 MB), so a shader declaring a huge varying
/// array is refused instead of exhausting memory.
pub const MAX_FLOATS: usize = 1 << 26;

/// An error of a run. Its message names the shader.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ExecError {
    /// The instruction budget ran out: a runaway loop, most likely.
    #[error(
        "shader \"{shader}\": instruction budget of {budget} exceeded at {at} (a runaway loop?)"
    )]
    Budget {
        /// The shader.
        shader: String,
        /// The budget.
        budget: u64,
        /// `file:line:col` of the node being evaluated.
        at: String,
    },
    /// A value the caller gave does not fit.
    #[error("shader \"{shader}\": {message}")]
    Input {
        /// The shader.
        shader: String,
        /// What is wrong.
        message: String,
    },
    /// Something the machine does not do (yet), at a position.
    #[error("shader \"{shader}\": {at}: {message}")]
    Unsupported {
        /// The shader.
        shader: String,
        /// `file:line:col`.
        at: String,
        /// What.
        message: String,
    },
}

/// What a run counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// IR nodes evaluated plus loop iterations.
    pub instructions: u64,
    /// Non-finite floats stored by assignments (at active points).
    pub nonfinite: u64,
    /// Array indices out of range (clamped to the nearest element).
    pub index_clamped: u64,
}

/// A grid of points and one shader to run over it: set the globals and parameters, run, read
/// the results.
pub struct GridContext<'a> {
    pub(crate) shader: &'a CheckedShader,
    pub(crate) nu: usize,
    pub(crate) nv: usize,
    pub(crate) n: usize,
    /// The globals, in [`GLOBALS`] order; `None` until set (then defaults at the run).
    pub(crate) globals: pool::Pooled<Vec<Option<Value>>>,
    /// The globals as the caller set them: each run starts from these, so running twice gives
    /// the same results (a displacement does not move `P` twice).
    pub(crate) inputs: pool::Pooled<Vec<Option<Value>>>,
    pub(crate) vars: pool::Pooled<Vec<Value>>,
    pub(crate) param_set: HashMap<usize, Value>,
    pub(crate) spaces: Spaces,
    pub(crate) lights: Option<&'a mut dyn Lights>,
    pub(crate) textures: Option<&'a mut dyn Textures>,
    pub(crate) budget: u64,
    pub(crate) stats: Stats,
    pub(crate) frames: Vec<stmt::FuncFrame>,
    pub(crate) light_cache: pool::Pooled<Option<pool::LightCache>>,
    /// The cached lights are those of every category at the global `P` as it is now (`P`
    /// is assigned only through `assign`, which drops the cache).
    pub(crate) light_cache_at_p: bool,
    pub(crate) light_out: Option<light::LightRecord>,
    pub(crate) current_light: Option<Vec<(String, Value)>>,
    pub(crate) messages: HashMap<(String, String), Value>,
    pub(crate) random_state: u64,
    pub(crate) printed: Vec<String>,
    pub(crate) at: crate::error::Pos,
}

impl<'a> GridContext<'a> {
    /// A context for `shader` over an `nu` x `nv` grid (each at least 1).
    pub fn new(shader: &'a CheckedShader, nu: usize, nv: usize) -> GridContext<'a> {
        let (nu, nv) = (nu.max(1), nv.max(1));
        GridContext {
            shader,
            nu,
            nv,
            n: nu.saturating_mul(nv),
            globals: pool::Pooled(vec![None; GLOBALS.len()]),
            inputs: pool::Pooled(vec![None; GLOBALS.len()]),
            vars: pool::Pooled(Vec::new()),
            param_set: HashMap::new(),
            spaces: Spaces::default(),
            lights: None,
            textures: None,
            budget: DEFAULT_BUDGET,
            stats: Stats::default(),
            frames: Vec::new(),
            light_cache: pool::Pooled(None),
            light_cache_at_p: false,
            light_out: None,
            current_light: None,
            messages: HashMap::new(),
            random_state: 0x9e37_79b9_7f4a_7c15,
            printed: Vec::new(),
            at: crate::error::Pos::default(),
        }
    }

    /// Points in the grid.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Never: a grid has at least one point.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Sets the instruction budget.
    pub fn set_budget(&mut self, budget: u64) {
        self.budget = budget;
    }

    /// Sets the named coordinate systems (and the seed of `random`).
    pub fn set_spaces(&mut self, spaces: Spaces) {
        self.spaces = spaces;
    }

    /// Sets the light callback `illuminance`, `ambient`, `diffuse`, `specular` and `phong` use.
    pub fn set_lights(&mut self, lights: &'a mut dyn Lights) {
        self.lights = Some(lights);
    }

    /// Sets the texture callback `texture`, `environment` and `shadow` use.
    pub fn set_textures(&mut self, textures: &'a mut dyn Textures) {
        self.textures = Some(textures);
    }

    /// Gives the answer to a message-passing or information call: `function` is `surface`,
    /// `displacement`, `atmosphere`, `incident`, `opposite`, `attribute`, `option`,
    /// `rendererinfo` or `textureinfo`, `name` the name asked (`textureinfo`: `"map:field"`).
    /// A call with no answer returns 0 and leaves its variable alone.
    pub fn set_message(&mut self, function: &str, name: &str, v: Value) {
        self.messages.insert((function.to_string(), name.to_string()), v);
    }

    /// The lines `printf` wrote during the last run.
    pub fn printed(&self) -> &[String] {
        &self.printed
    }

    fn input_err(&self, message: String) -> ExecError {
        let message = crate::error::OneLine(&message).to_string();
        ExecError::Input { shader: self.shader.name.clone(), message }
    }

    /// Sets a global variable to a value: a [`Num`] of the global's width, uniform or with one
    /// lane per point.
    pub fn set_global(&mut self, name: &str, v: Num) -> Result<(), ExecError> {
        let Some(k) = GLOBALS.iter().position(|g| g.name == name) else {
            return Err(self.input_err(format!("no global variable \"{name}\"")));
        };
        let w = value::width(GLOBALS[k].ty.base);
        if v.w != w || v.data.len() != if v.varying { w * self.n } else { w } {
            return Err(self.input_err(format!(
                "global \"{name}\" takes {w} floats per point ({} points), got {} floats",
                self.n,
                v.data.len()
            )));
        }
        // Kept once: a run starts its globals from the inputs, and `get` reads the input
        // until then.
        self.inputs[k] = Some(Value::Num(v));
        self.globals[k] = None;
        Ok(())
    }

    /// Sets a global to one value for the whole grid.
    pub fn set_uniform(&mut self, name: &str, data: &[f32]) -> Result<(), ExecError> {
        self.set_global(name, Num::uniform(data))
    }

    /// Sets a global to one value per point (`width * points` floats, point after point).
    pub fn set_varying(&mut self, name: &str, data: &[f32]) -> Result<(), ExecError> {
        let w = GLOBALS.iter().find(|g| g.name == name).map_or(1, |g| value::width(g.ty.base));
        let mut buf = pool::take(data.len());
        buf.extend_from_slice(data);
        self.set_global(name, Num { w, varying: true, data: buf })
    }

    /// Sets `u`, `v` (per point, evenly from `u0` to `u1` along a row and `v0` to `v1` down a
    /// column, as a dicer makes them), `du`, `dv` (one step), and `s`, `t` to the same values
    /// (the Specification's default texture coordinates; set them after to override).
    pub fn set_parametric(&mut self, u0: f32, u1: f32, v0: f32, v1: f32) -> Result<(), ExecError> {
        let (nu, nv) = (self.nu, self.nv);
        let step = |a: f32, b: f32, k: usize| if k > 1 { (b - a) / (k - 1) as f32 } else { 0.0 };
        let (du, dv) = (step(u0, u1, nu), step(v0, v1, nv));
        let at = |a: f32, b: f32, d: f32, i: usize, k: usize| {
            if i + 1 == k && k > 1 { b } else { a + d * i as f32 }
        };
        let u: Vec<f32> = (0..self.n).map(|i| at(u0, u1, du, i % nu, nu)).collect();
        let v: Vec<f32> = (0..self.n).map(|i| at(v0, v1, dv, i / nu, nv)).collect();
        self.set_varying("u", &u)?;
        self.set_varying("v", &v)?;
        self.set_varying("s", &u)?;
        self.set_varying("t", &v)?;
        self.set_uniform("du", &[du])?;
        self.set_uniform("dv", &[dv])
    }

    /// Sets a shader parameter (a float is broadcast to a triple's three components).
    pub fn set_param(&mut self, name: &str, v: Value) -> Result<(), ExecError> {
        let sh = self.shader;
        let Some(&id) = sh.params.iter().find(|&&i| sh.vars[i].name == name) else {
            return Err(self.input_err(format!("no parameter \"{name}\"")));
        };
        let ty = sh.vars[id].ty;
        let n = self.n;
        let w = value::width(ty.base);
        let fits_num = |x: &Num| {
            (x.w == 1 || x.w == w) && x.data.len() == if x.varying { x.w * n } else { x.w }
        };
        let fits_elem = |x: &Value| match x {
            Value::Num(x) => ty.base != crate::types::BaseType::String && fits_num(x),
            Value::Str(_) => ty.base == crate::types::BaseType::String,
            Value::Array(_) => false,
        };
        let ok = match (&v, ty.array) {
            (Value::Array(xs), Some(len)) => xs.len() == len as usize && xs.iter().all(fits_elem),
            (x, None) => fits_elem(x),
            _ => false,
        };
        if !ok {
            return Err(self.input_err(format!(
                "parameter \"{name}\" is {ty}: the value given does not fit ({n} points)"
            )));
        }
        if v.varying() && sh.vars[id].detail == Detail::Uniform {
            return Err(self.input_err(format!(
                "parameter \"{name}\" is uniform: one value per point needs it declared varying"
            )));
        }
        self.param_set.insert(id, v);
        Ok(())
    }

    /// A global after the run (or as set).
    pub fn get(&self, name: &str) -> Option<&Value> {
        let k = GLOBALS.iter().position(|g| g.name == name)?;
        self.global_value(k)
    }

    /// A global's triple at point `i`.
    pub fn get_v3(&self, name: &str, i: usize) -> Option<[f32; 3]> {
        Some(self.get(name)?.num().v3(i))
    }

    /// A global's float at point `i`.
    pub fn get_f(&self, name: &str, i: usize) -> Option<f32> {
        Some(self.get(name)?.num().f(i))
    }

    /// A parameter's value after the run (`output` parameters are the shader's results).
    pub fn param(&self, name: &str) -> Option<&Value> {
        let sh = self.shader;
        let id = *sh.params.iter().find(|&&i| sh.vars[i].name == name)?;
        self.vars.get(id)
    }

    /// Runs the shader over the grid: parameter defaults (in order, each seeing those before
    /// it) where not set, then the body.
    pub fn run(&mut self) -> Result<Stats, ExecError> {
        if self.n > MAX_POINTS {
            return Err(self.input_err(format!(
                "a grid of {} x {} points is over the limit of {MAX_POINTS}",
                self.nu, self.nv
            )));
        }
        let sh = self.shader;
        let need: u128 = sh
            .vars
            .iter()
            .map(|v| {
                let lanes = if v.detail == Detail::Varying { self.n } else { 1 };
                u128::from(v.ty.array.unwrap_or(1).max(1))
                    * value::width(v.ty.base) as u128
                    * lanes as u128
            })
            .sum();
        if need > MAX_FLOATS as u128 {
            return Err(self.input_err(format!(
                "its variables need {need} floats on a {} x {} grid, over the limit of {MAX_FLOATS}",
                self.nu, self.nv
            )));
        }
        self.stats = Stats::default();
        self.printed.clear();
        pool::recycle_lights(self.light_cache.take());
        self.init_globals();
        let n = self.n;
        self.recycle_vars();
        self.vars = pool::Pooled(
            sh.vars.iter().map(|v| Value::zero(v.ty, v.detail == Detail::Varying, n)).collect(),
        );
        self.frames = vec![stmt::FuncFrame::new(n)];
        self.init_params()?;
        self.exec_block(&sh.body, &Mask::all(n))?;
        Ok(self.stats)
    }

    /// The parameters' values as a run starts the body with them: each one set, or its
    /// default evaluated (in order, each seeing those before it). The body is not run. For
    /// `sloinfo`-style listings.
    pub fn defaults(&mut self) -> Result<Vec<(String, Value)>, ExecError> {
        let sh = self.shader;
        let n = self.n;
        self.stats = Stats::default();
        self.init_globals();
        self.vars = pool::Pooled(
            sh.vars.iter().map(|v| Value::zero(v.ty, v.detail == Detail::Varying, n)).collect(),
        );
        self.frames = vec![stmt::FuncFrame::new(n)];
        self.init_params()?;
        Ok(sh.params.iter().map(|&id| (sh.vars[id].name.clone(), self.vars[id].clone())).collect())
    }

    /// Sets every parameter: the value given, or its default evaluated.
    fn init_params(&mut self) -> Result<(), ExecError> {
        let sh = self.shader;
        let n = self.n;
        let all = Mask::all(n);
        for &id in &sh.params {
            let var = &sh.vars[id];
            let v = match (self.param_set.get(&id), &var.kind) {
                (Some(v), _) => v.clone(),
                (None, VarKind::Param { default: Some(d), .. }) => self.eval(d, &all)?,
                _ => continue,
            };
            let mut dst = std::mem::replace(&mut self.vars[id], Value::Str(String::new()));
            value::store(&mut dst, &v, &all, n);
            self.vars[id] = dst;
        }
        Ok(())
    }

    fn init_globals(&mut self) {
        let n = self.n;
        let written = &self.shader.globals_written;
        let light = self.shader.kind == ShaderKind::Light;
        for (k, g) in GLOBALS.iter().enumerate() {
            if let Some(old) = self.globals[k].take() {
                pool::recycle(old);
            }
            let varying = g.detail == Detail::Varying;
            let w = value::width(g.ty.base);
            // Places the shader writes (and the lights' L, Cl, Ol) hold a lane per point.
            let lit = matches!(g.name, "L" | "Cl" | "Ol");
            let lanes = varying && (written.contains(&g.name) || lit || (light && g.name == "Ps"));
            let fixed = matches!(g.name, "PI" | "ncomps");
            let given = matches!(self.inputs[k], Some(Value::Num(_)));
            if given && !fixed && !lanes && !written.contains(&g.name) {
                // Read in place from the input ([`Self::global_value`]): no copy per run.
                continue;
            }
            let v = match g.name {
                "PI" => Num::scalar(std::f32::consts::PI),
                "ncomps" => Num::scalar(3.0),
                _ => match self.inputs[k].as_ref() {
                    Some(Value::Num(v)) => v.clone(),
                    _ => match g.name {
                        "Cs" | "Os" => Num::uniform(&[1.0; 3]),
                        _ => Num::zeros(w, false, n),
                    },
                },
            };
            let v = if lanes && !v.varying { v.to_varying(n) } else { v };
            self.globals[k] = Some(Value::Num(v));
        }
    }

    /// Global `k` as the shader sees it: its own copy once written (or made varying), else
    /// the input as set (read in place), else its default.
    pub(crate) fn global_value(&self, k: usize) -> Option<&Value> {
        self.globals[k].as_ref().or(self.inputs[k].as_ref())
    }

    /// Gives the variables' buffers of an earlier run back to the pool.
    fn recycle_vars(&mut self) {
        pool::Recycle::recycle(&mut *self.vars);
    }

    pub(crate) fn global_index(name: &str) -> usize {
        GLOBALS.iter().position(|g| g.name == name).unwrap_or(0)
    }

    pub(crate) fn global_num(&self, name: &str) -> Num {
        match self.global_value(Self::global_index(name)) {
            Some(Value::Num(v)) => v.clone(),
            _ => Num::zeros(1, false, self.n),
        }
    }

    pub(crate) fn set_global_masked(&mut self, name: &str, v: &Num, mask: &Mask) {
        let k = Self::global_index(name);
        let n = self.n;
        if self.globals[k].is_none() {
            // Read in place until now: the run's own copy from here on.
            self.globals[k] = self.inputs[k].clone();
        }
        if let Some(Value::Num(dst)) = &mut self.globals[k] {
            if !dst.varying && (v.varying || mask.idx.len() != n) {
                *dst = dst.to_varying(n);
            }
            value::store_num(dst, v, mask, n);
        }
    }

    /// An error at the node being evaluated; the message is put on one line (it may quote
    /// a string the shader computed).
    pub(crate) fn err_at(&self, message: String) -> ExecError {
        ExecError::Unsupported {
            shader: self.shader.name.clone(),
            at: self.shader.sources.show(self.at),
            message: crate::error::OneLine(&message).to_string(),
        }
    }

    pub(crate) fn tick(&mut self) -> Result<(), ExecError> {
        self.stats.instructions += 1;
        if self.stats.instructions > self.budget {
            return Err(ExecError::Budget {
                shader: self.shader.name.clone(),
                budget: self.budget,
                at: self.shader.sources.show(self.at),
            });
        }
        Ok(())
    }
}
