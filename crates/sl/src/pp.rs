//! The C preprocessor: `#include`, `#define` (object- and function-like, `#`, `##`, variadic),
//! `#undef`, the conditional family with integer expressions and `defined`, `#line`, `#error`;
//! `#pragma` and `#warning` are ignored.
//!
//! It works on tokens of the RSL lexer, so its output is the parser's input. Every output token
//! keeps a position in a file the user wrote: a token written in a file keeps its own; a token
//! out of a macro body (or made by `#` or `##`) takes the position where the macro was used.
//! Macro expansion follows C's rescanning rule with hide sets, so recursive macros stop.
//!
//! This module reads files and hands out tokens; its parts:
//! - `source`: the tokens of one file and the `#line` state that positions them;
//! - `directive`: the directives and the conditional groups;
//! - `if_expr`: the expression of `#if` and `#elif`;
//! - `define`: macro definitions; `expand`: macro expansion;
//! - `include`: `#include` and where it looks.

use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};

use crate::error::{DResult, Diag, Pos, SourceMap};
use crate::lexer::{P, Tok, Token, lex};

use define::Macro;
use directive::Cond;
use expand::PTok;
use source::Frame;

/// Where the text to preprocess comes from.
pub(crate) enum Input<'a> {
    /// A file on disk.
    File(&'a Path),
    /// Text in memory with its display name (quoted includes then search the include paths).
    Text { name: &'a str, text: &'a str },
}

/// The preprocessor's state across the files of one compilation.
pub(crate) struct Preprocessor<'m> {
    map: &'m mut SourceMap,
    include_paths: Vec<PathBuf>,
    macros: HashMap<String, Macro>,
    names: Vec<String>,
    out: Vec<Token>,
    depth: usize,
    expanded: usize,
    /// Nesting of argument pre-expansion (F(F(F(...)))).
    arg_depth: usize,
}

/// Preprocesses `input`: the whole token stream, or the first error.
pub(crate) fn preprocess(
    input: Input<'_>,
    include_paths: &[PathBuf],
    defines: &[(String, String)],
    map: &mut SourceMap,
) -> DResult<Vec<Token>> {
    let mut pp = Preprocessor {
        map,
        include_paths: include_paths.to_vec(),
        macros: HashMap::new(),
        names: Vec::new(),
        out: Vec::new(),
        depth: 0,
        expanded: 0,
        arg_depth: 0,
    };
    let cmdline = pp.map.intern("<command line>");
    for (name, value) in defines {
        let body = lex(value.as_bytes(), cmdline)
            .into_iter()
            .map(|mut t| {
                t.line_start = false;
                t
            })
            .collect();
        pp.macros.insert(name.clone(), Macro { params: None, variadic: false, body });
    }
    match input {
        Input::File(path) => {
            let name = path.display().to_string();
            let id = pp.map.intern(&name);
            let text = std::fs::read(path).map_err(|e| Diag {
                pos: Pos { file: id, line: 0, col: 0 },
                message: format!("cannot read the shader: {e}"),
                io: true,
            })?;
            let dir = path.parent().map(Path::to_path_buf);
            pp.run_file(id, &text, dir)?;
        }
        Input::Text { name, text } => {
            let id = pp.map.intern(name);
            pp.run_file(id, text.as_bytes(), None)?;
        }
    }
    Ok(pp.out)
}

fn ident(t: &Token) -> Option<&str> {
    match &t.tok {
        Tok::Ident(s) => Some(s),
        _ => None,
    }
}

fn is_punct(t: &Token, p: P) -> bool {
    t.tok == Tok::Punct(p)
}

/// What a directive's line holds after its name, for messages.
fn got(toks: &[Token], i: usize) -> String {
    match toks.get(i) {
        Some(t) => t.tok.describe(),
        None => "the end of the line".into(),
    }
}

impl Preprocessor<'_> {
    /// Reads one file to the output.
    fn run_file(&mut self, id: u32, text: &[u8], dir: Option<PathBuf>) -> DResult<()> {
        let toks = lex(text, id);
        let mut frame = Frame { toks, i: 0, line_delta: 0, file_override: None, dir };
        let mut conds: Vec<Cond> = Vec::new();
        let mut queue: VecDeque<PTok> = VecDeque::new();
        while let Some(t) = frame.toks.get(frame.i) {
            if t.line_start && t.tok == Tok::Punct(P::Hash) {
                let hash = frame.adjust(t.clone());
                frame.i += 1;
                let line = frame.rest_of_line();
                self.directive(hash, line, &mut frame, &mut conds)?;
                continue;
            }
            let active = conds.last().is_none_or(|c| c.active);
            if !active {
                frame.i += 1;
                continue;
            }
            let t = frame.pull().expect("not a directive");
            queue.push_back(t);
            let mut out = Vec::new();
            self.expand(&mut queue, Some(&mut frame), &mut out)?;
            for p in out {
                self.emit(p.t)?;
            }
        }
        if let Some(c) = conds.last() {
            return Err(Diag::new(c.pos, format!("#{} without #endif", c.name)));
        }
        Ok(())
    }

    fn emit(&mut self, t: Token) -> DResult<()> {
        if let Tok::Bad(m) = &t.tok {
            return Err(Diag::new(t.pos, m.clone()));
        }
        self.out.push(t);
        Ok(())
    }
}

/// The text of tokens as written, one space where there was whitespace.
fn spell(toks: &[Token]) -> String {
    let mut s = String::new();
    for (k, t) in toks.iter().enumerate() {
        if k > 0 && t.space_before {
            s.push(' ');
        }
        s.push_str(&t.tok.spelling());
    }
    s
}

mod define;
mod directive;
mod expand;
mod if_expr;
mod include;
mod source;
