//! `reyes-render farm slurm|status`: a frame range split into tiles as a Slurm array job (one
//! task per tile and frame) with a merge job that runs after it, and reading their state
//! back (docs/farm.md). We write job scripts and call Slurm's own commands (`sbatch`,
//! `sacct`, `scontrol`); scheduling is Slurm's.
//!
//! Invariant: a task runs exactly the command a person would (`reyes-render SCENE --frames F
//! --tile I/N -o TILE`, then `reyes-render merge`), in the directory `farm slurm` was run
//! from, with the scene named as it was named there, so the merged frames are those of a
//! local render byte for byte.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use clap::{Parser, Subcommand};

use crate::args::{FrameList, parse_frames};
use crate::term::print;
use crate::{Exit, parse_failed};

/// Render on a farm (docs/farm.md).
#[derive(Parser, Debug)]
#[command(name = "reyes-render farm", bin_name = "reyes-render farm", version)]
struct FarmArgs {
    #[command(subcommand)]
    engine: Engine,
}

#[derive(Subcommand, Debug)]
enum Engine {
    /// Write and submit a Slurm array job (one task per tile and frame) and a merge job
    /// that runs after it (--dependency=afterok); prints the job ids.
    Slurm(Box<SlurmArgs>),
    /// The state of the jobs `farm slurm` submitted (from sacct, else scontrol).
    Status(StatusArgs),
}

#[derive(Parser, Debug)]
struct SlurmArgs {
    /// The scene file, named as the tasks will name it: relative to this directory, which
    /// every task starts in (a shared file system on a real cluster).
    scene: PathBuf,
    /// Tiles per frame.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=100_000))]
    tiles: u32,
    /// Frames, e.g. 1-100 or 1,3,5-9.
    #[arg(long, value_name = "LIST", value_parser = parse_frames)]
    frames: FrameList,
    /// Output of the merged frames: a run of # or a %0Nd takes the frame number, else it goes
    /// before the extension (out.0001.exr).
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Where the job scripts, tiles, checkpoints, logs and job ids go.
    #[arg(long, value_name = "DIR", default_value = "reyes-farm")]
    dir: PathBuf,
    /// Slurm partition (sbatch --partition).
    #[arg(long, value_name = "NAME")]
    partition: Option<String>,
    /// Slurm account (sbatch --account).
    #[arg(long, value_name = "NAME")]
    account: Option<String>,
    /// CPUs per task (sbatch --cpus-per-task); each task renders with that many threads.
    #[arg(long, value_name = "N", default_value_t = 1)]
    cpus_per_task: u32,
    /// Time limit per task (sbatch --time), e.g. 2:00:00.
    #[arg(long, value_name = "TIME")]
    time: Option<String>,
    /// Memory per task (sbatch --mem), e.g. 4G.
    #[arg(long, value_name = "SIZE")]
    mem: Option<String>,
    /// Another sbatch option for both jobs, e.g. --sbatch=--qos=low (repeatable).
    #[arg(long = "sbatch", value_name = "OPTION", allow_hyphen_values = true)]
    sbatch: Vec<String>,
    /// The reyes-render the tasks run (default: this one).
    #[arg(long, value_name = "PATH")]
    binary: Option<PathBuf>,
    /// Write the scripts, do not submit them.
    #[arg(long)]
    no_submit: bool,
    /// Options passed on to every render task (after --), e.g. -- --seed 7 --samples 4x4.
    #[arg(last = true, value_name = "RENDER_OPTIONS")]
    render: Vec<String>,
}

#[derive(Parser, Debug)]
struct StatusArgs {
    /// The directory `farm slurm` wrote (its --dir).
    #[arg(long, value_name = "DIR", default_value = "reyes-farm")]
    dir: PathBuf,
    /// Wait until every job has ended, polling every 2 seconds, for at most SECS seconds;
    /// exit 1 unless all completed.
    #[arg(long, value_name = "SECS")]
    wait: Option<u64>,
}

/// `reyes-render farm ...`: `args` starts at `farm`.
pub(crate) fn main(args: impl Iterator<Item = std::ffi::OsString>) -> Result<(), Exit> {
    crate::signals::install(false).map_err(|e| Exit::error(1, format_args!("signals: {e}")))?;
    let args =
        FarmArgs::try_parse_from(args).map_err(|e| parse_failed(e, "reyes-render farm --help"))?;
    match args.engine {
        Engine::Slurm(a) => slurm(&a),
        Engine::Status(a) => status(&a),
    }
}

/// Frame numbers of a list, in order, each once.
fn frame_numbers(list: &FrameList) -> Vec<i32> {
    let mut v: Vec<i32> = list.0.iter().flat_map(|&(a, b)| a..=b).collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// A word for a POSIX shell, single-quoted.
fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

fn path_word(p: &Path) -> String {
    quote(&p.display().to_string())
}

fn io(path: &Path, e: std::io::Error) -> Exit {
    Exit::error(1, format_args!("{}: {e}", path.display()))
}

/// The tile file of tile `i` of frame `f` under `dir`.
fn tile_path(dir: &Path, f: i32, i: u32) -> PathBuf {
    dir.join("tiles").join(format!("frame.{f:04}.tile.{i}.exr"))
}

/// Refuse, before anything is submitted, what every task would fail on: an output that is
/// not .exr or .png, a scene that does not load, a frame it does not have, more tiles than
/// buckets.
fn check(a: &SlurmArgs, frames: &[i32]) -> Result<(), Exit> {
    crate::check_output(&a.output)?;
    let options = reyes_rib::RiOptions { strict: false, frames: Some(a.frames.0.clone()) };
    let loaded = reyes_rib::load_scene_file(&a.scene, &options)
        .map_err(|e| Exit::error(e.exit_code(), &e))?;
    for &f in frames {
        let Some(frame) = loaded.frames.iter().find(|fr| fr.number.unwrap_or(f) == f) else {
            return Err(Exit::error(
                2,
                format_args!("{}: --frames: no frame {f}", a.scene.display()),
            ));
        };
        crate::pieces::buckets_of(&frame.scene, Some((1, a.tiles as usize))).map_err(|e| {
            Exit::error(
                2,
                format_args!("{}: {}", a.scene.display(), e.replace("--tile 1/", "--tiles ")),
            )
        })?;
    }
    Ok(())
}

fn slurm(a: &SlurmArgs) -> Result<(), Exit> {
    let frames = frame_numbers(&a.frames);
    check(a, &frames)?;
    let cwd = std::env::current_dir()
        .map_err(|e| Exit::error(1, format_args!("current directory: {e}")))?;
    let binary = match &a.binary {
        Some(b) => b.clone(),
        None => std::env::current_exe()
            .map_err(|e| Exit::error(1, format_args!("reyes-render: {e}")))?,
    };
    let dir = cwd.join(&a.dir);
    for sub in ["tiles", "logs", "checkpoint"] {
        std::fs::create_dir_all(dir.join(sub)).map_err(|e| io(&dir.join(sub), e))?;
    }
    let tasks = frames.len() as u64 * u64::from(a.tiles);
    let mut common = format!("#SBATCH --chdir={}\n", cwd.display());
    for (flag, value) in
        [("partition", &a.partition), ("account", &a.account), ("time", &a.time), ("mem", &a.mem)]
    {
        if let Some(v) = value {
            common.push_str(&format!("#SBATCH --{flag}={v}\n"));
        }
    }
    for o in &a.sbatch {
        common.push_str(&format!("#SBATCH {o}\n"));
    }
    let frame_words: Vec<String> = frames.iter().map(i32::to_string).collect();
    let extra: Vec<String> = a.render.iter().map(|s| quote(s)).collect();
    let render = format!(
        "#!/bin/sh\n\
         # reyes-render farm slurm: task k renders tile k % N + 1 of frame k / N.\n\
         #SBATCH --job-name=reyes-render\n\
         #SBATCH --array=0-{last}\n\
         #SBATCH --cpus-per-task={cpus}\n\
         #SBATCH --output={logs}/render-%A_%a.log\n\
         {common}\
         set -eu\n\
         frames=\"{frames}\"\n\
         n={n}\n\
         k=$SLURM_ARRAY_TASK_ID\n\
         set -- $frames\n\
         shift $((k / n))\n\
         frame=$1\n\
         tile=$((k % n + 1))\n\
         out={dir}/tiles/frame.####.tile.$tile.exr\n\
         exec {bin} {scene} --frames \"$frame\" --tile \"$tile/$n\" -o \"$out\" \\\n  \
         --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" --checkpoint {dir}/checkpoint/tile.$tile {extra}\n",
        last = tasks - 1,
        cpus = a.cpus_per_task,
        logs = dir.join("logs").display(),
        frames = frame_words.join(" "),
        n = a.tiles,
        dir = path_word(&dir),
        bin = path_word(&binary),
        scene = path_word(&a.scene),
        extra = extra.join(" "),
    );
    let mut merge = format!(
        "#!/bin/sh\n\
         # reyes-render farm slurm: merges each frame's tiles once every render task succeeded.\n\
         #SBATCH --job-name=reyes-merge\n\
         #SBATCH --output={logs}/merge-%j.log\n\
         {common}\
         set -eu\n",
        logs = dir.join("logs").display(),
    );
    for &f in &frames {
        let tiles: Vec<String> = (1..=a.tiles).map(|i| path_word(&tile_path(&dir, f, i))).collect();
        let out = crate::output::frame_path(&a.output, Some(f), true);
        merge.push_str(&format!(
            "{} merge {} -o {}\n",
            path_word(&binary),
            tiles.join(" "),
            path_word(&out)
        ));
    }
    let (render_script, merge_script) = (dir.join("render.sbatch"), dir.join("merge.sbatch"));
    std::fs::write(&render_script, render).map_err(|e| io(&render_script, e))?;
    std::fs::write(&merge_script, merge).map_err(|e| io(&merge_script, e))?;
    if a.no_submit {
        return print(&format!("{}\n{}\n", render_script.display(), merge_script.display()));
    }
    let render_id = sbatch(&[render_script.as_os_str().into()])?;
    let merge_id = sbatch(&[
        format!("--dependency=afterok:{render_id}").into(),
        merge_script.as_os_str().into(),
    ])?;
    let jobs = dir.join("jobs");
    std::fs::write(&jobs, format!("render {render_id}\nmerge {merge_id}\n"))
        .map_err(|e| io(&jobs, e))?;
    print(&format!(
        "render job {render_id}: {tasks} tasks ({} frames x {} tiles)\nmerge job {merge_id}: after render job {render_id} succeeds\n",
        frames.len(),
        a.tiles
    ))
}

/// Run a Slurm command, its standard output on success.
fn slurm_command(program: &str, args: &[std::ffi::OsString]) -> Result<String, Exit> {
    let out = Command::new(program).args(args).output().map_err(|e| {
        Exit::error(
            1,
            format_args!(
                "{program}: cannot run ({e}): is Slurm installed and on PATH? (tools/slurm/up.sh starts a single-node Slurm)"
            ),
        )
    })?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let line =
            err.lines().find(|l| !l.trim().is_empty()).unwrap_or("failed").trim().to_string();
        return Err(Exit::error(1, format_args!("{program}: {line}")));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Submit a job with `sbatch --parsable`: its id.
fn sbatch(args: &[std::ffi::OsString]) -> Result<String, Exit> {
    let mut all: Vec<std::ffi::OsString> = vec!["--parsable".into()];
    all.extend_from_slice(args);
    let out = slurm_command("sbatch", &all)?;
    // --parsable prints `ID` or `ID;CLUSTER`.
    let id = out.trim().split(';').next().unwrap_or_default().to_string();
    if id.is_empty() || !id.bytes().all(|b| b.is_ascii_digit()) {
        return Err(Exit::error(1, format_args!("sbatch: unexpected answer '{}'", out.trim())));
    }
    Ok(id)
}

/// The states of job `id`'s tasks: `(state, tasks)` pairs.
fn job_states(id: &str) -> Result<Vec<(String, u64)>, Exit> {
    // sacct where accounting is kept; else scontrol, which knows jobs until MinJobAge.
    if let Ok(out) = slurm_command(
        "sacct",
        &[
            "-n".into(),
            "-P".into(),
            "-X".into(),
            "-j".into(),
            id.into(),
            "--format=JobID,State".into(),
        ],
    ) {
        let states: Vec<(String, u64)> = out
            .lines()
            .filter_map(|l| l.split_once('|'))
            .map(|(job, state)| {
                (state.split_whitespace().next().unwrap_or(state).to_string(), tasks_in(job))
            })
            .collect();
        if !states.is_empty() {
            return Ok(states);
        }
    }
    let out = slurm_command("scontrol", &["-o".into(), "show".into(), "job".into(), id.into()])?;
    let field = |line: &str, key: &str| -> Option<String> {
        line.split_whitespace().find_map(|w| w.strip_prefix(key)).map(str::to_string)
    };
    Ok(out
        .lines()
        .filter_map(|l| {
            let state = field(l, "JobState=")?;
            let n = field(l, "ArrayTaskId=").map_or(1, |t| count_tasks(&t));
            Some((state, n))
        })
        .collect())
}

/// Tasks named by a sacct job id: `12_[3-5]` is 3, `12_4` or `12` is 1.
fn tasks_in(job: &str) -> u64 {
    match job.split_once("_[") {
        Some((_, range)) => count_tasks(range.trim_end_matches(']')),
        None => 1,
    }
}

/// Tasks of an array range `1-3,7` (a `%N` throttle ignored).
fn count_tasks(range: &str) -> u64 {
    let range = range.split('%').next().unwrap_or_default();
    range
        .split(',')
        .map(|p| match p.split_once('-') {
            Some((a, b)) => match (a.parse::<u64>(), b.parse::<u64>()) {
                (Ok(a), Ok(b)) if b >= a => b - a + 1,
                _ => 1,
            },
            None => 1,
        })
        .sum()
}

/// Whether a Slurm job state is final.
fn ended(state: &str) -> bool {
    !matches!(
        state,
        "PENDING"
            | "RUNNING"
            | "CONFIGURING"
            | "COMPLETING"
            | "REQUEUED"
            | "RESIZING"
            | "SUSPENDED"
            | "STAGE_OUT"
            | "SIGNALING"
    )
}

fn status(a: &StatusArgs) -> Result<(), Exit> {
    let path = a.dir.join("jobs");
    let text = std::fs::read_to_string(&path).map_err(|e| {
        Exit::error(1, format_args!("{}: {e} (run reyes-render farm slurm first)", path.display()))
    })?;
    let jobs: Vec<(String, String)> = text
        .lines()
        .filter_map(|l| l.split_once(' '))
        .map(|(name, id)| (name.to_string(), id.trim().to_string()))
        .collect();
    if jobs.is_empty() {
        return Err(Exit::error(2, format_args!("{}: no job ids", path.display())));
    }
    let until = a.wait.map(|s| Instant::now() + Duration::from_secs(s));
    loop {
        let mut report = String::new();
        let (mut all_ended, mut all_ok) = (true, true);
        for (name, id) in &jobs {
            let states = job_states(id)?;
            let mut counts: Vec<(String, u64)> = Vec::new();
            for (s, n) in states {
                all_ended &= ended(&s);
                all_ok &= s == "COMPLETED";
                match counts.iter_mut().find(|(k, _)| *k == s) {
                    Some(c) => c.1 += n,
                    None => counts.push((s, n)),
                }
            }
            if counts.is_empty() {
                all_ok = false;
                counts.push(("UNKNOWN".into(), 0));
            }
            let parts: Vec<String> = counts.iter().map(|(s, n)| format!("{n} {s}")).collect();
            report.push_str(&format!("{name} job {id}: {}\n", parts.join(", ")));
        }
        match until {
            None => return print(&report),
            Some(t) if all_ended || Instant::now() >= t => {
                print(&report)?;
                return if all_ok {
                    Ok(())
                } else if all_ended {
                    Err(Exit::error(
                        1,
                        format_args!(
                            "farm: a job did not complete (logs in {})",
                            a.dir.join("logs").display()
                        ),
                    ))
                } else {
                    Err(Exit::error(
                        1,
                        format_args!(
                            "farm status --wait: the jobs had not ended after {}s",
                            a.wait.unwrap_or(0)
                        ),
                    ))
                };
            }
            Some(_) => std::thread::sleep(Duration::from_secs(2)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn array_ranges_count_their_tasks() {
        assert_eq!(count_tasks("0-7"), 8);
        assert_eq!(count_tasks("1-3,7%2"), 4);
        assert_eq!(tasks_in("12_[3-5]"), 3);
        assert_eq!(tasks_in("12_4"), 1);
        assert!(ended("COMPLETED") && ended("FAILED") && !ended("PENDING"));
        assert_eq!(quote("it's"), r"'it'\''s'");
    }
}
