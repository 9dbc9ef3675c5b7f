//! Definitions and declarations: shaders, functions (typed or not), formal parameter groups,
//! local and `extern` variable declarations, array sizes and initialisers.

use crate::ast::*;
use crate::error::{DResult, Diag};
use crate::lexer::{P, Tok};
use crate::types::BaseType;

use super::{Parser, shader_kind};

impl Parser<'_> {
    pub(super) fn item(&mut self) -> DResult<Item> {
        if let Some(Tok::Ident(w)) = self.peek() {
            if w == "transformation" {
                let pos = self.pos();
                self.i += 1;
                // Parse it whole, so that a following definition is still read right.
                let _ = self.name("a shader name after \"transformation\"")?;
                self.expect(P::LParen, "after the shader name")?;
                self.formals(true)?;
                self.expect(P::LBrace, "to begin the shader body")?;
                self.block_rest()?;
                return Ok(Item::Transformation(pos));
            }
            if let Some(kind) = shader_kind(w)
                && matches!(self.peek_at(1), Some(Tok::Ident(_)))
            {
                self.i += 1;
                let (name, pos) = self.name("a shader name")?;
                self.expect(P::LParen, &format!("after the {kind} shader name \"{name}\""))?;
                let params = self.formals(true)?;
                self.expect(P::LBrace, &format!("to begin the body of shader \"{name}\""))?;
                let body = self.block_rest()?;
                return Ok(Item::Shader(Shader { kind, name, pos, params, body }));
            }
        }
        match self.function()? {
            Some(f) => Ok(Item::Function(f)),
            None => self.err("a shader or function definition"),
        }
    }

    /// A function definition, if one starts here.
    pub(super) fn function(&mut self) -> DResult<Option<Function>> {
        let start = self.i;
        let detail = self.detail();
        if detail.is_some() {
            self.i += 1;
        }
        let tpos = self.pos();
        let base = self.base_type();
        if base.is_some() {
            self.i += 1;
        }
        let is_def = matches!(self.peek(), Some(Tok::Ident(_)))
            && self.peek_at(1) == Some(&Tok::Punct(P::LParen));
        if !is_def || (base.is_none() && detail.is_some()) {
            self.i = start;
            return Ok(None);
        }
        let ret = TypeSpec { detail, base: base.unwrap_or(BaseType::Void), pos: tpos };
        let (name, pos) = self.name("a function name")?;
        self.expect(P::LParen, "after the function name")?;
        let params = self.formals(false)?;
        self.expect(P::LBrace, &format!("to begin the body of function \"{name}\""))?;
        let body = self.block_rest()?;
        Ok(Some(Function { ret, name, pos, params, body }))
    }

    /// Formal parameters after '(' through ')': groups `[output] [detail] type name [= default],
    /// ...` separated by ';' (or ',' before a new type).
    pub(super) fn formals(&mut self, shader: bool) -> DResult<Vec<Decl>> {
        let mut out = Vec::new();
        loop {
            if self.eat(P::RParen) {
                return Ok(out);
            }
            let output = self.is_word("output");
            if output {
                self.i += 1;
            }
            let detail = self.detail();
            if detail.is_some() {
                self.i += 1;
            }
            let tpos = self.pos();
            let Some(base) = self.base_type() else {
                return self.err(if out.is_empty() && !output && detail.is_none() {
                    "a parameter type or ')'"
                } else {
                    "a parameter type"
                });
            };
            if base == BaseType::Void {
                return Err(Diag::new(tpos, "a parameter cannot be void"));
            }
            self.i += 1;
            let ty = TypeSpec { detail, base, pos: tpos };
            let mut vars = Vec::new();
            loop {
                let (name, pos) = self.name("a parameter name")?;
                let array = self.array_spec(!shader)?;
                let init = if self.eat(P::Assign) { Some(self.initializer()?) } else { None };
                vars.push(VarDef { name, pos, array, init });
                if self.is(P::Comma) && !self.starts_formal(1) {
                    self.i += 1;
                    continue;
                }
                break;
            }
            out.push(Decl { output, is_extern: false, ty, vars });
            if self.eat(P::Semi) || self.eat(P::Comma) {
                continue;
            }
            if self.is(P::RParen) {
                continue;
            }
            return self.err("';', ',' or ')' after a parameter");
        }
    }

    /// Whether the token at offset k begins a new formal group.
    fn starts_formal(&self, k: usize) -> bool {
        matches!(self.peek_at(k), Some(Tok::Ident(s)) if s == "output" || s == "uniform" || s == "varying" || BaseType::from_keyword(s).is_some())
    }

    fn array_spec(&mut self, open_ok: bool) -> DResult<Option<ArraySpec>> {
        if !self.is(P::LBracket) {
            return Ok(None);
        }
        let pos = self.pos();
        self.i += 1;
        if self.is(P::RBracket) {
            if !open_ok {
                return Err(Diag::new(
                    pos,
                    "an array here needs a size: '[]' is for function parameters only",
                ));
            }
            self.i += 1;
            return Ok(Some(ArraySpec::Open));
        }
        let npos = self.pos();
        let n = match self.peek() {
            Some(Tok::Num(v, text)) => {
                if v.fract() != 0.0
                    || *v < 1.0
                    || *v > 1_000_000.0
                    || text.contains(['.', 'e', 'E'])
                {
                    return Err(Diag::new(
                        npos,
                        format!("array size must be a positive integer, got {text}"),
                    ));
                }
                *v as u32
            }
            _ => return self.err("an array size (a positive integer)"),
        };
        self.i += 1;
        self.expect(P::RBracket, "after the array size")?;
        Ok(Some(ArraySpec::Fixed(n)))
    }

    pub(super) fn initializer(&mut self) -> DResult<Expr> {
        if self.is(P::LBrace) {
            let pos = self.pos();
            self.i += 1;
            let mut items = Vec::new();
            if !self.eat(P::RBrace) {
                loop {
                    items.push(self.assign()?);
                    if self.eat(P::Comma) {
                        continue;
                    }
                    self.expect(P::RBrace, "or ',' in the array initialiser")?;
                    break;
                }
            }
            return Ok(Expr { kind: ExprKind::ArrayLit(items), pos });
        }
        self.assign()
    }

    pub(super) fn decl_or_function(&mut self) -> DResult<Stmt> {
        if let Some(f) = self.function()? {
            return Ok(Stmt::Function(f));
        }
        let is_extern = self.is_word("extern");
        if is_extern {
            self.i += 1;
        }
        if self.is_word("output") {
            return Err(Diag::new(self.pos(), "\"output\" is for parameters only"));
        }
        let detail = self.detail();
        if detail.is_some() {
            self.i += 1;
        }
        let tpos = self.pos();
        let Some(base) = self.base_type() else {
            return self.err("a type");
        };
        self.i += 1;
        if base == BaseType::Void {
            return Err(Diag::new(tpos, "a variable cannot be void"));
        }
        let ty = TypeSpec { detail, base, pos: tpos };
        let mut vars = Vec::new();
        loop {
            let (name, pos) = self.name("a variable name")?;
            let array = self.array_spec(false)?;
            let init = if self.eat(P::Assign) { Some(self.initializer()?) } else { None };
            vars.push(VarDef { name, pos, array, init });
            if self.eat(P::Comma) {
                continue;
            }
            if !self.is(P::Semi) {
                return self.err("';' or ',' after the declaration");
            }
            self.i += 1;
            break;
        }
        Ok(Stmt::Decl(Decl { output: false, is_extern, ty, vars }))
    }
}
