//! Source positions: the tokens of one file being read, with the `#line` state that renumbers
//! them (the line offset and the file name every token it hands out then carries).

use std::path::PathBuf;

use crate::error::{DResult, Diag, Pos};
use crate::lexer::{P, Tok, Token};

use super::expand::PTok;
use super::{Preprocessor, got};

/// The tokens of one file being read, and its `#line` state.
pub(super) struct Frame {
    pub(super) toks: Vec<Token>,
    pub(super) i: usize,
    pub(super) line_delta: i64,
    pub(super) file_override: Option<u32>,
    pub(super) dir: Option<PathBuf>,
}

impl Frame {
    /// `t` as `#line` has renumbered it.
    pub(super) fn adjust(&self, mut t: Token) -> Token {
        if self.line_delta != 0 {
            t.pos.line =
                (i64::from(t.pos.line) + self.line_delta).clamp(1, i64::from(u32::MAX)) as u32;
        }
        if let Some(f) = self.file_override {
            t.pos.file = f;
        }
        t
    }

    /// The next token if it is not the `#` of a directive.
    pub(super) fn pull(&mut self) -> Option<PTok> {
        let t = self.toks.get(self.i)?;
        if t.line_start && t.tok == Tok::Punct(P::Hash) {
            return None;
        }
        self.i += 1;
        let t = t.clone();
        Some(PTok::plain(self.adjust(t)))
    }

    /// The rest of the current logical line.
    pub(super) fn rest_of_line(&mut self) -> Vec<Token> {
        let mut out = Vec::new();
        while let Some(t) = self.toks.get(self.i) {
            if t.line_start {
                break;
            }
            self.i += 1;
            let t = t.clone();
            out.push(self.adjust(t));
        }
        out
    }
}

impl Preprocessor<'_> {
    /// `#line N ["file"]` (its tokens macro-expanded): the physical line after the directive,
    /// whose last token is at `end`, gets number N, and the frame's tokens the file name.
    pub(super) fn line(
        &mut self,
        hash: &Token,
        args: &[Token],
        end: Pos,
        frame: &mut Frame,
    ) -> DResult<()> {
        let toks = self.expand_line(args)?;
        let Some(Tok::Num(n, text)) = toks.first().map(|t| &t.tok) else {
            return Err(Diag::new(
                toks.first().map(|t| t.pos).unwrap_or(hash.pos),
                format!("#line: expected a line number, got {}", got(&toks, 0)),
            ));
        };
        if n.fract() != 0.0 || *n < 1.0 || *n > 2_147_483_647.0 || text.contains('.') {
            return Err(Diag::new(
                toks[0].pos,
                format!("#line: line number {text} is not a positive integer"),
            ));
        }
        let n = *n as i64;
        match toks.get(1).map(|t| &t.tok) {
            None => {}
            Some(Tok::Str(f)) => {
                let f = f.clone();
                frame.file_override = Some(self.map.intern(&f));
            }
            Some(_) => {
                return Err(Diag::new(
                    toks[1].pos,
                    format!("#line: expected a file name (a string), got {}", got(&toks, 1)),
                ));
            }
        }
        if let Some(t) = toks.get(2) {
            return Err(Diag::new(
                t.pos,
                format!("#line: unexpected {} after the file name", t.tok.shown()),
            ));
        }
        // The physical line after the directive gets number n.
        let last_phys = i64::from(end.line) - frame.line_delta;
        frame.line_delta = n - (last_phys + 1);
        Ok(())
    }
}
