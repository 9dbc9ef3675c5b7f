//! Macro expansion: C's rescanning rule with hide sets (so recursive macros stop), the
//! arguments of function-like macros (pre-expanded, except next to `#` and `##`), `#`
//! stringizing and `##` pasting, and `__LINE__`/`__FILE__`. Expanded tokens take the position
//! where the macro was used.

use std::collections::{HashMap, VecDeque};

use crate::error::{DResult, Diag, Pos};
use crate::lexer::{P, Tok, Token, lex};

use super::define::Macro;
use super::source::Frame;
use super::{Preprocessor, ident, is_punct, spell};

/// Deepest nesting of macro calls in macro arguments.
const MAX_ARG_DEPTH: usize = 200;
/// Most tokens macro expansion may make for one compilation: some 5 MB of source text, far
/// beyond any real shader's, and at most a few hundred megabytes of tokens while they are
/// made (each carries its hide set).
const MAX_EXPANDED: usize = 1_000_000;

/// A token during expansion, with the macros it may no longer expand (its hide set).
#[derive(Debug, Clone)]
pub(super) struct PTok {
    pub(super) t: Token,
    pub(super) hide: Vec<u32>,
}

impl PTok {
    pub(super) fn plain(t: Token) -> PTok {
        PTok { t, hide: Vec::new() }
    }
}

impl Preprocessor<'_> {
    /// The number that stands for macro `name` in hide sets.
    fn intern_name(&mut self, name: &str) -> u32 {
        if let Some(i) = self.names.iter().position(|n| n == name) {
            return i as u32;
        }
        self.names.push(name.to_string());
        (self.names.len() - 1) as u32
    }

    /// A directive's tokens, macro-expanded.
    pub(super) fn expand_line(&mut self, toks: &[Token]) -> DResult<Vec<Token>> {
        let mut q: VecDeque<PTok> = toks.iter().cloned().map(PTok::plain).collect();
        let mut out = Vec::new();
        self.expand(&mut q, None, &mut out)?;
        Ok(out.into_iter().map(|p| p.t).collect())
    }

    /// Expands macros in `input` (pulling more tokens from `frame` where a function-like
    /// macro's arguments continue) until `input` is empty.
    pub(super) fn expand(
        &mut self,
        input: &mut VecDeque<PTok>,
        mut frame: Option<&mut Frame>,
        out: &mut Vec<PTok>,
    ) -> DResult<()> {
        while let Some(tok) = input.pop_front() {
            let Some(name) = ident(&tok.t) else {
                out.push(tok);
                continue;
            };
            let Some(m) = self.macros.get(name).cloned() else {
                // The predefined macros of C that shaders use in messages.
                let name = name.to_string();
                let mut tok = tok;
                match name.as_str() {
                    "__LINE__" => {
                        let l = tok.t.pos.line;
                        tok.t.tok = Tok::Num(f64::from(l), l.to_string());
                    }
                    "__FILE__" => tok.t.tok = Tok::Str(self.map.name(tok.t.pos.file).to_string()),
                    _ => {}
                }
                out.push(tok);
                continue;
            };
            let name = name.to_string();
            let id = self.intern_name(&name);
            if tok.hide.contains(&id) {
                out.push(tok);
                continue;
            }
            let mut hide = tok.hide.clone();
            hide.push(id);
            let site = tok.t.pos;
            let result = match &m.params {
                None => self.substitute(&name, &m, &[], site, &hide)?,
                Some(_) => {
                    // A function-like macro's name not followed by '(' is an ordinary name.
                    if input.is_empty()
                        && let Some(f) = frame.as_deref_mut()
                        && let Some(t) = f.pull()
                    {
                        input.push_back(t);
                    }
                    if !input.front().is_some_and(|t| is_punct(&t.t, P::LParen)) {
                        out.push(tok);
                        continue;
                    }
                    input.pop_front();
                    let args = self.collect_args(&name, &m, site, input, frame.as_deref_mut())?;
                    self.substitute(&name, &m, &args, site, &hide)?
                }
            };
            self.expanded += result.len();
            if self.expanded > MAX_EXPANDED {
                return Err(too_many(&name, site));
            }
            for t in result.into_iter().rev() {
                input.push_front(t);
            }
        }
        Ok(())
    }

    /// The arguments of a function-like macro, after its '('.
    fn collect_args(
        &mut self,
        name: &str,
        m: &Macro,
        site: Pos,
        input: &mut VecDeque<PTok>,
        mut frame: Option<&mut Frame>,
    ) -> DResult<Vec<Vec<PTok>>> {
        let nparams = m.params.as_ref().map_or(0, Vec::len);
        let mut args: Vec<Vec<PTok>> = vec![Vec::new()];
        let mut depth = 0usize;
        loop {
            let t = match input.pop_front() {
                Some(t) => t,
                None => match frame.as_deref_mut().and_then(Frame::pull) {
                    Some(t) => t,
                    None => {
                        return Err(Diag::new(
                            site,
                            format!("macro \"{name}\": unterminated argument list (no ')')"),
                        ));
                    }
                },
            };
            match &t.t.tok {
                Tok::Punct(P::LParen) => depth += 1,
                Tok::Punct(P::RParen) if depth == 0 => break,
                Tok::Punct(P::RParen) => depth -= 1,
                Tok::Punct(P::Comma) if depth == 0 && !(m.variadic && args.len() == nparams) => {
                    args.push(Vec::new());
                    continue;
                }
                _ => {}
            }
            args.last_mut().expect("one at least").push(t);
        }
        if nparams == 0 && args.len() == 1 && args[0].is_empty() {
            args.clear();
        }
        if m.variadic && args.len() == nparams - 1 {
            args.push(Vec::new());
        }
        if args.len() != nparams {
            let s = |n: usize| if n == 1 { "" } else { "s" };
            return Err(Diag::new(
                site,
                format!(
                    "macro \"{name}\" takes {nparams} argument{}, got {}",
                    s(nparams),
                    args.len()
                ),
            ));
        }
        Ok(args)
    }

    /// The body of `m` with its arguments put in, `#` and `##` applied, positioned at `site`.
    fn substitute(
        &mut self,
        name: &str,
        m: &Macro,
        args: &[Vec<PTok>],
        site: Pos,
        hide: &[u32],
    ) -> DResult<Vec<PTok>> {
        let params: &[String] = m.params.as_deref().unwrap_or(&[]);
        let param_of = |t: &Token| ident(t).and_then(|n| params.iter().position(|p| p == n));
        let body = &m.body;
        let site_tok = |t: &Token| {
            let mut t = t.clone();
            t.pos = site;
            t.line_start = false;
            t
        };
        // First pass: a list of pieces, where '##' joins neighbours.
        let mut out: Vec<PTok> = Vec::new();
        let mut k = 0;
        let mut paste_next = false;
        let mut expanded_cache: HashMap<usize, Vec<PTok>> = HashMap::new();
        while k < body.len() {
            let t = &body[k];
            let mut piece: Vec<PTok>;
            if is_punct(t, P::Hash) && m.params.is_some() {
                let p = param_of(&body[k + 1]).expect("checked at #define");
                let text = stringize(&args[p]);
                let mut s = site_tok(t);
                s.tok = Tok::Str(text);
                piece = vec![PTok::plain(s)];
                k += 2;
            } else if let Some(p) = param_of(t) {
                let next_is_paste = body.get(k + 1).is_some_and(|t| is_punct(t, P::HashHash));
                if paste_next || next_is_paste {
                    piece = args[p].clone();
                } else {
                    let e = match expanded_cache.get(&p) {
                        Some(e) => e.clone(),
                        None => {
                            if self.arg_depth >= MAX_ARG_DEPTH {
                                return Err(Diag::new(
                                    site,
                                    format!(
                                        "macro \"{name}\": arguments nested more than {MAX_ARG_DEPTH} deep"
                                    ),
                                ));
                            }
                            let mut q: VecDeque<PTok> = args[p].iter().cloned().collect();
                            let mut e = Vec::new();
                            self.arg_depth += 1;
                            let r = self.expand(&mut q, None, &mut e);
                            self.arg_depth -= 1;
                            r?;
                            expanded_cache.insert(p, e.clone());
                            e
                        }
                    };
                    piece = e;
                }
                if let Some(first) = piece.first_mut() {
                    first.t.space_before = t.space_before;
                }
                k += 1;
            } else if is_punct(t, P::HashHash) {
                paste_next = true;
                k += 1;
                continue;
            } else {
                piece = vec![PTok::plain(site_tok(t))];
                k += 1;
            }
            if paste_next {
                paste_next = false;
                if let (Some(left), Some(right)) = (out.last(), piece.first()) {
                    let text = format!("{}{}", left.t.tok.spelling(), right.t.tok.spelling());
                    let lexed = lex(text.as_bytes(), site.file);
                    let ok = lexed.len() == 1 && !matches!(lexed[0].tok, Tok::Bad(_));
                    if !ok {
                        return Err(Diag::new(
                            site,
                            format!(
                                "macro \"{name}\": '##' pasting {} and {} does not give one token",
                                quote_spelling(&left.t.tok),
                                quote_spelling(&right.t.tok)
                            ),
                        ));
                    }
                    let mut joined = left.clone();
                    joined.t.tok = lexed[0].tok.clone();
                    joined.t.pos = site;
                    *out.last_mut().expect("checked") = joined;
                    piece.remove(0);
                }
            }
            // The budget holds while the body is built, not only after: a macro whose
            // parameter appears k times, nested n deep in its own arguments, makes k^n
            // copies, and the last level alone can be many gigabytes.
            if self.expanded + out.len() + piece.len() > MAX_EXPANDED {
                return Err(too_many(name, site));
            }
            out.extend(piece);
        }
        for t in &mut out {
            for h in hide {
                if !t.hide.contains(h) {
                    t.hide.push(*h);
                }
            }
        }
        Ok(out)
    }
}

/// The error of an expansion over [`MAX_EXPANDED`] tokens.
fn too_many(name: &str, site: Pos) -> Diag {
    Diag::new(site, format!("macro \"{name}\": expansion makes more than {MAX_EXPANDED} tokens"))
}

fn quote_spelling(t: &Tok) -> String {
    format!("\"{}\"", t.spelling().replace('"', "\\\""))
}

/// `#param`: the argument's spelling as a string's value.
fn stringize(arg: &[PTok]) -> String {
    let toks: Vec<Token> = arg.iter().map(|p| p.t.clone()).collect();
    spell(&toks)
}
