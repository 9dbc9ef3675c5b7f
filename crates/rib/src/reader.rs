//! Request stage: tokens to [`Request`]s, checked against the signature table and the
//! declarations, over a stack of open sources (`ReadArchive`).
//!
//! Invariants: the reader holds at most one token of look-ahead per open source, never a
//! request's tokens beyond the request being built, so memory is the current request plus one
//! read buffer per source. Every call of [`Reader::next_request`] consumes input or finishes a
//! source, so iterating to the end terminates on any input. A request never spans sources: the
//! end of an archive ends any request in it.

use std::fs;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::decl::{self, Class, Decl, Declarations, Storage};
use crate::error::{Location, Pos, RibError, Warning, quote};
use crate::lexer::{AnyArray, ArrayError, LexError, Lexer, Num, Tok, not_an_int};
use crate::request::{Data, Param, Request, Value};
use crate::signature::{Arg, ArgKind, RequestKind};
use crate::source::Source;

/// How a [`Reader`] behaves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReaderOptions {
    /// Follow `ReadArchive` inside the reader (the request is then not returned). Off by
    /// default: the state machine calls [`Reader::read_archive`] when it meets the request.
    pub follow_archives: bool,
    /// Collect `##` structural comments for [`Reader::take_structure_comments`]; off by default
    /// (they are skipped like other comments).
    pub keep_structure_comments: bool,
    /// Deepest nesting of archives accepted (the root source counts 1).
    pub max_depth: usize,
}

impl Default for ReaderOptions {
    fn default() -> Self {
        ReaderOptions { follow_archives: false, keep_structure_comments: false, max_depth: 64 }
    }
}

/// One open source on the include stack.
struct Frame {
    lexer: Option<Lexer>,
    name: Arc<str>,
    path: Option<PathBuf>,
    canonical: Option<PathBuf>,
    peeked: Option<(Pos, Tok)>,
    /// Skipping to the next request name after an error or an unknown request.
    resync: bool,
    /// The source is finished (end of input, or a fatal error was reported).
    done: bool,
    /// An error to report before reading (the source could not be opened).
    pending: Option<RibError>,
}

impl Frame {
    fn new(source: Source, keep_structure: bool) -> Frame {
        let name = source.name.clone();
        let path = source.path.clone();
        let canonical = path.as_ref().and_then(|p| fs::canonicalize(p).ok());
        let (lexer, pending) = match source.into_plain_reader() {
            Ok(read) => (Some(Lexer::new(read, keep_structure)), None),
            Err(e) => (None, Some(RibError::Io { file: name.clone(), source: e })),
        };
        Frame { lexer, name, path, canonical, peeked: None, resync: false, done: false, pending }
    }

    fn loc(&self, pos: Pos) -> Location {
        Location { file: self.name.clone(), pos }
    }

    /// The next token (the peeked one first).
    fn next(&mut self) -> Result<(Pos, Tok), LexError> {
        if let Some(t) = self.peeked.take() {
            return Ok(t);
        }
        match self.lexer.as_mut() {
            Some(l) => l.next(),
            None => Ok((Pos::default(), Tok::Eof)),
        }
    }

    /// The next token without consuming it.
    fn peek(&mut self) -> Result<&(Pos, Tok), LexError> {
        if self.peeked.is_none() {
            let t = self.next()?;
            self.peeked = Some(t);
        }
        Ok(self.peeked.get_or_insert((Pos::default(), Tok::Eof)))
    }

    fn lexer(&mut self) -> Result<&mut Lexer, LexError> {
        self.lexer.as_mut().ok_or_else(|| LexError::Syntax(Pos::default(), "no input".into()))
    }
}

/// Reads RIB requests one at a time from a source and the archives it includes.
///
/// ```
/// use reyes_rib::{Reader, Source, RequestKind};
/// let mut r = Reader::new(Source::from_bytes("mem.rib", "Sphere 1 -1 1 360 \"Kd\" 0.5"));
/// let sphere = r.next_request().unwrap().unwrap();
/// assert_eq!(sphere.kind, RequestKind::Sphere);
/// assert_eq!(sphere.float(3), Some(360.0));
/// assert_eq!(sphere.param("Kd").unwrap().floats(), Some(&[0.5][..]));
/// assert!(r.next_request().unwrap().is_none());
/// ```
pub struct Reader {
    frames: Vec<Frame>,
    decls: Declarations,
    warnings: Vec<Warning>,
    structure: Vec<(Location, String)>,
    color_samples: usize,
    saved_color_samples: Vec<usize>,
    options: ReaderOptions,
}

impl Reader {
    /// A reader over `source` with the default options. An unreadable source is reported by
    /// the first [`Reader::next_request`].
    pub fn new(source: Source) -> Reader {
        Reader::with_options(source, ReaderOptions::default())
    }

    /// A reader with options.
    pub fn with_options(source: Source, options: ReaderOptions) -> Reader {
        Reader {
            frames: vec![Frame::new(source, options.keep_structure_comments)],
            decls: Declarations::standard(),
            warnings: Vec::new(),
            structure: Vec::new(),
            color_samples: 3,
            saved_color_samples: Vec::new(),
            options,
        }
    }

    /// Opens a file (`-` for standard input) with the default options.
    pub fn open(path: impl AsRef<Path>) -> Result<Reader, RibError> {
        let path = path.as_ref();
        Source::open(path)
            .map(Reader::new)
            .map_err(|source| RibError::Io { file: Arc::from(path.display().to_string()), source })
    }

    /// The next request, `Ok(None)` at the end of the root source.
    ///
    /// Unknown requests are skipped with a warning. After a recoverable error (see
    /// [`RibError::is_recoverable`]) the next call goes on at the next request name.
    pub fn next_request(&mut self) -> Result<Option<Request>, RibError> {
        let result = self.next_inner();
        self.drain();
        result
    }

    fn next_inner(&mut self) -> Result<Option<Request>, RibError> {
        loop {
            let Some(frame) = self.frames.last_mut() else { return Ok(None) };
            if let Some(e) = frame.pending.take() {
                frame.done = true;
                return Err(e);
            }
            if frame.done {
                self.drain();
                self.frames.pop();
                continue;
            }
            let (pos, tok) = match frame.next() {
                Ok(t) => t,
                Err(e) => {
                    frame.resync = true;
                    return Err(lex_error(frame, e));
                }
            };
            match tok {
                Tok::Eof => frame.done = true,
                Tok::Request(kind) => {
                    frame.resync = false;
                    let mut parser = Parser {
                        frame,
                        decls: &self.decls,
                        color_samples: self.color_samples,
                        warnings: &mut self.warnings,
                        kind,
                        at: pos,
                        context: Context::None,
                        param_name: String::new(),
                        param_decl: None,
                    };
                    let request = match parser.request() {
                        Ok(r) => r,
                        Err(e) => {
                            if let Some(f) = self.frames.last_mut() {
                                f.resync = true;
                            }
                            return Err(e);
                        }
                    };
                    self.apply(&request)?;
                    if request.kind == RequestKind::ReadArchive && self.options.follow_archives {
                        self.read_archive(&request)?;
                        continue;
                    }
                    return Ok(Some(request));
                }
                Tok::Unknown(name) => {
                    frame.resync = true;
                    let at = frame.loc(pos);
                    self.warnings.push(Warning {
                        at,
                        message: format!("unknown request {} skipped", quote(&name)),
                    });
                }
                other => {
                    if !frame.resync {
                        frame.resync = true;
                        return Err(RibError::Syntax {
                            at: frame.loc(pos),
                            message: format!("expected a request name, got {}", other.describe()),
                        });
                    }
                }
            }
        }
    }

    /// Effects the reader itself needs: declarations, the colour size, its frame scoping.
    fn apply(&mut self, r: &Request) -> Result<(), RibError> {
        let err =
            |message: String| RibError::Request { at: r.at.clone(), request: r.name(), message };
        match r.kind {
            RequestKind::Declare => {
                let (Some(name), Some(text)) = (r.string(0), r.string(1)) else { return Ok(()) };
                if name.is_empty() || name.contains(|c: char| c.is_ascii_whitespace()) {
                    return Err(err(format!("bad name {}: one word expected", quote(name))));
                }
                match Decl::parse(text) {
                    Ok(d) => self.decls.declare(name, d),
                    Err(m) => {
                        return Err(err(format!(
                            "bad declaration {} for {}: {m}",
                            quote(text),
                            quote(name)
                        )));
                    }
                }
            }
            RequestKind::ColorSamples => {
                let (Some(a), Some(b)) = (r.floats(0), r.floats(1)) else { return Ok(()) };
                if a.is_empty() || a.len() % 3 != 0 || a.len() != b.len() {
                    return Err(err(format!(
                        "nRGB and RGBn must both hold 3*N numbers (N >= 1), got {} and {}",
                        a.len(),
                        b.len()
                    )));
                }
                self.color_samples = a.len() / 3;
            }
            RequestKind::FrameBegin => self.saved_color_samples.push(self.color_samples),
            RequestKind::FrameEnd => {
                if let Some(n) = self.saved_color_samples.pop() {
                    self.color_samples = n;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// Moves the lexers' warnings and structural comments into the reader's lists.
    fn drain(&mut self) {
        for f in &mut self.frames {
            if let Some(l) = f.lexer.as_mut() {
                for (pos, message) in l.warnings.drain(..) {
                    self.warnings
                        .push(Warning { at: Location { file: f.name.clone(), pos }, message });
                }
                if let Some(s) = l.structure.as_mut() {
                    for (pos, text) in s.drain(..) {
                        self.structure.push((Location { file: f.name.clone(), pos }, text));
                    }
                }
            }
        }
    }

    /// Warnings so far (unknown requests, undeclared parameters, odd escapes).
    pub fn warnings(&self) -> &[Warning] {
        &self.warnings
    }

    /// Takes the warnings so far, leaving none.
    pub fn take_warnings(&mut self) -> Vec<Warning> {
        std::mem::take(&mut self.warnings)
    }

    /// Takes the `##` comments collected so far (text after `##`), when
    /// [`ReaderOptions::keep_structure_comments`] is on.
    pub fn take_structure_comments(&mut self) -> Vec<(Location, String)> {
        std::mem::take(&mut self.structure)
    }

    /// The declaration table (predeclared names plus every `Declare` read so far).
    pub fn declarations(&self) -> &Declarations {
        &self.decls
    }

    /// The declaration table, for a caller that declares names itself.
    pub fn declarations_mut(&mut self) -> &mut Declarations {
        &mut self.decls
    }

    /// Floats per colour (3 unless `ColorSamples` changed it; restored at `FrameEnd`).
    pub fn color_samples(&self) -> usize {
        self.color_samples
    }

    /// Number of open sources (1 for the root, plus one per archive being read).
    pub fn depth(&self) -> usize {
        self.frames.len()
    }

    /// Display name of the source being read (the innermost archive).
    pub fn current_file(&self) -> Option<&str> {
        self.frames.last().map(|f| &*f.name)
    }

    /// The path `ReadArchive "name"` means when read at `at`: `name` itself if absolute, else
    /// relative to the directory of the file that holds `at` (the current directory for
    /// standard input and memory sources).
    pub fn resolve_archive(&self, name: &str, at: &Location) -> PathBuf {
        let name = Path::new(name);
        if name.is_absolute() {
            return name.to_path_buf();
        }
        let including = self
            .frames
            .iter()
            .rev()
            .find(|f| Arc::ptr_eq(&f.name, &at.file))
            .or(self.frames.last());
        match including.and_then(|f| f.path.as_deref()).and_then(Path::parent) {
            Some(dir) => dir.join(name),
            None => name.to_path_buf(),
        }
    }

    /// Follows a `ReadArchive` request: resolves its file (see [`Reader::resolve_archive`]) and
    /// pushes it, so the following requests come from the archive until its end.
    pub fn read_archive(&mut self, request: &Request) -> Result<(), RibError> {
        let Some(name) = request.string(0) else {
            return Err(RibError::Request {
                at: request.at.clone(),
                request: request.name(),
                message: "expected a file name".into(),
            });
        };
        let path = self.resolve_archive(name, &request.at);
        self.push_archive(&path, &request.at)
    }

    /// Opens the archive file `path` (already resolved) on top of the stack, as included by the
    /// request at `at`. Errors: an include cycle or too deep a nesting
    /// ([`RibError::Request`]), or an unreadable file ([`RibError::Archive`]).
    pub fn push_archive(&mut self, path: &Path, at: &Location) -> Result<(), RibError> {
        let display = path.display().to_string();
        let archive_error =
            |source| RibError::Archive { at: at.clone(), file: display.clone(), source };
        let canonical = fs::canonicalize(path).map_err(archive_error)?;
        self.check_push(Some(&canonical), &display, at)?;
        let source = Source::open(path).map_err(archive_error)?;
        let mut frame = Frame::new(source, self.options.keep_structure_comments);
        frame.canonical = Some(canonical);
        if let Some(e) = frame.pending.take() {
            let RibError::Io { source, .. } = e else { return Err(e) };
            return Err(RibError::Archive { at: at.clone(), file: display, source });
        }
        self.frames.push(frame);
        Ok(())
    }

    /// Pushes any source (an in-memory archive, say) on top of the stack, as included by the
    /// request at `at`; cycle detection applies when the source has a path.
    pub fn push_source(&mut self, source: Source, at: &Location) -> Result<(), RibError> {
        let canonical = source.path().and_then(|p| fs::canonicalize(p).ok());
        self.check_push(canonical.as_ref(), source.name.as_ref(), at)?;
        self.frames.push(Frame::new(source, self.options.keep_structure_comments));
        Ok(())
    }

    fn check_push(
        &self,
        canonical: Option<&PathBuf>,
        display: &str,
        at: &Location,
    ) -> Result<(), RibError> {
        let err =
            |message: String| RibError::Request { at: at.clone(), request: "ReadArchive", message };
        if let Some(c) = canonical
            && let Some(first) = self.frames.iter().position(|f| f.canonical.as_ref() == Some(c))
        {
            let mut chain: Vec<&str> = self.frames[first..].iter().map(|f| &*f.name).collect();
            chain.push(display);
            return Err(err(format!("include cycle {}", chain.join(" -> "))));
        }
        if self.frames.len() >= self.options.max_depth {
            return Err(err(format!("archives nested deeper than {}", self.options.max_depth)));
        }
        Ok(())
    }
}

impl Iterator for Reader {
    type Item = Result<Request, RibError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_request().transpose()
    }
}

impl std::fmt::Debug for Reader {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let files: Vec<&str> = self.frames.iter().map(|f| &*f.name).collect();
        f.debug_struct("Reader")
            .field("files", &files)
            .field("color_samples", &self.color_samples)
            .field("warnings", &self.warnings.len())
            .finish()
    }
}

/// Converts a lexical error; the fatal kinds finish the source.
fn lex_error(frame: &mut Frame, e: LexError) -> RibError {
    match e {
        LexError::Syntax(pos, message) => RibError::Syntax { at: frame.loc(pos), message },
        LexError::Binary(pos, byte) => {
            frame.done = true;
            RibError::Binary { at: frame.loc(pos), byte }
        }
        LexError::Io(source) => {
            frame.done = true;
            RibError::Io { file: frame.name.clone(), source }
        }
    }
}

/// What a parser is reading, for the messages of lexical errors met meanwhile (no allocation
/// for arguments: their names are static).
enum Context {
    /// Nothing that belongs to the request yet: the token may start the next one.
    None,
    /// A positional argument, by its name.
    Arg(&'static str),
    /// A parameter's value (the parser's `param_name` and `param_decl`).
    Param,
}

/// Builds one request from the current source.
struct Parser<'a> {
    frame: &'a mut Frame,
    decls: &'a Declarations,
    color_samples: usize,
    warnings: &'a mut Vec<Warning>,
    kind: RequestKind,
    at: Pos,
    /// What is being read (`argument radius`, `parameter "Kd" (uniform float)`), prefixed to
    /// lexical errors met meanwhile.
    context: Context,
    /// The parameter being read (moved into its [`Param`] at the end).
    param_name: String,
    /// Its declaration, if any.
    param_decl: Option<Decl>,
}

impl Parser<'_> {
    fn error(&self, pos: Pos, message: String) -> RibError {
        RibError::Request { at: self.frame.loc(pos), request: self.kind.name(), message }
    }

    /// A lexical error met inside the request: given the request's name and the context. With
    /// no context (the token may as well start the next request) it stays a lexical error.
    fn lex(&mut self, e: LexError) -> RibError {
        match e {
            LexError::Syntax(pos, m) => match &self.context {
                Context::None => lex_error(self.frame, LexError::Syntax(pos, m)),
                Context::Arg(name) => self.error(pos, format!("argument {name}: {m}")),
                Context::Param => self.error(pos, format!("{}: {m}", self.label())),
            },
            other => lex_error(self.frame, other),
        }
    }

    fn peek(&mut self) -> Result<(Pos, Tok), RibError> {
        match self.frame.peek() {
            Ok(t) => Ok(t.clone()),
            Err(e) => Err(self.lex(e)),
        }
    }

    /// Peeks at the next token's kind without cloning its contents.
    fn peek_kind(&mut self) -> Result<(Pos, Peeked), RibError> {
        match self.frame.peek() {
            Ok((p, t)) => Ok((*p, Peeked::of(t))),
            Err(e) => Err(self.lex(e)),
        }
    }

    fn next(&mut self) -> Result<(Pos, Tok), RibError> {
        match self.frame.next() {
            Ok(t) => Ok(t),
            Err(e) => Err(self.lex(e)),
        }
    }

    /// Converts an array error, naming what was being read.
    fn array(&mut self, what: &str, e: ArrayError) -> RibError {
        match e {
            ArrayError::Lex(LexError::Syntax(pos, m)) => self.error(pos, format!("{what}: {m}")),
            ArrayError::Lex(e) => self.lex(e),
            ArrayError::Unexpected(pos, m) => self.error(pos, format!("{what}: {m}")),
        }
    }

    fn request(&mut self) -> Result<Request, RibError> {
        let sig = self.kind.signature();
        let mut args = Vec::with_capacity(sig.args.len());
        self.context = sig.args.first().map_or(Context::None, |a| Context::Arg(a.name));
        let (open_at, first) = self.peek_kind()?;
        if sig.array_form && first == Peeked::Open {
            self.next()?;
            let mut v = Vec::new();
            if let Err(e) =
                self.frame.lexer().map_err(ArrayError::Lex).and_then(|l| l.floats(open_at, &mut v))
            {
                return Err(self.array("arguments", e));
            }
            if v.len() != sig.args.len() {
                return Err(self.error(
                    open_at,
                    format!("expected an array of {} numbers, got {}", sig.args.len(), v.len()),
                ));
            }
            args.extend(v.into_iter().map(Value::Float));
        } else {
            for (i, arg) in sig.args.iter().enumerate() {
                if i == sig.required {
                    // Optional arguments, or the next request: no context yet.
                    self.context = Context::None;
                    let (_, next) = self.peek_kind()?;
                    if !next.starts(arg.kind) {
                        break;
                    }
                }
                args.push(self.arg(arg)?);
            }
        }
        let params =
            if sig.params { self.params(args.len())? } else { self.no_params(args.len())? };
        Ok(Request { kind: self.kind, at: self.frame.loc(self.at), args, params })
    }

    /// Where a request without parameters ends: the next token must start another request.
    fn no_params(&mut self, nargs: usize) -> Result<Vec<Param>, RibError> {
        self.context = Context::None;
        let (pos, tok) = self.peek()?;
        match tok {
            Tok::Request(_) | Tok::Unknown(_) | Tok::Eof => Ok(Vec::new()),
            Tok::Str(_) if nargs == self.kind.signature().args.len() => Err(self.error(
                pos,
                format!(
                    "takes no parameter list, got {} ({})",
                    tok.describe(),
                    self.kind.synopsis()
                ),
            )),
            _ => Err(self.too_many(pos, &tok, nargs)),
        }
    }

    fn too_many(&self, pos: Pos, tok: &Tok, nargs: usize) -> RibError {
        let after = match nargs.checked_sub(1).and_then(|i| self.kind.signature().args.get(i)) {
            Some(arg) => arg.name,
            None => "the request name",
        };
        self.error(
            pos,
            format!(
                "too many arguments: {} after {after} ({})",
                tok.describe(),
                self.kind.synopsis()
            ),
        )
    }

    /// Reads one positional argument.
    fn arg(&mut self, arg: &Arg) -> Result<Value, RibError> {
        self.context = Context::Arg(arg.name);
        let (pos, tok) = self.peek()?;
        let wrong = |p: &Parser, got: &Tok| {
            p.error(
                pos,
                format!(
                    "argument {}: expected {}, got {}",
                    arg.name,
                    arg.kind.describe(),
                    got.describe()
                ),
            )
        };
        if matches!(tok, Tok::Request(_) | Tok::Unknown(_) | Tok::Eof) {
            return Err(self.error(
                self.at,
                format!(
                    "missing argument {} ({}) in {}",
                    arg.name,
                    arg.kind.describe(),
                    self.kind.synopsis()
                ),
            ));
        }
        let kind = match arg.kind {
            ArgKind::Color => ArgKind::Fixed(self.color_samples),
            ArgKind::Basis if matches!(tok, Tok::Str(_)) => ArgKind::Str,
            ArgKind::Basis => ArgKind::Fixed(16),
            k => k,
        };
        match (kind, &tok) {
            (ArgKind::Int, Tok::Num(n)) | (ArgKind::Handle, Tok::Num(n)) => {
                self.next()?;
                match n.i {
                    Some(i) => Ok(Value::Int(i)),
                    None => {
                        Err(self.error(pos, format!("argument {}: {}", arg.name, not_an_int(*n))))
                    }
                }
            }
            (ArgKind::Float, Tok::Num(n)) => {
                self.next()?;
                Ok(Value::Float(n.f))
            }
            (ArgKind::Str | ArgKind::Handle, Tok::Str(_)) => match self.next()? {
                (_, Tok::Str(s)) => Ok(Value::String(s)),
                (_, other) => Err(wrong(self, &other)),
            },
            (ArgKind::Ints, Tok::Open) => {
                self.next()?;
                let mut v = Vec::new();
                self.read_ints(pos, &mut v, arg.name)?;
                Ok(Value::Ints(v))
            }
            (ArgKind::Floats | ArgKind::Times, Tok::Open) => {
                self.next()?;
                let mut v = Vec::new();
                self.read_floats(pos, &mut v, arg.name)?;
                Ok(Value::Floats(v))
            }
            (ArgKind::Strings, Tok::Open) => {
                self.next()?;
                let mut v = Vec::new();
                let r = self
                    .frame
                    .lexer()
                    .map_err(ArrayError::Lex)
                    .and_then(|l| l.strings(pos, &mut v));
                if let Err(e) = r {
                    return Err(self.array(&format!("argument {}", arg.name), e));
                }
                Ok(Value::Strings(v))
            }
            (ArgKind::Times, Tok::Num(_)) => {
                let mut v = Vec::new();
                while let (_, Tok::Num(n)) = self.peek()? {
                    self.next()?;
                    v.push(n.f);
                }
                Ok(Value::Floats(v))
            }
            (ArgKind::Fixed(n), Tok::Open) => {
                self.next()?;
                let mut v = Vec::with_capacity(n);
                self.read_floats(pos, &mut v, arg.name)?;
                if v.len() != n {
                    return Err(self.error(
                        pos,
                        format!("argument {}: expected {n} numbers, got {}", arg.name, v.len()),
                    ));
                }
                Ok(Value::Floats(v))
            }
            (ArgKind::Fixed(n), Tok::Num(_)) => {
                let mut v = Vec::with_capacity(n);
                while v.len() < n {
                    match self.peek()? {
                        (_, Tok::Num(x)) => {
                            self.next()?;
                            v.push(x.f);
                        }
                        (p, other) => {
                            return Err(self.error(
                                p,
                                format!(
                                    "argument {}: expected {n} numbers, got {} then {}",
                                    arg.name,
                                    v.len(),
                                    other.describe()
                                ),
                            ));
                        }
                    }
                }
                Ok(Value::Floats(v))
            }
            _ => Err(wrong(self, &tok)),
        }
    }

    fn read_floats(&mut self, open: Pos, v: &mut Vec<f32>, what: &str) -> Result<(), RibError> {
        let r = self.frame.lexer().map_err(ArrayError::Lex).and_then(|l| l.floats(open, v));
        r.map_err(|e| self.array(&format!("argument {what}"), e))
    }

    fn read_ints(&mut self, open: Pos, v: &mut Vec<i32>, what: &str) -> Result<(), RibError> {
        let r = self.frame.lexer().map_err(ArrayError::Lex).and_then(|l| l.ints(open, v));
        r.map_err(|e| self.array(&format!("argument {what}"), e))
    }

    /// Reads `"token" value` pairs up to the next request.
    fn params(&mut self, nargs: usize) -> Result<Vec<Param>, RibError> {
        let mut params = Vec::new();
        loop {
            // A parameter name, or the next request: no context.
            self.context = Context::None;
            let (pos, tok) = self.peek()?;
            let token = match tok {
                Tok::Request(_) | Tok::Unknown(_) | Tok::Eof => return Ok(params),
                Tok::Str(s) => s,
                other if params.is_empty() => return Err(self.too_many(pos, &other, nargs)),
                other => {
                    return Err(self.error(
                        pos,
                        format!("expected a parameter name (a string), got {}", other.describe()),
                    ));
                }
            };
            self.next()?;
            params.push(self.param(pos, token)?);
        }
    }

    /// Reads the value of the parameter whose token string `token` was at `pos`.
    fn param(&mut self, pos: Pos, token: String) -> Result<Param, RibError> {
        let (inline, name) = match decl::parse_token(&token) {
            Ok((inline, None)) => (inline, token),
            Ok((inline, Some(name))) => (inline, name),
            Err(m) => {
                return Err(self.error(
                    pos,
                    format!("parameter {}: bad inline declaration: {m}", quote(&token)),
                ));
            }
        };
        let decl = inline.or_else(|| self.decls.get(&name).copied());
        self.param_name = name;
        self.param_decl = decl;
        self.context = Context::Param;
        let (vpos, next) = self.peek_kind()?;
        if !matches!(next, Peeked::Num | Peeked::Str | Peeked::Open) {
            let (_, tok) = self.peek()?;
            return Err(self.error(
                vpos,
                format!("{}: expected a value, got {}", self.label(), tok.describe()),
            ));
        }
        let data = match decl.map(|d| d.ty.storage()) {
            Some(Storage::Floats) => match self.next()? {
                (_, Tok::Num(n)) => Data::Floats(vec![n.f]),
                (p, Tok::Open) => {
                    let mut v = Vec::new();
                    let r = self
                        .frame
                        .lexer()
                        .map_err(ArrayError::Lex)
                        .and_then(|l| l.floats(p, &mut v));
                    r.map_err(|e| {
                        let l = self.label();
                        self.array(&l, e)
                    })?;
                    Data::Floats(v)
                }
                (p, other) => {
                    return Err(self.error(
                        p,
                        format!("{}: expected numbers, got {}", self.label(), other.describe()),
                    ));
                }
            },
            Some(Storage::Ints) => match self.next()? {
                (p, Tok::Num(n)) => match n.i {
                    Some(i) => Data::Ints(vec![i]),
                    None => {
                        return Err(self.error(p, format!("{}: {}", self.label(), not_an_int(n))));
                    }
                },
                (p, Tok::Open) => {
                    let mut v = Vec::new();
                    let r =
                        self.frame.lexer().map_err(ArrayError::Lex).and_then(|l| l.ints(p, &mut v));
                    r.map_err(|e| {
                        let l = self.label();
                        self.array(&l, e)
                    })?;
                    Data::Ints(v)
                }
                (p, other) => {
                    return Err(self.error(
                        p,
                        format!("{}: expected integers, got {}", self.label(), other.describe()),
                    ));
                }
            },
            Some(Storage::Strings) => match self.next()? {
                (_, Tok::Str(s)) => Data::Strings(vec![s]),
                (p, Tok::Open) => {
                    let mut v = Vec::new();
                    let r = self
                        .frame
                        .lexer()
                        .map_err(ArrayError::Lex)
                        .and_then(|l| l.strings(p, &mut v));
                    r.map_err(|e| {
                        let l = self.label();
                        self.array(&l, e)
                    })?;
                    Data::Strings(v)
                }
                (p, other) => {
                    return Err(self.error(
                        p,
                        format!("{}: expected strings, got {}", self.label(), other.describe()),
                    ));
                }
            },
            None => {
                let data = match self.next()? {
                    (_, Tok::Num(Num { i: Some(i), .. })) => Data::Ints(vec![i]),
                    (_, Tok::Num(n)) => Data::Floats(vec![n.f]),
                    (_, Tok::Str(s)) => Data::Strings(vec![s]),
                    (p, _) => {
                        let r = self.frame.lexer().map_err(ArrayError::Lex).and_then(|l| l.any(p));
                        match r.map_err(|e| {
                            let l = self.label();
                            self.array(&l, e)
                        })? {
                            AnyArray::Empty => Data::Floats(Vec::new()),
                            AnyArray::Ints(v) => Data::Ints(v),
                            AnyArray::Floats(v) => Data::Floats(v),
                            AnyArray::Strings(v) => Data::Strings(v),
                        }
                    }
                };
                self.warnings.push(Warning {
                    at: self.frame.loc(pos),
                    message: format!(
                        "{}: {} is not declared; kept as written",
                        self.kind.name(),
                        self.label()
                    ),
                });
                data
            }
        };
        if let Some(d) = decl {
            let size = d.scalars(self.color_samples);
            let n = data.len();
            if d.class == Class::Constant && n != size {
                return Err(self.error(
                    vpos,
                    format!("{}: expected {size} value{}, got {n}", self.label(), plural(size)),
                ));
            }
            if size > 0 && n % size != 0 {
                return Err(self.error(
                    vpos,
                    format!("{}: expected a multiple of {size} values, got {n}", self.label()),
                ));
            }
        }
        Ok(Param { name: std::mem::take(&mut self.param_name), decl, data, at: pos })
    }

    /// The parameter being read, for messages: `parameter "Kd" (uniform float)`.
    fn label(&self) -> String {
        match self.param_decl {
            Some(d) => format!("parameter {} ({d})", quote(&self.param_name)),
            None => format!("parameter {}", quote(&self.param_name)),
        }
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The kind of the next token, for decisions that need no contents.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Peeked {
    Name,
    Str,
    Num,
    Open,
    Close,
    Eof,
}

impl Peeked {
    fn of(t: &Tok) -> Peeked {
        match t {
            Tok::Request(_) | Tok::Unknown(_) => Peeked::Name,
            Tok::Str(_) => Peeked::Str,
            Tok::Num(_) => Peeked::Num,
            Tok::Open => Peeked::Open,
            Tok::Close => Peeked::Close,
            Tok::Eof => Peeked::Eof,
        }
    }

    /// True if a token of this kind can begin an argument of `kind` (decides whether optional
    /// arguments are present).
    fn starts(self, kind: ArgKind) -> bool {
        match self {
            Peeked::Num => matches!(
                kind,
                ArgKind::Int
                    | ArgKind::Float
                    | ArgKind::Handle
                    | ArgKind::Times
                    | ArgKind::Fixed(_)
                    | ArgKind::Color
                    | ArgKind::Basis
            ),
            Peeked::Str => matches!(kind, ArgKind::Str | ArgKind::Handle | ArgKind::Basis),
            Peeked::Open => matches!(
                kind,
                ArgKind::Ints
                    | ArgKind::Floats
                    | ArgKind::Strings
                    | ArgKind::Times
                    | ArgKind::Fixed(_)
                    | ArgKind::Color
                    | ArgKind::Basis
            ),
            Peeked::Name | Peeked::Close | Peeked::Eof => false,
        }
    }
}
