//! Expressions: each node computes its value for the whole grid, once when uniform, at the
//! active points when varying. Operators follow the Specification's table (the checker made
//! every promotion an explicit conversion, so operands arrive in their final types).

use crate::ast::{AssignOp, BinOp, UnOp};
use crate::ir::{Callee, Expr, ExprKind, Place};
use crate::types::{BaseType, Type};

use super::lanes::{map_v3, map_v3_f};
use super::pool;
use super::space::{mat_inverse, mat_mul};
use super::value::{self, Mask, Num, Value, map_c, map_c1, map_c2, map_n};
use super::{ExecError, GridContext};

impl GridContext<'_> {
    /// Evaluates `e` at the active points of `mask`.
    pub(crate) fn eval(&mut self, e: &Expr, mask: &Mask) -> Result<Value, ExecError> {
        self.at = e.pos;
        self.tick()?;
        let n = self.n;
        Ok(match &e.kind {
            ExprKind::Float(v) => Value::Num(Num::scalar(*v as f32)),
            ExprKind::Str(s) => Value::Str(s.clone()),
            ExprKind::Var(id) => self.vars[*id].clone(),
            ExprKind::Global(g) => self
                .global_value(Self::global_index(g))
                .cloned()
                .unwrap_or_else(|| Value::Num(Num::scalar(0.0))),
            ExprKind::Index(a, i) => {
                let a = self.eval(a, mask)?;
                let i = self.eval(i, mask)?;
                self.index(&a, i.num(), mask)
            }
            ExprKind::Convert(x) => {
                let v = self.eval(x, mask)?;
                convert(v, x.ty, e.ty, n, mask)
            }
            ExprKind::Unary(op, x) => {
                let x = self.eval(x, mask)?;
                let v = x.num();
                let r = Value::Num(match op {
                    UnOp::Neg => map_c1(n, mask, v, |x| -x),
                    UnOp::Not => map_c1(n, mask, v, |x| bool01(x == 0.0)),
                });
                pool::recycle(x);
                r
            }
            ExprKind::Binary(op @ (BinOp::And | BinOp::Or), a, b) => {
                let a = self.eval(a, mask)?;
                let a = a.num().clone();
                let want = *op == BinOp::Or;
                if !a.varying {
                    if (a.f(0) != 0.0) == want {
                        return Ok(Value::Num(Num::scalar(if want { 1.0 } else { 0.0 })));
                    }
                    let b = self.eval(b, mask)?;
                    return Ok(Value::Num(map_c(n, mask, &[b.num()], |x| bool01(x[0] != 0.0))));
                }
                // The right operand runs only where the left one does not decide.
                let rest = mask.when(&a, !want);
                let b = if rest.is_empty() {
                    Value::Num(Num::scalar(0.0))
                } else {
                    self.eval(b, &rest)?
                };
                let b = b.num();
                Value::Num(map_n(n, mask, &[&a, &b.to_varying(n)], 1, |l, o| {
                    let x = l[0][0] != 0.0;
                    o[0] = bool01(if x == want { want } else { l[1][0] != 0.0 });
                }))
            }
            ExprKind::Binary(op, a, b) => {
                let a = self.eval(a, mask)?;
                let b = self.eval(b, mask)?;
                if let (Value::Str(x), Value::Str(y)) = (&a, &b) {
                    let eq = x == y;
                    return Ok(Value::Num(Num::scalar(bool01(if *op == BinOp::Ne {
                        !eq
                    } else {
                        eq
                    }))));
                }
                let r = binary(*op, a.num(), b.num(), n, mask);
                pool::recycle(a);
                pool::recycle(b);
                Value::Num(r)
            }
            ExprKind::Assign { place, index, op, value } => {
                let v = self.eval(value, mask)?;
                let idx = match index {
                    Some(i) => Some(self.eval(i, mask)?),
                    None => None,
                };
                let v = if *op == AssignOp::Set {
                    v
                } else {
                    let cur = self.read_place(place);
                    let cur = match &idx {
                        Some(i) => self.index(&cur, i.num(), mask),
                        None => cur,
                    };
                    let bop = match op {
                        AssignOp::Add => BinOp::Add,
                        AssignOp::Sub => BinOp::Sub,
                        AssignOp::Mul => BinOp::Mul,
                        _ => BinOp::Div,
                    };
                    let r = binary(bop, cur.num(), v.num(), n, mask);
                    pool::recycle(cur);
                    pool::recycle(v);
                    Value::Num(r)
                };
                self.assign(place, idx.as_ref().map(Value::num), &v, mask);
                if let Some(i) = idx {
                    pool::recycle(i);
                }
                v
            }
            ExprKind::Cond(c, a, b) => {
                let c = self.eval(c, mask)?;
                let c = c.num().clone();
                if !c.varying {
                    return self.eval(if c.f(0) != 0.0 { a } else { b }, mask);
                }
                let (mt, mf) = (mask.when(&c, true), mask.when(&c, false));
                let mut out = Value::zero(e.ty, true, n);
                if !mt.is_empty() {
                    let x = self.eval(a, &mt)?;
                    value::store(&mut out, &x, &mt, n);
                    pool::recycle(x);
                }
                if !mf.is_empty() {
                    let y = self.eval(b, &mf)?;
                    value::store(&mut out, &y, &mf, n);
                    pool::recycle(y);
                }
                out
            }
            ExprKind::Construct { parts, space } => {
                let mut vals = Vec::with_capacity(parts.len());
                for p in parts {
                    vals.push(self.eval(p, mask)?);
                }
                let nums: Vec<&Num> = vals.iter().map(Value::num).collect();
                let w = value::width(e.ty.base);
                let v = map_n(n, mask, &nums, w, |l, o| {
                    for (c, oc) in o.iter_mut().enumerate() {
                        *oc = if l.len() == 1 { l[0][0] } else { l.get(c).map_or(0.0, |x| x[0]) };
                    }
                    if w == 16 && l.len() == 1 {
                        for (c, oc) in o.iter_mut().enumerate() {
                            *oc = if c % 5 == 0 { l[0][0] } else { 0.0 };
                        }
                    }
                });
                vals.into_iter().for_each(pool::recycle);
                match space {
                    Some(s) => Value::Num(self.in_space(s, e.ty.base, &v, mask)?),
                    None => Value::Num(v),
                }
            }
            ExprKind::SpaceCast { space, value } => {
                let v = self.eval(value, mask)?;
                Value::Num(self.in_space(space, e.ty.base, v.num(), mask)?)
            }
            ExprKind::Call { callee: Callee::User(f), args, .. } => {
                self.call_user(*f, args, e, mask)?
            }
            ExprKind::Call { callee: Callee::Builtin { name, .. }, args, options, channel }
                if matches!(*name, "texture" | "environment" | "shadow") =>
            {
                let mut vals = Vec::with_capacity(args.len());
                for a in args {
                    vals.push(self.eval(a, mask)?);
                }
                self.texture_call(name, e, &vals, channel.as_deref(), options, mask)?
            }
            ExprKind::Call { callee: Callee::Builtin { name, .. }, args, options, .. } => {
                self.builtin(name, e, args, options, mask)?
            }
            ExprKind::Array(v) => {
                let mut out = Vec::with_capacity(v.len());
                for x in v {
                    out.push(self.eval(x, mask)?);
                }
                Value::Array(out)
            }
        })
    }

    /// Element `i` of array `a` (an index out of range is clamped, and counted).
    pub(crate) fn index(&mut self, a: &Value, i: &Num, mask: &Mask) -> Value {
        let Value::Array(elems) = a else { return a.clone() };
        if elems.is_empty() {
            return Value::Num(Num::scalar(0.0));
        }
        let len = elems.len();
        let mut clamped = 0;
        let mut pick = |x: f32| {
            let k = x.floor();
            if !(k >= 0.0 && (k as usize) < len) {
                clamped += 1;
            }
            if k >= 0.0 { (k as usize).min(len - 1) } else { 0 }
        };
        let out = if !i.varying {
            elems[pick(i.f(0))].clone()
        } else {
            let mut out = match &elems[0] {
                Value::Num(x) => Value::Num(Num::zeros(x.w, true, self.n)),
                other => other.clone(),
            };
            if let Value::Num(o) = &mut out {
                for p in mask.iter() {
                    let k = pick(i.f(p));
                    let src = elems[k].num().lane(p);
                    let w = o.w.min(src.len());
                    o.lane_mut(p)[..w].copy_from_slice(&src[..w]);
                }
            }
            out
        };
        self.stats.index_clamped += clamped;
        out
    }

    pub(crate) fn read_place(&self, place: &Place) -> Value {
        match place {
            Place::Var(id) => self.vars[*id].clone(),
            Place::Global(g) => self
                .global_value(Self::global_index(g))
                .cloned()
                .unwrap_or_else(|| Value::Num(Num::scalar(0.0))),
        }
    }

    /// Stores `v` at `place` (element `idx` if given) at the active points.
    pub(crate) fn assign(&mut self, place: &Place, idx: Option<&Num>, v: &Value, mask: &Mask) {
        if let Value::Num(x) = v {
            self.stats.nonfinite += value::count_nonfinite(x, mask);
        }
        let n = self.n;
        match (place, idx) {
            (Place::Global(g), _) => {
                if *g == "P" {
                    pool::recycle_lights(self.light_cache.take());
                }
                self.set_global_masked(g, v.num(), mask);
            }
            (Place::Var(id), None) => value::store(&mut self.vars[*id], v, mask, n),
            (Place::Var(id), Some(i)) => {
                let Value::Array(elems) = &mut self.vars[*id] else { return };
                let len = elems.len();
                if len == 0 {
                    return;
                }
                let k_of = |x: f32| if x >= 0.0 { (x.floor() as usize).min(len - 1) } else { 0 };
                let mut clamped = 0;
                if !i.varying {
                    let x = i.f(0);
                    if !(x >= 0.0 && (x.floor() as usize) < len) {
                        clamped += 1;
                    }
                    value::store(&mut elems[k_of(x)], v, mask, n);
                } else {
                    for p in mask.iter() {
                        let x = i.f(p);
                        if !(x >= 0.0 && (x.floor() as usize) < len) {
                            clamped += 1;
                        }
                    }
                    for (k, elem) in elems.iter_mut().enumerate() {
                        let m = mask.filter(|p| k_of(i.f(p)) == k);
                        if !m.is_empty() {
                            value::store(elem, v, &m, n);
                        }
                    }
                }
                self.stats.index_clamped += clamped;
            }
        }
    }

    /// Writes `v` to the place an output argument names (`Var`, `Global`, `Index`).
    pub(crate) fn write_place(
        &mut self,
        a: &Expr,
        v: &Value,
        mask: &Mask,
    ) -> Result<(), ExecError> {
        match &a.kind {
            ExprKind::Var(id) => self.assign(&Place::Var(*id), None, v, mask),
            ExprKind::Global(g) => self.assign(&Place::Global(g), None, v, mask),
            ExprKind::Index(b, i) => {
                if let ExprKind::Var(id) = &b.kind {
                    let i = self.eval(i, mask)?;
                    self.assign(&Place::Var(*id), Some(i.num()), v, mask);
                }
            }
            ExprKind::Convert(x) => self.write_place(x, v, mask)?,
            _ => {}
        }
        Ok(())
    }
}

pub(crate) fn bool01(b: bool) -> f32 {
    if b { 1.0 } else { 0.0 }
}

/// The conversions the checker made explicit: float to triple or matrix, between spatial
/// types, float to boolean; arrays element by element.
pub(crate) fn convert(v: Value, from: Type, to: Type, n: usize, mask: &Mask) -> Value {
    match v {
        Value::Array(xs) => Value::Array(
            xs.into_iter().map(|x| convert(x, from.element(), to.element(), n, mask)).collect(),
        ),
        Value::Num(x) => {
            let (fb, tb) = (from.base, to.base);
            let r = match (fb, tb) {
                (BaseType::Float, t) if t.is_triple() => map_n(n, mask, &[&x], 3, |l, o| {
                    o.fill(l[0][0]);
                }),
                (BaseType::Float, BaseType::Matrix) => map_n(n, mask, &[&x], 16, |l, o| {
                    for (c, oc) in o.iter_mut().enumerate() {
                        *oc = if c % 5 == 0 { l[0][0] } else { 0.0 };
                    }
                }),
                (_, BaseType::Bool) if x.w == 1 => map_c(n, mask, &[&x], |a| bool01(a[0] != 0.0)),
                _ => return Value::Num(x),
            };
            pool::give(x.data);
            Value::Num(r)
        }
        other => other,
    }
}

/// Arithmetic, products, relations and equality on numbers of the operands' widths.
pub(crate) fn binary(op: BinOp, a: &Num, b: &Num, n: usize, mask: &Mask) -> Num {
    match op {
        BinOp::Mul | BinOp::Div if a.w == 16 && b.w == 16 => map_n(n, mask, &[a, b], 16, |l, o| {
            let x: [f32; 16] = l[0].try_into().unwrap_or([0.0; 16]);
            let y: [f32; 16] = l[1].try_into().unwrap_or([0.0; 16]);
            let y = if op == BinOp::Div { mat_inverse(&y) } else { y };
            o.copy_from_slice(&mat_mul(&x, &y));
        }),
        BinOp::Add => map_c2(n, mask, a, b, |x, y| x + y),
        BinOp::Sub => map_c2(n, mask, a, b, |x, y| x - y),
        BinOp::Mul => map_c2(n, mask, a, b, |x, y| x * y),
        BinOp::Div => map_c2(n, mask, a, b, |x, y| x / y),
        // Left to right, as the general case's `Iterator::sum` (which starts from -0, the
        // identity of addition).
        BinOp::Dot if a.w == 3 && b.w == 3 => {
            map_v3_f(n, mask, [a, b], |[x, y]| super::geom::dot(x, y))
        }
        BinOp::Cross if a.w == 3 && b.w == 3 => {
            map_v3(n, mask, [a, b], |[x, y]| super::geom::cross(x, y))
        }
        BinOp::Dot => map_n(n, mask, &[a, b], 1, |l, o| {
            o[0] = l[0].iter().zip(l[1]).map(|(x, y)| x * y).sum();
        }),
        BinOp::Cross => map_n(n, mask, &[a, b], 3, |l, o| {
            let (x, y) = (l[0], l[1]);
            if x.len() == 3 && y.len() == 3 {
                o.copy_from_slice(&super::geom::cross([x[0], x[1], x[2]], [y[0], y[1], y[2]]));
            }
        }),
        BinOp::Eq | BinOp::Ne => {
            let ne = op == BinOp::Ne;
            map_n(n, mask, &[a, b], 1, |l, o| {
                let w = l[0].len().max(l[1].len());
                let g = |s: &[f32], c: usize| if s.len() == 1 { s[0] } else { s[c] };
                let eq = (0..w).all(|c| g(l[0], c) == g(l[1], c));
                o[0] = bool01(eq != ne);
            })
        }
        BinOp::Lt => map_c2(n, mask, a, b, |x, y| bool01(x < y)),
        BinOp::Le => map_c2(n, mask, a, b, |x, y| bool01(x <= y)),
        BinOp::Gt => map_c2(n, mask, a, b, |x, y| bool01(x > y)),
        BinOp::Ge => map_c2(n, mask, a, b, |x, y| bool01(x >= y)),
        BinOp::And => map_c(n, mask, &[a, b], |x| bool01(x[0] != 0.0 && x[1] != 0.0)),
        BinOp::Or => map_c(n, mask, &[a, b], |x| bool01(x[0] != 0.0 || x[1] != 0.0)),
    }
}
