//! The command line: the arguments of `reyes-render`, `reyes-render merge` and `reyes-render
//! measure` (those of `reyes-render farm` are in [`crate::farm`]).

use std::path::PathBuf;
use std::time::Duration;

use clap::Parser;
use reyes_farm::{FrameList, Tile, job, progress};
use reyes_measure::DEFAULT_SAMPLES;

/// Render a scene (RON or RenderMan RIB) with a REYES micropolygon renderer and the stochastic
/// hider of US patent 4,897,806 (Appendix A).
#[derive(Parser, Debug)]
#[command(
    name = "reyes-render",
    version,
    after_help = "Mass properties (patent FIG. 23): reyes-render measure SCENE --object NAME \
                  [--samples N] [--seed N]\n  prints the volume and centre of mass of a closed \
                  object or CSG solid; see reyes-render measure --help\n\
                  Tiles: reyes-render merge TILE... -o OUT\n  reassembles the tiles of a frame \
                  (--tile) into the whole render's file; see docs/farm.md\n\
                  Slurm: reyes-render farm slurm SCENE --tiles N --frames A-B -o OUT, \
                  reyes-render farm status\n  submits a frame range as a tiled array job and \
                  a merge job; see reyes-render farm --help"
)]
pub(crate) struct Args {
    /// Scene file: RON (docs/scene-format.md) or RIB, plain or gzipped (docs/rib.md), by its
    /// extension or else its content; - reads standard input.
    pub scene: PathBuf,
    /// Output image: .exr (RGBA plus Z, and the scene's AOVs as layers) or .png (8-bit sRGB
    /// with alpha, dithered; docs/outputs.md); default for RIB: its Display name. A file of
    /// several frames writes numbered files: a run of # or a %0Nd in the name takes the frame
    /// number, else it is inserted before the extension (out.0001.exr).
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// Override the scene's seed.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Override the scene's pixel samples, as NxM (each 1 to 64).
    #[arg(long, value_name = "NxM", value_parser = job::parse_samples)]
    pub samples: Option<(u32, u32)>,
    /// Print statistics (hits, misses, lerps, visible points, micropolygons, time per stage).
    #[arg(long)]
    pub stats: bool,
    /// No progress bar (on a terminal) or progress lines (elsewhere).
    #[arg(short, long)]
    pub quiet: bool,
    /// Frames to render, e.g. 1-100 or 1,3,5-9: RIB FrameBegin blocks (default: every
    /// frame), or the frame numbers a RON scene's ${...} expressions take
    /// (docs/scene-format.md, "Animation"; needed when it has any).
    #[arg(long, value_name = "LIST")]
    pub frames: Option<FrameList>,
    /// What RIB tolerates with a warning (unknown shaders, exporter noise) is an error.
    #[arg(long)]
    pub strict: bool,
    /// Let `Procedural "RunProgram"` run the programs a RIB file names (off: refused).
    #[arg(long)]
    pub allow_run_program: bool,
    /// Memory budget, e.g. 4G or 512M (default: $REYES_MEMORY_LIMIT, else 3/4 of the smaller
    /// of physical memory and the address-space limit). A frame estimated not to fit is
    /// refused before it starts (exit 2); one that runs out while dicing stops (exit 1).
    #[arg(long, value_name = "SIZE", value_parser = reyes_render::budget::parse_size)]
    pub memory_limit: Option<u64>,
    /// Write +inf depth where nothing is visible, instead of the scene's outputs.zbackground
    /// (default 1e30, finite so that differences of two renders stay finite; docs/outputs.md).
    #[arg(long)]
    pub z_infinite: bool,
    /// Render only part of the frame: RenderMan's CropWindow, in screen fractions (0 left and
    /// top, 1 right and bottom). Each pixel gets exactly its value in the whole frame; the
    /// EXR's data window is the crop's pixels, its display window the whole frame.
    #[arg(long, value_name = "X0,X1,Y0,Y1", value_parser = job::parse_crop)]
    pub crop: Option<[f32; 4]>,
    /// Render tile I of N (1 <= I <= N) of the frame's buckets (of the crop window's, with
    /// --crop): a tile file (.exr) for `reyes-render merge` (docs/farm.md).
    #[arg(long, value_name = "I/N")]
    pub tile: Option<Tile>,
    /// Write each finished bucket to DIR as it completes; run again with the same arguments
    /// to skip those already done (docs/farm.md).
    #[arg(long, value_name = "DIR")]
    pub checkpoint: Option<PathBuf>,
    /// Seconds between progress lines when standard error is not a terminal (0: every
    /// bucket).
    #[arg(long, value_name = "SECS", default_value = "5", value_parser = progress::parse_every)]
    pub progress_every: Duration,
    /// Shading-language instructions per shader and grid (default 50,000,000); beyond: exit 1.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub shader_max_ops: Option<u64>,
}

/// `reyes-render merge TILE... -o OUT`.
#[derive(Parser, Debug)]
#[command(name = "reyes-render merge", bin_name = "reyes-render merge", version)]
pub(crate) struct MergeArgs {
    /// The tile files of one frame (every tile of it, each once), in any order.
    #[arg(required = true, value_name = "TILE")]
    pub tiles: Vec<PathBuf>,
    /// The frame's output: .exr or .png, as the whole render would write it.
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// Volume and centre of mass of a closed object or CSG solid (patent FIG. 23), by stratified
/// pseudo-random point sampling of its bounding box at shutter open: one jittered point in each
/// of about N equal cells, each tested for being inside. Prints each estimate with one standard
/// error, estimated from neighbouring cells paired (an overestimate).
#[derive(Parser, Debug)]
#[command(name = "reyes-render measure", bin_name = "reyes-render measure", version)]
pub(crate) struct MeasureArgs {
    /// Scene file of one frame, RON or RIB (docs/scene-format.md, docs/rib.md).
    pub scene: PathBuf,
    /// The object (`objects[].name`, RIB's `Attribute "identifier" "name"`) or CSG solid
    /// (`solids[].name`) to measure. Cylinders, cones and paraboloids count as closed.
    #[arg(long, value_name = "NAME")]
    pub object: String,
    /// About how many sample points (one per cell).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SAMPLES)]
    pub samples: u64,
    /// Seed of the jitter (default: the scene's seed).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
}
