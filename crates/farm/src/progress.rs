//! Progress of a frame as plain lines, in a fixed format that a farm manager parses
//! (docs/farm.md), and the estimate of the time left:
//!
//! ```text
//! progress: [frame F ][tile I/N ]P% (D/T buckets) HH:MM:SS elapsed HH:MM:SS left
//! ```
//!
//! `P` is `floor(100 D / T)`, `D` the buckets finished (those resumed from a checkpoint
//! included), `T` the buckets this run draws. The time left ([`Estimator`]) is the mean time
//! of the buckets rendered in this run applied to those remaining, `--:--:--` until one is
//! done. [`ProgressLines`] gives a line when
//! `every` has passed since the last one (on the next bucket to finish), and a last one at
//! 100% if any was given, so a render shorter than `every` has none.
//!
//! Invariant: progress never changes what is rendered; every function here takes the time
//! as an argument, so the lines and the estimate are functions of the buckets' finishing
//! times alone.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::Tile;

/// The estimate of a frame's time left, from the buckets this run renders.
#[derive(Debug, Clone)]
pub struct Estimator {
    total: u64,
    resumed: u64,
    done: u64,
    started: Instant,
}

impl Estimator {
    /// A frame of `total` buckets of which `resumed` were read back from a checkpoint, whose
    /// run started at `started`.
    pub fn new(total: u64, resumed: u64, started: Instant) -> Estimator {
        let resumed = resumed.min(total);
        Estimator { total, resumed, done: resumed, started }
    }

    /// One more bucket of this run finished, at `at`.
    pub fn bucket_done(&mut self, _at: Instant) {
        self.done += 1;
    }

    /// The buckets finished, those resumed included.
    pub fn done(&self) -> u64 {
        self.done
    }

    /// The buckets this run draws.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// The time since the run started.
    pub fn elapsed(&self, now: Instant) -> Duration {
        now.saturating_duration_since(self.started)
    }

    /// The time left at `now`: the mean time of the buckets this run rendered times those
    /// remaining; None until one is rendered.
    pub fn left(&self, now: Instant) -> Option<Duration> {
        let rendered = self.done - self.resumed;
        (rendered > 0).then(|| {
            let per_bucket = self.elapsed(now).as_secs_f64() / rendered as f64;
            Duration::from_secs_f64(per_bucket * self.total.saturating_sub(self.done) as f64)
        })
    }

    /// The progress line at `now`, labelled `label` ([`label`]).
    pub fn line(&self, label: &str, now: Instant) -> String {
        format_line(label, self.done, self.total, self.elapsed(now), self.left(now))
    }
}

/// The label of a frame's lines: `frame F ` for a numbered frame, `tile I/N ` for a tile,
/// both, or nothing.
pub fn label(frame: Option<i32>, tile: Option<Tile>) -> String {
    let mut label = String::new();
    if let Some(n) = frame {
        label.push_str(&format!("frame {n} "));
    }
    if let Some(t) = tile {
        label.push_str(&format!("tile {t} "));
    }
    label
}

/// The text of one progress line (after the program's `reyes-render: `).
pub fn format_line(
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

/// `HH:MM:SS` (hours may run past two digits).
pub fn clock(d: Duration) -> String {
    let s = d.as_secs();
    format!("{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
}

/// An interval between lines as text: seconds, from 0 to 86400 (a day).
pub fn parse_every(s: &str) -> Result<Duration, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..=86400.0).contains(&v) => Ok(Duration::from_secs_f64(v)),
        _ => Err(format!("expected seconds from 0 to 86400, got '{s}'")),
    }
}

/// The plain lines of one frame, from any thread: which to print, and when.
pub struct ProgressLines {
    label: String,
    every: Duration,
    state: Mutex<LinesState>,
}

struct LinesState {
    estimator: Estimator,
    last: Instant,
    printed: bool,
}

impl ProgressLines {
    /// Lines labelled `label` over `total` buckets of which `resumed` are done already, one
    /// every `every` at most, for a run that started at `now`.
    pub fn new(label: String, total: u64, resumed: u64, every: Duration, now: Instant) -> Self {
        let estimator = Estimator::new(total, resumed, now);
        ProgressLines {
            label,
            every,
            state: Mutex::new(LinesState { estimator, last: now, printed: false }),
        }
    }

    /// One more bucket finished, at `now`: the line to print, if `every` has passed since
    /// the last one and buckets remain (the 100% line is [`ProgressLines::finish`]'s).
    pub fn tick(&self, now: Instant) -> Option<String> {
        let mut s = self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        s.estimator.bucket_done(now);
        if now.saturating_duration_since(s.last) < self.every
            || s.estimator.done() >= s.estimator.total()
        {
            return None;
        }
        s.last = now;
        s.printed = true;
        Some(s.estimator.line(&self.label, now))
    }

    /// The frame is rendered, at `now`: the 100% line, if any line was printed.
    pub fn finish(&self, now: Instant) -> Option<String> {
        let s = self.state.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let e = &s.estimator;
        (s.printed && e.done() >= e.total()).then(|| e.line(&self.label, now))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn lines_have_the_documented_form() {
        let l = format_line(
            &label(Some(12), Some(Tile { index: 3, count: 7 })),
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
        assert_eq!(clock(Duration::from_secs(101 * 3600 + 42)), "101:00:42");
    }

    #[test]
    fn lines_come_every_interval_and_end_at_100_percent() {
        let t0 = Instant::now();
        let lines = ProgressLines::new("tile 2/3 ".into(), 3, 0, 10 * MS, t0);
        assert_eq!(lines.tick(t0 + 5 * MS), None, "within the interval");
        let l = lines.tick(t0 + 20 * MS).expect("a line");
        assert!(l.starts_with("progress: tile 2/3 66% (2/3 buckets)"), "{l}");
        assert_eq!(lines.tick(t0 + 40 * MS), None, "the last bucket's line is finish's");
        let l = lines.finish(t0 + 41 * MS).expect("the 100% line");
        assert_eq!(l, "progress: tile 2/3 100% (3/3 buckets) 00:00:00 elapsed 00:00:00 left");
        let quiet = ProgressLines::new(String::new(), 1, 0, Duration::from_secs(5), t0);
        assert_eq!(quiet.tick(t0 + MS), None);
        assert_eq!(quiet.finish(t0 + MS), None, "no line printed, so no 100% line");
    }
}
