//! The uniform/varying analysis: what makes a variable varying (a varying value assigned to
//! it, an assignment under varying control), the errors where a declared detail forbids it,
//! and `random()`'s one value for the grid where a uniform is wanted.

use crate::error::{DResult, Diag, Pos};
use crate::ir::*;
use crate::library::library;
use crate::types::Detail;

use super::Checker;

impl Checker<'_> {
    /// Makes variable `v` varying (an inferred one), or reports why it cannot be.
    pub(super) fn raise(
        &mut self,
        v: VarId,
        why: impl FnOnce() -> String,
        pos: Pos,
    ) -> DResult<()> {
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

    /// The detail rules of assigning `value` to variable `id`; a value varying only through
    /// `random()` is made uniform for a uniform variable (one random value for the grid).
    pub(super) fn assign_value(&mut self, id: VarId, value: &mut Expr, pos: Pos) -> DResult<()> {
        if value.detail == Detail::Varying
            && self.vars[id].detail == Detail::Uniform
            && self.vars[id].declared == Some(Detail::Uniform)
        {
            make_uniform(value);
        }
        self.assign_detail(id, value, pos)
    }

    /// The detail rules of assigning a value of `value`'s detail to variable `id`.
    pub(super) fn assign_detail(&mut self, id: VarId, value: &Expr, pos: Pos) -> DResult<()> {
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
}

/// Makes `e` uniform if only calls of `random()` make it varying (they then draw one value for
/// the grid); whether it succeeded.
pub(super) fn make_uniform(e: &mut Expr) -> bool {
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

pub(super) fn id_of(e: &Expr) -> Option<VarId> {
    match &e.kind {
        ExprKind::Var(id) => Some(*id),
        ExprKind::Index(b, _) => id_of(b),
        _ => None,
    }
}
