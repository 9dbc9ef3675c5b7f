//! Texture lookups: `texture`, `environment` and `shadow` go through a callback the renderer
//! implements ([`Textures`], over reyes-texture in the renderer), so this leaf crate reads no
//! files.
//!
//! The machine gives the callback, for each active point, the four corners of the region to
//! filter: the forms with four corners pass them as written; `texture(name, s, t)` makes them
//! from the derivatives, `(s, t)`, `(s, t) + Du du`, `(s, t) + Dv dv`, `(s, t) + Du du + Dv dv`
//! (the micropolygon's footprint in texture space); `texture(name)` does the same with the
//! globals `s` and `t`. `environment` passes the direction (or four), `shadow` the point (or
//! four). Options (`"blur"`, `"width"`, ...) pass through evaluated.

use crate::ir::Expr;

use super::value::{Mask, Num, Value, map_n};
use super::{ExecError, GridContext};

/// What is looked up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LookupKind {
    /// `texture`: corners are (s, t) pairs (floats, `w` 1).
    Texture,
    /// `environment`: corners are directions (`w` 3).
    Environment,
    /// `shadow`: corners are points (`w` 3).
    Shadow,
}

/// One lookup over a grid.
pub struct TextureQuery<'q> {
    /// Which function.
    pub kind: LookupKind,
    /// The map's name.
    pub name: &'q str,
    /// The first channel (`texture("map"[1], ...)`; 0 when not given).
    pub channel: usize,
    /// Channels wanted per point: 1 (float) or 3 (colour).
    pub channels: usize,
    /// `texture`: s0, t0, s1, t1, s2, t2, s3, t3 (each a float per point); `environment` and
    /// `shadow`: the one or four directions/points.
    pub coords: Vec<Num>,
    /// The options, evaluated.
    pub options: Vec<(String, Value)>,
    /// The points to look up.
    pub mask: &'q Mask,
}

/// The renderer's side: filtered lookups. The result is a `Num` of `channels` floats, uniform
/// or one lane per point.
pub trait Textures {
    /// Looks up a grid's worth of texture.
    fn lookup(&mut self, q: &TextureQuery<'_>) -> Result<Num, ExecError>;
}

impl GridContext<'_> {
    pub(crate) fn texture_call(
        &mut self,
        name: &str,
        e: &Expr,
        vals: &[Value],
        channel: Option<&Expr>,
        options: &[(String, Expr)],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let kind = match name {
            "texture" => LookupKind::Texture,
            "environment" => LookupKind::Environment,
            _ => LookupKind::Shadow,
        };
        let channel = match channel {
            Some(c) => self.eval(c, mask)?.num().f(0).max(0.0) as usize,
            None => 0,
        };
        let mut opts = Vec::with_capacity(options.len());
        for (k, v) in options {
            opts.push((k.clone(), self.eval(v, mask)?));
        }
        let n = self.n;
        let coords: Vec<Num> = if kind == LookupKind::Texture && vals.len() <= 3 {
            let (s, t) = if vals.len() == 3 {
                (vals[1].num().clone(), vals[2].num().clone())
            } else {
                (self.global_num("s"), self.global_num("t"))
            };
            let (du, dv) = (self.global_num("du"), self.global_num("dv"));
            let step = |x: &Num, along_v: bool, this: &Self| {
                let d = this.deriv(x, along_v, mask);
                let h = if along_v { &dv } else { &du };
                map_n(n, mask, &[&d, h], 1, |l, o| o[0] = l[0][0] * l[1][0])
            };
            let (su, sv, tu, tv) = (
                step(&s, false, self),
                step(&s, true, self),
                step(&t, false, self),
                step(&t, true, self),
            );
            let add = |a: &Num, b: &[&Num]| {
                let mut args = vec![a];
                args.extend_from_slice(b);
                map_n(n, mask, &args, 1, |l, o| o[0] = l.iter().map(|x| x[0]).sum())
            };
            vec![
                s.clone(),
                t.clone(),
                add(&s, &[&su]),
                add(&t, &[&tu]),
                add(&s, &[&sv]),
                add(&t, &[&tv]),
                add(&s, &[&su, &sv]),
                add(&t, &[&tu, &tv]),
            ]
        } else {
            vals[1..].iter().map(|v| v.num().clone()).collect()
        };
        let channels = super::value::width(e.ty.base);
        let Some(tex) = self.textures.as_deref_mut() else {
            return Err(self.err_at(format!("\"{name}\" needs a texture callback (set_textures)")));
        };
        let q = TextureQuery {
            kind,
            name: vals[0].str(),
            channel,
            channels,
            coords,
            options: opts,
            mask,
        };
        let out = tex.lookup(&q)?;
        if out.w != channels || out.data.len() != if out.varying { channels * n } else { channels }
        {
            return Err(self.err_at(format!(
                "the texture callback returned {} floats, not {channels} per point",
                out.data.len()
            )));
        }
        Ok(Value::Num(out))
    }
}
