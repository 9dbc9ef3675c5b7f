//! `Procedural "RunProgram"` (Spec 3.2, 5.7): a helper program writes RIB for the
//! procedural, read in place.
//!
//! Protocol: the program, looked up along `Option "searchpath" "procedural"` (else next to
//! the file naming it, else by the system's `PATH` for a bare name), is started with the
//! words of the first string as its arguments (split at white space; no shell). It gets one
//! line `detail datablock\n` on its standard input, `detail` the raster area of the
//! procedural's bound (as `DetailRange` measures it) and `datablock` the second string, and
//! writes RIB to its standard output ended by the byte `\377` (0xff). Then its standard
//! input is closed (a program that loops over requests ends at end of input) and it is
//! waited for (stopped if still running 5 seconds later). One program run per request.
//! A program that never writes the end byte nor ends holds the reading up.
//!
//! Invariants: nothing is run unless [`super::Permissions::run_program`] is set: a scene
//! file naming a program is a security decision for the person rendering it. The RIB it
//! writes is read as an archive named `RunProgram "program"`, at the procedural's place.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use glam::DVec3;

use super::detail::raster_area;
use super::frame::Machine;
use super::search::{Kind, Lookup};
use crate::{Request, RibError, Source};

/// The byte that ends a program's answer.
const END: u8 = 0xff;
/// How long a program may run on after its answer once its input is closed.
const LINGER: std::time::Duration = std::time::Duration::from_secs(5);

impl Machine {
    /// `Procedural "RunProgram" ["program args" "datablock"] [bound]`.
    pub(super) fn run_program(&mut self, r: &Request) -> Result<(), RibError> {
        let args = r.strings(1).unwrap_or(&[]);
        let (Some(command), data) = (args.first(), args.get(1).map_or("", String::as_str)) else {
            return Err(r.error("RunProgram needs the program and its data block"));
        };
        let mut words = command.split_whitespace();
        let Some(program) = words.next() else {
            return Err(r.error("RunProgram needs a program name"));
        };
        if !self.permissions.run_program {
            return Err(r.error(format!(
                "\"RunProgram\" would run the program {}, and running programs named by a \
                 scene is off: allow it with --allow-run-program",
                crate::error::quote(program)
            )));
        }
        let bound = match r.floats(2) {
            Some(b) if b.len() == 6 && b.iter().all(|v| v.is_finite()) => b,
            _ => return Err(r.error("expected a bound of 6 finite numbers")),
        };
        let m = self.to_world().at(f32::NEG_INFINITY);
        let corners = std::array::from_fn(|i: usize| {
            let p = DVec3::new(
                f64::from(bound[i & 1]),
                f64::from(bound[2 + ((i >> 1) & 1)]),
                f64::from(bound[4 + ((i >> 2) & 1)]),
            );
            m.project_point3(p).to_array()
        });
        let detail = raster_area(&corners, &self.frame_options)
            * f64::from(self.frame_options.relative_detail);
        let path = self.program_path(program, r);
        let rib = run(&path, words, &format!("{detail} {data}\n"))
            .map_err(|why| r.error(format!("program {}: {why}", crate::error::quote(program))))?;
        let name = format!("RunProgram \"{program}\"");
        let depth = self.reader.depth() + 1;
        self.reader.push_source(Source::from_bytes(&name, rib), &r.at)?;
        while let Some(q) = self.reader.next_request_within(depth)? {
            self.warnings.extend(self.reader.take_warnings());
            self.request(q)?;
        }
        self.warnings.extend(self.reader.take_warnings());
        Ok(())
    }

    /// The program `name`: along the procedural search path, else next to the file naming
    /// it when it is there, else `name` itself (a bare name is then found along `PATH`).
    fn program_path(&self, name: &str, r: &Request) -> PathBuf {
        let reader = &self.reader;
        let found = self
            .frame_options
            .search
            .find(Kind::Procedural, name, |n| reader.resolve_archive(n, &r.at));
        match found {
            Lookup::Found(p) => p,
            Lookup::Unsearched(p) | Lookup::Missing(p, _) if p.is_file() => p,
            _ => PathBuf::from(name),
        }
    }
}

/// Runs `program` with `args`, writes `request` to it and returns what it writes before the
/// end byte.
fn run<'a>(
    program: &Path,
    args: impl Iterator<Item = &'a str>,
    request: &str,
) -> Result<Vec<u8>, String> {
    let mut child = Command::new(program)
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .map_err(|e| format!("cannot be started: {e}"))?;
    let mut stdin = child.stdin.take().ok_or("has no standard input")?;
    let mut stdout = child.stdout.take().ok_or("has no standard output")?;
    // A program that ends without reading its input breaks the pipe: its answer still counts.
    let _ = stdin.write_all(request.as_bytes()).and_then(|()| stdin.flush());
    let mut rib = Vec::new();
    let mut chunk = [0u8; 8192];
    let ended = loop {
        let n = match stdout.read(&mut chunk) {
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(format!("cannot be read: {e}")),
        };
        if n == 0 {
            break false;
        }
        if let Some(i) = chunk[..n].iter().position(|&b| b == END) {
            rib.extend_from_slice(&chunk[..i]);
            break true;
        }
        rib.extend_from_slice(&chunk[..n]);
    };
    drop(stdin);
    drop(stdout);
    // Its answer is in: a program that does not end at the end of its input within
    // `LINGER` is stopped.
    let deadline = std::time::Instant::now() + LINGER;
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status.to_string(),
            Ok(None) if std::time::Instant::now() < deadline => {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            Ok(None) => {
                let _ = child.kill();
                let _ = child.wait();
                break "stopped after its answer".to_string();
            }
            Err(e) => return Err(format!("cannot be waited for: {e}")),
        }
    };
    if !ended {
        return Err(format!("ended ({status}) without the end byte \\377 after its RIB"));
    }
    Ok(rib)
}
