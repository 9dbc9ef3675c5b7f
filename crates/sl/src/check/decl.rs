//! Declarations: the shader and its parameters, function definitions (overloads, formals,
//! return rules) and the recursion check over their call graph, local and `extern` variables,
//! and initialisers.

use crate::ast::{self, ArraySpec, ExprKind as A};
use crate::error::{DResult, Diag, Pos, SourceMap};
use crate::globals::{Access, global};
use crate::ir::*;
use crate::types::{BaseType, Detail, Type};

use super::detail::make_uniform;
use super::{Checker, FuncCtx, Sym};

impl Checker<'_> {
    pub(super) fn shader(&mut self, file: &ast::File, sh: &ast::Shader) -> DResult<CheckedShader> {
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

    pub(super) fn decl_type(
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

    pub(super) fn function(&mut self, f: &ast::Function) -> DResult<()> {
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

    pub(super) fn check_recursion(&self) -> DResult<()> {
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

    pub(super) fn local_decl(&mut self, d: &ast::Decl, out: &mut Vec<Stmt>) -> DResult<()> {
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

    pub(super) fn initializer(&mut self, e: &ast::Expr, ty: Type, name: &str) -> DResult<Expr> {
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
}
