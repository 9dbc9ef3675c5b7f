//! Progress of a frame as plain lines, in a fixed format that a farm manager parses
//! (docs/farm.md), and the estimate of the time left:
//!
//! ```text
//! progress: [frame F ][tile I/N ]P% (D/T buckets) HH:MM:SS elapsed HH:MM:SS left
//! ```
//!
//! `P` is `floor(100 D / T)`, `D` the buckets finished (those resumed from a checkpoint
//! included), `T` the buckets this run draws. The time left ([`Estimator`]) is the rate at
//! which this run finishes buckets applied to those remaining; buckets resumed from a
//! checkpoint count toward `D` and never toward the rate. [`ProgressLines`] gives a line when
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
///
/// A resumed frame's first bucket finishes only after the render has set up and diced its
/// way through the rows the checkpoint already holds, which may take far longer than
/// rendering a bucket; so the rate is measured from this run's first finished bucket on:
/// the buckets finished since then over the time since then. With only that first bucket,
/// a fresh frame's estimate is its time per bucket (set-up included, all there is to go
/// by); a resumed frame has none yet.
#[derive(Debug, Clone)]
pub struct Estimator {
    total: u64,
    resumed: u64,
    done: u64,
    started: Instant,
    /// When this run's first bucket finished.
    first: Option<Instant>,
}

impl Estimator {
    /// A frame of `total` buckets of which `resumed` were read back from a checkpoint, whose
    /// run started at `started`.
    pub fn new(total: u64, resumed: u64, started: Instant) -> Estimator {
        let resumed = resumed.min(total);
        Estimator { total, resumed, done: resumed, started, first: None }
    }

    /// One more bucket of this run finished, at `at`.
    pub fn bucket_done(&mut self, at: Instant) {
        self.done += 1;
        self.first.get_or_insert(at);
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

    /// The time left at `now`: zero once every bucket is done; None until there is a rate
    /// to go by.
    pub fn left(&self, now: Instant) -> Option<Duration> {
        let remaining = self.total.saturating_sub(self.done);
        if remaining == 0 {
            return Some(Duration::ZERO);
        }
        let first = self.first?;
        let rendered = self.done - self.resumed;
        let per_bucket = if rendered >= 2 {
            now.saturating_duration_since(first).as_secs_f64() / (rendered - 1) as f64
        } else if self.resumed == 0 {
            first.saturating_duration_since(self.started).as_secs_f64()
        } else {
            return None;
        };
        Some(Duration::from_secs_f64(per_bucket * remaining as f64))
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

    /// The case reported after a resume: 634 of 1271 buckets read back, 1.62 s spent
    /// setting up and dicing the rows the checkpoint held before this run's first bucket
    /// finished, then a bucket every 4.7 ms (3 s for the rest). The first line said
    /// `00:17:09 left`, the catch-up time charged to one bucket and multiplied by 636.
    #[test]
    fn after_a_resume_the_rate_is_of_this_runs_buckets_alone() {
        let t0 = Instant::now();
        let mut e = Estimator::new(1271, 634, t0);
        assert_eq!(e.done(), 634);
        assert_eq!(e.left(t0), None, "nothing rendered yet");
        let first = t0 + 1620 * MS;
        e.bucket_done(first);
        assert_eq!(
            e.line("", first),
            "progress: 49% (635/1271 buckets) 00:00:01 elapsed --:--:-- left",
            "one bucket after the catch-up is no rate"
        );
        let mut now = first;
        for _ in 0..10 {
            now += Duration::from_micros(4700);
            e.bucket_done(now);
        }
        assert_eq!(e.done(), 645);
        let left = e.left(now).expect("a rate").as_secs_f64();
        assert!((left - 626.0 * 0.0047).abs() < 1e-6, "{left}");
        assert_eq!(
            e.line("", now),
            "progress: 50% (645/1271 buckets) 00:00:01 elapsed 00:00:02 left"
        );
        // The buckets read back never count toward the rate: the same run without them
        // left would see the same time per bucket.
        let mut fresh = Estimator::new(637, 0, t0);
        let mut now = first;
        fresh.bucket_done(now);
        for _ in 0..10 {
            now += Duration::from_micros(4700);
            fresh.bucket_done(now);
        }
        assert_eq!(fresh.left(now), e.left(now));
    }

    #[test]
    fn a_fresh_frame_estimates_from_its_first_bucket() {
        let t0 = Instant::now();
        let mut e = Estimator::new(10, 0, t0);
        let secs = |d: Option<Duration>| d.expect("an estimate").as_secs_f64();
        e.bucket_done(t0 + 200 * MS);
        assert!((secs(e.left(t0 + 200 * MS)) - 1.8).abs() < 1e-6, "200 ms a bucket, 9 left");
        e.bucket_done(t0 + 300 * MS);
        assert!((secs(e.left(t0 + 300 * MS)) - 0.8).abs() < 1e-6, "100 ms a bucket since");
        for k in 0..8 {
            e.bucket_done(t0 + (400 + 100 * k) * MS);
        }
        assert_eq!(e.left(t0 + 1100 * MS), Some(Duration::ZERO));
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
