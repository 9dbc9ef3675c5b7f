//! The expression of `#if` and `#elif`: `defined` replaced, the line macro-expanded, then C's
//! integer operators on 64-bit integers; the operands `&&`, `||` and `?:` skip are parsed but
//! not evaluated (so `0 && 1/0` is no error).

use crate::error::{DResult, Diag, Pos};
use crate::lexer::{P, Tok, Token};

use super::{Preprocessor, got, ident, is_punct};

impl Preprocessor<'_> {
    /// Evaluates a `#if`/`#elif` line.
    pub(super) fn eval_if(&mut self, hash: &Token, what: &str, args: &[Token]) -> DResult<bool> {
        // `defined X` and `defined(X)` are replaced before expansion.
        let mut toks: Vec<Token> = Vec::new();
        let mut k = 0;
        while k < args.len() {
            let t = &args[k];
            if ident(t) == Some("defined") {
                let (n, used) = match (args.get(k + 1), args.get(k + 2), args.get(k + 3)) {
                    (Some(a), Some(b), Some(c))
                        if is_punct(a, P::LParen)
                            && ident(b).is_some()
                            && is_punct(c, P::RParen) =>
                    {
                        (ident(b).expect("checked"), 4)
                    }
                    (Some(a), _, _) if ident(a).is_some() => (ident(a).expect("checked"), 2),
                    _ => {
                        return Err(Diag::new(
                            t.pos,
                            format!(
                                "{what}: \"defined\" takes a macro name: defined NAME or defined(NAME)"
                            ),
                        ));
                    }
                };
                let mut v = t.clone();
                let yes = self.macros.contains_key(n);
                v.tok = Tok::Num(if yes { 1.0 } else { 0.0 }, if yes { "1" } else { "0" }.into());
                toks.push(v);
                k += used;
                continue;
            }
            toks.push(t.clone());
            k += 1;
        }
        let toks = self.expand_line(&toks)?;
        if toks.is_empty() {
            return Err(Diag::new(hash.pos, format!("{what}: expected an expression")));
        }
        let mut e = IfExpr { toks: &toks, i: 0, what, end: hash.pos, eval: true };
        let v = e.ternary()?;
        if let Some(t) = toks.get(e.i) {
            return Err(Diag::new(
                t.pos,
                format!("{what}: unexpected {} after the expression", t.tok.shown()),
            ));
        }
        Ok(v != 0)
    }
}

/// The integer expression of `#if` (C's operators on 64-bit integers).
struct IfExpr<'a> {
    toks: &'a [Token],
    i: usize,
    what: &'a str,
    end: Pos,
    /// False in the operand `&&`, `||` or `?:` skip: parsed, not evaluated (no division error).
    eval: bool,
}

impl IfExpr<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.i).map(|t| &t.tok)
    }

    fn pos(&self) -> Pos {
        self.toks.get(self.i).map(|t| t.pos).or(self.toks.last().map(|t| t.pos)).unwrap_or(self.end)
    }

    fn eat(&mut self, p: P) -> bool {
        if self.peek() == Some(&Tok::Punct(p)) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn ternary(&mut self) -> DResult<i64> {
        let c = self.binary(0)?;
        if self.eat(P::Question) {
            let outer = self.eval;
            self.eval = outer && c != 0;
            let a = self.ternary();
            self.eval = outer;
            let a = a?;
            if !self.eat(P::Colon) {
                return Err(Diag::new(
                    self.pos(),
                    format!("{}: expected ':' of '?:', got {}", self.what, got(self.toks, self.i)),
                ));
            }
            self.eval = outer && c == 0;
            let b = self.ternary();
            self.eval = outer;
            return Ok(if c != 0 { a } else { b? });
        }
        Ok(c)
    }

    fn binary(&mut self, min: u8) -> DResult<i64> {
        let mut lhs = self.unary()?;
        while let Some(Tok::Punct(p)) = self.peek() {
            let p = *p;
            let prec = match p {
                P::OrOr => 1,
                P::AndAnd => 2,
                P::Pipe => 3,
                P::Caret => 4,
                P::Amp => 5,
                P::Eq | P::Ne => 6,
                P::Lt | P::Le | P::Gt | P::Ge => 7,
                P::Shl | P::Shr => 8,
                P::Plus | P::Minus => 9,
                P::Star | P::Slash | P::Percent => 10,
                _ => break,
            };
            if prec <= min {
                break;
            }
            let at = self.pos();
            self.i += 1;
            let outer = self.eval;
            match p {
                P::AndAnd => self.eval = outer && lhs != 0,
                P::OrOr => self.eval = outer && lhs == 0,
                _ => {}
            }
            let rhs = self.binary(prec);
            self.eval = outer;
            let rhs = rhs?;
            lhs = match p {
                P::OrOr => i64::from(lhs != 0 || rhs != 0),
                P::AndAnd => i64::from(lhs != 0 && rhs != 0),
                P::Pipe => lhs | rhs,
                P::Caret => lhs ^ rhs,
                P::Amp => lhs & rhs,
                P::Eq => i64::from(lhs == rhs),
                P::Ne => i64::from(lhs != rhs),
                P::Lt => i64::from(lhs < rhs),
                P::Le => i64::from(lhs <= rhs),
                P::Gt => i64::from(lhs > rhs),
                P::Ge => i64::from(lhs >= rhs),
                P::Shl => lhs.wrapping_shl(rhs as u32),
                P::Shr => lhs.wrapping_shr(rhs as u32),
                P::Plus => lhs.wrapping_add(rhs),
                P::Minus => lhs.wrapping_sub(rhs),
                P::Star => lhs.wrapping_mul(rhs),
                P::Slash | P::Percent => {
                    if rhs == 0 && self.eval {
                        return Err(Diag::new(at, format!("{}: division by zero", self.what)));
                    }
                    if rhs == 0 {
                        0
                    } else if p == P::Slash {
                        lhs.wrapping_div(rhs)
                    } else {
                        lhs.wrapping_rem(rhs)
                    }
                }
                _ => unreachable!("filtered above"),
            };
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> DResult<i64> {
        let at = self.pos();
        let Some(t) = self.peek().cloned() else {
            return Err(Diag::new(
                at,
                format!("{}: expected a value, got the end of the line", self.what),
            ));
        };
        self.i += 1;
        match t {
            Tok::Punct(P::Minus) => Ok(self.unary()?.wrapping_neg()),
            Tok::Punct(P::Plus) => self.unary(),
            Tok::Punct(P::Not) => Ok(i64::from(self.unary()? == 0)),
            Tok::Punct(P::Tilde) => Ok(!self.unary()?),
            Tok::Punct(P::LParen) => {
                let v = self.ternary()?;
                if !self.eat(P::RParen) {
                    return Err(Diag::new(
                        self.pos(),
                        format!("{}: expected ')', got {}", self.what, got(self.toks, self.i)),
                    ));
                }
                Ok(v)
            }
            Tok::Num(v, text) => {
                if v.fract() != 0.0 || text.contains(['.', 'e', 'E']) {
                    return Err(Diag::new(
                        at,
                        format!(
                            "{}: {text} is not an integer (#if takes integers only)",
                            self.what
                        ),
                    ));
                }
                Ok(v as i64)
            }
            // A name left after expansion is 0, as in C.
            Tok::Ident(_) => Ok(0),
            Tok::Bad(m) => Err(Diag::new(at, m)),
            other => Err(Diag::new(
                at,
                format!("{}: expected a value, got {}", self.what, other.describe()),
            )),
        }
    }
}
