//! RenderMan RIB front end, first layer: bytes to a stream of positioned, typed requests
//! (RenderMan Interface Specification 3.2, Appendix C.2 and the requests of Part I).
//!
//! Stage invariants: input is streamed (a bounded buffer per open source, one request built at a
//! time); every request handed on fits its signature in [`RequestKind::signature`] and its
//! parameters their declarations; every error is one line `file:line:col: Request: message`;
//! no input makes the reader panic or loop.
//!
//! The pieces, in pipeline order:
//! - [`Source`]: a file, stdin (`-`) or memory; gzip is decompressed transparently.
//! - the lexer (private): RIB tokens, ASCII and binary encodings mixed, with 1-based
//!   line:column positions (columns count bytes).
//! - [`Reader`]: requests from tokens, checked against the signature table
//!   ([`RequestKind`], [`Signature`]) and the declaration table ([`Declarations`]); an include
//!   stack for `ReadArchive` with cycle detection; [`Warning`]s for what is skipped or kept raw.
//!
//! The RI state machine (graphics state, transforms, scene mapping) is built on top: it loops
//! over [`Reader::next_request`], matches on [`Request::kind`], reads arguments with the typed
//! accessors ([`Request::float`], [`Request::floats`], ...) and parameters with
//! [`Request::param`], calls [`Reader::read_archive`] on `ReadArchive`, and reports its own
//! findings with [`Request::error`] and [`Request::warning`] in the same one-line form.

#![deny(missing_docs)]

mod decl;
mod error;
pub mod input;
mod lexer;
mod reader;
mod request;
pub mod ri;
mod signature;
mod source;

pub use decl::{Class, Decl, Declarations, STANDARD, Storage, Type};
pub use error::{Location, Pos, RibError, Warning};
pub use input::{Format, InputError, Refusal, detect, load_scene_file, load_scene_file_with};
pub use reader::{Reader, ReaderOptions};
pub use request::{Data, Param, Request, Value};
pub use ri::{
    Display, Frame, Loaded, MakeJob, Permissions, RiOptions, is_depth_driver, load, load_with,
};
pub use signature::{Arg, ArgKind, RequestKind, Signature};
pub use source::Source;

/// Reads every request of `source`, stopping at the first error; with the warnings.
///
/// A convenience for tests and tools; a renderer loops over [`Reader::next_request`] instead so
/// that requests are handled as they arrive.
pub fn read_all(source: Source) -> Result<(Vec<Request>, Vec<Warning>), RibError> {
    let mut reader = Reader::new(source);
    let mut out = Vec::new();
    while let Some(r) = reader.next_request()? {
        out.push(r);
    }
    Ok((out, reader.take_warnings()))
}
