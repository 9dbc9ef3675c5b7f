//! Calls and overload resolution: user functions before the standard library, a texture
//! map's channel, positional arguments then `"name", value` options, each overload scored by
//! its conversions (the cheapest wins, then the wanted return type, then float), output
//! arguments, and the details calls pass on.

use crate::ast::{self, ExprKind as A};
use crate::error::{DResult, Diag, Pos};
use crate::ir::*;
use crate::library::{Rest, Signature, library, texture_option};
use crate::types::{BaseType, Detail, Type};

use super::convert::{conv_cost, describe_type};
use super::detail::id_of;
use super::expr::is_loose;
use super::{Checker, Sym};

impl Checker<'_> {
    pub(super) fn call(
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
        // Output arguments are written with the call's detail; a message from another
        // shader may differ from point to point, so it makes its variable varying unless
        // the variable is declared uniform (`uniform float nonspec; lightsource(...)`).
        let message = matches!(
            name,
            "atmosphere" | "displacement" | "lightsource" | "surface" | "incident" | "opposite"
        );
        for (k, e) in out_args.iter().enumerate() {
            if sig.params.get(k).is_some_and(|p| p.output)
                && let Some(id) = id_of(e)
            {
                let detail = match self.vars[id].declared {
                    Some(d) if message => d,
                    None if message => Detail::Varying,
                    _ => detail,
                };
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

    /// The cost of calling `s` with these arguments (`None` for a parenthesised triple), or
    /// `None` if it does not fit.
    pub(super) fn match_sig(
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

    pub(super) fn no_match(
        &self,
        name: &str,
        sigs: Vec<String>,
        args: &[Option<Expr>],
        pos: Pos,
    ) -> Diag {
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

    pub(super) fn user_call(
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

    pub(super) fn user_sig(&self, f: FuncId) -> Signature {
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
