//! `cargo xtask fuzz [ARGS...]`: builds `reyes-fuzz` with the compiler's coverage
//! instrumentation and runs it; `cargo xtask fuzz cmin` shrinks the committed corpus.
//!
//! The instrumented build has its own target folder (`target/fuzz`) and is built for the host
//! triple given explicitly, so that RUSTFLAGS reach the fuzzed code but not build scripts or
//! proc macros (which run inside the compiler, where the coverage callbacks do not exist).
//! ARGS go to `reyes-fuzz` (`--execs N`, `--renders N`, `--targets ron,rib,render,sl`,
//! `--seed S`, `--save`, `--time-limit SECS`, ...); the run's files go to `target/fuzz/out`.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The instrumentation: SanitizerCoverage's edge level with trace-pc-guard callbacks.
const RUSTFLAGS: &str = "-C passes=sancov-module -C llvm-args=-sanitizer-coverage-level=3 \
                         -C llvm-args=-sanitizer-coverage-trace-pc-guard";

/// The targets, in the order they are fuzzed and minimised.
const TARGETS: &[&str] = &["ron", "rib", "render", "sl"];

fn host() -> Result<String, String> {
    let out = Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .arg("-vV")
        .output()
        .map_err(|e| format!("rustc -vV: {e}"))?;
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .ok_or_else(|| "rustc -vV: no host line".into())
}

/// Builds the instrumented fuzzer; its path.
fn build(root: &Path) -> Result<PathBuf, String> {
    let host = host()?;
    let target_dir = root.join("target/fuzz");
    let status = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .current_dir(root)
        .args(["build", "--release", "--package", "reyes-fuzz", "--target", &host])
        .arg("--target-dir")
        .arg(&target_dir)
        .env("RUSTFLAGS", RUSTFLAGS)
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .status()
        .map_err(|e| format!("cargo build: {e}"))?;
    if !status.success() {
        return Err("the instrumented build failed".into());
    }
    Ok(target_dir.join(host).join("release/reyes-fuzz"))
}

/// Runs `cargo xtask fuzz ARGS...`.
pub fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let exe = build(root)?;
    if args.first().map(String::as_str) == Some("cmin") {
        return cmin(root, &exe);
    }
    let status = Command::new(&exe)
        .arg("fuzz")
        .arg("--corpus")
        .arg(root.join("crates/fuzz/corpus"))
        .arg("--out")
        .arg(root.join("target/fuzz/out"))
        .args(args)
        .status()
        .map_err(|e| format!("{}: {e}", exe.display()))?;
    if status.success() { Ok(()) } else { Err("inputs failed (see above)".into()) }
}

/// Replaces each target's committed corpus by the smallest inputs that cover every edge the
/// corpus and the last run's new inputs (`target/fuzz/out/new-TARGET`) cover.
fn cmin(root: &Path, exe: &Path) -> Result<(), String> {
    let corpus = root.join("crates/fuzz/corpus");
    let out = root.join("target/fuzz/out");
    for t in TARGETS {
        let tmp = out.join(format!("cmin-{t}"));
        let _ = std::fs::remove_dir_all(&tmp);
        let from = [corpus.join(t), out.join(format!("new-{t}"))];
        let status = Command::new(exe)
            .arg("cmin")
            .arg(t)
            .args(from.iter().filter(|d| d.exists()))
            .arg("--into")
            .arg(&tmp)
            .status()
            .map_err(|e| format!("{}: {e}", exe.display()))?;
        if !status.success() {
            return Err(format!("cmin {t} failed"));
        }
        let dst = corpus.join(t);
        let _ = std::fs::remove_dir_all(&dst);
        std::fs::rename(&tmp, &dst).map_err(|e| format!("{}: {e}", dst.display()))?;
    }
    Ok(())
}
