//! The `reyes-fuzz` command (run by `cargo xtask fuzz`; see docs/reliability.md, "Fuzzing").
//!
//! ```text
//! reyes-fuzz [fuzz] [--targets ron,rib,render,sl,tex] [--execs N] [--renders N] [--seed S]
//!            [--corpus DIR] [--out DIR] [--save] [--timeout SECS] [--memory MIB]
//!            [--time-limit SECS] [--quiet]
//! reyes-fuzz replay TARGET FILE...
//! reyes-fuzz cmin TARGET FROM_DIR... --into DIR
//! ```
//!
//! `fuzz` supervises one worker process per target (this program, `worker`): a worker that
//! dies or hangs is a failure of the input it was running, which is saved, and a new worker
//! goes on with the executions left. Exit code 0 when nothing failed, 1 when something did,
//! 2 for usage errors. `replay` runs inputs once each (the regression tests use it), `cmin`
//! keeps the smallest inputs that together cover every edge the given ones cover (an
//! instrumented build only). `render-one` is the render child.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{Duration, Instant};

use reyes_fuzz::coverage;
use reyes_fuzz::engine::{self, Child, HANG_EXIT, Options, Report};
use reyes_fuzz::target::{self, Failure, Target, Verdict};
use reyes_fuzz::{limits, rng::Rng};

const USAGE: &str = "usage: reyes-fuzz [fuzz] [--targets ron,rib,render,sl,tex] [--execs N] [--renders N] \
[--seed S] [--corpus DIR] [--out DIR] [--save] [--timeout SECS] [--memory MIB] [--time-limit SECS] \
[--quiet] | replay TARGET FILE... | cmin TARGET DIR... --into DIR";

/// Workers restarted after a crash, at most, per target.
const MAX_RESTARTS: u32 = 20;

/// The options of `fuzz` (and of its workers).
#[derive(Debug, Clone)]
struct Args {
    targets: Vec<Target>,
    execs: u64,
    renders: u64,
    seed: u64,
    corpus: PathBuf,
    out: PathBuf,
    save: bool,
    timeout: u64,
    memory_mib: u64,
    time_limit: Option<u64>,
    quiet: bool,
}

impl Default for Args {
    fn default() -> Args {
        Args {
            targets: vec![Target::Ron, Target::Rib, Target::Render, Target::Sl, Target::Tex],
            execs: 100_000,
            renders: 1_000,
            seed: 1,
            corpus: PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus"),
            out: PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/fuzz/out"),
            save: false,
            timeout: 10,
            memory_mib: 2048,
            time_limit: None,
            quiet: false,
        }
    }
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut a = Args::default();
    let mut it = args.iter();
    while let Some(flag) = it.next() {
        let mut value = || it.next().cloned().ok_or_else(|| format!("{flag} needs a value"));
        let number = |v: String| v.parse::<u64>().map_err(|_| format!("{flag}: not a number: {v}"));
        match flag.as_str() {
            "--targets" => {
                a.targets = value()?
                    .split(',')
                    .map(|t| Target::parse(t).ok_or_else(|| format!("unknown target {t}")))
                    .collect::<Result<_, _>>()?
            }
            "--execs" => a.execs = number(value()?)?,
            "--renders" => a.renders = number(value()?)?,
            "--seed" => a.seed = number(value()?)?,
            "--corpus" => a.corpus = PathBuf::from(value()?),
            "--out" => a.out = PathBuf::from(value()?),
            "--save" => a.save = true,
            "--timeout" => a.timeout = number(value()?)?.max(1),
            "--memory" => a.memory_mib = number(value()?)?,
            "--time-limit" => a.time_limit = Some(number(value()?)?),
            "--quiet" => a.quiet = true,
            _ => return Err(format!("unknown argument {flag}")),
        }
    }
    Ok(a)
}

/// The seed folders of a target: the hand-picked seeds (`seeds/ron`, `seeds/rib`,
/// `seeds/sl`, never minimised away) and what earlier runs found (`ron`, `rib`, `render`,
/// `sl`, minimised by `cmin`); renders start from all of the scenes.
fn seed_dirs(corpus: &Path, target: Target) -> Vec<PathBuf> {
    let dirs: &[&str] = match target {
        Target::Ron => &["seeds/ron", "ron"],
        Target::Rib => &["seeds/rib", "rib"],
        Target::Render => &["seeds/ron", "seeds/rib", "ron", "rib", "render"],
        Target::Sl => &["seeds/sl", "sl"],
        Target::Tex => &["seeds/tex", "tex"],
    };
    dirs.iter().map(|d| corpus.join(d)).collect()
}

/// Where a run writes the inputs that found new coverage: the corpus itself with `--save`,
/// else `OUT/new-TARGET`.
fn save_dir(a: &Args, target: Target) -> PathBuf {
    if a.save { a.corpus.join(target.name()) } else { a.out.join(format!("new-{}", target.name())) }
}

/// A worker's options. Its seeds include what this run has saved so far, so that a worker
/// started after one died goes on from the coverage reached.
fn options(a: &Args, target: Target, execs: u64, seed: u64) -> Options {
    let mut seeds = seed_dirs(&a.corpus, target);
    if target == Target::Sl {
        // The standard shaders the renderer ships are seeds too (not copied into the corpus).
        seeds.push(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../sl/shaders"));
    }
    let save = save_dir(a, target);
    if !seeds.contains(&save) {
        seeds.push(save.clone());
    }
    Options {
        target,
        execs,
        seed,
        seeds,
        save: Some(save),
        out: a.out.clone(),
        timeout: Duration::from_secs(a.timeout),
        memory: a.memory_mib << 20,
        time_limit: a.time_limit.map(Duration::from_secs),
        progress: !a.quiet,
        status: Some(a.out.join(format!("status-{}", target.name()))),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let code = match args.first().map(String::as_str) {
        Some("worker") => worker(&args[1..]),
        Some("render-one") => render_one(&args[1..]),
        Some("replay") => replay(&args[1..]),
        Some("cmin") => cmin(&args[1..]),
        Some("fuzz") => fuzz(&args[1..]),
        Some("--help" | "-h" | "help") => {
            println!("{USAGE}");
            Ok(0)
        }
        _ => fuzz(&args),
    };
    match code {
        Ok(c) => ExitCode::from(c),
        Err(e) => {
            eprintln!("reyes-fuzz: {e}\n{USAGE}");
            ExitCode::from(2)
        }
    }
}

/// `worker TARGET EXECS SEED ARGS...`: one fuzzing loop, its report written to
/// `OUT/status-TARGET`.
fn worker(args: &[String]) -> Result<u8, String> {
    let [target, execs, seed, rest @ ..] = args else { return Err("worker: arguments".into()) };
    let target = Target::parse(target).ok_or("worker: target")?;
    let a = parse_args(rest)?;
    let execs = execs.parse().map_err(|_| "worker: execs")?;
    let seed = seed.parse().map_err(|_| "worker: seed")?;
    let opts = options(&a, target, execs, seed);
    if let Ok(word) = std::env::var("REYES_FUZZ_CANARY")
        && !word.starts_with("render-")
    {
        target::set_canary(Box::new(canary(&word)));
    }
    let report = engine::run(&opts).map_err(|e| format!("{}: {e}", a.out.display()))?;
    if let Some(status) = &opts.status {
        fs::write(status, report.to_text()).map_err(|e| format!("{}: {e}", status.display()))?;
    }
    Ok(0)
}

/// For the fuzzer's own tests: makes every input containing `canary` panic, abort or hang
/// (`REYES_FUZZ_CANARY=panic|abort|hang`) in a worker, or in a render child
/// (`render-panic|render-abort|render-hang`), to show that each is caught and saved.
fn canary(word: &str) -> impl Fn(&[u8]) + Send + Sync + 'static {
    let word = word.to_string();
    move |input: &[u8]| {
        if input.windows(6).any(|w| w == b"canary") {
            match word.as_str() {
                "panic" => panic!("canary"),
                "abort" => std::process::abort(),
                "hang" => loop {
                    std::hint::spin_loop();
                },
                _ => {}
            }
        }
    }
}

/// `render-one INPUT OUT MEMORY_BYTES CPU_SECONDS [COVERAGE]`: the render child.
fn render_one(args: &[String]) -> Result<u8, String> {
    let [input, out, memory, cpu, rest @ ..] = args else {
        return Err("render-one: arguments".into());
    };
    let memory: u64 = memory.parse().map_err(|_| "render-one: memory")?;
    let cpu: u64 = cpu.parse().map_err(|_| "render-one: cpu")?;
    limits::cap(memory, cpu).map_err(|e| format!("render-one: setrlimit: {e}"))?;
    if let Some(word) =
        std::env::var("REYES_FUZZ_CANARY").ok().as_deref().and_then(|w| w.strip_prefix("render-"))
    {
        canary(word)(&fs::read(input).unwrap_or_default());
    }
    let code = target::render_child(Path::new(input), Path::new(out));
    if let Some(cov) = rest.first() {
        let _ = fs::write(cov, coverage::dump());
    }
    Ok(code)
}

/// `replay TARGET [--timeout SECS] [--memory MIB] FILE...`: each input once, a render with
/// the fuzzer's limits (10 s, 2 GiB unless given); exit 1 if any failed.
fn replay(args: &[String]) -> Result<u8, String> {
    let [target, rest @ ..] = args else { return Err("replay: arguments".into()) };
    let target = Target::parse(target).ok_or_else(|| format!("unknown target {target}"))?;
    // Flags come in pairs (`--timeout 2 --memory 512`), then the files.
    let mut flags = 0;
    while rest.get(flags).is_some_and(|a| a.starts_with("--")) {
        flags += 2;
    }
    let a = parse_args(&rest[..flags.min(rest.len())])?;
    let files = &rest[flags.min(rest.len())..];
    target::quiet_panics();
    let scratch = std::env::temp_dir().join(format!("reyes-fuzz-replay-{}", std::process::id()));
    fs::create_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    let child = Child {
        scratch: &scratch,
        timeout: Duration::from_secs(a.timeout),
        memory: a.memory_mib << 20,
    };
    let mut failed = false;
    for file in files {
        let input = fs::read(file).map_err(|e| format!("{file}: {e}"))?;
        let result = match target {
            Target::Ron => target::run_in_process(reyes_rib::Format::Ron, &input),
            Target::Rib => target::run_in_process(reyes_rib::Format::Rib, &input),
            Target::Render => match target::run_in_process(target::detect(&input), &input) {
                Ok(Verdict::Accepted) => child.render(&input).map(|(v, _)| v),
                other => other,
            },
            Target::Sl => target::run_sl(&input),
            Target::Tex => target::run_tex(&input),
        };
        match result {
            Ok(v) => println!("{file}: {v:?}"),
            Err(Failure { kind, message }) => {
                failed = true;
                println!("{file}: FAILED: {kind}: {message}");
            }
        }
    }
    let _ = fs::remove_dir_all(&scratch);
    Ok(u8::from(failed))
}

/// `cmin TARGET DIR... --into DIR`: a small set of the inputs (in bytes) that together take
/// the edges the inputs take (but those only one input would add), written to the folder
/// after `--into`.
fn cmin(args: &[String]) -> Result<u8, String> {
    let [target, rest @ ..] = args else { return Err("cmin: arguments".into()) };
    let target = Target::parse(target).ok_or_else(|| format!("unknown target {target}"))?;
    let into = rest.iter().position(|a| a == "--into").ok_or("cmin: --into DIR")?;
    let dst = PathBuf::from(rest.get(into + 1).ok_or("cmin: --into DIR")?);
    let dirs: Vec<PathBuf> = rest[..into].iter().map(PathBuf::from).collect();
    if !coverage::instrumented() {
        return Err("cmin needs the instrumented build (cargo xtask fuzz --cmin)".into());
    }
    target::quiet_panics();
    let scratch = std::env::temp_dir().join(format!("reyes-fuzz-cmin-{}", std::process::id()));
    fs::create_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    let child = Child { scratch: &scratch, timeout: Duration::from_secs(30), memory: 2048 << 20 };
    let mut inputs = engine::read_inputs(&dirs);
    inputs.sort_by_key(|(p, b)| (b.len(), p.clone()));
    inputs.dedup_by(|a, b| a.1 == b.1);
    let mut best: HashMap<u32, usize> = HashMap::new();
    let mut edges_of: Vec<Vec<u32>> = Vec::with_capacity(inputs.len());
    for (i, (_, input)) in inputs.iter().enumerate() {
        coverage::clear();
        let pairs = match target {
            Target::Ron | Target::Rib => {
                let format = if target == Target::Ron {
                    reyes_rib::Format::Ron
                } else {
                    reyes_rib::Format::Rib
                };
                let _ = target::run_in_process(format, input);
                coverage::parse(&coverage::dump())
            }
            Target::Sl => {
                let _ = target::run_sl(input);
                coverage::parse(&coverage::dump())
            }
            Target::Tex => {
                let _ = target::run_tex(input);
                coverage::parse(&coverage::dump())
            }
            Target::Render => {
                let ok = target::run_in_process(target::detect(input), input);
                coverage::clear();
                match ok {
                    Ok(Verdict::Accepted) => {
                        child.render(input).map(|(_, p)| p).unwrap_or_default()
                    }
                    _ => Vec::new(),
                }
            }
        };
        for &(edge, _) in &pairs {
            best.entry(edge).or_insert(i);
        }
        edges_of.push(pairs.into_iter().map(|(e, _)| e).collect());
    }
    // Greedy weighted set cover: repeatedly keep the input that takes the most edges not yet
    // covered per byte (plus 64, so tiny inputs do not win on nothing). Scores only fall as
    // edges get covered, so a popped score that is still the best after recounting is the
    // best (lazy greedy).
    let mut covered: HashSet<u32> = HashSet::new();
    let score = |i: usize, covered: &HashSet<u32>| {
        let new = edges_of[i].iter().filter(|e| !covered.contains(e)).count();
        (new as u64 * 1_000_000 / (inputs[i].1.len() as u64 + 64), new)
    };
    let mut heap: BinaryHeap<(u64, Reverse<usize>)> =
        (0..inputs.len()).map(|i| (score(i, &covered).0, Reverse(i))).collect();
    let mut keep: Vec<usize> = Vec::new();
    while let Some((s, Reverse(i))) = heap.pop() {
        let (now, new) = score(i, &covered);
        // An input that adds one edge alone is dropped: such edges are mostly noise (a hash
        // map's probe sequence, seeded at random per process, takes its own edges).
        if new < 2 {
            continue;
        }
        if now < s && heap.peek().is_some_and(|&(top, _)| top > now) {
            heap.push((now, Reverse(i)));
            continue;
        }
        covered.extend(edges_of[i].iter().copied());
        keep.push(i);
    }
    keep.sort_unstable();
    fs::create_dir_all(&dst).map_err(|e| format!("{}: {e}", dst.display()))?;
    let mut bytes = 0;
    for &i in &keep {
        let (path, input) = &inputs[i];
        let name =
            path.file_name().map(PathBuf::from).unwrap_or_else(|| engine::hash(input).into());
        fs::write(dst.join(name), input).map_err(|e| format!("{}: {e}", dst.display()))?;
        bytes += input.len();
    }
    let _ = fs::remove_dir_all(&scratch);
    println!(
        "cmin {}: {} inputs ({} edges) -> {} ({} bytes, {} edges)",
        target.name(),
        inputs.len(),
        best.len(),
        keep.len(),
        bytes,
        covered.len()
    );
    Ok(0)
}

/// `fuzz`: one supervised worker per target, then the summary.
fn fuzz(args: &[String]) -> Result<u8, String> {
    let a = parse_args(args)?;
    fs::create_dir_all(&a.out).map_err(|e| format!("{}: {e}", a.out.display()))?;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut any_failed = false;
    let mut rng = Rng::new(a.seed);
    for &target in &a.targets {
        if !a.save {
            // A run starts from the corpus alone, whatever an earlier run left.
            let _ = fs::remove_dir_all(save_dir(&a, target));
        }
        let execs = if target == Target::Render { a.renders } else { a.execs };
        let report = supervise(&exe, &a, target, execs, &mut rng)?;
        let secs = report.elapsed.as_secs_f64().max(1e-9);
        println!(
            "{}: {} execs in {:.1} s ({:.0}/s), {} accepted, corpus {} inputs ({} bytes), edges {}/{}, failures {} ({} failing runs)",
            target.name(),
            report.execs,
            secs,
            report.execs as f64 / secs,
            report.accepted,
            report.corpus,
            report.corpus_bytes,
            report.edges,
            report.edges_total,
            report.failures.len(),
            report.failing
        );
        for (f, path) in &report.failures {
            println!("  {}: {}: {}", f.kind, path.display(), f.message);
        }
        any_failed |= !report.failures.is_empty();
    }
    Ok(u8::from(any_failed))
}

/// Runs workers for `target` until `execs` are done: a worker that dies is a failure of the
/// input it was running, and the next worker goes on with another seed.
fn supervise(
    exe: &Path,
    a: &Args,
    target: Target,
    execs: u64,
    rng: &mut Rng,
) -> Result<Report, String> {
    let start = Instant::now();
    let status_path = a.out.join(format!("status-{}", target.name()));
    let current_path = a.out.join(format!("current-{}", target.name()));
    let mut total = Report::default();
    let mut left = execs;
    let mut seed = a.seed;
    for restart in 0..=MAX_RESTARTS {
        let _ = fs::remove_file(&status_path);
        let mut cmd = Command::new(exe);
        cmd.arg("worker").arg(target.name()).arg(left.to_string()).arg(seed.to_string());
        cmd.arg("--corpus").arg(&a.corpus).arg("--out").arg(&a.out);
        cmd.arg("--timeout").arg(a.timeout.to_string());
        cmd.arg("--memory").arg(a.memory_mib.to_string());
        if a.save {
            cmd.arg("--save");
        }
        if a.quiet {
            cmd.arg("--quiet");
        }
        if let Some(t) = a.time_limit {
            let spent = start.elapsed().as_secs();
            cmd.arg("--time-limit").arg(t.saturating_sub(spent).max(1).to_string());
        }
        let status = cmd.status().map_err(|e| format!("cannot run a worker: {e}"))?;
        let report = Report::from_text(&fs::read_to_string(&status_path).unwrap_or_default());
        let done = report.execs.min(left);
        total.execs += report.execs;
        total.accepted += report.accepted;
        total.failing += report.failing;
        total.failures.extend(report.failures.iter().cloned());
        total.corpus = total.corpus.max(report.corpus);
        total.corpus_bytes = total.corpus_bytes.max(report.corpus_bytes);
        total.edges = total.edges.max(report.edges);
        total.edges_total = total.edges_total.max(report.edges_total);
        if status.success() {
            break;
        }
        let seeded = report.seeded;
        // The worker died: blame the input it was running.
        use std::os::unix::process::ExitStatusExt;
        let input = fs::read(&current_path).unwrap_or_default();
        let kind = if status.code() == Some(HANG_EXIT) { "hang" } else { "abort" };
        let path = a.out.join("crashes").join(format!(
            "{}-{kind}-{}.{}",
            target.name(),
            engine::hash(&input),
            if target == Target::Sl {
                "sl"
            } else if target == Target::Tex {
                "tex"
            } else if target::detect(&input) == reyes_rib::Format::Ron && target != Target::Rib {
                "ron"
            } else {
                "rib"
            }
        ));
        let _ = fs::create_dir_all(a.out.join("crashes"));
        let _ = fs::write(&path, &input);
        let how = match (status.code(), status.signal()) {
            (Some(HANG_EXIT), _) => format!("ran longer than {} s", a.timeout),
            (_, Some(sig)) => format!("worker killed by signal {sig}"),
            (code, _) => format!("worker exited with {code:?}"),
        };
        eprintln!(
            "reyes-fuzz: {}: {kind}: {how}; input saved to {}",
            target.name(),
            path.display()
        );
        total.failures.push((Failure::new(kind, how), path));
        total.failing += 1;
        if restart == MAX_RESTARTS || !seeded {
            break;
        }
        left = left.saturating_sub(done.max(1));
        seed = rng.next_u64();
    }
    total.elapsed = start.elapsed();
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_parse_and_bad_ones_are_refused() {
        let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let a = parse_args(&s(&["--targets", "rib,render", "--execs", "5", "--save"])).unwrap();
        assert_eq!(a.targets, vec![Target::Rib, Target::Render]);
        assert_eq!((a.execs, a.save), (5, true));
        assert!(parse_args(&s(&["--targets", "mesh"])).is_err());
        assert!(parse_args(&s(&["--execs"])).is_err());
        assert!(parse_args(&s(&["--execs", "x"])).is_err());
        assert!(parse_args(&s(&["--bogus"])).is_err());
    }
}
