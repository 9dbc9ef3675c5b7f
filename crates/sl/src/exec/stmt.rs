//! Statements: blocks, `if`, loops, `break n`, `continue n`, `return`, and user function calls.
//!
//! One mechanism serves uniform and varying control flow. A block runs under a [`Mask`]; after
//! each statement that can leave (a `break`, `continue`, `return`, or a compound statement
//! holding one) the mask is narrowed to the points still alive: not returned from the current
//! function, and neither exited nor continued in any loop it is in. When no point is left the
//! rest of the block is skipped. A uniform condition branches once for the grid; a varying
//! one splits the mask.

use crate::ir::{Expr, Stmt};

use super::pool;
use super::value::{self, Mask, Value};
use super::{ExecError, GridContext};

/// One loop being run: the points that left it (`break`, or an outer `continue`/`break` or a
/// `return`), and those that `continue`d it this iteration.
pub(crate) struct LoopFrame {
    exited: Vec<bool>,
    continued: Vec<bool>,
}

/// One function invocation (the shader body is the first): its loops, the points that
/// returned, and the result.
pub(crate) struct FuncFrame {
    loops: Vec<LoopFrame>,
    returned: Vec<bool>,
    ret: Option<Value>,
}

impl FuncFrame {
    pub(crate) fn new(n: usize) -> FuncFrame {
        FuncFrame { loops: Vec::new(), returned: vec![false; n], ret: None }
    }
}

fn leaves(st: &Stmt) -> bool {
    !matches!(st, Stmt::Expr(_) | Stmt::Local { .. })
}

impl GridContext<'_> {
    fn alive(&self, i: usize) -> bool {
        let Some(f) = self.frames.last() else { return true };
        !f.returned[i] && f.loops.iter().all(|l| !l.exited[i] && !l.continued[i])
    }

    /// The points of `mask` still alive.
    pub(crate) fn narrow(&self, mask: &Mask) -> Mask {
        mask.filter(|i| self.alive(i))
    }

    pub(crate) fn exec_block(&mut self, stmts: &[Stmt], mask: &Mask) -> Result<(), ExecError> {
        let mut m = mask.clone();
        for st in stmts {
            if m.is_empty() {
                break;
            }
            self.exec(st, &m)?;
            // Rebuilt only when some point left (the common case is none).
            if leaves(st) && m.iter().any(|i| !self.alive(i)) {
                m = self.narrow(&m);
            }
        }
        Ok(())
    }

    fn exec(&mut self, st: &Stmt, mask: &Mask) -> Result<(), ExecError> {
        match st {
            Stmt::Expr(e) => {
                let v = self.eval(e, mask)?;
                pool::recycle(v);
            }
            Stmt::Local { var, init } => {
                if let Some(e) = init {
                    let v = self.eval(e, mask)?;
                    self.store_var(*var, &v, mask);
                    pool::recycle(v);
                }
            }
            Stmt::Block(b) => self.exec_block(b, mask)?,
            Stmt::If { cond, then, els } => {
                let cv = self.eval(cond, mask)?;
                let c = cv.num();
                if !c.varying {
                    let branch = if c.f(0) != 0.0 { then } else { els };
                    pool::recycle(cv);
                    self.exec_block(branch, mask)?;
                } else {
                    let (mt, mf) = (mask.when(c, true), mask.when(c, false));
                    pool::recycle(cv);
                    if !mt.is_empty() {
                        self.exec_block(then, &mt)?;
                    }
                    if !mf.is_empty() {
                        self.exec_block(els, &mf)?;
                    }
                }
            }
            Stmt::Loop { cond, body, step, .. } => {
                self.exec_loop(cond, body, step.as_ref(), mask)?
            }
            Stmt::Break(k) => self.leave(*k as usize, false, mask),
            Stmt::Continue(k) => self.leave(*k as usize, true, mask),
            Stmt::Return(e) => {
                if let Some(e) = e {
                    let v = self.eval(e, mask)?;
                    let n = self.n;
                    if let Some(f) = self.frames.last_mut() {
                        match &mut f.ret {
                            Some(r) => value::store(r, &v, mask, n),
                            None => {
                                let mut r = Value::zero(e.ty, v.varying(), n);
                                value::store(&mut r, &v, mask, n);
                                f.ret = Some(r);
                            }
                        }
                    }
                }
                if let Some(f) = self.frames.last_mut() {
                    for i in mask.iter() {
                        f.returned[i] = true;
                    }
                }
            }
            Stmt::Illuminance { category, position, cone, body, .. } => {
                self.illuminance(category.as_ref(), position, cone.as_ref(), body, mask)?
            }
            Stmt::Illuminate { position, cone, body } => {
                self.illuminate(Some(position), cone.as_ref(), body, mask)?
            }
            Stmt::Solar { cone, body } => self.illuminate(None, cone.as_ref(), body, mask)?,
        }
        Ok(())
    }

    /// `break k` (or `continue k`): the active points leave the inner `k` loops (the
    /// outermost of them only for this iteration, for `continue`).
    fn leave(&mut self, k: usize, cont: bool, mask: &Mask) {
        let Some(f) = self.frames.last_mut() else { return };
        let len = f.loops.len();
        let k = k.clamp(1, len.max(1));
        for (j, l) in f.loops.iter_mut().enumerate().skip(len.saturating_sub(k)) {
            let flags = if cont && j == len - k { &mut l.continued } else { &mut l.exited };
            for i in mask.iter() {
                flags[i] = true;
            }
        }
    }

    fn exec_loop(
        &mut self,
        cond: &Expr,
        body: &[Stmt],
        step: Option<&Expr>,
        mask: &Mask,
    ) -> Result<(), ExecError> {
        let n = self.n;
        if let Some(f) = self.frames.last_mut() {
            f.loops.push(LoopFrame { exited: vec![false; n], continued: vec![false; n] });
        }
        let mut m = mask.clone();
        let r = (|| {
            loop {
                self.tick()?;
                let c = self.eval(cond, &m)?;
                let c = c.num();
                if !c.varying {
                    if c.f(0) == 0.0 {
                        break;
                    }
                } else {
                    m = m.when(c, true);
                }
                if m.is_empty() {
                    break;
                }
                self.exec_block(body, &m)?;
                if let Some(l) = self.frames.last_mut().and_then(|f| f.loops.last_mut()) {
                    l.continued.iter_mut().for_each(|c| *c = false);
                }
                m = self.narrow(&m);
                if m.is_empty() {
                    break;
                }
                if let Some(s) = step {
                    self.eval(s, &m)?;
                }
            }
            Ok(())
        })();
        if let Some(f) = self.frames.last_mut() {
            f.loops.pop();
        }
        r
    }

    /// Calls user function `f` under `mask`; output formals are written back to their places.
    pub(crate) fn call_user(
        &mut self,
        f: usize,
        args: &[Expr],
        ret: &Expr,
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let sh = self.shader;
        let func = &sh.functions[f];
        let mut vals = Vec::with_capacity(args.len());
        for a in args {
            vals.push(self.eval(a, mask)?);
        }
        for (&id, v) in func.params.iter().zip(&vals) {
            self.store_var(id, v, mask);
        }
        if self.frames.len() > 256 {
            return Err(self.err_at("function calls nested over 256 deep".into()));
        }
        let mut frame = FuncFrame::new(self.n);
        // The result has the function's detail from the start, so returns under different
        // masks each store their points.
        if func.ret.base != crate::types::BaseType::Void {
            frame.ret =
                Some(Value::zero(func.ret, func.ret_detail == crate::Detail::Varying, self.n));
        }
        self.frames.push(frame);
        let r = self.exec_block(&func.body, mask);
        let frame = self.frames.pop();
        r?;
        for (&id, a) in func.params.iter().zip(args) {
            if matches!(sh.vars[id].kind, crate::ir::VarKind::Formal { output: true, .. }) {
                let v = self.vars[id].clone();
                self.write_place(a, &v, mask)?;
            }
        }
        Ok(frame
            .and_then(|f| f.ret)
            .unwrap_or_else(|| Value::zero(ret.ty, ret.detail == crate::Detail::Varying, self.n)))
    }

    /// Stores `v` into variable `id` at the active points.
    pub(crate) fn store_var(&mut self, id: usize, v: &Value, mask: &Mask) {
        let n = self.n;
        if let Value::Num(x) = v {
            self.stats.nonfinite += value::count_nonfinite(x, mask);
        }
        if let Some(dst) = self.vars.get_mut(id) {
            value::store(dst, v, mask, n);
        }
    }
}
