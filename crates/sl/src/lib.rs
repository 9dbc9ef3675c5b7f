//! RenderMan Shading Language front end: RSL 1 as the RenderMan Interface Specification 3.2,
//! Part II (chapters 11-16) defines it, compiled to a checked, typed IR, and the grid machine
//! ([`exec`]) that runs the IR over whole grids of points.
//!
//! Stage invariants: every token maps back to `file:line:col` of a file the user wrote (through
//! `#include`s and macro expansions, which report the expansion site); every error is one line,
//! `file:line:col: message`, naming the construct; no input makes the front end panic or loop;
//! in the output every expression has a type and a detail (uniform or varying) known at compile
//! time, every call is resolved to one overload, and every implicit conversion is explicit.
//!
//! The pieces, in pipeline order:
//! - the lexer ([`lexer`]): bytes to tokens, backslash-newline spliced, comments skipped;
//! - the preprocessor (private `pp`): `#include`, `#define` (with `#`, `##`, variadic),
//!   `#undef`, `#if`/`#ifdef`/`#ifndef`/`#elif`/`#else`/`#endif`, `#line`, `#error`;
//! - the parser (private): tokens to the syntax tree ([`ast`]);
//! - the checker (private): scopes, types, the operator and overload rules, the predefined
//!   variables of each shader type ([`globals`]), the standard library's signatures
//!   ([`library`]), recursion, and the uniform/varying analysis, to the IR ([`ir`]);
//! - the grid machine ([`exec`]): the IR run over an `nu` x `nv` grid, uniform values once and
//!   varying ones per point under masks, with the library, derivatives and the light callback.
//!
//! ```
//! let shader = reyes_sl::compile_str(
//!     "matte.sl",
//!     "surface matte(float Ka = 1, Kd = 1;) {
//!          normal Nf = faceforward(normalize(N), I);
//!          Oi = Os;
//!          Ci = Os * Cs * (Ka * ambient() + Kd * diffuse(Nf));
//!      }",
//!     &[],
//! )
//! .unwrap();
//! assert_eq!(shader.name, "matte");
//! ```

pub mod ast;
mod check;
mod error;
pub mod exec;
pub mod globals;
pub mod ir;
pub mod lexer;
pub mod library;
mod parser;
mod pp;
pub mod shaders;
pub mod tool;
pub mod types;

use std::path::{Path, PathBuf};

pub use error::{Pos, SlError, SourceMap};
pub use ir::CheckedShader;
pub use types::{BaseType, Detail, ShaderKind, Type};

/// What to compile: a file, or text in memory with the name its errors show.
#[derive(Debug, Clone, Copy)]
pub enum Source<'a> {
    /// A shader file; quoted `#include`s look in its folder first.
    File(&'a Path),
    /// Shader text; quoted `#include`s search the include paths only.
    Text {
        /// The name positions show (e.g. `plastic.sl`).
        name: &'a str,
        /// The source.
        text: &'a str,
    },
}

/// Options beyond the include path.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Folders `#include` searches (after the including file's folder, for quoted names).
    pub include_paths: Vec<PathBuf>,
    /// Macros defined before the source is read (`-DNAME=VALUE`): name and body text.
    pub defines: Vec<(String, String)>,
}

/// Compiles one shader source to its checked IR.
pub fn compile(source: Source<'_>, include_paths: &[PathBuf]) -> Result<CheckedShader, SlError> {
    compile_with(source, &Options { include_paths: include_paths.to_vec(), defines: Vec::new() })
}

/// Compiles a shader file.
pub fn compile_file(path: &Path, include_paths: &[PathBuf]) -> Result<CheckedShader, SlError> {
    compile(Source::File(path), include_paths)
}

/// Compiles shader text named `name`.
pub fn compile_str(
    name: &str,
    text: &str,
    include_paths: &[PathBuf],
) -> Result<CheckedShader, SlError> {
    compile(Source::Text { name, text }, include_paths)
}

/// Compiles with [`Options`].
pub fn compile_with(source: Source<'_>, options: &Options) -> Result<CheckedShader, SlError> {
    let (toks, map) = tokens(source, options)?;
    let file = parser::parse(&toks).map_err(|d| d.into_error(&map))?;
    check::check(&file, map.clone()).map_err(|d| d.into_error(&map))
}

/// Preprocesses only: the source's tokens after `#include`s and macros, each with its
/// position shown as `file:line:col`. For tests and tools.
pub fn preprocess(source: Source<'_>, options: &Options) -> Result<Vec<(String, String)>, SlError> {
    let (toks, map) = tokens(source, options)?;
    Ok(toks.into_iter().map(|t| (t.tok.spelling(), map.show(t.pos))).collect())
}

/// The preprocessed tokens of `source`, with the map that places them; the first stage of
/// every entry above.
fn tokens(
    source: Source<'_>,
    options: &Options,
) -> Result<(Vec<lexer::Token>, SourceMap), SlError> {
    let mut map = SourceMap::default();
    // The main file is file 0, which a position with nothing to point at (the end of an
    // empty file) names.
    let input = match source {
        Source::File(p) => {
            map.intern(&p.display().to_string());
            pp::Input::File(p)
        }
        Source::Text { name, text } => {
            map.intern(name);
            pp::Input::Text { name, text }
        }
    };
    let toks = pp::preprocess(input, &options.include_paths, &options.defines, &mut map)
        .map_err(|d| d.into_error(&map))?;
    Ok((toks, map))
}

/// Parses only (preprocessor and parser, no checking): the syntax tree.
pub fn parse(source: Source<'_>, options: &Options) -> Result<ast::File, SlError> {
    let (toks, map) = tokens(source, options)?;
    parser::parse(&toks).map_err(|d| d.into_error(&map))
}
