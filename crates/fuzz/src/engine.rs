//! The fuzzing loop of one target, and the render child's supervision.
//!
//! A worker reads its seeds, runs each once, then repeats: pick an input of the corpus,
//! mutate it, run it, keep it in the corpus (and on disk) when it covered an edge or a hit
//! count class not seen before, save it under `crashes/` when it failed. Loader inputs run in
//! this process; before each, the input is written to `OUT/current-TARGET`, so that when the
//! worker dies (an abort, a stack overflow) or its watchdog ends it (a hang), the supervisor
//! (`reyes-fuzz fuzz`, src/main.rs) knows which input did it. A render input that loads runs in a child
//! process ([`render`]).
//!
//! Invariant: for a given seed, corpus and build the inputs tried are the same, in the same
//! order (coverage feedback included: it depends only on what ran).

use std::fs::{self, File};
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::time::{Duration, Instant};

use reyes_rib::Format;

use crate::coverage::{self, Map};
use crate::limits;
use crate::mutate::Mutator;
use crate::rng::Rng;
use crate::target::{self, Failure, Target, Verdict};

/// Exit code of a worker whose watchdog found an input running too long.
pub const HANG_EXIT: i32 = 77;

/// The longest input tried (bytes); seeds are cut to it.
pub const MAX_LEN: usize = 64 * 1024;

/// Grammar words every dictionary has, besides the corpus's own words.
const EXTRA_WORDS: &[&str] = &[
    "Some(",
    "None",
    "true",
    "false",
    "()",
    "[]",
    "(",
    ")",
    "[",
    "]",
    ",",
    ":",
    "\"\"",
    "AttributeBegin\n",
    "AttributeEnd\n",
    "TransformBegin\n",
    "TransformEnd\n",
    "WorldBegin\n",
    "WorldEnd\n",
    "FrameBegin 1\n",
    "FrameEnd\n",
    "MotionBegin [0 1]\n",
    "MotionEnd\n",
    "SolidBegin \"union\"\n",
    "SolidBegin \"primitive\"\n",
    "SolidEnd\n",
    "ObjectBegin 1\n",
    "ObjectEnd\n",
    "ObjectInstance 1\n",
];

/// How a worker runs.
#[derive(Debug, Clone)]
pub struct Options {
    /// What is fuzzed.
    pub target: Target,
    /// Executions of mutants (for renders: renders of mutants that load).
    pub execs: u64,
    /// The random seed.
    pub seed: u64,
    /// Folders of seed inputs, read in name order.
    pub seeds: Vec<PathBuf>,
    /// Where inputs that found new coverage are written (None: kept in memory only).
    pub save: Option<PathBuf>,
    /// The run's folder: `crashes/`, `current-TARGET`, the render child's scratch files.
    pub out: PathBuf,
    /// Longest one execution may take before it is a hang.
    pub timeout: Duration,
    /// Address-space cap of a render child, in bytes.
    pub memory: u64,
    /// Stop after this long even if `execs` are not done.
    pub time_limit: Option<Duration>,
    /// Print progress to stderr every few seconds.
    pub progress: bool,
    /// Where the report so far is written every two seconds (for the supervisor).
    pub status: Option<PathBuf>,
}

/// What a worker did.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// Executions, seeds included.
    pub execs: u64,
    /// Of which the scene was accepted (rendered, for renders).
    pub accepted: u64,
    /// Inputs that failed, with the file each was saved to (distinct panics, up to ten hangs
    /// and ten signals).
    pub failures: Vec<(Failure, PathBuf)>,
    /// Executions that failed, all of them.
    pub failing: u64,
    /// Inputs in the corpus at the end.
    pub corpus: usize,
    /// Their total size in bytes.
    pub corpus_bytes: usize,
    /// Edges covered (0 uninstrumented).
    pub edges: usize,
    /// Instrumented edges of the program (0 uninstrumented).
    pub edges_total: usize,
    /// Wall-clock time.
    pub elapsed: Duration,
    /// The seeds have all run (a worker that dies before is not restarted: it would die
    /// again on the same seed).
    pub seeded: bool,
}

impl Report {
    /// The report as `key value` lines (what a worker hands its supervisor).
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "seeded {}\nfailing {}\nexecs {}\naccepted {}\ncorpus {}\ncorpus_bytes {}\nedges {}\nedges_total {}\nseconds {:.3}\n",
            u8::from(self.seeded),
            self.failing,
            self.execs,
            self.accepted,
            self.corpus,
            self.corpus_bytes,
            self.edges,
            self.edges_total,
            self.elapsed.as_secs_f64()
        );
        for (f, path) in &self.failures {
            s += &format!(
                "failure {}\t{}\t{}\n",
                f.kind,
                path.display(),
                f.message.replace('\n', " ")
            );
        }
        s
    }

    /// Reads [`Report::to_text`] back.
    pub fn from_text(text: &str) -> Report {
        let mut r = Report::default();
        for line in text.lines() {
            let (key, value) = line.split_once(' ').unwrap_or((line, ""));
            let n = || value.trim().parse::<u64>().unwrap_or(0);
            match key {
                "seeded" => r.seeded = n() == 1,
                "execs" => r.execs = n(),
                "failing" => r.failing = n(),
                "accepted" => r.accepted = n(),
                "corpus" => r.corpus = n() as usize,
                "corpus_bytes" => r.corpus_bytes = n() as usize,
                "edges" => r.edges = n() as usize,
                "edges_total" => r.edges_total = n() as usize,
                "seconds" => {
                    r.elapsed = Duration::from_secs_f64(value.trim().parse().unwrap_or(0.0))
                }
                "failure" => {
                    let mut parts = value.splitn(3, '\t');
                    let kind = match parts.next().unwrap_or("") {
                        "panic" => "panic",
                        "bad-error" => "bad-error",
                        "signal" => "signal",
                        "hang" => "hang",
                        "abort" => "abort",
                        _ => "exit",
                    };
                    let path = PathBuf::from(parts.next().unwrap_or(""));
                    r.failures.push((Failure::new(kind, parts.next().unwrap_or("")), path));
                }
                _ => {}
            }
        }
        r
    }
}

/// The input files of `dirs`, in name order within each folder, cut to [`MAX_LEN`].
pub fn read_inputs(dirs: &[PathBuf]) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    for dir in dirs {
        let Ok(entries) = fs::read_dir(dir) else { continue };
        let mut paths: Vec<PathBuf> =
            entries.filter_map(|e| e.ok()).map(|e| e.path()).filter(|p| p.is_file()).collect();
        paths.sort();
        for p in paths {
            if let Ok(mut bytes) = fs::read(&p) {
                bytes.truncate(MAX_LEN);
                out.push((p, bytes));
            }
        }
    }
    out
}

/// A short stable name for an input (FNV-1a, 64 bits, in hex).
pub fn hash(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// The extension of an input's file: what [`target::detect`] makes of it.
fn extension(target: Target, input: &[u8]) -> &'static str {
    let format = match target {
        Target::Ron => Format::Ron,
        Target::Rib => Format::Rib,
        Target::Render => target::detect(input),
        Target::Sl => return "sl",
        Target::Tex => return "tex",
    };
    match format {
        Format::Ron => "ron",
        Format::Rib => "rib",
    }
}

/// Writes each input about to run to one file, for the supervisor to find after a crash.
struct Current(File);

impl Current {
    fn create(path: &Path) -> std::io::Result<Current> {
        File::create(path).map(Current)
    }

    fn set(&mut self, input: &[u8]) {
        let f = &mut self.0;
        let _ = f.seek(SeekFrom::Start(0)).and_then(|_| f.write_all(input));
        let _ = f.set_len(input.len() as u64);
    }
}

/// Ends the process with [`HANG_EXIT`] when one execution has used more CPU time than the
/// limit (CPU time, not wall-clock time: a machine shared with other work stalls processes
/// for seconds, and a stall is not a hang).
struct Watchdog {
    /// The process's CPU time when the current execution started (ns, +1), 0 when idle.
    started: Arc<AtomicU64>,
}

impl Watchdog {
    fn spawn(timeout: Duration) -> Watchdog {
        let started = Arc::new(AtomicU64::new(0));
        let s = Arc::clone(&started);
        std::thread::spawn(move || {
            loop {
                std::thread::sleep(Duration::from_millis(100));
                let t = s.load(Relaxed);
                let now = limits::cpu_time().as_nanos() as u64 + 1;
                if t != 0 && now.saturating_sub(t) > timeout.as_nanos() as u64 {
                    eprintln!("reyes-fuzz: an input used more than {timeout:?} of CPU: a hang");
                    std::process::exit(HANG_EXIT);
                }
            }
        });
        Watchdog { started }
    }

    fn start(&self) {
        self.started.store(limits::cpu_time().as_nanos() as u64 + 1, Relaxed);
    }

    fn stop(&self) {
        self.started.store(0, Relaxed);
    }
}

/// Runs one worker: the seeds, then `execs` mutants.
pub fn run(opts: &Options) -> std::io::Result<Report> {
    let start = Instant::now();
    let crashes = opts.out.join("crashes");
    fs::create_dir_all(&crashes)?;
    let scratch = opts.out.join(format!("scratch-{}", opts.target.name()));
    fs::create_dir_all(&scratch)?;
    if let Some(dir) = &opts.save {
        fs::create_dir_all(dir)?;
    }
    let mut current = Current::create(&opts.out.join(format!("current-{}", opts.target.name())))?;
    let watchdog = Watchdog::spawn(opts.timeout);
    target::quiet_panics();

    let seeds = read_inputs(&opts.seeds);
    let mut corpus: Vec<Vec<u8>> = Vec::new();
    let datas: Vec<Vec<u8>> = seeds.iter().map(|(_, b)| b.clone()).collect();
    let mutator = Mutator::new(&datas, EXTRA_WORDS, MAX_LEN);
    let mut rng = Rng::new(opts.seed);
    let mut map = Map::new();
    let mut report = Report { edges_total: coverage::edges_total(), ..Report::default() };
    let mut signatures: Vec<String> = Vec::new();
    let mut last_print = Instant::now();
    let mut last_progress = Instant::now();
    let child = Child { scratch: &scratch, timeout: opts.timeout, memory: opts.memory };

    // Runs one input: None when it was not run (a render input that does not load), else
    // whether it found new coverage and whether its scene was accepted.
    let mut exec = |input: &[u8], report: &mut Report, map: &mut Map| -> Option<(bool, bool)> {
        coverage::clear();
        let result = match opts.target {
            Target::Ron | Target::Rib => {
                let format = if opts.target == Target::Ron { Format::Ron } else { Format::Rib };
                current.set(input);
                watchdog.start();
                let r = target::run_in_process(format, input);
                watchdog.stop();
                let new = map.merge();
                r.map(|v| (v, new))
            }
            Target::Sl | Target::Tex => {
                current.set(input);
                watchdog.start();
                let r = if opts.target == Target::Sl {
                    target::run_sl(input)
                } else {
                    target::run_tex(input)
                };
                watchdog.stop();
                let new = map.merge();
                r.map(|v| (v, new))
            }
            Target::Render => {
                // Inputs that do not load are the loader targets' business: only scenes that
                // load are rendered (and counted).
                current.set(input);
                let format = target::detect(input);
                watchdog.start();
                let loaded = target::run_in_process(format, input);
                watchdog.stop();
                match loaded {
                    Ok(Verdict::Rejected) => {
                        coverage::clear();
                        return None;
                    }
                    Ok(Verdict::Accepted) => child.render(input).map(|(v, pairs)| {
                        coverage::clear();
                        (v, map.merge_pairs(&pairs))
                    }),
                    Err(f) => Err(f),
                }
            }
        };
        report.execs += 1;
        match result {
            Ok((verdict, new)) => {
                let accepted = verdict == Verdict::Accepted;
                report.accepted += u64::from(accepted);
                Some((new, accepted))
            }
            Err(failure) => {
                // Panics are told apart by their location: one input each. A hang or a signal
                // says nothing of where, so up to ten inputs of each are kept.
                report.failing += 1;
                let sig = failure.signature();
                let seen = signatures.iter().filter(|s| **s == sig).count();
                let keep =
                    if failure.kind == "panic" || failure.kind == "bad-error" { 1 } else { 10 };
                let path = crashes.join(format!(
                    "{}-{}-{}.{}",
                    opts.target.name(),
                    failure.kind,
                    hash(input),
                    extension(opts.target, input)
                ));
                if seen < keep {
                    eprintln!(
                        "reyes-fuzz: {}: {}: {}",
                        opts.target.name(),
                        failure.kind,
                        failure.message
                    );
                    eprintln!("reyes-fuzz: input saved to {}", path.display());
                    signatures.push(sig);
                    let _ = fs::write(&path, input);
                    report.failures.push((failure, path));
                }
                Some((false, false))
            }
        }
    };

    // Indices into `corpus` of the inputs whose scene was accepted: most parents are drawn from
    // these, since a mutant of a valid scene reaches the validator and the renderer far more
    // often than a mutant of a syntax error.
    let mut valid: Vec<usize> = Vec::new();
    for (_, input) in &seeds {
        if let Some((_, true)) = exec(input, &mut report, &mut map) {
            valid.push(corpus.len());
        }
        corpus.push(input.clone());
    }
    if corpus.is_empty() {
        corpus.push(Vec::new());
    }
    report.seeded = true;
    if let Some(status) = &opts.status {
        fs::write(status, report.to_text())?;
    }
    let mut done = 0u64;
    let mut tries = 0u64;
    while done < opts.execs {
        if opts.time_limit.is_some_and(|t| start.elapsed() > t) {
            break;
        }
        tries += 1;
        if tries > opts.execs.saturating_mul(1000).max(1000) {
            break; // nothing the mutator makes loads: give up rather than spin
        }
        let parent = if !valid.is_empty() && !rng.one_in(4) {
            corpus[*rng.pick(&valid)].as_slice()
        } else {
            // Of two inputs drawn, the shorter: short inputs run faster and mutate to the
            // point more often.
            let (a, b) = (&corpus[rng.below(corpus.len())], &corpus[rng.below(corpus.len())]);
            if a.len() <= b.len() { a } else { b }
        };
        let mutant = mutator.mutate(&mut rng, parent, &corpus);
        let Some((new, accepted)) = exec(&mutant, &mut report, &mut map) else { continue };
        done += 1;
        if new {
            if accepted {
                valid.push(corpus.len());
            }
            if let Some(dir) = &opts.save {
                let name = format!("{}.{}", hash(&mutant), extension(opts.target, &mutant));
                fs::write(dir.join(name), &mutant)?;
            }
            corpus.push(mutant);
        }
        if last_print.elapsed() > Duration::from_secs(2) {
            last_print = Instant::now();
            if let Some(status) = &opts.status {
                report.corpus = corpus.len();
                report.edges = map.edges();
                report.elapsed = start.elapsed();
                let _ = fs::write(status, report.to_text());
            }
        }
        if opts.progress && last_progress.elapsed() > Duration::from_secs(10) {
            last_progress = Instant::now();
            let secs = start.elapsed().as_secs_f64();
            eprintln!(
                "reyes-fuzz: {}: {} execs ({:.0}/s), corpus {}, edges {}/{}, failures {}",
                opts.target.name(),
                report.execs,
                report.execs as f64 / secs,
                corpus.len(),
                map.edges(),
                report.edges_total,
                report.failures.len()
            );
        }
    }
    current.set(b"");
    report.corpus = corpus.len();
    report.corpus_bytes = corpus.iter().map(Vec::len).sum();
    report.edges = map.edges();
    report.elapsed = start.elapsed();
    Ok(report)
}

/// How render children are run.
pub struct Child<'a> {
    /// Scratch folder: the input, the outputs, stderr, the coverage dump.
    pub scratch: &'a Path,
    /// CPU-time limit (the child's RLIMIT_CPU); the wall-clock limit is 30 times it, for
    /// a child that hangs without using the CPU (on a loaded machine a render waits
    /// for the CPU many times longer than it uses it).
    pub timeout: Duration,
    /// Address-space cap in bytes.
    pub memory: u64,
}

impl Child<'_> {
    /// Renders `input` in a child process (this program, `render-one`); with the child's
    /// coverage when instrumented.
    pub fn render(&self, input: &[u8]) -> Result<(Verdict, Vec<(u32, u8)>), Failure> {
        use std::os::unix::process::ExitStatusExt;
        let io = |e: std::io::Error| Failure::new("exit", format!("cannot run the child: {e}"));
        let file = self.scratch.join("input");
        let stderr_path = self.scratch.join("stderr");
        let cov = self.scratch.join("coverage");
        fs::write(&file, input).map_err(io)?;
        let _ = fs::remove_file(&cov);
        let exe = std::env::current_exe().map_err(io)?;
        let mut cmd = Command::new(exe);
        cmd.arg("render-one")
            .arg(&file)
            .arg(self.scratch)
            .arg(self.memory.to_string())
            .arg(self.timeout.as_secs().max(1).to_string());
        if coverage::instrumented() {
            cmd.arg(&cov);
        }
        let stderr = File::create(&stderr_path).map_err(io)?;
        let mut child = cmd
            .current_dir(self.scratch)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(stderr)
            .spawn()
            .map_err(io)?;
        let started = Instant::now();
        let mut nap = Duration::from_micros(200);
        let status = loop {
            if let Some(status) = child.try_wait().map_err(io)? {
                break Some(status);
            }
            if started.elapsed() > self.timeout * 30 {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            std::thread::sleep(nap);
            nap = (nap * 2).min(Duration::from_millis(20));
        };
        let err = fs::read_to_string(&stderr_path).unwrap_or_default();
        let pairs = fs::read(&cov).map(|b| coverage::parse(&b)).unwrap_or_default();
        let Some(status) = status else {
            return Err(Failure::new(
                "hang",
                format!("render ran longer than {:?} of wall-clock time", self.timeout * 30),
            ));
        };
        if status.signal() == Some(libc::SIGXCPU) {
            return Err(Failure::new(
                "hang",
                format!("render used more than {:?} of CPU time", self.timeout),
            ));
        }
        classify(status, &err).map(|v| (v, pairs))
    }
}

/// The verdict on a render child that exited with `status` after writing `stderr`.
pub fn classify(status: ExitStatus, stderr: &str) -> Result<Verdict, Failure> {
    use std::os::unix::process::ExitStatusExt;
    let first = |s: &str| s.lines().find(|l| !l.trim().is_empty()).unwrap_or("").to_string();
    if let Some(sig) = status.signal() {
        let name = match sig {
            libc::SIGABRT => "SIGABRT",
            libc::SIGSEGV => "SIGSEGV",
            libc::SIGKILL => "SIGKILL",
            libc::SIGXCPU => "SIGXCPU",
            libc::SIGBUS => "SIGBUS",
            libc::SIGILL => "SIGILL",
            _ => "signal",
        };
        return Err(Failure::new("signal", format!("{name} ({sig}): {}", first(stderr))));
    }
    match status.code() {
        Some(0) => Ok(Verdict::Accepted),
        Some(101) => {
            let at = stderr
                .lines()
                .position(|l| l.contains("panicked at"))
                .map(|i| {
                    let head = stderr.lines().nth(i).unwrap_or("");
                    let loc = head.split("panicked at ").nth(1).unwrap_or("").trim_end_matches(':');
                    let msg = stderr.lines().nth(i + 1).unwrap_or("");
                    format!("{loc}: {msg}")
                })
                .unwrap_or_else(|| first(stderr));
            Err(Failure::new("panic", at))
        }
        Some(c @ (1 | 2)) => {
            let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
            if lines.len() == 1 {
                Ok(Verdict::Rejected)
            } else {
                Err(Failure::new(
                    "bad-error",
                    format!("exit {c} with {} lines of stderr: {:?}", lines.len(), stderr),
                ))
            }
        }
        Some(c) => Err(Failure::new("exit", format!("exit {c}: {}", first(stderr)))),
        None => Err(Failure::new("exit", "no exit status")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::process::ExitStatusExt;

    #[test]
    fn children_are_judged_by_status_and_stderr() {
        let exit = |c: i32| ExitStatus::from_raw(c << 8);
        assert_eq!(classify(exit(0), ""), Ok(Verdict::Accepted));
        assert_eq!(classify(exit(2), "x.ron:1:1: bad\n"), Ok(Verdict::Rejected));
        assert_eq!(classify(exit(1), "render: out of memory\n"), Ok(Verdict::Rejected));
        assert_eq!(classify(exit(1), "").unwrap_err().kind, "bad-error");
        assert_eq!(classify(exit(2), "a\nb\n").unwrap_err().kind, "bad-error");
        assert_eq!(classify(exit(3), "").unwrap_err().kind, "exit");
        let panic = "thread 'main' panicked at crates/a/src/b.rs:3:9:\nindex out of bounds\n";
        let f = classify(exit(101), panic).unwrap_err();
        assert_eq!(
            (f.kind, f.message.as_str()),
            ("panic", "crates/a/src/b.rs:3:9: index out of bounds")
        );
        let f = classify(ExitStatus::from_raw(libc::SIGABRT), "").unwrap_err();
        assert_eq!(f.kind, "signal");
        assert!(f.message.starts_with("SIGABRT"), "{}", f.message);
    }

    #[test]
    fn reports_read_back() {
        let r = Report {
            execs: 10,
            accepted: 4,
            failures: vec![(Failure::new("panic", "a.rs:1: x"), PathBuf::from("c/x.ron"))],
            corpus: 3,
            corpus_bytes: 300,
            edges: 7,
            edges_total: 70,
            elapsed: Duration::from_millis(1500),
            seeded: true,
            failing: 2,
        };
        let back = Report::from_text(&r.to_text());
        assert_eq!(back.to_text(), r.to_text());
    }

    #[test]
    fn hashes_are_stable_names() {
        assert_eq!(hash(b""), "cbf29ce484222325");
        assert_ne!(hash(b"a"), hash(b"b"));
    }
}
