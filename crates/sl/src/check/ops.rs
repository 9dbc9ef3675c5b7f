//! Binary operators: the operand whose type depends on its context is checked in the
//! other's, then the Specification's operator table (arithmetic on triples and matrices, dot
//! and cross products, relations, equality, the logical operators) with the promotions made
//! explicit.

use crate::ast::{self, BinOp};
use crate::error::{DResult, Diag, Pos};
use crate::ir::*;
use crate::types::{BaseType, Detail, Type};

use super::Checker;
use super::convert::describe_type;
use super::expr::{context_dependent, is_loose};

impl Checker<'_> {
    pub(super) fn binary(
        &mut self,
        op: BinOp,
        l: &ast::Expr,
        r: &ast::Expr,
        want: Option<Type>,
        pos: Pos,
    ) -> DResult<Expr> {
        if matches!(op, BinOp::And | BinOp::Or) {
            let a = self.condition(l, &format!("the left operand of '{}'", op.as_str()))?;
            let varying = a.detail == Detail::Varying;
            if varying {
                self.ctrl.push(a.pos);
            }
            let b = self.condition(r, &format!("the right operand of '{}'", op.as_str()));
            if varying {
                self.ctrl.pop();
            }
            let b = b?;
            let d = a.detail.join(b.detail);
            return Ok(Expr {
                kind: ExprKind::Binary(op, Box::new(a), Box::new(b)),
                ty: Type::BOOL,
                detail: d,
                pos,
            });
        }
        // The operand whose type depends on its context is checked second, in the other's.
        let operand_want = match op {
            BinOp::Dot | BinOp::Cross => Some(Type::VECTOR),
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => want,
            _ => None,
        };
        let (a, b) = match (context_dependent(l), context_dependent(r)) {
            (true, false) => {
                let b = self.expr(r, None)?;
                let a = self.operand(l, &b, operand_want)?;
                (a, b)
            }
            (false, true) => {
                let a = self.expr(l, None)?;
                let b = self.operand(r, &a, operand_want)?;
                (a, b)
            }
            _ => {
                let wa = if is_loose(l) { operand_want } else { None };
                let a = self.expr(l, wa)?;
                let b = self.operand(r, &a, operand_want)?;
                (a, b)
            }
        };
        self.binary_typed(op, a, b, pos)
    }

    /// An operand checked knowing the other operand.
    pub(super) fn operand(
        &mut self,
        e: &ast::Expr,
        other: &Expr,
        want: Option<Type>,
    ) -> DResult<Expr> {
        let w = if other.ty.array.is_none()
            && (other.ty.base.is_triple() || other.ty.base == BaseType::Matrix)
        {
            Some(other.ty)
        } else if is_loose(e) {
            want
        } else {
            None
        };
        self.expr(e, w)
    }

    pub(super) fn binary_typed(&mut self, op: BinOp, a: Expr, b: Expr, pos: Pos) -> DResult<Expr> {
        use BaseType as B;
        let (ta, tb) = (a.ty, b.ty);
        let bad = || {
            Err(Diag::new(
                pos,
                format!(
                    "operator '{}' cannot take {} and {}",
                    op.as_str(),
                    describe_type(ta),
                    describe_type(tb)
                ),
            ))
        };
        if ta.is_array() || tb.is_array() {
            return bad();
        }
        let detail = a.detail.join(b.detail);
        let promote = |e: Expr, to: Type| -> Expr {
            if e.ty == to {
                e
            } else {
                Expr { ty: to, detail: e.detail, pos: e.pos, kind: ExprKind::Convert(Box::new(e)) }
            }
        };
        let (x, y) = (ta.base, tb.base);
        let result = |ty: Type, a: Expr, b: Expr| {
            Ok(Expr { kind: ExprKind::Binary(op, Box::new(a), Box::new(b)), ty, detail, pos })
        };
        match op {
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div => {
                if x == B::Matrix || y == B::Matrix {
                    return match (op, x, y) {
                        (BinOp::Mul | BinOp::Div, B::Matrix, B::Matrix) => {
                            result(Type::MATRIX, a, b)
                        }
                        (BinOp::Mul, B::Float, B::Matrix)
                        | (BinOp::Mul | BinOp::Div, B::Matrix, B::Float) => {
                            result(Type::MATRIX, a, b)
                        }
                        _ => bad(),
                    };
                }
                if !x.is_numeric() || !y.is_numeric() {
                    return bad();
                }
                let ty = match (x, y) {
                    (B::Float, B::Float) => B::Float,
                    (B::Float, t) | (t, B::Float) => t,
                    (B::Color, B::Color) => B::Color,
                    (B::Color, _) | (_, B::Color) => return bad(),
                    (B::Point, B::Point) if op == BinOp::Sub => B::Vector,
                    (B::Point, _) | (_, B::Point) => B::Point,
                    (s, t) if s == t => s,
                    _ => B::Vector,
                };
                // Both operands in one type: floats promoted; point - point stays point.
                let operand_ty = if x == y {
                    ta
                } else if x == B::Float {
                    tb
                } else if y == B::Float {
                    ta
                } else {
                    Type::scalar(ty)
                };
                let operand_ty = if ty == B::Vector && x == B::Point && y == B::Point {
                    Type::POINT
                } else {
                    operand_ty
                };
                let a = promote(a, operand_ty);
                let b = promote(b, operand_ty);
                result(Type::scalar(ty), a, b)
            }
            BinOp::Dot | BinOp::Cross => {
                if !x.is_spatial() || !y.is_spatial() {
                    return bad();
                }
                result(if op == BinOp::Dot { Type::FLOAT } else { Type::VECTOR }, a, b)
            }
            BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                if x != B::Float || y != B::Float {
                    return bad();
                }
                result(Type::BOOL, a, b)
            }
            BinOp::Eq | BinOp::Ne => {
                let common = if ta == tb {
                    Some(ta)
                } else if x == B::Float && (y.is_triple() || y == B::Matrix) {
                    Some(tb)
                } else if y == B::Float && (x.is_triple() || x == B::Matrix) {
                    Some(ta)
                } else if x.is_spatial() && y.is_spatial() {
                    Some(Type::POINT)
                } else {
                    None
                };
                let Some(t) = common else { return bad() };
                if t.base == B::Void {
                    return bad();
                }
                let a = promote(a, t);
                let b = promote(b, t);
                result(Type::BOOL, a, b)
            }
            BinOp::And | BinOp::Or => unreachable!("handled above"),
        }
    }
}
