//! Building one request from the current source's tokens: positional arguments against the
//! request's signature, then the parameter list against the declarations.
//!
//! Invariant: a request handed on fits its signature; a malformed one is an error naming the
//! request and the argument or parameter, and the source resynchronises at the next name.

use super::*;

/// What a parser is reading, for the messages of lexical errors met meanwhile (no allocation
/// for arguments: their names are static).
pub(super) enum Context {
    /// Nothing that belongs to the request yet: the token may start the next one.
    None,
    /// A positional argument, by its name.
    Arg(&'static str),
    /// A parameter's value (the parser's `param_name` and `param_decl`).
    Param,
}

/// Builds one request from the current source.
pub(super) struct Parser<'a> {
    pub(super) frame: &'a mut Frame,
    pub(super) decls: &'a Declarations,
    pub(super) color_samples: usize,
    pub(super) warnings: &'a mut Vec<Warning>,
    pub(super) kind: RequestKind,
    pub(super) at: Pos,
    /// What is being read (`argument radius`, `parameter "Kd" (uniform float)`), prefixed to
    /// lexical errors met meanwhile.
    pub(super) context: Context,
    /// The parameter being read (moved into its [`Param`] at the end).
    pub(super) param_name: String,
    /// Its declaration, if any.
    pub(super) param_decl: Option<Decl>,
    /// What RenderMan renderers tolerate with a warning is an error ([`super::ReaderOptions`]).
    pub(super) strict: bool,
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

    pub(super) fn request(&mut self) -> Result<Request, RibError> {
        let sig = self.kind.signature();
        let mut args = Vec::with_capacity(sig.args.len());
        self.context = sig.args.first().map_or(Context::None, |a| Context::Arg(a.name));
        let (open_at, first) = self.peek_kind()?;
        if sig.array_form && first == Peeked::Open {
            self.next()?;
            let mut v = Vec::new();
            self.read_array(open_at, &mut v, Lexer::floats, |_| "arguments".to_string())?;
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
        if let Tok::Unknown(word) = &tok
            && matches!(arg.kind, ArgKind::Float | ArgKind::Int | ArgKind::Color)
            && is_non_finite_word(word)
        {
            // `Rotate NaN 0 1 0`: a non-finite value written out by an exporter, not a
            // missing argument followed by an unknown request.
            return Err(self.error(
                pos,
                format!(
                    "argument {}: expected {}, got {word:?}: RIB numbers are finite (NaN and infinity cannot be written)",
                    arg.name,
                    arg.kind.describe()
                ),
            ));
        }
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
                self.arg_array(pos, &mut v, Lexer::ints, arg.name)?;
                Ok(Value::Ints(v))
            }
            (ArgKind::Floats | ArgKind::Times, Tok::Open) => {
                self.next()?;
                let mut v = Vec::new();
                self.arg_array(pos, &mut v, Lexer::floats, arg.name)?;
                Ok(Value::Floats(v))
            }
            (ArgKind::Strings, Tok::Open) => {
                self.next()?;
                let mut v = Vec::new();
                self.arg_array(pos, &mut v, Lexer::strings, arg.name)?;
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
                self.arg_array(pos, &mut v, Lexer::floats, arg.name)?;
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

    /// Reads the rest of the array opened at `open` into `v` with the lexer's `read`; an
    /// error names `what` was being read (built only then).
    fn read_array<T>(
        &mut self,
        open: Pos,
        v: &mut Vec<T>,
        read: impl FnOnce(&mut Lexer, Pos, &mut Vec<T>) -> Result<(), ArrayError>,
        what: impl FnOnce(&Self) -> String,
    ) -> Result<(), RibError> {
        let r = self.frame.lexer().map_err(ArrayError::Lex).and_then(|l| read(l, open, v));
        r.map_err(|e| {
            let what = what(self);
            self.array(&what, e)
        })
    }

    /// Argument `name`'s array opened at `open`, read into `v` with the lexer's `read`.
    fn arg_array<T>(
        &mut self,
        open: Pos,
        v: &mut Vec<T>,
        read: impl FnOnce(&mut Lexer, Pos, &mut Vec<T>) -> Result<(), ArrayError>,
        name: &str,
    ) -> Result<(), RibError> {
        self.read_array(open, v, read, |_| format!("argument {name}"))
    }

    /// The parameter's values as an array opened at `open`, read with the lexer's `read`.
    fn param_array<T>(
        &mut self,
        open: Pos,
        read: impl FnOnce(&mut Lexer, Pos, &mut Vec<T>) -> Result<(), ArrayError>,
    ) -> Result<Vec<T>, RibError> {
        let mut v = Vec::new();
        self.read_array(open, &mut v, read, Self::label)?;
        Ok(v)
    }

    /// A parameter's value of the wrong kind: `expected numbers, got ...`.
    fn expected(&self, pos: Pos, what: &str, got: &Tok) -> RibError {
        self.error(pos, format!("{}: expected {what}, got {}", self.label(), got.describe()))
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
            params.extend(self.param(pos, token)?);
        }
    }

    /// Reads the value of the parameter whose token string `token` was at `pos`. The
    /// parameters of RenderMan's RIS requests (`"reference color baseColor"`, `"bxdf"`...)
    /// are not interpreted: they are read as written, unchecked and untold (the request
    /// itself is told once by the state machine).
    /// None: a parameter of an unknown type, read and skipped with a warning.
    fn param(&mut self, pos: Pos, token: String) -> Result<Option<Param>, RibError> {
        let ris = self.kind.is_ris();
        let mut skipped = false;
        let (inline, name) = match decl::parse_token(&token) {
            _ if ris => (None, token),
            Ok((inline, None)) => (inline, token),
            Ok((inline, Some(name))) => (inline, name),
            // A type this reader does not know (PRMan's `mpoint` of blobby, a typo): RenderMan
            // renderers skip the parameter with a message and go on; so does this one (its
            // value is read as an undeclared one's, then dropped).
            Err(m) if m.starts_with("unknown type") && !self.strict => {
                self.warnings.push(Warning {
                    at: self.frame.loc(pos),
                    message: format!(
                        "{}: parameter {}: {m}: the parameter is skipped",
                        self.kind.name(),
                        quote(&token)
                    ),
                });
                skipped = true;
                (None, token)
            }
            Err(m) => {
                let strict =
                    if self.strict && m.starts_with("unknown type") { " (--strict)" } else { "" };
                return Err(self.error(
                    pos,
                    format!("parameter {}: bad inline declaration: {m}{strict}", quote(&token)),
                ));
            }
        };
        let decl = if ris { None } else { inline.or_else(|| self.decls.get(&name).copied()) };
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
                (p, Tok::Open) => Data::Floats(self.param_array(p, Lexer::floats)?),
                (p, other) => return Err(self.expected(p, "numbers", &other)),
            },
            Some(Storage::Ints) => match self.next()? {
                (p, Tok::Num(n)) => match n.i {
                    Some(i) => Data::Ints(vec![i]),
                    None => {
                        return Err(self.error(p, format!("{}: {}", self.label(), not_an_int(n))));
                    }
                },
                (p, Tok::Open) => Data::Ints(self.param_array(p, Lexer::ints)?),
                (p, other) => return Err(self.expected(p, "integers", &other)),
            },
            Some(Storage::Strings) => match self.next()? {
                (_, Tok::Str(s)) => Data::Strings(vec![s]),
                (p, Tok::Open) => Data::Strings(self.param_array(p, Lexer::strings)?),
                (p, other) => return Err(self.expected(p, "strings", &other)),
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
                if !ris && !skipped {
                    self.warnings.push(Warning {
                        at: self.frame.loc(pos),
                        message: format!(
                            "{}: {} is not declared; kept as written",
                            self.kind.name(),
                            self.label()
                        ),
                    });
                }
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
        let name = std::mem::take(&mut self.param_name);
        Ok((!skipped).then_some(Param { name, decl, data, at: pos }))
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

/// Whether a bare word is how a program prints a non-finite float (`nan`, `NaN`, `inf`,
/// `Infinity`, `nan(ind)`): RIB has no such numbers.
fn is_non_finite_word(word: &str) -> bool {
    let w = word.to_ascii_lowercase();
    matches!(w.as_str(), "nan" | "inf" | "infinity") || w.starts_with("nan(")
}
