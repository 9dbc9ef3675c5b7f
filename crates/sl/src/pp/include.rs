//! `#include`: the file name (quoted, `<...>`, or from macros), where it is searched (the
//! including file's folder first for a quoted name, then the include paths), and the nesting
//! limit.

use std::path::{Path, PathBuf};

use crate::error::{DResult, Diag};
use crate::lexer::{P, Tok, Token};

use super::source::Frame;
use super::{Preprocessor, got, is_punct};

/// Deepest `#include` nesting (a file including itself is stopped here).
const MAX_INCLUDE_DEPTH: usize = 64;

impl Preprocessor<'_> {
    pub(super) fn include(
        &mut self,
        hash: &Token,
        args: &[Token],
        frame: &mut Frame,
    ) -> DResult<()> {
        let toks = if matches!(args.first().map(|t| &t.tok), Some(Tok::Str(_) | Tok::Punct(P::Lt)))
        {
            args.to_vec()
        } else {
            self.expand_line(args)?
        };
        let (name, quoted, after) = match toks.first().map(|t| &t.tok) {
            Some(Tok::Str(s)) => (s.clone(), true, 1),
            Some(Tok::Punct(P::Lt)) => {
                let mut s = String::new();
                let mut k = 1;
                loop {
                    match toks.get(k) {
                        None => {
                            return Err(Diag::new(
                                toks[0].pos,
                                "#include: '<' without '>' around the file name",
                            ));
                        }
                        Some(t) if is_punct(t, P::Gt) => break,
                        Some(t) => {
                            if t.space_before && k > 1 {
                                s.push(' ');
                            }
                            s.push_str(&t.tok.spelling());
                        }
                    }
                    k += 1;
                }
                (s, false, k + 1)
            }
            _ => {
                return Err(Diag::new(
                    toks.first().map(|t| t.pos).unwrap_or(hash.pos),
                    format!(
                        "#include: expected a file name (\"file\" or <file>), got {}",
                        got(&toks, 0)
                    ),
                ));
            }
        };
        if let Some(t) = toks.get(after) {
            return Err(Diag::new(
                t.pos,
                format!("#include: unexpected {} after the file name", t.tok.shown()),
            ));
        }
        let shown = if quoted { format!("\"{name}\"") } else { format!("<{name}>") };
        if name.is_empty() {
            return Err(Diag::new(hash.pos, format!("#include {shown}: empty file name")));
        }
        if self.depth >= MAX_INCLUDE_DEPTH {
            return Err(Diag::new(
                hash.pos,
                format!(
                    "#include {shown}: includes nested more than {MAX_INCLUDE_DEPTH} deep (does a file include itself?)"
                ),
            ));
        }
        let mut dirs: Vec<PathBuf> = Vec::new();
        if quoted && let Some(d) = &frame.dir {
            dirs.push(d.clone());
        }
        dirs.extend(self.include_paths.iter().cloned());
        let given = Path::new(&name);
        let found = if given.is_absolute() {
            given.is_file().then(|| given.to_path_buf())
        } else {
            dirs.iter().map(|d| d.join(given)).find(|p| p.is_file())
        };
        let Some(path) = found else {
            let searched = if given.is_absolute() {
                String::new()
            } else if dirs.is_empty() {
                " (no include path given)".to_string()
            } else {
                format!(
                    " (searched {})",
                    dirs.iter().map(|d| d.display().to_string()).collect::<Vec<_>>().join(", ")
                )
            };
            return Err(Diag::new(hash.pos, format!("#include {shown}: file not found{searched}")));
        };
        let text = std::fs::read(&path).map_err(|e| Diag {
            pos: hash.pos,
            message: format!("#include {shown}: cannot read {}: {e}", path.display()),
            io: true,
        })?;
        let id = self.map.intern(&path.display().to_string());
        self.depth += 1;
        let r = self.run_file(id, &text, path.parent().map(Path::to_path_buf));
        self.depth -= 1;
        r
    }
}
