//! Assignments and the places they write: a variable, an array element or a writable
//! predefined variable of the shader type; `op=` typed as `x = x op y`.

use crate::ast::{self, AssignOp, ExprKind as A};
use crate::error::{DResult, Diag, Pos};
use crate::globals::{Access, global};
use crate::ir::*;
use crate::library::library;
use crate::types::{BaseType, Detail, Type};

use super::convert::{conv_cost, describe_type};
use super::detail::make_uniform;
use super::{Checker, Sym};

impl Checker<'_> {
    /// The place an assignment (or an output argument) writes.
    pub(super) fn place(
        &mut self,
        target: &ast::Expr,
        what: &str,
    ) -> DResult<(Place, Option<Expr>, Type, Pos)> {
        let (name, npos, index) = match &target.kind {
            A::Name(n) => (n, target.pos, None),
            A::Index(b, i) => match &b.kind {
                A::Name(n) => (n, b.pos, Some(i)),
                _ => {
                    return Err(Diag::new(
                        target.pos,
                        format!("{what}: only a variable or an array element can be assigned"),
                    ));
                }
            },
            _ => {
                return Err(Diag::new(
                    target.pos,
                    format!("{what}: only a variable or an array element can be assigned"),
                ));
            }
        };
        let (place, ty) = match self.lookup_var(name, npos)? {
            Some(Sym::Var(id)) => (Place::Var(id), self.vars[id].ty),
            Some(Sym::Global(g)) => {
                match g.access(self.kind) {
                    Access::None => {
                        return Err(Diag::new(
                            npos,
                            format!(
                                "{} shaders have no predefined variable \"{}\"",
                                self.kind, g.name
                            ),
                        ));
                    }
                    Access::Read => {
                        return Err(Diag::new(
                            npos,
                            format!("\"{}\" is read-only in {} shaders", g.name, self.kind),
                        ));
                    }
                    Access::ReadWrite => {}
                }
                if !self.written.contains(&g.name) {
                    self.written.push(g.name);
                }
                (Place::Global(g.name), g.ty)
            }
            _ => {
                if library().get(name).is_some() || !self.lookup_funcs(name).is_empty() {
                    return Err(Diag::new(
                        npos,
                        format!("{what}: \"{name}\" is a function, not a variable"),
                    ));
                }
                return Err(Diag::new(npos, format!("undeclared variable \"{name}\"")));
            }
        };
        let (index, ty) = match index {
            None => (None, ty),
            Some(i) => {
                if ty.array.is_none() {
                    return Err(Diag::new(
                        target.pos,
                        format!("indexing \"{name}\", a {ty}, which is not an array"),
                    ));
                }
                (Some(self.index(i, ty)?), ty.element())
            }
        };
        Ok((place, index, ty, npos))
    }

    pub(super) fn write_place(
        &mut self,
        place: &Place,
        index: Option<&Expr>,
        detail: Detail,
        pos: Pos,
    ) -> DResult<()> {
        let d = detail.join(index.map_or(Detail::Uniform, |i| i.detail));
        if let Place::Var(id) = place {
            let probe = Expr { kind: ExprKind::Float(0.0), ty: Type::FLOAT, detail: d, pos };
            self.assign_detail(*id, &probe, pos)?;
        }
        Ok(())
    }

    pub(super) fn assign(
        &mut self,
        op: AssignOp,
        target: &ast::Expr,
        value: &ast::Expr,
        pos: Pos,
    ) -> DResult<Expr> {
        let (place, index, ty, _npos) = self.place(target, &format!("'{}'", op.as_str()))?;
        let v = self.expr(value, Some(ty))?;
        let v = match op.binop() {
            None => self.convert(
                v,
                ty,
                &format!("the value assigned to \"{}\"", self.place_name(&place)),
            )?,
            Some(b) => {
                // x op= y must type as x = x op y, with the result of x's type.
                let cur = Expr { kind: ExprKind::Float(0.0), ty, detail: Detail::Uniform, pos };
                let r = self.binary_typed(b, cur, v.clone(), pos)?;
                if conv_cost(r.ty, ty).is_none() {
                    return Err(Diag::new(
                        pos,
                        format!(
                            "'{}' on a {ty} with a {} gives a {}",
                            op.as_str(),
                            describe_type(v.ty),
                            r.ty
                        ),
                    ));
                }
                if ty.base == BaseType::Matrix || v.ty == ty {
                    v
                } else if v.ty == Type::FLOAT || (v.ty.base.is_spatial() && ty.base.is_spatial()) {
                    Expr { ty, detail: v.detail, pos: v.pos, kind: ExprKind::Convert(Box::new(v)) }
                } else {
                    v
                }
            }
        };
        let mut v = v;
        if let (Place::Var(id), None) = (&place, &index)
            && self.vars[*id].declared == Some(Detail::Uniform)
        {
            make_uniform(&mut v);
        }
        self.write_place(&place, index.as_ref(), v.detail, pos)?;
        let detail = match &place {
            Place::Var(id) => self.vars[*id].detail,
            Place::Global(g) => global(g).map_or(Detail::Varying, |g| g.detail),
        };
        Ok(Expr {
            kind: ExprKind::Assign { place, index: index.map(Box::new), op, value: Box::new(v) },
            ty,
            detail,
            pos,
        })
    }

    pub(super) fn place_name(&self, p: &Place) -> String {
        match p {
            Place::Var(id) => self.vars[*id].name.clone(),
            Place::Global(g) => (*g).to_string(),
        }
    }

    pub(super) fn place_expr(
        &mut self,
        place: Place,
        index: Option<Expr>,
        ty: Type,
        pos: Pos,
    ) -> Expr {
        let (kind, detail) = match &place {
            Place::Var(id) => (ExprKind::Var(*id), self.vars[*id].detail),
            Place::Global(g) => {
                (ExprKind::Global(g), global(g).map_or(Detail::Varying, |g| g.detail))
            }
        };
        let whole_ty = match &place {
            Place::Var(id) => self.vars[*id].ty,
            Place::Global(g) => global(g).map_or(ty, |g| g.ty),
        };
        let base = Expr { kind, ty: whole_ty, detail, pos };
        match index {
            None => base,
            Some(i) => {
                let d = detail.join(i.detail);
                Expr { kind: ExprKind::Index(Box::new(base), Box::new(i)), ty, detail: d, pos }
            }
        }
    }
}
