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
//!
//! This module holds the passes and the checker's state; the rules are in its parts:
//! - `scope`: scopes and symbols, name lookup and the `extern` rule;
//! - `decl`: the shader, function definitions, recursion, local and `extern` declarations;
//! - `stmt`: statements and control flow, the light statements;
//! - `expr`: expressions, typecasts and constructors; `ops`: the binary operators;
//! - `assign`: assignments and the places they write;
//! - `call`: calls and overload resolution; `convert`: the implicit conversions;
//! - `detail`: the uniform/varying analysis.

use std::collections::HashMap;

use crate::ast;
use crate::error::{DResult, Diag, Pos, SourceMap};
use crate::globals::Global;
use crate::ir::*;
use crate::types::{Detail, ShaderKind, Type};

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
}

mod assign;
mod call;
mod convert;
mod decl;
mod detail;
mod expr;
mod ops;
mod scope;
mod stmt;
