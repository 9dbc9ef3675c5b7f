//! The parser: preprocessed tokens to the syntax tree ([`crate::ast`]), by recursive descent.
//!
//! Operator precedence, loosest first (as the Specification's compilers have it): assignment
//! (right), `?:` (right), `||`, `&&`, relations (`== != < <= > >=`), `+ -`, `^`, `* /`, `.`,
//! unary (`-`, `!`, typecasts), postfix `[ ]`.

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
    fn peek(&self) -> Option<&'a Tok> {
        self.toks.get(self.i).map(|t| &t.tok)
    }

    fn peek_at(&self, k: usize) -> Option<&'a Tok> {
        self.toks.get(self.i + k).map(|t| &t.tok)
    }

    fn pos(&self) -> Pos {
        self.toks.get(self.i).map(|t| t.pos).unwrap_or(self.end)
    }

    fn got(&self) -> String {
        match self.peek() {
            Some(t) => t.describe(),
            None => "the end of the input".into(),
        }
    }

    fn err<T>(&self, what: impl std::fmt::Display) -> DResult<T> {
        Err(Diag::new(self.pos(), format!("expected {what}, got {}", self.got())))
    }

    fn is(&self, p: P) -> bool {
        self.peek() == Some(&Tok::Punct(p))
    }

    fn is_word(&self, w: &str) -> bool {
        matches!(self.peek(), Some(Tok::Ident(s)) if s == w)
    }

    fn eat(&mut self, p: P) -> bool {
        if self.is(p) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn expect(&mut self, p: P, context: &str) -> DResult<Pos> {
        let pos = self.pos();
        if self.eat(p) { Ok(pos) } else { self.err(format_args!("'{}' {context}", p.as_str())) }
    }

    fn enter(&mut self) -> DResult<()> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(Diag::new(self.pos(), format!("nesting deeper than {MAX_DEPTH} levels")));
        }
        Ok(())
    }

    /// A name that is not a keyword, for `what`.
    fn name(&mut self, what: &str) -> DResult<(String, Pos)> {
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

    fn base_type(&self) -> Option<BaseType> {
        match self.peek() {
            Some(Tok::Ident(s)) => BaseType::from_keyword(s),
            _ => None,
        }
    }

    fn detail(&self) -> Option<Detail> {
        match self.peek() {
            Some(Tok::Ident(s)) if s == "uniform" => Some(Detail::Uniform),
            Some(Tok::Ident(s)) if s == "varying" => Some(Detail::Varying),
            _ => None,
        }
    }

    // ---------------------------------------------------------------- definitions

    fn item(&mut self) -> DResult<Item> {
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
    fn function(&mut self) -> DResult<Option<Function>> {
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
    fn formals(&mut self, shader: bool) -> DResult<Vec<Decl>> {
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

    fn initializer(&mut self) -> DResult<Expr> {
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

    // ---------------------------------------------------------------- statements

    /// Statements after '{' through '}'.
    fn block_rest(&mut self) -> DResult<Vec<Stmt>> {
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

    fn stmt(&mut self) -> DResult<Stmt> {
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
                let mut args = Vec::new();
                if !self.eat(P::RParen) {
                    loop {
                        args.push(self.assign()?);
                        if self.eat(P::Comma) {
                            continue;
                        }
                        self.expect(P::RParen, &format!("or ',' in the arguments of \"{which}\""))?;
                        break;
                    }
                }
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

    fn decl_or_function(&mut self) -> DResult<Stmt> {
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

    // ---------------------------------------------------------------- expressions

    fn expr(&mut self) -> DResult<Expr> {
        self.assign()
    }

    fn assign(&mut self) -> DResult<Expr> {
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
                let mut args = Vec::new();
                if !self.eat(P::RParen) {
                    loop {
                        args.push(self.assign()?);
                        if self.eat(P::Comma) {
                            continue;
                        }
                        self.expect(P::RParen, &format!("or ',' in the arguments of \"{s}\""))?;
                        break;
                    }
                }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lexer::lex;

    fn parse_str(s: &str) -> DResult<File> {
        parse(&lex(s.as_bytes(), 0))
    }

    fn body_expr(s: &str) -> Expr {
        let f = parse_str(&format!("surface x() {{ {s}; }}")).unwrap();
        let Item::Shader(sh) = &f.items[0] else { panic!() };
        let Stmt::Expr(e) = &sh.body[0] else { panic!("{:?}", sh.body[0]) };
        e.clone()
    }

    fn show(e: &Expr) -> String {
        match &e.kind {
            ExprKind::Num(v) => format!("{v}"),
            ExprKind::Str(s) => format!("{s:?}"),
            ExprKind::Name(n) => n.clone(),
            ExprKind::Index(a, b) => format!("{}[{}]", show(a), show(b)),
            ExprKind::Call(n, a) => {
                format!("{n}({})", a.iter().map(show).collect::<Vec<_>>().join(","))
            }
            ExprKind::Unary(UnOp::Neg, a) => format!("(-{})", show(a)),
            ExprKind::Unary(UnOp::Not, a) => format!("(!{})", show(a)),
            ExprKind::Binary(op, a, b) => format!("({} {} {})", show(a), op.as_str(), show(b)),
            ExprKind::Assign(op, a, b) => format!("({} {} {})", show(a), op.as_str(), show(b)),
            ExprKind::Cond(c, a, b) => format!("({} ? {} : {})", show(c), show(a), show(b)),
            ExprKind::Cast(t, s, a) => match s {
                Some((s, _)) => format!("({t} {s:?} {})", show(a)),
                None => format!("({t} {})", show(a)),
            },
            ExprKind::Tuple(v) | ExprKind::ArrayLit(v) => {
                format!("<{}>", v.iter().map(show).collect::<Vec<_>>().join(","))
            }
        }
    }

    #[test]
    fn precedence() {
        assert_eq!(show(&body_expr("a = b + c * d . e")), "(a = (b + (c * (d . e))))");
        assert_eq!(show(&body_expr("a ^ b * c + d")), "((a ^ (b * c)) + d)");
        assert_eq!(show(&body_expr("x = a < b && c || d")), "(x = (((a < b) && c) || d))");
        assert_eq!(show(&body_expr("x = c ? a : b ? d : e")), "(x = (c ? a : (b ? d : e)))");
        assert_eq!(show(&body_expr("a = b = c")), "(a = (b = c))");
        assert_eq!(show(&body_expr("x = -a . b")), "(x = ((-a) . b))");
        assert_eq!(show(&body_expr("x = a - b - c")), "(x = ((a - b) - c))");
    }

    #[test]
    fn casts_tuples_channels() {
        assert_eq!(
            show(&body_expr("c = color \"hsv\" (h, s, v)")),
            "(c = (color \"hsv\" <h,s,v>))"
        );
        assert_eq!(show(&body_expr("p = point (1, 2, 3)")), "(p = (point <1,2,3>))");
        assert_eq!(show(&body_expr("m = matrix \"shader\" 1")), "(m = (matrix \"shader\" 1))");
        assert_eq!(show(&body_expr("c = color noise(P) * 2")), "(c = ((color noise(P)) * 2))");
        assert_eq!(show(&body_expr("f = texture(\"m\"[1], s, t)")), "(f = texture(\"m\"[1],s,t))");
        assert_eq!(show(&body_expr("a[i] += 2")), "(a[i] += 2)");
    }

    #[test]
    fn formals_with_commas_and_semicolons() {
        let f = parse_str(
            "float f(float a, b; output color c; float d[], e) { return a; } surface s(float Ka = 1; varying color x = 0;) {}",
        )
        .unwrap();
        let Item::Function(func) = &f.items[0] else { panic!() };
        assert_eq!(func.params.len(), 3);
        assert_eq!(func.params[0].vars.len(), 2);
        assert!(func.params[1].output);
        assert_eq!(func.params[2].vars[0].array, Some(ArraySpec::Open));
        let Item::Shader(s) = &f.items[1] else { panic!() };
        assert_eq!(s.params.len(), 2);
        assert_eq!(s.params[1].ty.detail, Some(Detail::Varying));
    }

    #[test]
    fn statements() {
        let f = parse_str(
            "light l() { illuminate(P, N, 1) { Cl = 1; } solar() ; }
             surface s() { float i; for (i = 0; i < 3; i += 1) { if (i > 1) break 1; else continue; }
               while (i > 0) i -= 1; illuminance(\"cat\", P, N, 1) { Ci += Cl; }
               float g(float x) { return x; } Ci = g(1); }",
        )
        .unwrap();
        assert_eq!(f.items.len(), 2);
    }
}
