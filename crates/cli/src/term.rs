//! Everything the command prints goes through here, so that no write to a closed pipe or a
//! full device can panic (as `println!` and `eprintln!` do), the progress display included.
//!
//! Standard output: a closed pipe (`| head -0`) ends the printing quietly, any other failure
//! (`> /dev/full`) becomes a one-line error with exit code 1. Standard error: failures are
//! ignored, as there is nowhere left to report them. Progress: a bar on a terminal
//! (percentage, rate, time left), else reyes-farm's plain lines (docs/farm.md,
//! [`reyes_farm::progress`]), nothing with `--quiet`; it never changes what is rendered, and
//! the bar is cleared from the terminal however the frame ends.

use std::fmt::Display;
use std::io::{ErrorKind, IsTerminal, Write};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use reyes_farm::{FrameJob, ProgressLines};

use crate::Exit;
use crate::args::Args;

/// Print `text` to standard output and flush it. A reader that went away is not an error
/// (the output is simply not wanted); any other failure is, naming standard output.
pub(crate) fn print(text: &str) -> Result<(), Exit> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) => stdout_failed(e),
    }
}

/// What a failed write to standard output means: quiet for a closed pipe, exit 1 otherwise.
pub(crate) fn stdout_failed(e: std::io::Error) -> Result<(), Exit> {
    match e.kind() {
        ErrorKind::BrokenPipe => Ok(()),
        _ => Err(Exit::error(1, format_args!("standard output: {e}"))),
    }
}

/// One line `reyes-render: LINE` on standard error, if it can be written at all; one line
/// whatever a path in it holds: control characters are written escaped
/// ([`reyes_farm::one_line`]).
pub(crate) fn say(line: impl Display) {
    let _ = writeln!(std::io::stderr().lock(), "reyes-render: {}", reyes_farm::one_line(line));
}

/// How a frame shows its progress: nothing (`--quiet`), a bar on a terminal, or plain lines.
pub(crate) enum Progress {
    None,
    Bar(ProgressBar),
    Lines(ProgressLines),
}

impl Progress {
    /// The progress of `job`'s frame, as `args` ask: its buckets to render, those resumed
    /// from a checkpoint already done.
    pub(crate) fn new(args: &Args, job: &FrameJob) -> Progress {
        let (label, total, resumed) = (job.label(), job.total(), job.resumed());
        if args.quiet {
            return Progress::None;
        }
        if !std::io::stderr().is_terminal() {
            let (every, now) = (args.progress_every, Instant::now());
            return Progress::Lines(ProgressLines::new(label, total, resumed, every, now));
        }
        let bar = ProgressBar::new(total);
        let template =
            "{bar:40} {percent:>3}% {pos}/{len} buckets {per_sec} {elapsed} elapsed, {eta} left";
        if let Ok(style) = ProgressStyle::with_template(&format!("{label}{template}")) {
            bar.set_style(style);
        }
        bar.set_position(resumed);
        bar.reset_eta();
        Progress::Bar(bar)
    }

    /// One more bucket finished.
    pub(crate) fn tick(&self) {
        match self {
            Progress::None => {}
            Progress::Bar(b) => b.inc(1),
            Progress::Lines(l) => l.tick(Instant::now()).into_iter().for_each(say),
        }
    }

    /// The frame ended, `rendered` or not: the 100% line if it was and lines were printed.
    pub(crate) fn finish(self, rendered: bool) {
        if let (Progress::Lines(l), true) = (&self, rendered) {
            l.finish(Instant::now()).into_iter().for_each(say);
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Progress::Bar(b) = self {
            b.finish_and_clear();
        }
    }
}
