//! Expressions by precedence climbing, loosest first: assignment, `?:`, the binary operators
//! (the table in `binop`), unary operators and typecasts, postfix `[ ]`, primaries (constants,
//! names, calls, parenthesised lists).

use crate::ast::*;
use crate::error::{DResult, Diag};
use crate::lexer::{P, Tok};
use crate::types::BaseType;

use super::{Parser, RESERVED, shader_kind};

impl Parser<'_> {
    pub(super) fn expr(&mut self) -> DResult<Expr> {
        self.assign()
    }

    pub(super) fn assign(&mut self) -> DResult<Expr> {
        self.assign_inner()
    }

    fn assign_inner(&mut self) -> DResult<Expr> {
        let lhs = self.ternary()?;
        let op = match self.peek() {
            Some(Tok::Punct(P::Assign)) => AssignOp::Set,
            Some(Tok::Punct(P::AddAssign)) => AssignOp::Add,
            Some(Tok::Punct(P::SubAssign)) => AssignOp::Sub,
            Some(Tok::Punct(P::MulAssign)) => AssignOp::Mul,
            Some(Tok::Punct(P::DivAssign)) => AssignOp::Div,
            _ => return Ok(lhs),
        };
        let pos = self.pos();
        self.i += 1;
        self.enter()?;
        let rhs = self.assign();
        self.depth -= 1;
        Ok(Expr { kind: ExprKind::Assign(op, Box::new(lhs), Box::new(rhs?)), pos })
    }

    fn ternary(&mut self) -> DResult<Expr> {
        let c = self.binary(0)?;
        if !self.is(P::Question) {
            return Ok(c);
        }
        let pos = self.pos();
        self.i += 1;
        self.enter()?;
        let a = self.assign()?;
        self.expect(P::Colon, "of '?:'")?;
        let b = self.ternary()?;
        self.depth -= 1;
        Ok(Expr { kind: ExprKind::Cond(Box::new(c), Box::new(a), Box::new(b)), pos })
    }

    fn binop(&self) -> Option<(BinOp, u8)> {
        let Some(Tok::Punct(p)) = self.peek() else { return None };
        Some(match p {
            P::OrOr => (BinOp::Or, 1),
            P::AndAnd => (BinOp::And, 2),
            P::Eq => (BinOp::Eq, 3),
            P::Ne => (BinOp::Ne, 3),
            P::Lt => (BinOp::Lt, 3),
            P::Le => (BinOp::Le, 3),
            P::Gt => (BinOp::Gt, 3),
            P::Ge => (BinOp::Ge, 3),
            P::Plus => (BinOp::Add, 4),
            P::Minus => (BinOp::Sub, 4),
            P::Caret => (BinOp::Cross, 5),
            P::Star => (BinOp::Mul, 6),
            P::Slash => (BinOp::Div, 6),
            P::Dot => (BinOp::Dot, 7),
            _ => return None,
        })
    }

    fn binary(&mut self, min: u8) -> DResult<Expr> {
        let mut lhs = self.unary()?;
        // Each operator of a chain makes the tree one deeper (a + b + c ...): counted.
        let depth = self.depth;
        let mut r = Ok(());
        while let Some((op, prec)) = self.binop() {
            if prec <= min {
                break;
            }
            let pos = self.pos();
            self.i += 1;
            if let Err(e) = self.enter() {
                r = Err(e);
                break;
            }
            let rhs = match self.binary(prec) {
                Ok(rhs) => rhs,
                Err(e) => {
                    r = Err(e);
                    break;
                }
            };
            lhs = Expr { kind: ExprKind::Binary(op, Box::new(lhs), Box::new(rhs)), pos };
        }
        self.depth = depth;
        r.map(|()| lhs)
    }

    fn unary(&mut self) -> DResult<Expr> {
        self.enter()?;
        let r = self.unary_inner();
        self.depth -= 1;
        r
    }

    fn unary_inner(&mut self) -> DResult<Expr> {
        let pos = self.pos();
        match self.peek() {
            Some(Tok::Punct(P::Minus)) => {
                self.i += 1;
                let e = self.unary()?;
                return Ok(Expr { kind: ExprKind::Unary(UnOp::Neg, Box::new(e)), pos });
            }
            Some(Tok::Punct(P::Plus)) => {
                self.i += 1;
                return self.unary();
            }
            Some(Tok::Punct(P::Not)) => {
                self.i += 1;
                let e = self.unary()?;
                return Ok(Expr { kind: ExprKind::Unary(UnOp::Not, Box::new(e)), pos });
            }
            Some(Tok::Punct(p @ (P::PlusPlus | P::MinusMinus))) => {
                return Err(Diag::new(
                    pos,
                    format!("'{}' is not an RSL operator (write x += 1 or x -= 1)", p.as_str()),
                ));
            }
            _ => {}
        }
        if let Some(base) = self.base_type() {
            // A typecast or space-typed constructor: type ["space"] unary.
            if base == BaseType::Void {
                return Err(Diag::new(pos, "cannot cast to void"));
            }
            self.i += 1;
            let mut space = None;
            if let Some(Tok::Str(s)) = self.peek() {
                let spos = self.pos();
                let next_starts_operand = matches!(
                    self.peek_at(1),
                    Some(
                        Tok::Punct(P::LParen) | Tok::Punct(P::Minus) | Tok::Num(..) | Tok::Ident(_)
                    )
                );
                if next_starts_operand {
                    space = Some((s.clone(), spos));
                    self.i += 1;
                }
            }
            let e = self.unary()?;
            return Ok(Expr { kind: ExprKind::Cast(base, space, Box::new(e)), pos });
        }
        self.postfix()
    }

    fn postfix(&mut self) -> DResult<Expr> {
        let mut e = self.primary()?;
        while self.is(P::LBracket) {
            let pos = self.pos();
            self.i += 1;
            let idx = self.expr()?;
            self.expect(P::RBracket, "to close the index")?;
            e = Expr { kind: ExprKind::Index(Box::new(e), Box::new(idx)), pos };
        }
        if let Some(Tok::Punct(p @ (P::PlusPlus | P::MinusMinus))) = self.peek() {
            return Err(Diag::new(
                self.pos(),
                format!("'{}' is not an RSL operator (write x += 1 or x -= 1)", p.as_str()),
            ));
        }
        Ok(e)
    }

    fn primary(&mut self) -> DResult<Expr> {
        let pos = self.pos();
        match self.peek() {
            Some(Tok::Num(v, _)) => {
                self.i += 1;
                Ok(Expr { kind: ExprKind::Num(*v), pos })
            }
            Some(Tok::Str(s)) => {
                // Adjacent string constants join, as in C ("a" "b" is "ab"; an extension PRMan
                // has, and what a macro's # string next to a literal needs).
                let mut text = s.clone();
                self.i += 1;
                while let Some(Tok::Str(more)) = self.peek() {
                    text.push_str(more);
                    self.i += 1;
                }
                Ok(Expr { kind: ExprKind::Str(text), pos })
            }
            Some(Tok::Ident(s))
                if RESERVED.contains(&s.as_str())
                    && !(shader_kind(s).is_some()
                        && self.peek_at(1) == Some(&Tok::Punct(P::LParen))) =>
            {
                Err(Diag::new(pos, format!("expected an expression, got the keyword \"{s}\"")))
            }
            Some(Tok::Ident(s)) => {
                self.i += 1;
                if !self.is(P::LParen) {
                    return Ok(Expr { kind: ExprKind::Name(s.clone()), pos });
                }
                self.i += 1;
                let args = self.arguments(s)?;
                Ok(Expr { kind: ExprKind::Call(s.clone(), args), pos })
            }
            Some(Tok::Punct(P::LParen)) => {
                self.i += 1;
                let first = self.assign()?;
                if self.eat(P::RParen) {
                    return Ok(first);
                }
                if !self.is(P::Comma) {
                    return self.err("')' or ','");
                }
                let mut items = vec![first];
                while self.eat(P::Comma) {
                    items.push(self.assign()?);
                }
                self.expect(P::RParen, "to close the parenthesised list")?;
                Ok(Expr { kind: ExprKind::Tuple(items), pos })
            }
            Some(Tok::Punct(P::LBrace)) => {
                Err(Diag::new(pos, "an array initialiser {…} is allowed only in a declaration"))
            }
            _ => self.err("an expression"),
        }
    }
}
