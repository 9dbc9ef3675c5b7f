//! Directives: the dispatch on a directive's name, the conditional groups (`#if`, `#ifdef`,
//! `#ifndef`, `#elif`, `#else`, `#endif`) that switch the output on and off, `#undef`,
//! `#error`, and the directives ignored.

use crate::error::{DResult, Diag, Pos};
use crate::lexer::{Tok, Token};

use super::source::Frame;
use super::{Preprocessor, got, ident, spell};

/// One `#if` group being read.
pub(super) struct Cond {
    /// Tokens of this branch are kept.
    pub(super) active: bool,
    /// Some branch of this group was taken already.
    pub(super) taken: bool,
    /// `#else` was seen.
    pub(super) in_else: bool,
    /// The enclosing group is active.
    pub(super) parent_active: bool,
    /// Where the `#if` is, for "unterminated".
    pub(super) pos: Pos,
    /// Which directive opened it.
    pub(super) name: &'static str,
}

impl Preprocessor<'_> {
    /// One directive: `hash` is its '#', `line` the rest of its line.
    pub(super) fn directive(
        &mut self,
        hash: Token,
        line: Vec<Token>,
        frame: &mut Frame,
        conds: &mut Vec<Cond>,
    ) -> DResult<()> {
        let active = conds.last().is_none_or(|c| c.active);
        let Some(first) = line.first() else {
            return Ok(()); // the null directive
        };
        let name = match &first.tok {
            Tok::Ident(s) => s.clone(),
            _ if !active => return Ok(()),
            Tok::Bad(m) => return Err(Diag::new(first.pos, m.clone())),
            other => {
                return Err(Diag::new(
                    first.pos,
                    format!("expected a directive name after '#', got {}", other.describe()),
                ));
            }
        };
        let args = &line[1..];
        let end = line.last().map(|t| t.pos).unwrap_or(hash.pos);
        match name.as_str() {
            "if" | "ifdef" | "ifndef" => {
                let static_name: &'static str = match name.as_str() {
                    "if" => "if",
                    "ifdef" => "ifdef",
                    _ => "ifndef",
                };
                let value = if !active {
                    false
                } else if name == "if" {
                    self.eval_if(&hash, "#if", args)?
                } else {
                    let n = self.directive_name(&hash, &format!("#{name}"), args)?;
                    self.macros.contains_key(&n) == (name == "ifdef")
                };
                conds.push(Cond {
                    active: active && value,
                    taken: value,
                    in_else: false,
                    parent_active: active,
                    pos: hash.pos,
                    name: static_name,
                });
            }
            "elif" => {
                let Some(c) = conds.last() else {
                    return Err(Diag::new(hash.pos, "#elif without #if"));
                };
                if c.in_else {
                    return Err(Diag::new(hash.pos, "#elif after #else"));
                }
                let (parent, taken) = (c.parent_active, c.taken);
                let value =
                    if parent && !taken { self.eval_if(&hash, "#elif", args)? } else { false };
                let c = conds.last_mut().expect("checked");
                c.active = parent && !taken && value;
                c.taken |= value;
            }
            "else" => {
                let Some(c) = conds.last_mut() else {
                    return Err(Diag::new(hash.pos, "#else without #if"));
                };
                if c.in_else {
                    return Err(Diag::new(hash.pos, "#else after #else"));
                }
                c.in_else = true;
                c.active = c.parent_active && !c.taken;
                c.taken = true;
                if let Some(t) = args.first().filter(|_| c.parent_active) {
                    return Err(Diag::new(
                        t.pos,
                        format!("#else: unexpected {} after #else", t.tok.shown()),
                    ));
                }
            }
            "endif" => {
                let Some(c) = conds.pop() else {
                    return Err(Diag::new(hash.pos, "#endif without #if"));
                };
                if let Some(t) = args.first().filter(|_| c.parent_active) {
                    return Err(Diag::new(
                        t.pos,
                        format!("#endif: unexpected {} after #endif", t.tok.shown()),
                    ));
                }
            }
            _ if !active => {}
            "define" => self.define(&hash, args)?,
            "undef" => {
                let n = self.directive_name(&hash, "#undef", args)?;
                self.macros.remove(&n);
            }
            "include" => self.include(&hash, args, frame)?,
            "line" => self.line(&hash, args, end, frame)?,
            "error" => {
                let text = spell(args);
                return Err(Diag::new(hash.pos, format!("#error {text}").trim_end().to_string()));
            }
            "pragma" | "warning" | "ident" => {}
            other => {
                return Err(Diag::new(first.pos, format!("unknown directive #{other}")));
            }
        }
        Ok(())
    }

    /// The one name a directive takes (`#ifdef X`, `#undef X`).
    pub(super) fn directive_name(
        &self,
        hash: &Token,
        what: &str,
        args: &[Token],
    ) -> DResult<String> {
        let Some(n) = args.first().and_then(ident) else {
            return Err(Diag::new(
                args.first().map(|t| t.pos).unwrap_or(hash.pos),
                format!("{what}: expected a macro name, got {}", got(args, 0)),
            ));
        };
        if let Some(t) = args.get(1) {
            return Err(Diag::new(
                t.pos,
                format!("{what}: unexpected {} after the macro name", t.tok.shown()),
            ));
        }
        Ok(n.to_string())
    }
}
