//! Expressions: constants, names and predefined variables, indexing, unary operators, `?:`,
//! typecasts and space-typed constructors; which expressions take their type from their
//! context (parenthesised triples and arithmetic on them).

use crate::ast::{self, BinOp, ExprKind as A, UnOp};
use crate::error::{DResult, Diag, Pos};
use crate::globals::{Access, Global};
use crate::ir::*;
use crate::library::library;
use crate::types::{BaseType, Detail, ShaderKind, Type};

use super::convert::{conv_cost, describe_type};
use super::{Checker, Sym};

pub(super) fn is_loose(e: &ast::Expr) -> bool {
    match &e.kind {
        A::Tuple(_) => true,
        A::Unary(UnOp::Neg, x) => is_loose(x),
        A::Binary(BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div, a, b) => {
            is_loose(a) || is_loose(b)
        }
        A::Cond(_, a, b) => is_loose(a) || is_loose(b),
        _ => false,
    }
}

pub(super) fn context_dependent(e: &ast::Expr) -> bool {
    matches!(e.kind, A::Call(..)) || is_loose(e)
}

impl Checker<'_> {
    pub(super) fn expr(&mut self, e: &ast::Expr, want: Option<Type>) -> DResult<Expr> {
        let pos = e.pos;
        let mk = |kind, ty, detail| Expr { kind, ty, detail, pos };
        match &e.kind {
            A::Num(v) => Ok(mk(ExprKind::Float(*v), Type::FLOAT, Detail::Uniform)),
            A::Str(s) => Ok(mk(ExprKind::Str(s.clone()), Type::STRING, Detail::Uniform)),
            A::Name(n) => self.name(n, pos),
            A::ArrayLit(_) => {
                Err(Diag::new(pos, "an array initialiser {…} is allowed only in a declaration"))
            }
            A::Tuple(items) => {
                let target = match want {
                    Some(t)
                        if t.array.is_none()
                            && (t.base.is_triple() || t.base == BaseType::Matrix) =>
                    {
                        t.base
                    }
                    _ if items.len() == 16 => BaseType::Matrix,
                    _ => BaseType::Point,
                };
                self.construct(items, target, None, pos)
            }
            A::Index(base, idx) => {
                let b = self.expr(base, None)?;
                if b.ty.array.is_none() {
                    let hint = if b.ty == Type::STRING {
                        " (a channel [n] follows only the map name of texture, environment and shadow)"
                    } else {
                        ""
                    };
                    return Err(Diag::new(
                        pos,
                        format!("indexing a {}, which is not an array{hint}", describe_type(b.ty)),
                    ));
                }
                let i = self.index(idx, b.ty)?;
                let detail = b.detail.join(i.detail);
                Ok(mk(ExprKind::Index(Box::new(b.clone()), Box::new(i)), b.ty.element(), detail))
            }
            A::Unary(UnOp::Neg, x) => {
                let v = self.expr(x, want)?;
                if !v.ty.base.is_numeric() || v.ty.is_array() {
                    return Err(Diag::new(
                        pos,
                        format!(
                            "unary '-' takes a float, colour, point, vector, normal or matrix, got {}",
                            describe_type(v.ty)
                        ),
                    ));
                }
                let (ty, d) = (v.ty, v.detail);
                Ok(mk(ExprKind::Unary(UnOp::Neg, Box::new(v)), ty, d))
            }
            A::Unary(UnOp::Not, x) => {
                let v = self.expr(x, None)?;
                let v = self.as_condition(v, "the operand of '!'")?;
                let d = v.detail;
                Ok(mk(ExprKind::Unary(UnOp::Not, Box::new(v)), Type::BOOL, d))
            }
            A::Binary(op, l, r) => self.binary(*op, l, r, want, pos),
            A::Assign(op, target, value) => self.assign(*op, target, value, pos),
            A::Cond(c, a, b) => {
                let c = self.condition(c, "the condition of '?:'")?;
                let varying = c.detail == Detail::Varying;
                if varying {
                    self.ctrl.push(c.pos);
                }
                let x = self.expr(a, want);
                let y = match &x {
                    Ok(x) => self.expr(b, Some(want.unwrap_or(x.ty))),
                    Err(_) => Ok(mk(ExprKind::Float(0.0), Type::FLOAT, Detail::Uniform)),
                };
                if varying {
                    self.ctrl.pop();
                }
                let (x, y) = (x?, y?);
                let ty = if x.ty == y.ty {
                    x.ty
                } else if conv_cost(x.ty, y.ty).is_some()
                    && (x.ty == Type::FLOAT || y.ty.base == BaseType::Point)
                {
                    y.ty
                } else if conv_cost(y.ty, x.ty).is_some() {
                    x.ty
                } else {
                    return Err(Diag::new(
                        pos,
                        format!(
                            "the branches of '?:' have different types: {} and {}",
                            describe_type(x.ty),
                            describe_type(y.ty)
                        ),
                    ));
                };
                let x = self.convert(x, ty, "a branch of '?:'")?;
                let y = self.convert(y, ty, "a branch of '?:'")?;
                let detail = c.detail.join(x.detail).join(y.detail);
                Ok(mk(ExprKind::Cond(Box::new(c), Box::new(x), Box::new(y)), ty, detail))
            }
            A::Cast(base, space, x) => self.cast(*base, space.as_ref(), x, pos),
            A::Call(name, args) => self.call(name, args, want, pos),
        }
    }

    pub(super) fn index(&mut self, idx: &ast::Expr, arr: Type) -> DResult<Expr> {
        let i = self.expr(idx, Some(Type::FLOAT))?;
        if i.ty != Type::FLOAT {
            return Err(Diag::new(
                i.pos,
                format!("an array index must be a float, got {}", describe_type(i.ty)),
            ));
        }
        if let (Some(v), Some(n)) = (i.as_const(), arr.array)
            && n > 0
            && (v < 0.0 || v >= f64::from(n) || v.fract() != 0.0)
        {
            return Err(Diag::new(
                i.pos,
                format!("index {v} is out of range for {arr} (0 to {})", n - 1),
            ));
        }
        Ok(i)
    }

    pub(super) fn name(&mut self, n: &str, pos: Pos) -> DResult<Expr> {
        match self.lookup_var(n, pos)? {
            Some(Sym::Var(id)) => {
                let v = &self.vars[id];
                Ok(Expr { kind: ExprKind::Var(id), ty: v.ty, detail: v.detail, pos })
            }
            Some(Sym::Global(g)) => {
                self.global_read(g, pos)?;
                Ok(Expr { kind: ExprKind::Global(g.name), ty: g.ty, detail: g.detail, pos })
            }
            _ => {
                if !self.lookup_funcs(n).is_empty() || library().get(n).is_some() {
                    return Err(Diag::new(
                        pos,
                        format!("\"{n}\" is a function: call it as {n}(...)"),
                    ));
                }
                Err(Diag::new(pos, format!("undeclared variable \"{n}\"")))
            }
        }
    }

    pub(super) fn global_read(&mut self, g: &'static Global, pos: Pos) -> DResult<()> {
        if g.access(self.kind) == Access::None {
            return Err(Diag::new(
                pos,
                format!("{} shaders have no predefined variable \"{}\"", self.kind, g.name),
            ));
        }
        if g.in_illuminance
            && self.kind == ShaderKind::Surface
            && self.illuminance == 0
            && self.fstack.is_empty()
        {
            return Err(Diag::new(
                pos,
                format!("\"{}\" is defined only inside an illuminance statement", g.name),
            ));
        }
        self.note_read(g);
        Ok(())
    }

    pub(super) fn construct(
        &mut self,
        items: &[ast::Expr],
        target: BaseType,
        space: Option<(String, Pos)>,
        pos: Pos,
    ) -> DResult<Expr> {
        let n = items.len();
        let ok = match target {
            BaseType::Matrix => n == 16,
            b if b.is_triple() => n == 3,
            _ => false,
        };
        if !ok {
            let need = if target == BaseType::Matrix { "16" } else { "3" };
            return Err(Diag::new(
                pos,
                format!("a {target} is made of {need} floats, got a list of {n}"),
            ));
        }
        let mut parts = Vec::new();
        let mut detail = Detail::Uniform;
        for it in items {
            let v = self.expr(it, Some(Type::FLOAT))?;
            if v.ty != Type::FLOAT {
                return Err(Diag::new(
                    v.pos,
                    format!(
                        "a component of a {target} must be a float, got {}",
                        describe_type(v.ty)
                    ),
                ));
            }
            detail = detail.join(v.detail);
            parts.push(v);
        }
        let space = space.map(|(s, spos)| self.check_space(target, s, spos)).transpose()?;
        Ok(Expr {
            kind: ExprKind::Construct { parts, space },
            ty: Type::scalar(target),
            detail,
            pos,
        })
    }

    pub(super) fn check_space(&self, target: BaseType, s: String, pos: Pos) -> DResult<String> {
        if target == BaseType::Color {
            const COLOR_SPACES: &[&str] = &["rgb", "hsv", "hsl", "xyz", "XYZ", "xyY", "YIQ"];
            if !COLOR_SPACES.contains(&s.as_str()) {
                return Err(Diag::new(
                    pos,
                    format!("unknown colour space \"{s}\" (rgb, hsv, hsl, xyz, xyY, YIQ)"),
                ));
            }
        }
        Ok(s)
    }

    pub(super) fn cast(
        &mut self,
        base: BaseType,
        space: Option<&(String, Pos)>,
        x: &ast::Expr,
        pos: Pos,
    ) -> DResult<Expr> {
        if let A::Tuple(items) = &x.kind {
            return self.construct(items, base, space.cloned(), pos);
        }
        if base == BaseType::String {
            return Err(Diag::new(pos, "no cast to string"));
        }
        let v = self.expr(x, Some(Type::scalar(base)))?;
        let target = Type::scalar(base);
        if v.ty.is_array() {
            return Err(Diag::new(pos, format!("cannot cast an array ({}) to {base}", v.ty)));
        }
        let ok = v.ty == target
            || v.ty == Type::FLOAT && (base.is_triple() || base == BaseType::Matrix)
            || v.ty.base.is_triple() && base.is_triple();
        if !ok {
            return Err(Diag::new(pos, format!("cannot cast {} to {base}", describe_type(v.ty))));
        }
        let detail = v.detail;
        let value = if v.ty == target {
            v
        } else {
            Expr { kind: ExprKind::Convert(Box::new(v)), ty: target, detail, pos }
        };
        match space {
            None => Ok(value),
            Some((s, spos)) => {
                if base == BaseType::Float {
                    return Err(Diag::new(*spos, "a float has no space"));
                }
                let s = self.check_space(base, s.clone(), *spos)?;
                Ok(Expr {
                    kind: ExprKind::SpaceCast { space: s, value: Box::new(value) },
                    ty: target,
                    detail,
                    pos,
                })
            }
        }
    }
}
