//! `#define`: object- and function-like macros, variadic ones, and the checks on a body's
//! `#` and `##` made once, where the macro is defined.

use crate::error::{DResult, Diag};
use crate::lexer::{P, Tok, Token};

use super::{Preprocessor, got, ident, is_punct};

/// A macro definition.
#[derive(Debug, Clone)]
pub(super) struct Macro {
    /// `None` for object-like macros.
    pub(super) params: Option<Vec<String>>,
    pub(super) variadic: bool,
    pub(super) body: Vec<Token>,
}

impl Preprocessor<'_> {
    pub(super) fn define(&mut self, hash: &Token, args: &[Token]) -> DResult<()> {
        let Some(name) = args.first().and_then(ident) else {
            return Err(Diag::new(
                args.first().map(|t| t.pos).unwrap_or(hash.pos),
                format!("#define: expected a macro name, got {}", got(args, 0)),
            ));
        };
        let name = name.to_string();
        if name == "defined" {
            return Err(Diag::new(args[0].pos, "#define: \"defined\" cannot be a macro name"));
        }
        let mut i = 1;
        let mut params = None;
        let mut variadic = false;
        if args.get(1).is_some_and(|t| is_punct(t, P::LParen) && !t.space_before) {
            let mut ps: Vec<String> = Vec::new();
            i = 2;
            loop {
                let t = args.get(i);
                match t.map(|t| &t.tok) {
                    Some(Tok::Punct(P::RParen)) if ps.is_empty() => {
                        i += 1;
                        break;
                    }
                    Some(Tok::Ident(p)) => {
                        if ps.contains(p) {
                            return Err(Diag::new(
                                args[i].pos,
                                format!("#define {name}: parameter \"{p}\" appears twice"),
                            ));
                        }
                        ps.push(p.clone());
                        i += 1;
                    }
                    Some(Tok::Punct(P::Dot))
                        if args.get(i + 1).is_some_and(|t| is_punct(t, P::Dot))
                            && args.get(i + 2).is_some_and(|t| is_punct(t, P::Dot)) =>
                    {
                        variadic = true;
                        ps.push("__VA_ARGS__".into());
                        i += 3;
                        if !args.get(i).is_some_and(|t| is_punct(t, P::RParen)) {
                            return Err(Diag::new(
                                args.get(i).map(|t| t.pos).unwrap_or(hash.pos),
                                format!(
                                    "#define {name}: expected ')' after '...', got {}",
                                    got(args, i)
                                ),
                            ));
                        }
                    }
                    _ => {
                        return Err(Diag::new(
                            t.map(|t| t.pos).unwrap_or(args[0].pos),
                            format!(
                                "#define {name}: expected a parameter name, got {}",
                                got(args, i)
                            ),
                        ));
                    }
                }
                match args.get(i).map(|t| &t.tok) {
                    Some(Tok::Punct(P::Comma)) if !variadic => i += 1,
                    Some(Tok::Punct(P::RParen)) => {
                        i += 1;
                        break;
                    }
                    _ => {
                        return Err(Diag::new(
                            args.get(i).map(|t| t.pos).unwrap_or(args[0].pos),
                            format!(
                                "#define {name}: expected ',' or ')' in the parameter list, got {}",
                                got(args, i)
                            ),
                        ));
                    }
                }
            }
            params = Some(ps);
        }
        let mut body: Vec<Token> = args[i..].to_vec();
        if let Some(t) = body.first_mut() {
            t.space_before = false;
        }
        for t in &mut body {
            t.line_start = false;
        }
        if let Some(t) = body.first().filter(|t| is_punct(t, P::HashHash)) {
            return Err(Diag::new(
                t.pos,
                format!("#define {name}: '##' cannot begin a macro body"),
            ));
        }
        if let Some(t) = body.last().filter(|t| is_punct(t, P::HashHash)) {
            return Err(Diag::new(t.pos, format!("#define {name}: '##' cannot end a macro body")));
        }
        if let Some(ps) = &params {
            for (k, t) in body.iter().enumerate() {
                if is_punct(t, P::Hash) {
                    let ok =
                        body.get(k + 1).and_then(ident).is_some_and(|n| ps.iter().any(|p| p == n));
                    if !ok {
                        return Err(Diag::new(
                            t.pos,
                            format!("#define {name}: '#' is not followed by a macro parameter"),
                        ));
                    }
                }
            }
        }
        self.macros.insert(name, Macro { params, variadic, body });
        Ok(())
    }
}
