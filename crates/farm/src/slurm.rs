//! A frame range split into tiles as a Slurm array job (one task per tile and frame) with a
//! merge job that runs after it, and their state read back (docs/farm.md, "Slurm"). We write
//! job scripts and call Slurm's own commands (`sbatch`, `sacct`, `scontrol`); scheduling is
//! Slurm's.
//!
//! Invariant: a task runs exactly the command a person would (`reyes-render SCENE --frames F
//! --tile I/N -o TILE`, then `reyes-render merge`), in the directory the job was set up
//! from, with the scene named as it was named there, so the merged frames are those of a
//! local render byte for byte.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use crate::output::{check_output, create_directory_of, frame_path};
use crate::tile::buckets_of;
use crate::{FarmError, FrameList, Tile, one_line};

/// A Slurm job to set up: what `reyes-render farm slurm` is asked.
#[derive(Debug, Clone)]
pub struct SlurmJob {
    /// The scene file, named as the tasks will name it: relative to the current directory,
    /// which every task starts in.
    pub scene: PathBuf,
    /// Tiles per frame.
    pub tiles: u32,
    /// The frames.
    pub frames: FrameList,
    /// Output of the merged frames (frame numbers go in as [`frame_path`] puts them).
    pub output: PathBuf,
    /// Where the job scripts, tiles, checkpoints, logs and job ids go.
    pub dir: PathBuf,
    /// `sbatch --partition`.
    pub partition: Option<String>,
    /// `sbatch --account`.
    pub account: Option<String>,
    /// `sbatch --cpus-per-task`, and each task's render threads.
    pub cpus_per_task: u32,
    /// `sbatch --time`, per task.
    pub time: Option<String>,
    /// `sbatch --mem`, per task.
    pub mem: Option<String>,
    /// Other sbatch options for both jobs (`--qos=low`).
    pub sbatch: Vec<String>,
    /// The `reyes-render` the tasks run.
    pub binary: PathBuf,
    /// Options passed on to every render task.
    pub render: Vec<String>,
}

/// The job scripts written, ready to submit.
#[derive(Debug, Clone)]
pub struct Scripts {
    /// The job's directory (absolute).
    pub dir: PathBuf,
    /// `DIR/render.sbatch`: the array job.
    pub render: PathBuf,
    /// `DIR/merge.sbatch`: the merge job.
    pub merge: PathBuf,
    /// The frames.
    pub frames: usize,
    /// Tiles per frame.
    pub tiles: u32,
}

/// The jobs submitted.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Submitted {
    /// The array job's id.
    pub render: String,
    /// The merge job's id.
    pub merge: String,
    /// The array job's tasks.
    pub tasks: u64,
    /// The frames.
    pub frames: usize,
    /// Tiles per frame.
    pub tiles: u32,
}

impl Submitted {
    /// What to tell the user: the two job ids, one line each.
    pub fn summary(&self) -> String {
        format!(
            "render job {r}: {} tasks ({} frames x {} tiles)\nmerge job {}: after render job {r} succeeds\n",
            self.tasks,
            self.frames,
            self.tiles,
            self.merge,
            r = self.render
        )
    }
}

/// A word for a POSIX shell, single-quoted.
pub fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

fn path_word(p: &Path) -> String {
    quote(&p.display().to_string())
}

fn io(path: &Path, e: std::io::Error) -> FarmError {
    FarmError::failed(format_args!("{}: {e}", one_line(path.display())))
}

/// The tile file of tile `i` of frame `f` under `dir`.
pub fn tile_path(dir: &Path, f: i32, i: u32) -> PathBuf {
    dir.join("tiles").join(format!("frame.{f:04}.tile.{i}.exr"))
}

impl SlurmJob {
    /// Refuse what every task would fail on, before anything is written or submitted: an
    /// output that is not .exr or .png, a scene that does not load, a frame it does not have,
    /// more tiles than buckets. The frame numbers, in order.
    pub fn check(&self) -> Result<Vec<i32>, FarmError> {
        check_output(&self.output, true)?;
        let options = reyes_rib::RiOptions { strict: false, frames: Some(self.frames.0.clone()) };
        let loaded = reyes_rib::load_scene_file(&self.scene, &options)?;
        let scene = one_line(self.scene.display());
        let frames = self.frames.numbers();
        for &f in &frames {
            let Some(frame) = loaded.frames.iter().find(|fr| fr.number.unwrap_or(f) == f) else {
                return Err(FarmError::invalid(format_args!("{scene}: --frames: no frame {f}")));
            };
            let tile = Tile { index: 1, count: self.tiles as usize };
            if let Err(e) = buckets_of(&frame.scene, Some(tile)) {
                return Err(FarmError::invalid(format_args!(
                    "{scene}: --tiles {}: the frame has {} buckets, so at most {} tiles",
                    self.tiles, e.buckets, e.buckets
                )));
            }
        }
        Ok(frames)
    }

    /// The array job's script, for the job directory `dir` and the working directory `cwd`:
    /// task k renders tile `k % N + 1` of the `k / N`-th of `frames`.
    pub fn render_script(&self, dir: &Path, cwd: &Path, frames: &[i32]) -> String {
        let tasks = frames.len() as u64 * u64::from(self.tiles);
        let frame_words: Vec<String> = frames.iter().map(i32::to_string).collect();
        let extra: Vec<String> = self.render.iter().map(|s| quote(s)).collect();
        format!(
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
            last = tasks.saturating_sub(1),
            cpus = self.cpus_per_task,
            logs = dir.join("logs").display(),
            common = self.common(cwd),
            frames = frame_words.join(" "),
            n = self.tiles,
            dir = path_word(dir),
            bin = path_word(&self.binary),
            scene = path_word(&self.scene),
            extra = extra.join(" "),
        )
    }

    /// The merge job's script: each frame's tiles merged, once every render task succeeded.
    pub fn merge_script(&self, dir: &Path, cwd: &Path, frames: &[i32]) -> String {
        let mut merge = format!(
            "#!/bin/sh\n\
             # reyes-render farm slurm: merges each frame's tiles once every render task succeeded.\n\
             #SBATCH --job-name=reyes-merge\n\
             #SBATCH --output={logs}/merge-%j.log\n\
             {common}\
             set -eu\n",
            logs = dir.join("logs").display(),
            common = self.common(cwd),
        );
        for &f in frames {
            let tiles: Vec<String> =
                (1..=self.tiles).map(|i| path_word(&tile_path(dir, f, i))).collect();
            let out = frame_path(&self.output, Some(f), true);
            merge.push_str(&format!(
                "{} merge {} -o {}\n",
                path_word(&self.binary),
                tiles.join(" "),
                path_word(&out)
            ));
        }
        merge
    }

    /// The `#SBATCH` lines both jobs share.
    fn common(&self, cwd: &Path) -> String {
        let mut common = format!("#SBATCH --chdir={}\n", cwd.display());
        let options = [
            ("partition", &self.partition),
            ("account", &self.account),
            ("time", &self.time),
            ("mem", &self.mem),
        ];
        for (flag, value) in options {
            if let Some(v) = value {
                common.push_str(&format!("#SBATCH --{flag}={v}\n"));
            }
        }
        for o in &self.sbatch {
            common.push_str(&format!("#SBATCH {o}\n"));
        }
        common
    }

    /// Check the job ([`SlurmJob::check`]), make its directory (with `tiles/`, `logs/` and
    /// `checkpoint/`) and the merged frames' directory, and write the two scripts.
    pub fn write(&self) -> Result<Scripts, FarmError> {
        let frames = self.check()?;
        let cwd = std::env::current_dir()
            .map_err(|e| FarmError::failed(format_args!("current directory: {e}")))?;
        let dir = cwd.join(&self.dir);
        for sub in ["tiles", "logs", "checkpoint"] {
            std::fs::create_dir_all(dir.join(sub)).map_err(|e| io(&dir.join(sub), e))?;
        }
        create_directory_of(&self.output)?;
        let (render, merge) = (dir.join("render.sbatch"), dir.join("merge.sbatch"));
        std::fs::write(&render, self.render_script(&dir, &cwd, &frames))
            .map_err(|e| io(&render, e))?;
        std::fs::write(&merge, self.merge_script(&dir, &cwd, &frames))
            .map_err(|e| io(&merge, e))?;
        Ok(Scripts { dir, render, merge, frames: frames.len(), tiles: self.tiles })
    }
}

impl Scripts {
    /// Submit the array job, then the merge job after it (`--dependency=afterok`), and keep
    /// their ids in `DIR/jobs` for [`status`].
    pub fn submit(&self) -> Result<Submitted, FarmError> {
        let render = sbatch(&[self.render.as_os_str().into()])?;
        let merge = sbatch(&[
            format!("--dependency=afterok:{render}").into(),
            self.merge.as_os_str().into(),
        ])?;
        let jobs = self.dir.join("jobs");
        std::fs::write(&jobs, format!("render {render}\nmerge {merge}\n"))
            .map_err(|e| io(&jobs, e))?;
        let tasks = self.frames as u64 * u64::from(self.tiles);
        Ok(Submitted { render, merge, tasks, frames: self.frames, tiles: self.tiles })
    }
}

/// Run a Slurm command: its standard output on success.
fn slurm_command(program: &str, args: &[OsString]) -> Result<String, FarmError> {
    let out = Command::new(program).args(args).output().map_err(|e| {
        FarmError::failed(format_args!(
            "{program}: cannot run ({e}): is Slurm installed and on PATH? (tools/slurm/up.sh starts a single-node Slurm)"
        ))
    })?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let line = err.lines().find(|l| !l.trim().is_empty()).unwrap_or("failed").trim();
        return Err(FarmError::failed(format_args!("{program}: {}", one_line(line))));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Submit a job with `sbatch --parsable`: its id.
fn sbatch(args: &[OsString]) -> Result<String, FarmError> {
    let mut all: Vec<OsString> = vec!["--parsable".into()];
    all.extend_from_slice(args);
    let out = slurm_command("sbatch", &all)?;
    parse_sbatch(&out).ok_or_else(|| {
        FarmError::failed(format_args!("sbatch: unexpected answer '{}'", one_line(out.trim())))
    })
}

/// The job id in what `sbatch --parsable` prints (`ID` or `ID;CLUSTER`).
pub fn parse_sbatch(out: &str) -> Option<String> {
    let id = out.trim().split(';').next().unwrap_or_default();
    (!id.is_empty() && id.bytes().all(|b| b.is_ascii_digit())).then(|| id.to_string())
}

/// The states of job `id`'s tasks, as `(state, tasks)` pairs: from sacct where accounting
/// is kept, else from scontrol, which knows jobs until `MinJobAge`.
pub fn job_states(id: &str) -> Result<Vec<(String, u64)>, FarmError> {
    let sacct = ["-n", "-P", "-X", "-j", id, "--format=JobID,State"].map(OsString::from);
    if let Ok(out) = slurm_command("sacct", &sacct) {
        let states = parse_sacct(&out);
        if !states.is_empty() {
            return Ok(states);
        }
    }
    let out = slurm_command("scontrol", &["-o", "show", "job", id].map(OsString::from))?;
    Ok(parse_scontrol(&out))
}

/// `(state, tasks)` of each line `JOBID|STATE` of `sacct -n -P -X --format=JobID,State`.
pub fn parse_sacct(out: &str) -> Vec<(String, u64)> {
    out.lines()
        .filter_map(|l| l.split_once('|'))
        .map(|(job, state)| {
            (state.split_whitespace().next().unwrap_or(state).to_string(), tasks_in(job))
        })
        .collect()
}

/// `(state, tasks)` of each line of `scontrol -o show job`.
pub fn parse_scontrol(out: &str) -> Vec<(String, u64)> {
    let field = |line: &str, key: &str| -> Option<String> {
        line.split_whitespace().find_map(|w| w.strip_prefix(key)).map(str::to_string)
    };
    out.lines()
        .filter_map(|l| {
            let state = field(l, "JobState=")?;
            let n = field(l, "ArrayTaskId=").map_or(1, |t| count_tasks(&t));
            Some((state, n))
        })
        .collect()
}

/// Tasks named by a sacct job id: `12_[3-5]` is 3, `12_4` or `12` is 1.
pub fn tasks_in(job: &str) -> u64 {
    match job.split_once("_[") {
        Some((_, range)) => count_tasks(range.trim_end_matches(']')),
        None => 1,
    }
}

/// Tasks of an array range `1-3,7` (a `%N` throttle ignored).
pub fn count_tasks(range: &str) -> u64 {
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
pub fn ended(state: &str) -> bool {
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

/// What [`status`] found: the report to show, and why the jobs did not succeed, when asked
/// to wait for them and they did not.
#[derive(Debug)]
pub struct Status {
    /// One line per job: `NAME job ID: N STATE[, N STATE...]`.
    pub report: String,
    /// With a wait: a job that did not complete, or the wait ran out.
    pub failure: Option<FarmError>,
}

/// The state of the jobs whose ids `DIR/jobs` keeps; with `wait` seconds, polled every 2
/// seconds until every job has ended or the time is up (a failure unless all completed).
pub fn status(dir: &Path, wait: Option<u64>) -> Result<Status, FarmError> {
    let path = dir.join("jobs");
    let shown = one_line(path.display());
    let text = std::fs::read_to_string(&path).map_err(|e| {
        FarmError::failed(format_args!("{shown}: {e} (run reyes-render farm slurm first)"))
    })?;
    let jobs: Vec<(&str, &str)> =
        text.lines().filter_map(|l| l.split_once(' ')).map(|(n, id)| (n, id.trim())).collect();
    if jobs.is_empty() {
        return Err(FarmError::invalid(format_args!("{shown}: no job ids")));
    }
    let until = wait.map(|s| Instant::now() + Duration::from_secs(s));
    loop {
        let mut report = String::new();
        let (mut all_ended, mut all_ok) = (true, true);
        for &(name, id) in &jobs {
            let mut counts: Vec<(String, u64)> = Vec::new();
            for (s, n) in job_states(id)? {
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
            report.push_str(&format!("{name} job {id}: {}\n", one_line(parts.join(", "))));
        }
        let failure = match until {
            None => None,
            Some(t) if !all_ended && Instant::now() < t => {
                std::thread::sleep(Duration::from_secs(2));
                continue;
            }
            Some(_) if all_ok => None,
            Some(_) if all_ended => Some(FarmError::failed(format_args!(
                "farm: a job did not complete (logs in {})",
                one_line(dir.join("logs").display())
            ))),
            Some(_) => Some(FarmError::failed(format_args!(
                "farm status --wait: the jobs had not ended after {}s",
                wait.unwrap_or(0)
            ))),
        };
        return Ok(Status { report, failure });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slurm_answers_parse() {
        assert_eq!(count_tasks("0-7"), 8);
        assert_eq!(count_tasks("1-3,7%2"), 4);
        assert_eq!(tasks_in("12_[3-5]"), 3);
        assert_eq!(tasks_in("12_4"), 1);
        assert!(ended("COMPLETED") && ended("FAILED") && !ended("PENDING"));
        assert_eq!(quote("it's"), r"'it'\''s'");
        assert_eq!(parse_sbatch("42;cluster\n"), Some("42".into()));
        assert_eq!(parse_sbatch("Submitted batch job 42"), None);
        let sacct = "12_[0-5]|PENDING\n12_6|RUNNING\n12_7|CANCELLED by 0\n";
        assert_eq!(
            parse_sacct(sacct),
            [("PENDING".into(), 6), ("RUNNING".into(), 1), ("CANCELLED".into(), 1)]
        );
        let scontrol = "JobId=13 ArrayJobId=12 ArrayTaskId=0-3 JobState=PENDING Reason=None\n\
                        JobId=14 JobState=COMPLETED\n";
        assert_eq!(parse_scontrol(scontrol), [("PENDING".into(), 4), ("COMPLETED".into(), 1)]);
    }

    #[test]
    fn scripts_run_each_tile_of_each_frame_then_merge() {
        let job = SlurmJob {
            scene: "shot.ron".into(),
            tiles: 3,
            frames: "4-5".parse().unwrap(),
            output: "frames/f.####.exr".into(),
            dir: "reyes-farm".into(),
            partition: Some("render".into()),
            account: None,
            cpus_per_task: 4,
            time: None,
            mem: Some("8G".into()),
            sbatch: vec!["--qos=low".into()],
            binary: "/opt/reyes-render".into(),
            render: vec!["--seed".into(), "7".into()],
        };
        let (dir, cwd) = (Path::new("/work/reyes-farm"), Path::new("/work"));
        let render = job.render_script(dir, cwd, &[4, 5]);
        for line in [
            "#SBATCH --array=0-5\n",
            "#SBATCH --cpus-per-task=4\n",
            "#SBATCH --chdir=/work\n#SBATCH --partition=render\n#SBATCH --mem=8G\n#SBATCH --qos=low\n",
            "frames=\"4 5\"\nn=3\n",
            "exec '/opt/reyes-render' 'shot.ron' --frames \"$frame\" --tile \"$tile/$n\"",
            "--checkpoint '/work/reyes-farm'/checkpoint/tile.$tile '--seed' '7'\n",
        ] {
            assert!(render.contains(line), "{line} not in\n{render}");
        }
        let merge = job.merge_script(dir, cwd, &[4, 5]);
        assert!(
            merge.ends_with(
                "'/opt/reyes-render' merge '/work/reyes-farm/tiles/frame.0005.tile.1.exr' \
             '/work/reyes-farm/tiles/frame.0005.tile.2.exr' \
             '/work/reyes-farm/tiles/frame.0005.tile.3.exr' -o 'frames/f.0005.exr'\n"
            ),
            "{merge}"
        );
    }
}
