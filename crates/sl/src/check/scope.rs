//! Scopes and symbols: variables made and declared, names looked up through the scopes (a
//! function body reaches outer variables only through `extern`, Specification 15.5), and
//! the function overloads a name has.

use std::collections::HashMap;

use crate::error::{DResult, Diag, Pos};
use crate::globals::{Global, global};
use crate::ir::*;
use crate::types::{Detail, Type};

use super::{Checker, Scope, Sym};

impl Checker<'_> {
    pub(super) fn new_var(
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

    pub(super) fn declare(&mut self, name: &str, sym: Sym, pos: Pos) -> DResult<()> {
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
    pub(super) fn lookup_var(&self, name: &str, pos: Pos) -> DResult<Option<Sym>> {
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

    pub(super) fn lookup_funcs(&self, name: &str) -> Vec<FuncId> {
        let mut out = Vec::new();
        for s in self.scopes.iter().rev() {
            if let Some(Sym::Funcs(list)) = s.names.get(name) {
                out.extend(list.iter().copied());
            }
        }
        out
    }

    pub(super) fn lookup_funcs_at(&self, scope: usize, name: &str) -> Vec<FuncId> {
        match self.scopes[scope].names.get(name) {
            Some(Sym::Funcs(l)) => l.clone(),
            _ => Vec::new(),
        }
    }

    pub(super) fn push_scope(&mut self, boundary: bool) {
        self.scopes.push(Scope { names: HashMap::new(), boundary });
    }

    pub(super) fn pop_scope(&mut self) {
        self.scopes.pop();
    }

    pub(super) fn note_read(&mut self, g: &'static Global) {
        if !self.read.contains(&g.name) {
            self.read.push(g.name);
        }
    }

    pub(super) fn is_outer(&self, id: VarId) -> bool {
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
}
