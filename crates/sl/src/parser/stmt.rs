//! Statements: blocks, `if`, the loops, `break`/`continue` with a loop count, `return`, the
//! light statements, and telling a declaration or a nested function from an expression.

use crate::ast::*;
use crate::error::{DResult, Diag};
use crate::lexer::{P, Tok};
use crate::types::BaseType;

use super::Parser;

impl Parser<'_> {
    /// Statements after '{' through '}'.
    pub(super) fn block_rest(&mut self) -> DResult<Vec<Stmt>> {
        let mut out = Vec::new();
        loop {
            if self.eat(P::RBrace) {
                return Ok(out);
            }
            if self.peek().is_none() {
                return self.err("'}' to close the block");
            }
            out.push(self.stmt()?);
        }
    }

    pub(super) fn stmt(&mut self) -> DResult<Stmt> {
        self.enter()?;
        let s = self.stmt_inner();
        self.depth -= 1;
        s
    }

    fn paren_cond(&mut self, what: &str) -> DResult<Expr> {
        self.expect(P::LParen, &format!("after \"{what}\""))?;
        let c = self.expr()?;
        self.expect(P::RParen, &format!("to close the condition of \"{what}\""))?;
        Ok(c)
    }

    fn stmt_inner(&mut self) -> DResult<Stmt> {
        let pos = self.pos();
        if self.eat(P::Semi) {
            return Ok(Stmt::Empty);
        }
        if self.eat(P::LBrace) {
            return Ok(Stmt::Block(self.block_rest()?));
        }
        let Some(Tok::Ident(w)) = self.peek() else {
            return self.expr_stmt();
        };
        match w.as_str() {
            "if" => {
                self.i += 1;
                let cond = self.paren_cond("if")?;
                let then = Box::new(self.stmt()?);
                let els = if self.is_word("else") {
                    self.i += 1;
                    Some(Box::new(self.stmt()?))
                } else {
                    None
                };
                Ok(Stmt::If { cond, then, els })
            }
            "else" => Err(Diag::new(pos, "\"else\" without \"if\"")),
            "while" => {
                self.i += 1;
                let cond = self.paren_cond("while")?;
                Ok(Stmt::While { cond, body: Box::new(self.stmt()?) })
            }
            "for" => {
                self.i += 1;
                self.expect(P::LParen, "after \"for\"")?;
                if self.base_type().is_some() || self.detail().is_some() {
                    return Err(Diag::new(
                        self.pos(),
                        "a declaration cannot begin a \"for\" (declare the variable before the loop)",
                    ));
                }
                let init = if self.is(P::Semi) { None } else { Some(self.expr()?) };
                self.expect(P::Semi, "after the initialiser of \"for\"")?;
                let cond = if self.is(P::Semi) { None } else { Some(self.expr()?) };
                self.expect(P::Semi, "after the condition of \"for\"")?;
                let step = if self.is(P::RParen) { None } else { Some(self.expr()?) };
                self.expect(P::RParen, "to close the header of \"for\"")?;
                Ok(Stmt::For { init, cond, step, body: Box::new(self.stmt()?), pos })
            }
            "break" | "continue" => {
                let is_break = w == "break";
                self.i += 1;
                let mut n = 1;
                if let Some(Tok::Num(v, text)) = self.peek() {
                    if v.fract() != 0.0 || *v < 1.0 || *v > 1000.0 || text.contains(['.', 'e', 'E'])
                    {
                        return Err(Diag::new(
                            self.pos(),
                            format!(
                                "\"{}\" takes a loop count (a positive integer), got {text}",
                                if is_break { "break" } else { "continue" }
                            ),
                        ));
                    }
                    n = *v as u32;
                    self.i += 1;
                }
                self.expect(
                    P::Semi,
                    &format!("after \"{}\"", if is_break { "break" } else { "continue" }),
                )?;
                Ok(if is_break { Stmt::Break(n, pos) } else { Stmt::Continue(n, pos) })
            }
            "return" => {
                self.i += 1;
                let value = if self.is(P::Semi) { None } else { Some(self.expr()?) };
                self.expect(P::Semi, "after \"return\"")?;
                Ok(Stmt::Return(value, pos))
            }
            "illuminance" | "illuminate" | "solar" => {
                let which = w.clone();
                self.i += 1;
                self.expect(P::LParen, &format!("after \"{which}\""))?;
                let args = self.arguments(&which)?;
                let body = Box::new(self.stmt()?);
                Ok(match which.as_str() {
                    "illuminance" => Stmt::Illuminance { args, body, pos },
                    "illuminate" => Stmt::Illuminate { args, body, pos },
                    _ => Stmt::Solar { args, body, pos },
                })
            }
            "extern" | "output" | "uniform" | "varying" => self.decl_or_function(),
            "surface" | "displacement" | "light" | "volume" | "imager" | "transformation"
                if matches!(self.peek_at(1), Some(Tok::Ident(_))) =>
            {
                Err(Diag::new(
                    pos,
                    format!("a {w} shader cannot be defined inside another definition"),
                ))
            }
            _ if self.base_type().is_some() => {
                // `color (1,0,0);` is a cast statement; otherwise a declaration.
                if matches!(self.peek_at(1), Some(Tok::Ident(_))) {
                    self.decl_or_function()
                } else {
                    self.expr_stmt()
                }
            }
            _ => {
                // An untyped function definition: `name (formals) {`.
                if self.peek_at(1) == Some(&Tok::Punct(P::LParen))
                    && self.looks_like_untyped_def()
                    && let Some(f) = self.function()?
                {
                    return Ok(Stmt::Function(f));
                }
                self.expr_stmt()
            }
        }
    }

    /// `name ( ... ) {` with a type keyword right after '(' (or `()` then '{').
    fn looks_like_untyped_def(&self) -> bool {
        let after = self.peek_at(2);
        match after {
            Some(Tok::Punct(P::RParen)) => self.peek_at(3) == Some(&Tok::Punct(P::LBrace)),
            Some(Tok::Ident(s)) => {
                (s == "output"
                    || s == "uniform"
                    || s == "varying"
                    || BaseType::from_keyword(s).is_some())
                    && matches!(self.peek_at(3), Some(Tok::Ident(_)))
            }
            _ => false,
        }
    }

    fn expr_stmt(&mut self) -> DResult<Stmt> {
        let e = self.expr()?;
        if !self.is(P::Semi) {
            return self.err("';' after the expression");
        }
        self.i += 1;
        Ok(Stmt::Expr(e))
    }
}
