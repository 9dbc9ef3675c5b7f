//! The parser: preprocessed tokens to the syntax tree ([`crate::ast`]), by recursive descent.
//!
//! Operator precedence, loosest first (as the Specification's compilers have it): assignment
//! (right), `?:` (right), `||`, `&&`, relations (`== != < <= > >=`), `+ -`, `^`, `* /`, `.`,
//! unary (`-`, `!`, typecasts), postfix `[ ]`.
//!
//! This module holds the token cursor; the grammar is in its parts: `decl` (definitions and
//! declarations), `stmt` (statements) and `expr` (expressions).

use crate::ast::*;
use crate::error::{DResult, Diag, Pos};
use crate::lexer::{P, Tok, Token};
use crate::types::{BaseType, Detail, ShaderKind};

/// Words that cannot name a variable or function.
const RESERVED: &[&str] = &[
    "float",
    "color",
    "point",
    "vector",
    "normal",
    "matrix",
    "string",
    "void",
    "uniform",
    "varying",
    "output",
    "extern",
    "if",
    "else",
    "while",
    "for",
    "break",
    "continue",
    "return",
    "illuminance",
    "illuminate",
    "solar",
    "surface",
    "displacement",
    "light",
    "volume",
    "imager",
    "transformation",
];

/// Deepest nesting of expressions and statements (deeper input is refused, not a stack overflow).
const MAX_DEPTH: u32 = 256;

/// Parses a whole token stream.
pub(crate) fn parse(toks: &[Token]) -> DResult<File> {
    let end = toks.last().map(|t| t.pos).unwrap_or(Pos { file: 0, line: 1, col: 1 });
    let mut p = Parser { toks, i: 0, end, depth: 0 };
    let mut items = Vec::new();
    while p.i < toks.len() {
        items.push(p.item()?);
    }
    Ok(File { items, end })
}

struct Parser<'a> {
    toks: &'a [Token],
    i: usize,
    end: Pos,
    depth: u32,
}

fn shader_kind(s: &str) -> Option<ShaderKind> {
    Some(match s {
        "surface" => ShaderKind::Surface,
        "displacement" => ShaderKind::Displacement,
        "light" => ShaderKind::Light,
        "volume" => ShaderKind::Volume,
        "imager" => ShaderKind::Imager,
        _ => return None,
    })
}

impl<'a> Parser<'a> {
    pub(super) fn peek(&self) -> Option<&'a Tok> {
        self.toks.get(self.i).map(|t| &t.tok)
    }

    pub(super) fn peek_at(&self, k: usize) -> Option<&'a Tok> {
        self.toks.get(self.i + k).map(|t| &t.tok)
    }

    pub(super) fn pos(&self) -> Pos {
        self.toks.get(self.i).map(|t| t.pos).unwrap_or(self.end)
    }

    fn got(&self) -> String {
        match self.peek() {
            Some(t) => t.describe(),
            None => "the end of the input".into(),
        }
    }

    pub(super) fn err<T>(&self, what: impl std::fmt::Display) -> DResult<T> {
        Err(Diag::new(self.pos(), format!("expected {what}, got {}", self.got())))
    }

    pub(super) fn is(&self, p: P) -> bool {
        self.peek() == Some(&Tok::Punct(p))
    }

    pub(super) fn is_word(&self, w: &str) -> bool {
        matches!(self.peek(), Some(Tok::Ident(s)) if s == w)
    }

    pub(super) fn eat(&mut self, p: P) -> bool {
        if self.is(p) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    pub(super) fn expect(&mut self, p: P, context: &str) -> DResult<Pos> {
        let pos = self.pos();
        if self.eat(p) { Ok(pos) } else { self.err(format_args!("'{}' {context}", p.as_str())) }
    }

    /// The arguments of a call or light statement named `name`, after its `(`: expressions
    /// separated by `,`, up to and including the `)`.
    pub(super) fn arguments(&mut self, name: &str) -> DResult<Vec<Expr>> {
        let mut args = Vec::new();
        if !self.eat(P::RParen) {
            loop {
                args.push(self.assign()?);
                if self.eat(P::Comma) {
                    continue;
                }
                self.expect(P::RParen, &format!("or ',' in the arguments of \"{name}\""))?;
                break;
            }
        }
        Ok(args)
    }

    pub(super) fn enter(&mut self) -> DResult<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(Diag::new(self.pos(), format!("nesting deeper than {MAX_DEPTH} levels")));
        }
        Ok(())
    }

    /// A name that is not a keyword, for `what`.
    pub(super) fn name(&mut self, what: &str) -> DResult<(String, Pos)> {
        let pos = self.pos();
        match self.peek() {
            Some(Tok::Ident(s)) if !RESERVED.contains(&s.as_str()) => {
                self.i += 1;
                Ok((s.clone(), pos))
            }
            Some(Tok::Ident(s)) => Err(Diag::new(
                pos,
                format!("expected {what}, got the keyword \"{s}\" (reserved, not a name)"),
            )),
            _ => self.err(what),
        }
    }

    pub(super) fn base_type(&self) -> Option<BaseType> {
        match self.peek() {
            Some(Tok::Ident(s)) => BaseType::from_keyword(s),
            _ => None,
        }
    }

    pub(super) fn detail(&self) -> Option<Detail> {
        match self.peek() {
            Some(Tok::Ident(s)) if s == "uniform" => Some(Detail::Uniform),
            Some(Tok::Ident(s)) if s == "varying" => Some(Detail::Varying),
            _ => None,
        }
    }
}

mod decl;
mod expr;
mod stmt;

#[cfg(test)]
mod tests;
