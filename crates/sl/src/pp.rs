//! The C preprocessor: `#include`, `#define` (object- and function-like, `#`, `##`, variadic),
//! `#undef`, the conditional family with integer expressions and `defined`, `#line`, `#error`;
//! `#pragma` and `#warning` are ignored.
//!
//! It works on tokens of the RSL lexer, so its output is the parser's input. Every output token
//! keeps a position in a file the user wrote: a token written in a file keeps its own; a token
//! out of a macro body (or made by `#` or `##`) takes the position where the macro was used.
//! Macro expansion follows C's rescanning rule with hide sets, so recursive macros stop.

use std::collections::{HashMap, VecDeque};
use std::path::{Path, PathBuf};

use crate::error::{DResult, Diag, Pos, SourceMap};
use crate::lexer::{P, Tok, Token, lex};

/// Deepest `#include` nesting (a file including itself is stopped here).
const MAX_INCLUDE_DEPTH: usize = 64;
/// Deepest nesting of macro calls in macro arguments.
const MAX_ARG_DEPTH: usize = 200;
/// Most tokens macro expansion may make for one compilation.
const MAX_EXPANDED: usize = 4_000_000;

/// Where the text to preprocess comes from.
pub(crate) enum Input<'a> {
    /// A file on disk.
    File(&'a Path),
    /// Text in memory with its display name (quoted includes then search the include paths).
    Text { name: &'a str, text: &'a str },
}

/// A macro definition.
#[derive(Debug, Clone)]
struct Macro {
    /// `None` for object-like macros.
    params: Option<Vec<String>>,
    variadic: bool,
    body: Vec<Token>,
}

/// A token during expansion, with the macros it may no longer expand (its hide set).
#[derive(Debug, Clone)]
struct PTok {
    t: Token,
    hide: Vec<u32>,
}

impl PTok {
    fn plain(t: Token) -> PTok {
        PTok { t, hide: Vec::new() }
    }
}

/// One `#if` group being read.
struct Cond {
    /// Tokens of this branch are kept.
    active: bool,
    /// Some branch of this group was taken already.
    taken: bool,
    /// `#else` was seen.
    in_else: bool,
    /// The enclosing group is active.
    parent_active: bool,
    /// Where the `#if` is, for "unterminated".
    pos: Pos,
    /// Which directive opened it.
    name: &'static str,
}

/// The tokens of one file being read, and its `#line` state.
struct Frame {
    toks: Vec<Token>,
    i: usize,
    line_delta: i64,
    file_override: Option<u32>,
    dir: Option<PathBuf>,
}

impl Frame {
    fn adjust(&self, mut t: Token) -> Token {
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
    fn pull(&mut self) -> Option<PTok> {
        let t = self.toks.get(self.i)?;
        if t.line_start && t.tok == Tok::Punct(P::Hash) {
            return None;
        }
        self.i += 1;
        let t = t.clone();
        Some(PTok::plain(self.adjust(t)))
    }

    /// The rest of the current logical line.
    fn rest_of_line(&mut self) -> Vec<Token> {
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
    fn intern_name(&mut self, name: &str) -> u32 {
        if let Some(i) = self.names.iter().position(|n| n == name) {
            return i as u32;
        }
        self.names.push(name.to_string());
        (self.names.len() - 1) as u32
    }

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

    fn directive(
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
            "line" => {
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
                            format!(
                                "#line: expected a file name (a string), got {}",
                                got(&toks, 1)
                            ),
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
            }
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
    fn directive_name(&self, hash: &Token, what: &str, args: &[Token]) -> DResult<String> {
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

    fn define(&mut self, hash: &Token, args: &[Token]) -> DResult<()> {
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

    fn include(&mut self, hash: &Token, args: &[Token], frame: &mut Frame) -> DResult<()> {
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

    /// A directive's tokens, macro-expanded.
    fn expand_line(&mut self, toks: &[Token]) -> DResult<Vec<Token>> {
        let mut q: VecDeque<PTok> = toks.iter().cloned().map(PTok::plain).collect();
        let mut out = Vec::new();
        self.expand(&mut q, None, &mut out)?;
        Ok(out.into_iter().map(|p| p.t).collect())
    }

    /// Expands macros in `input` (pulling more tokens from `frame` where a function-like
    /// macro's arguments continue) until `input` is empty.
    fn expand(
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
                return Err(Diag::new(
                    site,
                    format!("macro \"{name}\": expansion makes more than {MAX_EXPANDED} tokens"),
                ));
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

    /// Evaluates a `#if`/`#elif` line.
    fn eval_if(&mut self, hash: &Token, what: &str, args: &[Token]) -> DResult<bool> {
        // `defined X` and `defined(X)` are replaced before expansion.
        let mut toks: Vec<Token> = Vec::new();
        let mut k = 0;
        while k < args.len() {
            let t = &args[k];
            if ident(t) == Some("defined") {
                let (n, used) = match (args.get(k + 1), args.get(k + 2), args.get(k + 3)) {
                    (Some(a), Some(b), Some(c))
                        if is_punct(a, P::LParen)
                            && ident(b).is_some()
                            && is_punct(c, P::RParen) =>
                    {
                        (ident(b).expect("checked"), 4)
                    }
                    (Some(a), _, _) if ident(a).is_some() => (ident(a).expect("checked"), 2),
                    _ => {
                        return Err(Diag::new(
                            t.pos,
                            format!(
                                "{what}: \"defined\" takes a macro name: defined NAME or defined(NAME)"
                            ),
                        ));
                    }
                };
                let mut v = t.clone();
                let yes = self.macros.contains_key(n);
                v.tok = Tok::Num(if yes { 1.0 } else { 0.0 }, if yes { "1" } else { "0" }.into());
                toks.push(v);
                k += used;
                continue;
            }
            toks.push(t.clone());
            k += 1;
        }
        let toks = self.expand_line(&toks)?;
        if toks.is_empty() {
            return Err(Diag::new(hash.pos, format!("{what}: expected an expression")));
        }
        let mut e = IfExpr { toks: &toks, i: 0, what, end: hash.pos, eval: true };
        let v = e.ternary()?;
        if let Some(t) = toks.get(e.i) {
            return Err(Diag::new(
                t.pos,
                format!("{what}: unexpected {} after the expression", t.tok.shown()),
            ));
        }
        Ok(v != 0)
    }
}

fn quote_spelling(t: &Tok) -> String {
    format!("\"{}\"", t.spelling().replace('"', "\\\""))
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

/// `#param`: the argument's spelling as a string's value.
fn stringize(arg: &[PTok]) -> String {
    let toks: Vec<Token> = arg.iter().map(|p| p.t.clone()).collect();
    spell(&toks)
}

/// The integer expression of `#if` (C's operators on 64-bit integers).
struct IfExpr<'a> {
    toks: &'a [Token],
    i: usize,
    what: &'a str,
    end: Pos,
    /// False in the operand `&&`, `||` or `?:` skip: parsed, not evaluated (no division error).
    eval: bool,
}

impl IfExpr<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.i).map(|t| &t.tok)
    }

    fn pos(&self) -> Pos {
        self.toks.get(self.i).map(|t| t.pos).or(self.toks.last().map(|t| t.pos)).unwrap_or(self.end)
    }

    fn eat(&mut self, p: P) -> bool {
        if self.peek() == Some(&Tok::Punct(p)) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn ternary(&mut self) -> DResult<i64> {
        let c = self.binary(0)?;
        if self.eat(P::Question) {
            let outer = self.eval;
            self.eval = outer && c != 0;
            let a = self.ternary();
            self.eval = outer;
            let a = a?;
            if !self.eat(P::Colon) {
                return Err(Diag::new(
                    self.pos(),
                    format!("{}: expected ':' of '?:', got {}", self.what, got(self.toks, self.i)),
                ));
            }
            self.eval = outer && c == 0;
            let b = self.ternary();
            self.eval = outer;
            return Ok(if c != 0 { a } else { b? });
        }
        Ok(c)
    }

    fn binary(&mut self, min: u8) -> DResult<i64> {
        let mut lhs = self.unary()?;
        while let Some(Tok::Punct(p)) = self.peek() {
            let p = *p;
            let prec = match p {
                P::OrOr => 1,
                P::AndAnd => 2,
                P::Pipe => 3,
                P::Caret => 4,
                P::Amp => 5,
                P::Eq | P::Ne => 6,
                P::Lt | P::Le | P::Gt | P::Ge => 7,
                P::Shl | P::Shr => 8,
                P::Plus | P::Minus => 9,
                P::Star | P::Slash | P::Percent => 10,
                _ => break,
            };
            if prec <= min {
                break;
            }
            let at = self.pos();
            self.i += 1;
            let outer = self.eval;
            match p {
                P::AndAnd => self.eval = outer && lhs != 0,
                P::OrOr => self.eval = outer && lhs == 0,
                _ => {}
            }
            let rhs = self.binary(prec);
            self.eval = outer;
            let rhs = rhs?;
            lhs = match p {
                P::OrOr => i64::from(lhs != 0 || rhs != 0),
                P::AndAnd => i64::from(lhs != 0 && rhs != 0),
                P::Pipe => lhs | rhs,
                P::Caret => lhs ^ rhs,
                P::Amp => lhs & rhs,
                P::Eq => i64::from(lhs == rhs),
                P::Ne => i64::from(lhs != rhs),
                P::Lt => i64::from(lhs < rhs),
                P::Le => i64::from(lhs <= rhs),
                P::Gt => i64::from(lhs > rhs),
                P::Ge => i64::from(lhs >= rhs),
                P::Shl => lhs.wrapping_shl(rhs as u32),
                P::Shr => lhs.wrapping_shr(rhs as u32),
                P::Plus => lhs.wrapping_add(rhs),
                P::Minus => lhs.wrapping_sub(rhs),
                P::Star => lhs.wrapping_mul(rhs),
                P::Slash | P::Percent => {
                    if rhs == 0 && self.eval {
                        return Err(Diag::new(at, format!("{}: division by zero", self.what)));
                    }
                    if rhs == 0 {
                        0
                    } else if p == P::Slash {
                        lhs.wrapping_div(rhs)
                    } else {
                        lhs.wrapping_rem(rhs)
                    }
                }
                _ => unreachable!("filtered above"),
            };
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> DResult<i64> {
        let at = self.pos();
        let Some(t) = self.peek().cloned() else {
            return Err(Diag::new(
                at,
                format!("{}: expected a value, got the end of the line", self.what),
            ));
        };
        self.i += 1;
        match t {
            Tok::Punct(P::Minus) => Ok(self.unary()?.wrapping_neg()),
            Tok::Punct(P::Plus) => self.unary(),
            Tok::Punct(P::Not) => Ok(i64::from(self.unary()? == 0)),
            Tok::Punct(P::Tilde) => Ok(!self.unary()?),
            Tok::Punct(P::LParen) => {
                let v = self.ternary()?;
                if !self.eat(P::RParen) {
                    return Err(Diag::new(
                        self.pos(),
                        format!("{}: expected ')', got {}", self.what, got(self.toks, self.i)),
                    ));
                }
                Ok(v)
            }
            Tok::Num(v, text) => {
                if v.fract() != 0.0 || text.contains(['.', 'e', 'E']) {
                    return Err(Diag::new(
                        at,
                        format!(
                            "{}: {text} is not an integer (#if takes integers only)",
                            self.what
                        ),
                    ));
                }
                Ok(v as i64)
            }
            // A name left after expansion is 0, as in C.
            Tok::Ident(_) => Ok(0),
            Tok::Bad(m) => Err(Diag::new(at, m)),
            other => Err(Diag::new(
                at,
                format!("{}: expected a value, got {}", self.what, other.describe()),
            )),
        }
    }
}
