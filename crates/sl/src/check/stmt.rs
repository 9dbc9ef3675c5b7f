//! Statements and control flow: blocks, conditions, `if`, loops with `break`/`continue`
//! levels, `return`, and the light statements `illuminance`, `illuminate`, `solar`; varying
//! conditions push the varying-control stack the uniform/varying analysis reads.

use crate::ast;
use crate::error::{DResult, Diag, Pos};
use crate::ir::*;
use crate::types::{BaseType, Detail, ShaderKind, Type};

use super::convert::describe_type;
use super::{Checker, LoopCtx};

impl Checker<'_> {
    pub(super) fn block(&mut self, stmts: &[ast::Stmt], scope: bool) -> DResult<Vec<Stmt>> {
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

    pub(super) fn sub(&mut self, s: &ast::Stmt) -> DResult<Vec<Stmt>> {
        match s {
            ast::Stmt::Block(b) => self.block(b, true),
            other => self.block(std::slice::from_ref(other), true),
        }
    }

    pub(super) fn condition(&mut self, e: &ast::Expr, what: &str) -> DResult<Expr> {
        let c = self.expr(e, None)?;
        self.as_condition(c, what)
    }

    pub(super) fn as_condition(&mut self, c: Expr, what: &str) -> DResult<Expr> {
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

    pub(super) fn stmt(&mut self, s: &ast::Stmt, out: &mut Vec<Stmt>) -> DResult<()> {
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
    pub(super) fn cone_and_options(
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

    pub(super) fn r#loop(
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
}

fn body_pos(s: &ast::Stmt) -> Pos {
    match s {
        ast::Stmt::Expr(e) => e.pos,
        ast::Stmt::Break(_, p) | ast::Stmt::Continue(_, p) | ast::Stmt::Return(_, p) => *p,
        _ => Pos::default(),
    }
}
