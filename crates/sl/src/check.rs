//! The checker: syntax tree to typed IR ([`crate::ir`]), with the Specification's scoping,
//! type, overload and uniform/varying rules.
//!
//! Uniform/varying analysis is a fixpoint: the whole shader is checked in passes; a variable
//! without a declared detail starts uniform and becomes varying when it is assigned a varying
//! value or assigned under varying control flow (an `if`/loop with a varying condition, a loop
//! that a `break`/`continue` under varying control leaves, a function after a `return` under
//! varying control, the bodies of `illuminance`, `illuminate`, `solar`); a formal parameter
//! without a declared detail is as varying as the arguments passed to it. Details only grow
//! between passes, so the passes stop; errors are the same in every pass, so the first is
//! reported when found.

use std::collections::HashMap;

use crate::ast::{self, ArraySpec, AssignOp, BinOp, ExprKind as A, UnOp};
use crate::error::{DResult, Diag, Pos, SourceMap};
use crate::globals::{Access, Global, global};
use crate::ir::*;
use crate::library::{Rest, Signature, library, texture_option};
use crate::types::{BaseType, Detail, ShaderKind, Type};

/// Checks a parsed file: exactly one shader, and the functions before it.
pub(crate) fn check(file: &ast::File, sources: SourceMap) -> DResult<CheckedShader> {
    let mut shader: Option<&ast::Shader> = None;
    for item in &file.items {
        match item {
            ast::Item::Transformation(pos) => {
                return Err(Diag::new(
                    *pos,
                    "transformation shaders are not supported (RenderMan Interface 3.2 reserves them; no renderer runs them)",
                ));
            }
            ast::Item::Shader(s) => {
                if let Some(first) = shader {
                    return Err(Diag::new(
                        s.pos,
                        format!(
                            "a second shader \"{}\" in one file (the first is \"{}\" at line {})",
                            s.name, first.name, first.pos.line
                        ),
                    ));
                }
                shader = Some(s);
            }
            ast::Item::Function(_) => {}
        }
    }
    let Some(shader) = shader else {
        return Err(Diag::new(
            file.end,
            "no shader definition (surface, displacement, light, volume or imager) in the file",
        ));
    };
    let mut memo = Memo::default();
    for _pass in 0..1000 {
        let mut c = Checker::new(shader.kind, &mut memo);
        let out = c.shader(file, shader)?;
        let changed = c.changed;
        if !changed {
            let mut out = out;
            out.sources = sources;
            return Ok(out);
        }
    }
    Err(Diag::new(shader.pos, "internal limit: the uniform/varying analysis did not settle"))
}

/// What one pass learns for the next.
#[derive(Default)]
struct Memo {
    /// Inferred detail per variable id.
    var: Vec<Detail>,
    /// Loops (by order of appearance) found varying.
    loops: Vec<bool>,
    /// Functions with a return under varying control.
    func_varying: Vec<bool>,
}

#[derive(Debug, Clone)]
enum Sym {
    Var(VarId),
    Global(&'static Global),
    Funcs(Vec<FuncId>),
}

struct Scope {
    names: HashMap<String, Sym>,
    /// The body of a function: outer variables are reached only through `extern`.
    boundary: bool,
}

struct LoopCtx {
    ordinal: usize,
    ctrl_base: usize,
}

struct FuncCtx {
    id: FuncId,
    ret: Type,
    ret_detail: Detail,
    ctrl_base: usize,
    loop_base: usize,
    returned: bool,
}

struct Checker<'m> {
    kind: ShaderKind,
    memo: &'m mut Memo,
    changed: bool,
    vars: Vec<Var>,
    funcs: Vec<Function>,
    /// Functions each function calls, with where.
    calls: Vec<Vec<(FuncId, Pos)>>,
    /// Outer variables each function writes (through extern).
    extern_writes: Vec<Vec<VarId>>,
    scopes: Vec<Scope>,
    ctrl: Vec<Pos>,
    loops: Vec<LoopCtx>,
    loop_count: usize,
    fstack: Vec<FuncCtx>,
    illuminance: u32,
    light_block: u32,
    read: Vec<&'static str>,
    written: Vec<&'static str>,
    /// Varying-control depth where each variable was declared: assignments deeper than that
    /// are under varying control for it.
    decl_ctrl: Vec<usize>,
}

fn is_loose(e: &ast::Expr) -> bool {
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

fn context_dependent(e: &ast::Expr) -> bool {
    matches!(e.kind, A::Call(..)) || is_loose(e)
}

fn conv_cost(from: Type, to: Type) -> Option<u32> {
    if from.array.is_some() || to.array.is_some() {
        let same_base = from.base == to.base;
        return match (from.array, to.array) {
            (Some(n), Some(m)) if same_base && (n == m || m == 0) => Some(0),
            _ => None,
        };
    }
    if from == to {
        return Some(0);
    }
    match (from.base, to.base) {
        (BaseType::Float, b) if b.is_triple() || b == BaseType::Matrix => Some(1),
        (a, b) if a.is_spatial() && b.is_spatial() => Some(1),
        _ => None,
    }
}

fn describe_type(t: Type) -> String {
    t.to_string()
}

impl<'m> Checker<'m> {
    fn new(kind: ShaderKind, memo: &'m mut Memo) -> Checker<'m> {
        Checker {
            kind,
            memo,
            changed: false,
            vars: Vec::new(),
            funcs: Vec::new(),
            calls: Vec::new(),
            extern_writes: Vec::new(),
            scopes: vec![Scope { names: HashMap::new(), boundary: false }],
            ctrl: Vec::new(),
            loops: Vec::new(),
            loop_count: 0,
            fstack: Vec::new(),
            illuminance: 0,
            light_block: 0,
            read: Vec::new(),
            written: Vec::new(),
            decl_ctrl: Vec::new(),
        }
    }

    // ---------------------------------------------------------------- variables and scopes

    fn new_var(
        &mut self,
        name: &str,
        ty: Type,
        declared: Option<Detail>,
        kind: VarKind,
        pos: Pos,
    ) -> VarId {
        let id = self.vars.len();
        if self.memo.var.len() <= id {
            self.memo.var.push(Detail::Uniform);
        }
        let default = match (&kind, declared) {
            (_, Some(d)) => d,
            // Shader parameters are uniform unless declared varying.
            (VarKind::Param { .. }, None) => Detail::Uniform,
            _ => self.memo.var[id],
        };
        self.vars.push(Var { name: name.to_string(), ty, detail: default, declared, kind, pos });
        self.decl_ctrl.push(self.ctrl.len());
        id
    }

    fn declare(&mut self, name: &str, sym: Sym, pos: Pos) -> DResult<()> {
        let scope = self.scopes.last_mut().expect("a scope");
        if let Some(old) = scope.names.get(name) {
            let is_func = matches!(sym, Sym::Funcs(_));
            if !matches!(old, Sym::Funcs(_)) || !is_func {
                return Err(Diag::new(
                    pos,
                    format!("\"{name}\" is already declared in this scope"),
                ));
            }
        }
        match (scope.names.get_mut(name), sym) {
            (Some(Sym::Funcs(list)), Sym::Funcs(new)) => list.extend(new),
            (_, sym) => {
                scope.names.insert(name.to_string(), sym);
            }
        }
        Ok(())
    }

    /// A variable or global by name, following the extern rule.
    fn lookup_var(&self, name: &str, pos: Pos) -> DResult<Option<Sym>> {
        let mut crossed = false;
        for s in self.scopes.iter().rev() {
            if let Some(sym) = s.names.get(name) {
                match sym {
                    Sym::Funcs(_) => {}
                    Sym::Var(_) if crossed => {
                        return Err(Diag::new(
                            pos,
                            format!(
                                "\"{name}\" belongs to an enclosing scope: a function reaches it only through \"extern\" (declare extern {} {name};)",
                                self.vars[match sym {
                                    Sym::Var(v) => *v,
                                    _ => unreachable!(),
                                }]
                                .ty
                                .base
                            ),
                        ));
                    }
                    _ => return Ok(Some(sym.clone())),
                }
            }
            if s.boundary {
                crossed = true;
            }
        }
        Ok(global(name).map(Sym::Global))
    }

    fn lookup_funcs(&self, name: &str) -> Vec<FuncId> {
        let mut out = Vec::new();
        for s in self.scopes.iter().rev() {
            if let Some(Sym::Funcs(list)) = s.names.get(name) {
                out.extend(list.iter().copied());
            }
        }
        out
    }

    fn push_scope(&mut self, boundary: bool) {
        self.scopes.push(Scope { names: HashMap::new(), boundary });
    }

    fn pop_scope(&mut self) {
        self.scopes.pop();
    }

    fn note_read(&mut self, g: &'static Global) {
        if !self.read.contains(&g.name) {
            self.read.push(g.name);
        }
    }

    /// Makes variable `v` varying (an inferred one), or reports why it cannot be.
    fn raise(&mut self, v: VarId, why: impl FnOnce() -> String, pos: Pos) -> DResult<()> {
        if self.vars[v].detail == Detail::Varying {
            return Ok(());
        }
        if self.vars[v].declared.is_some() || matches!(self.vars[v].kind, VarKind::Param { .. }) {
            return Err(Diag::new(pos, why()));
        }
        self.vars[v].detail = Detail::Varying;
        if self.memo.var[v] != Detail::Varying {
            self.memo.var[v] = Detail::Varying;
            self.changed = true;
        }
        Ok(())
    }

    // ---------------------------------------------------------------- definitions

    fn shader(&mut self, file: &ast::File, sh: &ast::Shader) -> DResult<CheckedShader> {
        // File-level functions before the shader are visible in it.
        for item in &file.items {
            match item {
                ast::Item::Function(f) => self.function(f)?,
                ast::Item::Shader(s) if std::ptr::eq(s, sh) => break,
                _ => {}
            }
        }
        self.push_scope(false);
        let mut params = Vec::new();
        for d in &sh.params {
            for v in &d.vars {
                let ty = self.decl_type(d.ty.base, v.array, v.pos, false)?;
                let Some(init) = &v.init else {
                    return Err(Diag::new(
                        v.pos,
                        format!("shader parameter \"{}\" needs a default value", v.name),
                    ));
                };
                let mut value = self.initializer(init, ty, &v.name)?;
                let id = self.new_var(
                    &v.name,
                    ty,
                    d.ty.detail,
                    VarKind::Param { default: None, output: d.output },
                    v.pos,
                );
                if self.vars[id].detail == Detail::Uniform {
                    make_uniform(&mut value);
                }
                if value.detail == Detail::Varying && self.vars[id].detail == Detail::Uniform {
                    return Err(Diag::new(
                        init.pos,
                        format!(
                            "the default of uniform parameter \"{}\" is varying (declare it varying)",
                            v.name
                        ),
                    ));
                }
                self.vars[id].kind = VarKind::Param { default: Some(value), output: d.output };
                self.declare(&v.name, Sym::Var(id), v.pos)?;
                params.push(id);
            }
        }
        let body = self.block(&sh.body, false)?;
        self.pop_scope();
        self.check_recursion()?;
        Ok(CheckedShader {
            kind: sh.kind,
            name: sh.name.clone(),
            pos: sh.pos,
            params,
            vars: std::mem::take(&mut self.vars),
            functions: std::mem::take(&mut self.funcs),
            body,
            globals_read: std::mem::take(&mut self.read),
            globals_written: std::mem::take(&mut self.written),
            sources: SourceMap::default(),
        })
    }

    fn decl_type(
        &self,
        base: BaseType,
        array: Option<ArraySpec>,
        pos: Pos,
        formal: bool,
    ) -> DResult<Type> {
        Ok(match array {
            None => Type::scalar(base),
            Some(ArraySpec::Fixed(n)) => Type { base, array: Some(n) },
            Some(ArraySpec::Open) if formal => Type { base, array: Some(0) },
            Some(ArraySpec::Open) => {
                return Err(Diag::new(pos, "an array needs a size here"));
            }
        })
    }

    fn function(&mut self, f: &ast::Function) -> DResult<()> {
        let id = self.funcs.len();
        if self.memo.func_varying.len() <= id {
            self.memo.func_varying.push(false);
        }
        let ret = Type::scalar(f.ret.base);
        self.funcs.push(Function {
            name: f.name.clone(),
            ret,
            ret_detail: f.ret.detail.unwrap_or(Detail::Uniform),
            params: Vec::new(),
            body: Vec::new(),
            pos: f.pos,
        });
        self.calls.push(Vec::new());
        self.extern_writes.push(Vec::new());
        if global(&f.name).is_some() {
            return Err(Diag::new(
                f.pos,
                format!("function \"{}\" has the name of a predefined variable", f.name),
            ));
        }
        // Formals first (so an overload's signature is known), then the name, then the body.
        self.push_scope(true);
        let mut params = Vec::new();
        for d in &f.params {
            for v in &d.vars {
                let ty = self.decl_type(d.ty.base, v.array, v.pos, true)?;
                if v.init.is_some() {
                    return Err(Diag::new(
                        v.pos,
                        format!("function parameter \"{}\" cannot have a default", v.name),
                    ));
                }
                let pid = self.new_var(
                    &v.name,
                    ty,
                    d.ty.detail,
                    VarKind::Formal { func: id, output: d.output },
                    v.pos,
                );
                self.declare(&v.name, Sym::Var(pid), v.pos)?;
                params.push(pid);
            }
        }
        self.funcs[id].params = params.clone();
        // Visible in its own body (so that recursion is found and reported) and after it.
        let outer = self.scopes.len() - 2;
        let sig: Vec<Type> = params.iter().map(|&p| self.vars[p].ty).collect();
        for &other in &self.lookup_funcs_at(outer, &f.name) {
            let osig: Vec<Type> =
                self.funcs[other].params.iter().map(|&p| self.vars[p].ty).collect();
            if osig == sig {
                return Err(Diag::new(
                    f.pos,
                    format!(
                        "function \"{}\" is already defined with these parameter types (line {})",
                        f.name, self.funcs[other].pos.line
                    ),
                ));
            }
        }
        match self.scopes[outer].names.get_mut(&f.name) {
            Some(Sym::Funcs(list)) => list.push(id),
            Some(_) => {
                return Err(Diag::new(
                    f.pos,
                    format!("\"{}\" is already declared in this scope", f.name),
                ));
            }
            None => {
                self.scopes[outer].names.insert(f.name.clone(), Sym::Funcs(vec![id]));
            }
        }
        let saved_ctrl = std::mem::take(&mut self.ctrl);
        let saved_loops = std::mem::take(&mut self.loops);
        if self.memo.func_varying[id] {
            self.ctrl.push(f.pos);
        }
        self.fstack.push(FuncCtx {
            id,
            ret,
            ret_detail: f.ret.detail.unwrap_or(Detail::Uniform),
            ctrl_base: self.ctrl.len(),
            loop_base: 0,
            returned: false,
        });
        let body = self.block(&f.body, false);
        let ctx = self.fstack.pop().expect("pushed");
        self.ctrl = saved_ctrl;
        self.loops = saved_loops;
        self.pop_scope();
        let body = body?;
        if ret.base != BaseType::Void && !ctx.returned {
            return Err(Diag::new(
                f.pos,
                format!("function \"{}\" returns {} but has no return statement", f.name, ret),
            ));
        }
        let mut rd = ctx.ret_detail;
        if self.memo.func_varying[id] {
            rd = Detail::Varying;
        }
        if f.ret.detail == Some(Detail::Uniform) && rd == Detail::Varying {
            return Err(Diag::new(
                f.pos,
                format!("function \"{}\" is declared uniform but returns a varying value", f.name),
            ));
        }
        self.funcs[id].ret_detail = rd;
        self.funcs[id].body = body;
        Ok(())
    }

    fn lookup_funcs_at(&self, scope: usize, name: &str) -> Vec<FuncId> {
        match self.scopes[scope].names.get(name) {
            Some(Sym::Funcs(l)) => l.clone(),
            _ => Vec::new(),
        }
    }

    fn check_recursion(&self) -> DResult<()> {
        // Depth-first search for a cycle in the call graph.
        let n = self.funcs.len();
        let mut state = vec![0u8; n];
        fn dfs(
            c: &Checker<'_>,
            f: usize,
            state: &mut [u8],
            path: &mut Vec<usize>,
        ) -> Option<(Vec<usize>, Pos)> {
            state[f] = 1;
            path.push(f);
            for &(g, pos) in &c.calls[f] {
                if state[g] == 1 {
                    let start = path.iter().position(|&x| x == g).expect("on the path");
                    let mut cycle = path[start..].to_vec();
                    cycle.push(g);
                    return Some((cycle, pos));
                }
                if state[g] == 0
                    && let Some(r) = dfs(c, g, state, path)
                {
                    return Some(r);
                }
            }
            path.pop();
            state[f] = 2;
            None
        }
        for f in 0..n {
            if state[f] == 0 {
                let mut path = Vec::new();
                if let Some((cycle, pos)) = dfs(self, f, &mut state, &mut path) {
                    let names: Vec<&str> =
                        cycle.iter().map(|&i| self.funcs[i].name.as_str()).collect();
                    let msg = if cycle.len() == 2 {
                        format!(
                            "function \"{}\" calls itself: recursion is not allowed in RSL",
                            names[0]
                        )
                    } else {
                        format!("recursion is not allowed in RSL: {}", names.join(" calls "))
                    };
                    return Err(Diag::new(pos, msg));
                }
            }
        }
        Ok(())
    }

    // ---------------------------------------------------------------- statements

    fn block(&mut self, stmts: &[ast::Stmt], scope: bool) -> DResult<Vec<Stmt>> {
        if scope {
            self.push_scope(false);
        }
        let mut out = Vec::new();
        let mut r = Ok(());
        for s in stmts {
            match self.stmt(s, &mut out) {
                Ok(()) => {}
                Err(e) => {
                    r = Err(e);
                    break;
                }
            }
        }
        if scope {
            self.pop_scope();
        }
        r.map(|()| out)
    }

    fn sub(&mut self, s: &ast::Stmt) -> DResult<Vec<Stmt>> {
        match s {
            ast::Stmt::Block(b) => self.block(b, true),
            other => self.block(std::slice::from_ref(other), true),
        }
    }

    fn condition(&mut self, e: &ast::Expr, what: &str) -> DResult<Expr> {
        let c = self.expr(e, None)?;
        self.as_condition(c, what)
    }

    fn as_condition(&mut self, c: Expr, what: &str) -> DResult<Expr> {
        match c.ty {
            Type::BOOL => Ok(c),
            Type::FLOAT => Ok(Expr {
                ty: Type::BOOL,
                detail: c.detail,
                pos: c.pos,
                kind: ExprKind::Convert(Box::new(c)),
            }),
            t => Err(Diag::new(
                c.pos,
                format!("{what} must be a relation or a float, got {}", describe_type(t)),
            )),
        }
    }

    fn stmt(&mut self, s: &ast::Stmt, out: &mut Vec<Stmt>) -> DResult<()> {
        match s {
            ast::Stmt::Empty => {}
            ast::Stmt::Expr(e) => {
                let e = self.expr(e, None)?;
                out.push(Stmt::Expr(e));
            }
            ast::Stmt::Block(b) => out.push(Stmt::Block(self.block(b, true)?)),
            ast::Stmt::Decl(d) => self.local_decl(d, out)?,
            ast::Stmt::Function(f) => self.function(f)?,
            ast::Stmt::If { cond, then, els } => {
                let cond = self.condition(cond, "the condition of \"if\"")?;
                let varying = cond.detail == Detail::Varying;
                if varying {
                    self.ctrl.push(cond.pos);
                }
                let then = self.sub(then);
                let els = match (&then, els) {
                    (Ok(_), Some(e)) => self.sub(e),
                    _ => Ok(Vec::new()),
                };
                if varying {
                    self.ctrl.pop();
                }
                out.push(Stmt::If { cond, then: then?, els: els? });
            }
            ast::Stmt::While { cond, body } => {
                let l = self.r#loop(Some(cond), None, body, "while")?;
                out.push(l);
            }
            ast::Stmt::For { init, cond, step, body, pos: _ } => {
                if let Some(i) = init {
                    let i = self.expr(i, None)?;
                    out.push(Stmt::Expr(i));
                }
                let l = self.r#loop(cond.as_ref(), step.as_ref(), body, "for")?;
                out.push(l);
            }
            ast::Stmt::Break(n, pos) | ast::Stmt::Continue(n, pos) => {
                let is_break = matches!(s, ast::Stmt::Break(..));
                let word = if is_break { "break" } else { "continue" };
                let base = self.fstack.last().map_or(0, |f| f.loop_base);
                let depth = self.loops.len() - base;
                if depth == 0 {
                    return Err(Diag::new(*pos, format!("\"{word}\" outside a loop")));
                }
                if *n as usize > depth {
                    return Err(Diag::new(
                        *pos,
                        format!("\"{word} {n}\" leaves {n} loops, but only {depth} enclose it"),
                    ));
                }
                let k = self.loops.len();
                for l in &self.loops[k - *n as usize..] {
                    if self.ctrl.len() > l.ctrl_base && !self.memo.loops[l.ordinal] {
                        self.memo.loops[l.ordinal] = true;
                        self.changed = true;
                    }
                }
                out.push(if is_break { Stmt::Break(*n) } else { Stmt::Continue(*n) });
            }
            ast::Stmt::Return(value, pos) => {
                let Some(f) = self.fstack.last() else {
                    return Err(Diag::new(
                        *pos,
                        "\"return\" outside a function (a shader body does not return)",
                    ));
                };
                let (ret, id, base) = (f.ret, f.id, f.ctrl_base);
                let v = match value {
                    None if ret.base != BaseType::Void => {
                        return Err(Diag::new(
                            *pos,
                            format!(
                                "\"return\" without a value in function \"{}\", which returns {ret}",
                                self.funcs[id].name
                            ),
                        ));
                    }
                    None => None,
                    Some(e) if ret.base == BaseType::Void => {
                        return Err(Diag::new(
                            e.pos,
                            format!(
                                "function \"{}\" returns void, but \"return\" has a value",
                                self.funcs[id].name
                            ),
                        ));
                    }
                    Some(e) => {
                        let v = self.expr(e, Some(ret))?;
                        Some(self.convert(
                            v,
                            ret,
                            &format!("the return value of \"{}\"", self.funcs[id].name),
                        )?)
                    }
                };
                let varying_ctrl = self.ctrl.len() > base;
                if varying_ctrl && !self.memo.func_varying[id] {
                    self.memo.func_varying[id] = true;
                    self.changed = true;
                }
                let f = self.fstack.last_mut().expect("checked");
                f.returned = true;
                if let Some(v) = &v {
                    f.ret_detail = f.ret_detail.join(v.detail);
                }
                out.push(Stmt::Return(v));
            }
            ast::Stmt::Illuminance { args, body, pos } => {
                if !matches!(self.kind, ShaderKind::Surface | ShaderKind::Volume) {
                    return Err(Diag::new(
                        *pos,
                        format!(
                            "\"illuminance\" is for surface and volume shaders, not {} shaders",
                            self.kind
                        ),
                    ));
                }
                let mut checked = Vec::new();
                for a in args {
                    checked.push(self.expr(a, None)?);
                }
                let mut it = checked.into_iter().peekable();
                let category =
                    if it.peek().is_some_and(|e| e.ty == Type::STRING) { it.next() } else { None };
                let Some(position) = it.next() else {
                    return Err(Diag::new(
                        *pos,
                        "\"illuminance\" needs a position: illuminance ([category,] P [, axis, angle]) statement",
                    ));
                };
                let position =
                    self.convert(position, Type::POINT, "the position of \"illuminance\"")?;
                let rest: Vec<Expr> = it.collect();
                let (cone, options) = self.cone_and_options(rest, "illuminance")?;
                self.illuminance += 1;
                self.ctrl.push(*pos);
                let body = self.sub(body);
                self.ctrl.pop();
                self.illuminance -= 1;
                out.push(Stmt::Illuminance { category, position, cone, options, body: body? });
            }
            ast::Stmt::Illuminate { args, body, pos } | ast::Stmt::Solar { args, body, pos } => {
                let is_solar = matches!(s, ast::Stmt::Solar { .. });
                let word = if is_solar { "solar" } else { "illuminate" };
                if self.kind != ShaderKind::Light {
                    return Err(Diag::new(
                        *pos,
                        format!("\"{word}\" is for light shaders, not {} shaders", self.kind),
                    ));
                }
                if self.light_block > 0 {
                    return Err(Diag::new(
                        *pos,
                        format!("\"{word}\" inside another illuminate or solar"),
                    ));
                }
                let mut checked = Vec::new();
                for a in args {
                    checked.push(self.expr(a, None)?);
                }
                let mut it = checked.into_iter();
                let position = if is_solar {
                    None
                } else {
                    let Some(p) = it.next() else {
                        return Err(Diag::new(
                            *pos,
                            "\"illuminate\" needs a position: illuminate (P [, axis, angle]) statement",
                        ));
                    };
                    Some(self.convert(p, Type::POINT, "the position of \"illuminate\"")?)
                };
                let rest: Vec<Expr> = it.collect();
                let (cone, options) = self.cone_and_options(rest, word)?;
                if let Some((o, _)) = options.first() {
                    return Err(Diag::new(
                        *pos,
                        format!("\"{word}\" takes no options, got \"{o}\""),
                    ));
                }
                self.light_block += 1;
                self.ctrl.push(*pos);
                let body = self.sub(body);
                self.ctrl.pop();
                self.light_block -= 1;
                let body = body?;
                out.push(match position {
                    Some(position) => Stmt::Illuminate { position, cone, body },
                    None => Stmt::Solar { cone, body },
                });
            }
        }
        Ok(())
    }

    /// `[axis, angle] ["name", value]...` after the position of a light statement.
    #[allow(clippy::type_complexity)]
    fn cone_and_options(
        &mut self,
        rest: Vec<Expr>,
        word: &str,
    ) -> DResult<(Option<(Expr, Expr)>, Vec<(String, Expr)>)> {
        let mut it = rest.into_iter().peekable();
        let mut cone = None;
        if it.peek().is_some_and(|e| e.ty != Type::STRING) {
            let axis = it.next().expect("peeked");
            let Some(angle) = it.next() else {
                return Err(Diag::new(
                    axis.pos,
                    format!("\"{word}\": an axis needs an angle after it"),
                ));
            };
            let axis = self.convert(axis, Type::VECTOR, &format!("the axis of \"{word}\""))?;
            let angle = self.convert(angle, Type::FLOAT, &format!("the angle of \"{word}\""))?;
            cone = Some((axis, angle));
        }
        let mut options = Vec::new();
        while let Some(name) = it.next() {
            let ExprKind::Str(n) = &name.kind else {
                return Err(Diag::new(
                    name.pos,
                    format!(
                        "\"{word}\": expected an option name (a string constant), got {}",
                        describe_type(name.ty)
                    ),
                ));
            };
            let Some(value) = it.next() else {
                return Err(Diag::new(
                    name.pos,
                    format!("\"{word}\": option \"{n}\" has no value"),
                ));
            };
            options.push((n.clone(), value));
        }
        Ok((cone, options))
    }

    fn r#loop(
        &mut self,
        cond: Option<&ast::Expr>,
        step: Option<&ast::Expr>,
        body: &ast::Stmt,
        word: &str,
    ) -> DResult<Stmt> {
        let ordinal = self.loop_count;
        self.loop_count += 1;
        if self.memo.loops.len() <= ordinal {
            self.memo.loops.push(false);
        }
        let cond = match cond {
            Some(c) => self.condition(c, &format!("the condition of \"{word}\""))?,
            None => Expr {
                kind: ExprKind::Float(1.0),
                ty: Type::FLOAT,
                detail: Detail::Uniform,
                pos: body_pos(body),
            },
        };
        let cond = if cond.ty == Type::FLOAT { self.as_condition(cond, "")? } else { cond };
        let varying = cond.detail == Detail::Varying || self.memo.loops[ordinal];
        if varying {
            self.ctrl.push(cond.pos);
        }
        self.loops.push(LoopCtx { ordinal, ctrl_base: self.ctrl.len() });
        let b = self.sub(body);
        let st = match (&b, step) {
            (Ok(_), Some(s)) => self.expr(s, None).map(Some),
            _ => Ok(None),
        };
        self.loops.pop();
        if varying {
            self.ctrl.pop();
        }
        Ok(Stmt::Loop { cond, body: b?, step: st?, varying: varying || self.memo.loops[ordinal] })
    }

    fn local_decl(&mut self, d: &ast::Decl, out: &mut Vec<Stmt>) -> DResult<()> {
        for v in &d.vars {
            let ty = self.decl_type(d.ty.base, v.array, v.pos, false)?;
            if d.is_extern {
                if v.init.is_some() {
                    return Err(Diag::new(
                        v.pos,
                        format!("extern \"{}\" cannot have an initialiser", v.name),
                    ));
                }
                // Find the outer variable, crossing function boundaries.
                let mut found = None;
                for s in self.scopes.iter().rev() {
                    if let Some(sym @ (Sym::Var(_) | Sym::Global(_))) = s.names.get(&v.name) {
                        found = Some(sym.clone());
                        break;
                    }
                }
                let found = found.or_else(|| global(&v.name).map(Sym::Global));
                let (oty, odetail) = match &found {
                    Some(Sym::Var(id)) => (self.vars[*id].ty, self.vars[*id].detail),
                    Some(Sym::Global(g)) => {
                        if g.access(self.kind) == Access::None {
                            return Err(Diag::new(
                                v.pos,
                                format!(
                                    "extern \"{}\": {} shaders have no predefined variable \"{}\"",
                                    v.name, self.kind, v.name
                                ),
                            ));
                        }
                        (g.ty, g.detail)
                    }
                    _ => {
                        return Err(Diag::new(
                            v.pos,
                            format!(
                                "extern \"{}\": no variable of that name in an enclosing scope",
                                v.name
                            ),
                        ));
                    }
                };
                let compatible = oty == ty
                    || (oty.base.is_spatial() && ty.base.is_spatial() && oty.array == ty.array);
                if !compatible {
                    return Err(Diag::new(
                        v.pos,
                        format!(
                            "extern \"{}\" is declared {ty}, but the variable it names is {oty}",
                            v.name
                        ),
                    ));
                }
                if d.ty.detail == Some(Detail::Uniform)
                    && odetail == Detail::Varying
                    && matches!(found, Some(Sym::Global(_)))
                {
                    return Err(Diag::new(
                        v.pos,
                        format!(
                            "extern \"{}\" is declared uniform, but the variable it names is varying",
                            v.name
                        ),
                    ));
                }
                self.declare(&v.name, found.expect("matched"), v.pos)?;
                continue;
            }
            let id = self.new_var(&v.name, ty, d.ty.detail, VarKind::Local, v.pos);
            let init = match &v.init {
                Some(e) => {
                    let mut value = self.initializer(e, ty, &v.name)?;
                    self.assign_value(id, &mut value, e.pos)?;
                    Some(value)
                }
                None => None,
            };
            self.declare(&v.name, Sym::Var(id), v.pos)?;
            out.push(Stmt::Local { var: id, init });
        }
        Ok(())
    }

    fn initializer(&mut self, e: &ast::Expr, ty: Type, name: &str) -> DResult<Expr> {
        if let A::ArrayLit(items) = &e.kind {
            let Some(n) = ty.array else {
                return Err(Diag::new(
                    e.pos,
                    format!("an array initialiser {{…}} for \"{name}\", a {ty}"),
                ));
            };
            if items.len() as u32 != n {
                return Err(Diag::new(
                    e.pos,
                    format!("the initialiser has {} values for \"{name}\", a {ty}", items.len()),
                ));
            }
            let mut parts = Vec::new();
            let mut detail = Detail::Uniform;
            for it in items {
                let v = self.expr(it, Some(ty.element()))?;
                let v = self.convert(v, ty.element(), &format!("an element of \"{name}\""))?;
                detail = detail.join(v.detail);
                parts.push(v);
            }
            return Ok(Expr { kind: ExprKind::Array(parts), ty, detail, pos: e.pos });
        }
        let v = self.expr(e, Some(ty))?;
        self.convert(v, ty, &format!("the initial value of \"{name}\""))
    }

    /// The detail rules of assigning `value` to variable `id`; a value varying only through
    /// `random()` is made uniform for a uniform variable (one random value for the grid).
    fn assign_value(&mut self, id: VarId, value: &mut Expr, pos: Pos) -> DResult<()> {
        if value.detail == Detail::Varying
            && self.vars[id].detail == Detail::Uniform
            && self.vars[id].declared == Some(Detail::Uniform)
        {
            make_uniform(value);
        }
        self.assign_detail(id, value, pos)
    }

    /// The detail rules of assigning a value of `value`'s detail to variable `id`.
    fn assign_detail(&mut self, id: VarId, value: &Expr, pos: Pos) -> DResult<()> {
        let name = self.vars[id].name.clone();
        if value.detail == Detail::Varying {
            self.raise(
                id,
                || format!("cannot assign a varying value to uniform variable \"{name}\""),
                pos,
            )?;
        }
        if let Some(&c) = self.ctrl.last().filter(|_| self.ctrl.len() > self.decl_ctrl[id]) {
            self.raise(
                id,
                || format!("cannot assign to uniform variable \"{name}\" under varying control (the condition at {}:{} is varying)", c.line, c.col),
                pos,
            )?;
        }
        // Writes to outer variables from a function body.
        if let Some(f) = self.fstack.last() {
            let fid = f.id;
            let owned = match self.vars[id].kind {
                VarKind::Formal { func, .. } => func == fid,
                _ => false,
            };
            if !owned && !self.extern_writes[fid].contains(&id) && self.is_outer(id) {
                self.extern_writes[fid].push(id);
            }
        }
        Ok(())
    }

    fn is_outer(&self, id: VarId) -> bool {
        // A variable declared outside the innermost function body.
        let mut in_function = true;
        for s in self.scopes.iter().rev() {
            if s.names.values().any(|sym| matches!(sym, Sym::Var(v) if *v == id)) {
                return !in_function;
            }
            if s.boundary {
                in_function = false;
            }
        }
        false
    }

    // ---------------------------------------------------------------- conversions

    /// `e` converted to `to` (assignment rules), or an error naming `what`.
    fn convert(&mut self, e: Expr, to: Type, what: &str) -> DResult<Expr> {
        if e.ty == to {
            return Ok(e);
        }
        if to.array == Some(0) && e.ty.array.is_some() && e.ty.base == to.base {
            return Ok(e);
        }
        if conv_cost(e.ty, to).is_some() {
            return Ok(Expr {
                ty: to,
                detail: e.detail,
                pos: e.pos,
                kind: ExprKind::Convert(Box::new(e)),
            });
        }
        let hint = if e.ty.base.is_triple() && to.base.is_triple() {
            format!(" (write a cast: {} (...))", to.base)
        } else {
            String::new()
        };
        Err(Diag::new(e.pos, format!("{what} must be {to}, got {}{hint}", describe_type(e.ty))))
    }

    // ---------------------------------------------------------------- expressions

    fn expr(&mut self, e: &ast::Expr, want: Option<Type>) -> DResult<Expr> {
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

    fn index(&mut self, idx: &ast::Expr, arr: Type) -> DResult<Expr> {
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

    fn name(&mut self, n: &str, pos: Pos) -> DResult<Expr> {
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

    fn global_read(&mut self, g: &'static Global, pos: Pos) -> DResult<()> {
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

    fn construct(
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

    fn check_space(&self, target: BaseType, s: String, pos: Pos) -> DResult<String> {
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

    fn cast(
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

    fn binary(
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
    fn operand(&mut self, e: &ast::Expr, other: &Expr, want: Option<Type>) -> DResult<Expr> {
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

    fn binary_typed(&mut self, op: BinOp, a: Expr, b: Expr, pos: Pos) -> DResult<Expr> {
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

    /// The place an assignment (or an output argument) writes.
    fn place(
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

    fn write_place(
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

    fn assign(
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

    fn place_name(&self, p: &Place) -> String {
        match p {
            Place::Var(id) => self.vars[*id].name.clone(),
            Place::Global(g) => (*g).to_string(),
        }
    }

    // ---------------------------------------------------------------- calls

    fn call(
        &mut self,
        name: &str,
        args: &[ast::Expr],
        want: Option<Type>,
        pos: Pos,
    ) -> DResult<Expr> {
        if self.lookup_var(name, pos).ok().flatten().is_some_and(|s| matches!(s, Sym::Var(_)))
            && self.lookup_funcs(name).is_empty()
        {
            return Err(Diag::new(pos, format!("\"{name}\" is a variable, not a function")));
        }
        let users = self.lookup_funcs(name);
        if !users.is_empty() {
            return self.user_call(name, &users, args, want, pos);
        }
        let Some(sigs) = library().get(name) else {
            return Err(Diag::new(pos, format!("unknown function \"{name}\"")));
        };
        let lib_name =
            library().names().iter().find(|n| **n == name).copied().expect("in the table");
        let is_texture = matches!(name, "texture" | "environment" | "shadow");
        // Arguments: a texture map's channel, positional values, then name/value options.
        let mut channel = None;
        let mut checked: Vec<Option<Expr>> = Vec::new();
        for (k, a) in args.iter().enumerate() {
            if k == 0
                && is_texture
                && let A::Index(b, i) = &a.kind
            {
                {
                    let base = self.expr(b, None)?;
                    if base.ty == Type::STRING {
                        let c = self.expr(i, Some(Type::FLOAT))?;
                        if c.ty != Type::FLOAT {
                            return Err(Diag::new(
                                c.pos,
                                format!(
                                    "the channel of a texture map must be a float, got {}",
                                    describe_type(c.ty)
                                ),
                            ));
                        }
                        channel = Some(Box::new(c));
                        checked.push(Some(base));
                        continue;
                    }
                }
            }
            checked.push(if is_loose(a) { None } else { Some(self.expr(a, None)?) });
        }
        let uses_params = sigs.iter().any(|s| s.rest == Rest::Params);
        // Where the options begin: the first string constant after the first argument.
        let mut npos = args.len();
        if uses_params {
            for (k, c) in checked.iter().enumerate().skip(1) {
                if matches!(c, Some(e) if matches!(e.kind, ExprKind::Str(_))) {
                    // A string constant where a signature takes a string positionally is not an option.
                    let positional_string = sigs
                        .iter()
                        .any(|s| s.params.get(k).is_some_and(|p| p.ty == Some(Type::STRING)));
                    if !positional_string {
                        npos = k;
                        break;
                    }
                }
            }
        }
        let positional = &args[..npos];
        // Score each overload.
        let mut best: Vec<(u32, usize)> = Vec::new();
        for (i, s) in sigs.iter().enumerate() {
            if let Some(cost) = self.match_sig(s, &checked[..npos], positional, npos < args.len()) {
                best.push((cost, i));
            }
        }
        if best.is_empty() {
            return Err(self.no_match(
                name,
                sigs.iter().map(|s| s.show(name)).collect(),
                &checked[..npos],
                pos,
            ));
        }
        let min = best.iter().map(|b| b.0).min().expect("non-empty");
        best.retain(|b| b.0 == min);
        let pick = best
            .iter()
            .find(|b| want.is_some_and(|w| sigs[b.1].ret == w))
            .or_else(|| best.iter().find(|b| sigs[b.1].ret == Type::FLOAT))
            .or_else(|| best.first())
            .expect("non-empty")
            .1;
        let sig = &sigs[pick];
        let mut out_args = Vec::new();
        let mut detail = if sig.varying { Detail::Varying } else { Detail::Uniform };
        for (k, a) in positional.iter().enumerate() {
            let p = sig.params.get(k).copied();
            let pty = match (p, sig.rest) {
                (Some(p), _) => p.ty,
                (None, Rest::Same(t)) => Some(t),
                _ => None,
            };
            if p.is_some_and(|p| p.output) {
                let (place, index, ty, ppos) =
                    self.place(a, &format!("output argument {} of \"{name}\"", k + 1))?;
                let e = self.place_expr(place, index, ty, ppos);
                out_args.push(e);
                continue;
            }
            let e = match checked[k].take() {
                Some(e) => e,
                None => self.expr(a, pty)?,
            };
            let e = match pty {
                Some(t) => self.convert(e, t, &format!("argument {} of \"{name}\"", k + 1))?,
                None => e,
            };
            detail = detail.join(e.detail);
            out_args.push(e);
        }
        // Output arguments are written with the call's detail.
        for (k, e) in out_args.iter().enumerate() {
            if sig.params.get(k).is_some_and(|p| p.output)
                && let Some(id) = id_of(e)
            {
                let probe =
                    Expr { kind: ExprKind::Float(0.0), ty: Type::FLOAT, detail, pos: e.pos };
                self.assign_detail(id, &probe, e.pos)?;
            }
        }
        let mut options = Vec::new();
        let mut k = npos;
        while k < args.len() {
            let Some(name_expr) = checked[k].take() else {
                return Err(Diag::new(
                    args[k].pos,
                    format!(
                        "\"{name}\": expected an option name (a string), got a parenthesised list"
                    ),
                ));
            };
            let ExprKind::Str(oname) = &name_expr.kind else {
                return Err(Diag::new(
                    name_expr.pos,
                    format!(
                        "\"{name}\": expected an option name (a string constant), got {}",
                        describe_type(name_expr.ty)
                    ),
                ));
            };
            let Some(value_ast) = args.get(k + 1) else {
                return Err(Diag::new(
                    name_expr.pos,
                    format!("\"{name}\": option \"{oname}\" has no value"),
                ));
            };
            let value = match checked[k + 1].take() {
                Some(v) => v,
                None => self.expr(value_ast, None)?,
            };
            if let Some(t) = texture_option(oname)
                && (value.ty.base != t || value.ty.is_array())
            {
                return Err(Diag::new(
                    value.pos,
                    format!(
                        "\"{name}\": option \"{oname}\" takes a {t}, got {}",
                        describe_type(value.ty)
                    ),
                ));
            }
            detail = detail.join(value.detail);
            options.push((oname.clone(), value));
            k += 2;
        }
        if let Some(c) = &channel {
            detail = detail.join(c.detail);
        }
        Ok(Expr {
            kind: ExprKind::Call {
                callee: Callee::Builtin { name: lib_name, overload: pick },
                args: out_args,
                channel,
                options,
            },
            ty: sig.ret,
            detail,
            pos,
        })
    }

    fn place_expr(&mut self, place: Place, index: Option<Expr>, ty: Type, pos: Pos) -> Expr {
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

    /// The cost of calling `s` with these arguments (`None` for a parenthesised triple), or
    /// `None` if it does not fit.
    fn match_sig(
        &self,
        s: &Signature,
        args: &[Option<Expr>],
        asts: &[ast::Expr],
        has_options: bool,
    ) -> Option<u32> {
        if has_options && s.rest != Rest::Params {
            return None;
        }
        let n = args.len();
        let fixed = s.params.len();
        match s.rest {
            Rest::None | Rest::Params if n != fixed => return None,
            Rest::Same(_) | Rest::Any if n < fixed => return None,
            _ => {}
        }
        let mut cost = 0;
        for (k, a) in args.iter().enumerate() {
            let (pty, output) = match s.params.get(k) {
                Some(p) => (p.ty, p.output),
                None => match s.rest {
                    Rest::Same(t) => (Some(t), false),
                    _ => (None, false),
                },
            };
            if output && !matches!(asts[k].kind, A::Name(_) | A::Index(..)) {
                return None;
            }
            let Some(pty) = pty else { continue };
            match a {
                None => {
                    if !(pty.base.is_triple() || pty.base == BaseType::Matrix) || pty.is_array() {
                        return None;
                    }
                    cost += 1;
                }
                Some(e) => {
                    if output {
                        if e.ty != pty
                            && !(e.ty.base.is_spatial()
                                && pty.base.is_spatial()
                                && e.ty.array == pty.array)
                        {
                            return None;
                        }
                        continue;
                    }
                    cost += conv_cost(e.ty, pty)?;
                }
            }
        }
        Some(cost)
    }

    fn no_match(&self, name: &str, sigs: Vec<String>, args: &[Option<Expr>], pos: Pos) -> Diag {
        let got: Vec<String> = args
            .iter()
            .map(|a| a.as_ref().map_or("(...)".to_string(), |e| describe_type(e.ty)))
            .collect();
        let shown: Vec<String> = sigs.iter().take(4).cloned().collect();
        let more =
            if sigs.len() > 4 { format!(" and {} more", sigs.len() - 4) } else { String::new() };
        Diag::new(
            pos,
            format!(
                "no \"{name}\" takes ({}); it takes {}{more}",
                got.join(", "),
                shown.join(" or ")
            ),
        )
    }

    fn user_call(
        &mut self,
        name: &str,
        cands: &[FuncId],
        args: &[ast::Expr],
        want: Option<Type>,
        pos: Pos,
    ) -> DResult<Expr> {
        let checked: Vec<Option<Expr>> = args
            .iter()
            .map(|a| if is_loose(a) { Ok(None) } else { self.expr(a, None).map(Some) })
            .collect::<DResult<_>>()?;
        let mut best: Vec<(u32, FuncId)> = Vec::new();
        for &f in cands {
            let sig = self.user_sig(f);
            if let Some(c) = self.match_sig(&sig, &checked, args, false) {
                best.push((c, f));
            }
        }
        if best.is_empty() {
            let sigs = cands.iter().map(|&f| self.user_sig(f).show(name)).collect();
            return Err(self.no_match(name, sigs, &checked, pos));
        }
        let min = best.iter().map(|b| b.0).min().expect("non-empty");
        best.retain(|b| b.0 == min);
        let f = best
            .iter()
            .find(|b| want.is_some_and(|w| self.funcs[b.1].ret == w))
            .or_else(|| best.iter().find(|b| self.funcs[b.1].ret == Type::FLOAT))
            .or_else(|| best.first())
            .expect("non-empty")
            .1;
        if let Some(cur) = self.fstack.last() {
            let caller = cur.id;
            self.calls[caller].push((f, pos));
        }
        let params = self.funcs[f].params.clone();
        let mut out_args = Vec::new();
        let mut detail = self.funcs[f].ret_detail;
        let mut checked = checked;
        for (k, a) in args.iter().enumerate() {
            let p = params[k];
            let (pty, output) = (
                self.vars[p].ty,
                matches!(self.vars[p].kind, VarKind::Formal { output: true, .. }),
            );
            let e = if output {
                let (place, index, ty, ppos) =
                    self.place(a, &format!("output argument {} of \"{name}\"", k + 1))?;
                self.place_expr(place, index, ty, ppos)
            } else {
                let e = match checked[k].take() {
                    Some(e) => e,
                    None => self.expr(a, Some(pty))?,
                };
                self.convert(e, pty, &format!("argument {} of \"{name}\"", k + 1))?
            };
            // The formal is as varying as what is passed to it.
            if e.detail == Detail::Varying && self.vars[p].detail == Detail::Uniform {
                let fname = self.funcs[f].name.clone();
                let pname = self.vars[p].name.clone();
                self.raise(p, || format!("argument {} of \"{fname}\" is varying, but parameter \"{pname}\" is declared uniform", k + 1), e.pos)?;
            }
            if self.vars[p].detail == Detail::Varying && !output {
                // A varying formal makes the result varying only through the body: ret_detail.
            }
            detail = detail.join(if output { Detail::Uniform } else { e.detail });
            out_args.push(e);
        }
        // Output formals written varying make their actuals varying; so does a call under
        // varying control.
        for (k, e) in out_args.iter().enumerate() {
            let p = params[k];
            if matches!(self.vars[p].kind, VarKind::Formal { output: true, .. })
                && let Some(id) = id_of(e)
            {
                let probe = Expr {
                    kind: ExprKind::Float(0.0),
                    ty: Type::FLOAT,
                    detail: self.vars[p].detail,
                    pos: e.pos,
                };
                self.assign_detail(id, &probe, e.pos)?;
            }
        }
        if !self.ctrl.is_empty() {
            for id in self.extern_writes[f].clone() {
                let probe = Expr {
                    kind: ExprKind::Float(0.0),
                    ty: Type::FLOAT,
                    detail: Detail::Uniform,
                    pos,
                };
                self.assign_detail(id, &probe, pos)?;
            }
        }
        let ret = self.funcs[f].ret;
        Ok(Expr {
            kind: ExprKind::Call {
                callee: Callee::User(f),
                args: out_args,
                channel: None,
                options: Vec::new(),
            },
            ty: ret,
            detail,
            pos,
        })
    }

    fn user_sig(&self, f: FuncId) -> Signature {
        let func = &self.funcs[f];
        Signature {
            ret: func.ret,
            params: func
                .params
                .iter()
                .map(|&p| crate::library::BParam {
                    ty: Some(self.vars[p].ty),
                    output: matches!(self.vars[p].kind, VarKind::Formal { output: true, .. }),
                })
                .collect(),
            rest: Rest::None,
            varying: false,
            extension: false,
        }
    }
}

/// Makes `e` uniform if only calls of `random()` make it varying (they then draw one value for
/// the grid); whether it succeeded.
fn make_uniform(e: &mut Expr) -> bool {
    if e.detail == Detail::Uniform {
        return true;
    }
    let ok = match &mut e.kind {
        ExprKind::Call { callee: Callee::Builtin { name: "random", .. }, .. } => true,
        ExprKind::Call { callee: Callee::Builtin { .. }, args, channel: None, options }
            if options.is_empty() =>
        {
            let mut ok = true;
            for a in args.iter_mut() {
                ok &= make_uniform(a);
            }
            ok && !builtin_always_varying(e)
        }
        ExprKind::Convert(x) | ExprKind::Unary(_, x) => make_uniform(x),
        ExprKind::Binary(_, a, b) => make_uniform(a) & make_uniform(b),
        ExprKind::Cond(c, a, b) => make_uniform(c) & make_uniform(a) & make_uniform(b),
        ExprKind::Construct { parts, .. } | ExprKind::Array(parts) => {
            let mut ok = true;
            for p in parts.iter_mut() {
                ok &= make_uniform(p);
            }
            ok
        }
        ExprKind::SpaceCast { value, .. } => make_uniform(value),
        _ => false,
    };
    if ok {
        e.detail = Detail::Uniform;
    }
    ok
}

fn builtin_always_varying(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Call { callee: Callee::Builtin { name, overload }, .. } => {
            library().get(name).is_some_and(|s| s[*overload].varying)
        }
        _ => false,
    }
}

fn id_of(e: &Expr) -> Option<VarId> {
    match &e.kind {
        ExprKind::Var(id) => Some(*id),
        ExprKind::Index(b, _) => id_of(b),
        _ => None,
    }
}

fn body_pos(s: &ast::Stmt) -> Pos {
    match s {
        ast::Stmt::Expr(e) => e.pos,
        ast::Stmt::Break(_, p) | ast::Stmt::Continue(_, p) | ast::Stmt::Return(_, p) => *p,
        _ => Pos::default(),
    }
}
