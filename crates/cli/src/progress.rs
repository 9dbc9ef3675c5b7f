//! Progress of a frame: a bar on a terminal (percentage, rate, time left), and elsewhere
//! (a farm's log) plain lines in a fixed format that a farm manager parses (docs/farm.md):
//!
//! ```text
//! reyes-render: progress: [frame F ][tile I/N ]P% (D/T buckets) HH:MM:SS elapsed HH:MM:SS left
//! ```
//!
//! `P` is `floor(100 D / T)`, `D` the buckets finished (those resumed from a checkpoint
//! included), `T` the buckets this run draws; the time left is the rate of the buckets
//! rendered in this run applied to those remaining, `--:--:--` until one is done. A line is
//! printed when `every` has passed since the last one (on the next bucket to finish), and a
//! last one at 100% if any was printed, so a render shorter than `every` prints none.
//!
//! Invariant: progress never changes what is rendered; it is cleared from a terminal however
//! the frame ends.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

use crate::term::say;

/// How a frame shows its progress.
pub(crate) enum Progress {
    /// Nothing (`--quiet`).
    None,
    /// A bar on the terminal.
    Bar(ProgressBar),
    /// Plain lines.
    Lines(Mutex<Lines>),
}

/// The state of the plain lines.
pub(crate) struct Lines {
    label: String,
    total: u64,
    done: u64,
    resumed: u64,
    started: Instant,
    last: Instant,
    every: Duration,
    printed: bool,
}

impl Progress {
    /// Progress over `total` buckets of which `resumed` are done already, labelled `label`
    /// (`frame 3 tile 2/4 `, or empty): a bar when `terminal`, else lines every `every`.
    pub(crate) fn new(
        quiet: bool,
        terminal: bool,
        label: String,
        total: u64,
        resumed: u64,
        every: Duration,
    ) -> Progress {
        if quiet {
            return Progress::None;
        }
        if terminal {
            let bar = ProgressBar::new(total);
            let template = "{bar:40} {percent:>3}% {pos}/{len} buckets {per_sec} {elapsed} elapsed, {eta} left";
            if let Ok(style) = ProgressStyle::with_template(&format!("{label}{template}")) {
                bar.set_style(style);
            }
            bar.set_position(resumed);
            bar.reset_eta();
            return Progress::Bar(bar);
        }
        let now = Instant::now();
        Progress::Lines(Mutex::new(Lines {
            label,
            total,
            done: resumed,
            resumed,
            started: now,
            last: now,
            every,
            printed: false,
        }))
    }

    /// One more bucket finished.
    pub(crate) fn tick(&self) {
        match self {
            Progress::None => {}
            Progress::Bar(b) => b.inc(1),
            Progress::Lines(m) => {
                let mut l = m.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
                l.done += 1;
                let now = Instant::now();
                if now.duration_since(l.last) >= l.every && l.done < l.total {
                    l.last = now;
                    l.printed = true;
                    say(l.line(now));
                }
            }
        }
    }

    /// The frame is rendered: clear the bar, or print the 100% line if lines were printed.
    pub(crate) fn finish(&self) {
        if let Progress::Lines(m) = self {
            let l = m.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            if l.printed && l.done >= l.total {
                say(l.line(Instant::now()));
            }
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

impl Lines {
    fn line(&self, now: Instant) -> String {
        let elapsed = now.duration_since(self.started);
        let rendered = self.done - self.resumed;
        let left = (rendered > 0).then(|| {
            let per = elapsed.as_secs_f64() / rendered as f64;
            Duration::from_secs_f64(per * (self.total - self.done.min(self.total)) as f64)
        });
        format_line(&self.label, self.done, self.total, elapsed, left)
    }
}

/// The text of one progress line (after `reyes-render: `).
pub(crate) fn format_line(
    label: &str,
    done: u64,
    total: u64,
    elapsed: Duration,
    left: Option<Duration>,
) -> String {
    let pct = (done * 100).checked_div(total).unwrap_or(100).min(100);
    let left = left.map_or_else(|| "--:--:--".to_string(), clock);
    format!(
        "progress: {label}{pct}% ({done}/{total} buckets) {} elapsed {left} left",
        clock(elapsed)
    )
}

/// `HH:MM:SS` (hours may exceed two digits).
fn clock(d: Duration) -> String {
    let s = d.as_secs();
    format!("{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_have_the_documented_form() {
        let l = format_line(
            "frame 12 tile 3/7 ",
            120,
            324,
            Duration::from_secs(42),
            Some(Duration::from_secs(72)),
        );
        assert_eq!(
            l,
            "progress: frame 12 tile 3/7 37% (120/324 buckets) 00:00:42 elapsed 00:01:12 left"
        );
        let l = format_line("", 0, 5, Duration::from_secs(3725), None);
        assert_eq!(l, "progress: 0% (0/5 buckets) 01:02:05 elapsed --:--:-- left");
    }
}
