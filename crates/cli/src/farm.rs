//! `reyes-render farm slurm|status`: their arguments, and what reyes-farm's
//! [`reyes_farm::slurm`] did, printed: a frame range as a Slurm array job of tiles with a
//! merge job after it, and their state read back (docs/farm.md).

use std::path::PathBuf;

use clap::Parser;
use reyes_farm::FrameList;
use reyes_farm::slurm::{SlurmJob, status};

use crate::Exit;
use crate::term::print;

/// Render on a farm (docs/farm.md).
#[derive(Parser, Debug)]
#[command(name = "reyes-render farm", bin_name = "reyes-render farm", version)]
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
    #[arg(long, value_name = "LIST")]
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
    let a = match crate::parse(args, false, "reyes-render farm --help")? {
        Engine::Slurm(a) => *a,
        Engine::Status(a) => {
            let found = status(&a.dir, a.wait)?;
            print(&found.report)?;
            return found.failure.map_or(Ok(()), |e| Err(e.into()));
        }
    };
    let binary = a.binary.map_or_else(std::env::current_exe, Ok);
    let binary = binary.map_err(|e| Exit::error(1, format_args!("reyes-render: {e}")))?;
    let job = SlurmJob {
        scene: a.scene,
        tiles: a.tiles,
        frames: a.frames,
        output: a.output,
        dir: a.dir,
        partition: a.partition,
        account: a.account,
        cpus_per_task: a.cpus_per_task,
        time: a.time,
        mem: a.mem,
        sbatch: a.sbatch,
        binary,
        render: a.render,
    };
    let scripts = job.write()?;
    if a.no_submit {
        return print(&format!("{}\n{}\n", scripts.render.display(), scripts.merge.display()));
    }
    print(&scripts.submit()?.summary())
}
