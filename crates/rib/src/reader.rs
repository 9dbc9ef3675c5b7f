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

mod parser;

use parser::{Context, Parser};

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
    /// `--strict`: a parameter of a type this reader does not know is an error, not a
    /// warning and a skipped parameter.
    pub strict: bool,
}

impl Default for ReaderOptions {
    fn default() -> Self {
        ReaderOptions {
            follow_archives: false,
            keep_structure_comments: false,
            max_depth: 64,
            strict: false,
        }
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
        let result = self.next_inner(0);
        self.drain();
        result
    }

    /// The next request of the sources from `depth` up ([`Reader::depth`] counts the root
    /// 1), `Ok(None)` when the source at `depth` ends (it is then closed): reads an archive
    /// pushed at `depth` to its end, in place, without going on in the file that included
    /// it.
    ///
    /// ```
    /// use reyes_rib::{Reader, Source};
    /// let mut r = Reader::new(Source::from_bytes("main.rib", "WorldBegin WorldEnd"));
    /// let at = r.next_request().unwrap().unwrap().at;
    /// r.push_source(Source::from_bytes("part.rib", "Sphere 1 -1 1 360"), &at).unwrap();
    /// assert_eq!(r.next_request_within(2).unwrap().unwrap().name(), "Sphere");
    /// assert!(r.next_request_within(2).unwrap().is_none());
    /// assert_eq!(r.next_request().unwrap().unwrap().name(), "WorldEnd");
    /// ```
    pub fn next_request_within(&mut self, depth: usize) -> Result<Option<Request>, RibError> {
        if self.frames.len() < depth {
            return Ok(None);
        }
        let result = self.next_inner(depth);
        self.drain();
        result
    }

    /// The next request; `Ok(None)` at the end of the root, or when the source at `floor`
    /// (if above 0) ends.
    fn next_inner(&mut self, floor: usize) -> Result<Option<Request>, RibError> {
        loop {
            let Some(frame) = self.frames.last_mut() else { return Ok(None) };
            if let Some(e) = frame.pending.take() {
                frame.done = true;
                return Err(e);
            }
            if frame.done {
                self.drain();
                self.frames.pop();
                if self.frames.len() < floor {
                    return Ok(None);
                }
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
                        strict: self.options.strict,
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
