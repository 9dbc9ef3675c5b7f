//! The shader commands of `reyes-render shader`, as the RenderMan tool chain has them:
//!
//! ```text
//! reyes-render shader check [-I DIR]... FILE.sl...   compile and report, like aqsl or sdrc
//! reyes-render shader info [-I DIR]... NAME|FILE.sl  type, parameters, storage, defaults and
//!                                                    outputs, like sloinfo
//! ```
//!
//! `-I DIR` adds a folder to the `#include` path and, for `info`, to the folders searched for
//! `NAME.sl` (after the current one; the built-in standard shaders come last). Exit codes are
//! the renderer's: 0 success, 2 a shader that does not compile or a usage error, 1 a file that
//! cannot be read. Every error is one line.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::exec::{GridContext, Value};
use crate::ir::{CheckedShader, VarKind};
use crate::{SlError, Source, compile, compile_str, shaders};

/// What a command prints and how it ends.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Outcome {
    /// Standard output.
    pub stdout: String,
    /// Lines for standard error (errors and warnings, one line each).
    pub errors: Vec<String>,
    /// The exit code.
    pub code: u8,
}

const USAGE: &str = "usage: reyes-render shader check [-I DIR]... FILE.sl... | \
                     reyes-render shader info [-I DIR]... NAME|FILE.sl";

/// [`run`]'s outcome as `(stdout, errors, exit code)`, the form the command line takes for
/// each of its tools.
pub fn run_parts(args: &[String]) -> (String, Vec<String>, u8) {
    let o = run(args);
    (o.stdout, o.errors, o.code)
}

/// Runs `shader ARGS...` (the arguments after `shader`).
pub fn run(args: &[String]) -> Outcome {
    let mut dirs = Vec::new();
    let mut names = Vec::new();
    let mut it = args.iter().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "-I" => match it.next() {
                Some(d) => dirs.push(PathBuf::from(d)),
                None => return usage("-I needs a folder"),
            },
            _ if a.starts_with("-I") => dirs.push(PathBuf::from(&a[2..])),
            "-h" | "--help" => {
                return Outcome { stdout: format!("{USAGE}\n"), ..Outcome::default() };
            }
            _ if a.starts_with('-') => return usage(&format!("unknown option {a}")),
            _ => names.push(a.clone()),
        }
    }
    match (args.first().map(String::as_str), names.as_slice()) {
        (Some("check"), []) => usage("check: no shader file given"),
        (Some("check"), files) => check(files, &dirs),
        (Some("info"), [name]) => info(name, &dirs),
        (Some("info"), _) => usage("info: give one shader name or file"),
        (Some(other), _) => usage(&format!("unknown shader command {other:?}")),
        (None, _) => usage("no shader command"),
    }
}

fn usage(what: &str) -> Outcome {
    Outcome { errors: vec![format!("error: {what} ({USAGE})")], code: 2, ..Outcome::default() }
}

/// The exit code of `e` as the renderer's commands give it.
fn code_of(e: &SlError) -> u8 {
    if e.exit_code() == 1 { 1 } else { 2 }
}

/// Compiles each file: one line per file on standard output when it compiles, its one-line
/// error otherwise; the worst exit code.
fn check(files: &[String], dirs: &[PathBuf]) -> Outcome {
    let mut out = Outcome::default();
    for f in files {
        match compile(Source::File(Path::new(f)), dirs) {
            Ok(sh) => {
                let n = sh.params.len();
                let _ = writeln!(
                    out.stdout,
                    "{f}: ok: {} \"{}\", {n} parameter{}",
                    sh.kind,
                    sh.name,
                    if n == 1 { "" } else { "s" }
                );
            }
            Err(e) => {
                out.errors.push(format!("error: {e}"));
                out.code = out.code.max(code_of(&e));
            }
        }
    }
    out
}

/// The shader `name`: a file if it names one (or ends in `.sl`), else `NAME.sl` in the current
/// folder, then in `dirs`, then a built-in standard shader.
pub fn resolve(name: &str, dirs: &[PathBuf]) -> Result<CheckedShader, (u8, String)> {
    let as_file = Path::new(name);
    if name.ends_with(".sl") || as_file.is_file() {
        return compile(Source::File(as_file), dirs).map_err(|e| (code_of(&e), e.to_string()));
    }
    let file = format!("{name}.sl");
    let mut searched = vec![PathBuf::from(".")];
    searched.extend(dirs.iter().cloned());
    for dir in &searched {
        let path = dir.join(&file);
        if path.is_file() {
            return compile(Source::File(&path), dirs).map_err(|e| (code_of(&e), e.to_string()));
        }
    }
    if let Some(text) = shaders::standard(name) {
        return compile_str(&file, text, dirs).map_err(|e| (code_of(&e), e.to_string()));
    }
    let shown: Vec<String> = searched.iter().map(|d| d.display().to_string()).collect();
    Err((
        2,
        format!(
            "{}: no shader of that name: {file} is in none of {} and it is not a built-in standard shader",
            crate::error::OneLine(name),
            crate::error::OneLine(&shown.join(", "))
        ),
    ))
}

fn info(name: &str, dirs: &[PathBuf]) -> Outcome {
    match resolve(name, dirs) {
        Ok(sh) => match describe(&sh) {
            Ok(stdout) => Outcome { stdout, ..Outcome::default() },
            Err(e) => {
                Outcome { errors: vec![format!("error: {e}")], code: 2, ..Outcome::default() }
            }
        },
        Err((code, e)) => {
            Outcome { errors: vec![format!("error: {e}")], code, ..Outcome::default() }
        }
    }
}

/// `sloinfo`'s listing: the shader's type and name, then each parameter with its storage,
/// type and default value (evaluated as a render evaluates it, on one point).
///
/// # Errors
///
/// A default whose evaluation fails (it runs out of the instruction budget, for instance).
pub fn describe(sh: &CheckedShader) -> Result<String, String> {
    let mut grid = GridContext::new(sh, 1, 1);
    let values = grid.defaults().map_err(|e| e.to_string())?;
    let mut out = format!("{} \"{}\"\n", sh.kind, sh.name);
    for (&id, (_, value)) in sh.params.iter().zip(&values) {
        let v = &sh.vars[id];
        let output = matches!(v.kind, VarKind::Param { output: true, .. });
        let _ = writeln!(
            out,
            "    \"{}\" \"{}{} {}\"\n        default {}",
            v.name,
            if output { "output " } else { "" },
            v.detail.name(),
            v.ty,
            show(value)
        );
    }
    Ok(out)
}

/// A value as RIB would write it: a number, `[a b c]`, a quoted string, `{...}` for arrays.
fn show(v: &Value) -> String {
    match v {
        Value::Num(n) => {
            let lane: Vec<String> = n.data.iter().take(n.w).map(|x| format!("{x}")).collect();
            if lane.len() == 1 { lane[0].clone() } else { format!("[{}]", lane.join(" ")) }
        }
        Value::Str(s) => format!("\"{}\"", crate::error::OneLine(s)),
        Value::Array(items) => {
            format!("{{{}}}", items.iter().map(show).collect::<Vec<_>>().join(", "))
        }
    }
}
