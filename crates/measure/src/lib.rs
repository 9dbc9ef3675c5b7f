//! Mass properties by pseudo-random point sampling: patent FIG. 23, where the sampling
//! techniques of the patent "determine a center of mass of an object", and "the pseudo-random
//! nature of this sampling assures that the measurement will be made on the actual object and
//! not some alias image of it".
//!
//! [`measure`] estimates the volume and the centre of mass (uniform density) of one closed
//! object, or one CSG solid, of a scene, as it stands at shutter open (time 0: the first
//! `motion` key and the first `deform` key when there are keys).
//!
//! * **Sampling.** The world-space bounding box is split into `nx x ny x nz` equal cells, as
//!   near cubic as the box allows, each count even, about `samples` in all; each cell gets one
//!   point uniformly distributed in it (stratified, "jittered" sampling, the spatial analogue
//!   of FIG. 6). The jitter of a cell is a hash of the seed and the cell index, and cells are
//!   summed in fixed groups added in a fixed order, so the answer depends only on the scene,
//!   the name, the sample count and the seed, never on threads or scheduling.
//! * **Inside test.** Spheres, cylinders, cones, paraboloids and tori: closed forms in object
//!   space, the world point carried back through the inverse object-to-world matrix.
//!   Cylinders, cones and paraboloids count as closed by their end caps, as they are when used
//!   in a solid. Meshes: parity of the crossings of a ray with the mesh alone (a
//!   [`reyes_trace::Tracer`] over that one object) in a fixed, slightly perturbed direction;
//!   when that ray passes near an edge of a face (where it may count one crossing twice or
//!   none), the majority of three rays in different directions. Solids: the operands'
//!   answers combined by the tree.
//! * **Estimates.** volume = box volume x inside fraction; centre = mean of the inside points.
//! * **Standard errors** come from the strata themselves ("collapsed strata"). With one point
//!   per stratum the variance of a sum `sum y_i` is `sum Var(y_i)`, which one point per stratum
//!   cannot estimate directly; pairing every cell with a neighbour (all counts are even, so the
//!   cells fall into 2 x 2 x 2 blocks) and taking `sum over pairs (y_a - y_b)^2` does: its
//!   expectation is the true variance plus `sum (mu_a - mu_b)^2 >= 0`, the squared differences
//!   of neighbouring strata's means, so it errs on the large side, never the small. For the
//!   volume, `y` is the inside indicator, pairs along x. For centre coordinate k (a ratio
//!   estimate, linearised), `y = inside x (p_k - centre_k)`, paired along another axis (x with
//!   y, y with z, z with x) so that the pair's offset along k does not enter the difference.
//!   This is far tighter than the binomial bound `p (1 - p) / N` of unstratified sampling,
//!   which would ignore that only cells cut by the surface vary at all.

mod estimator;
mod inside;
mod report;

use std::fmt;
use std::path::{Path, PathBuf};

use glam::DVec3;
use reyes_scene::Scene;

use crate::estimator::{grid, sample};
use crate::inside::{Node, member, solid_node};

/// Default number of sample points.
pub const DEFAULT_SAMPLES: u64 = 1_000_000;
/// Most sample points of one measurement.
pub const MAX_SAMPLES: u64 = 100_000_000_000;

/// What to measure with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeasureOptions {
    /// About how many sample points, from 1 to [`MAX_SAMPLES`] (at least 8 are taken: a
    /// 2 x 2 x 2 grid).
    pub samples: u64,
    /// Seed of the jitter.
    pub seed: u64,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions { samples: DEFAULT_SAMPLES, seed: 0 }
    }
}

/// What a name resolved to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Target {
    /// `objects[index]`, of shape `shape` (e.g. `"Sphere"`).
    Object {
        /// Index in `Scene::objects`.
        index: usize,
        /// The shape's variant name.
        shape: &'static str,
    },
    /// `solids[index]`.
    Solid {
        /// Index in `Scene::solids`.
        index: usize,
    },
}

/// A centre of mass with its standard errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Centre {
    /// World-space centre of mass.
    pub at: DVec3,
    /// One standard error per axis.
    pub se: DVec3,
}

/// The result of [`measure`].
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    /// The name measured.
    pub name: String,
    /// What it names.
    pub target: Target,
    /// The sampled box, world space (`min > max` on some axis when it is empty).
    pub bounds: (DVec3, DVec3),
    /// Cells per axis (one point each).
    pub grid: [u64; 3],
    /// Seed of the jitter.
    pub seed: u64,
    /// Points found inside.
    pub inside: u64,
    /// Estimated volume.
    pub volume: f64,
    /// One standard error of `volume`.
    pub volume_se: f64,
    /// Estimated centre of mass; `None` when no point is inside.
    pub centre: Option<Centre>,
}

impl Measurement {
    /// Number of sample points taken.
    pub fn points(&self) -> u64 {
        if self.box_is_empty() { 0 } else { self.grid.iter().product() }
    }

    fn box_is_empty(&self) -> bool {
        let (lo, hi) = self.bounds;
        !(lo.cmple(hi).all())
    }
}

/// Why a measurement could not be made. Every one displays as one line naming the option
/// at fault, and is a usage error (exit code 2).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MeasureError {
    /// `samples` is 0 or more than [`MAX_SAMPLES`].
    Samples(u64),
    /// No object or solid has the name.
    NotFound {
        /// The name asked for.
        name: String,
        /// The scene file.
        file: PathBuf,
    },
    /// More than one object or solid has the name.
    Ambiguous {
        /// The name asked for.
        name: String,
        /// The first two things named so, e.g. `objects[0]`, `solids[1]`.
        first: String,
        /// See `first`.
        second: String,
    },
    /// The object (or an operand of the solid) bounds no volume.
    NotClosed {
        /// What, e.g. `object "lid"`.
        what: String,
        /// Why, e.g. `Disk`.
        why: String,
    },
    /// The object's transform at shutter open flattens it.
    Degenerate {
        /// What, e.g. `object "lid"`.
        what: String,
        /// Why.
        why: String,
    },
}

impl MeasureError {
    /// Process exit status: 2 (usage).
    pub fn exit_code(&self) -> u8 {
        2
    }
}

impl fmt::Display for MeasureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeasureError::Samples(n) => {
                write!(f, "--samples: must be from 1 to {MAX_SAMPLES}, got {n}")
            }
            MeasureError::NotFound { name, file } => write!(
                f,
                "--object: no object or solid named {} in {}",
                quoted(name),
                one_line(&file.display().to_string())
            ),
            MeasureError::Ambiguous { name, first, second } => write!(
                f,
                "--object: the name {} is ambiguous: {first} and {second} both have it",
                quoted(name)
            ),
            MeasureError::NotClosed { what, why } => write!(
                f,
                "--object: {what} is not closed ({}), so it bounds no volume",
                one_line(why)
            ),
            MeasureError::Degenerate { what, why } => {
                write!(f, "--object: {what} cannot be measured: {}", one_line(why))
            }
        }
    }
}

impl std::error::Error for MeasureError {}

/// A name for a message: quoted, escaped, clipped to 64 characters.
fn quoted(name: &str) -> String {
    let clipped: String = if name.chars().count() > 64 {
        name.chars().take(63).chain(['…']).collect()
    } else {
        name.to_string()
    };
    format!("{clipped:?}")
}

/// `s` with control characters and line separators escaped.
fn one_line(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Measures the object or solid named `name` in `scene` (loaded from `file`, which is used in
/// messages only). See the module documentation for the method.
pub fn measure(
    scene: &Scene,
    file: &Path,
    name: &str,
    opts: &MeasureOptions,
) -> Result<Measurement, MeasureError> {
    if opts.samples == 0 || opts.samples > MAX_SAMPLES {
        return Err(MeasureError::Samples(opts.samples));
    }
    let named: Vec<(String, Target)> = if name.is_empty() {
        Vec::new()
    } else {
        let objects =
            scene.objects.iter().enumerate().filter(|(_, o)| o.name == name).map(|(index, o)| {
                (format!("objects[{index}]"), Target::Object { index, shape: o.shape.name() })
            });
        let solids = scene
            .solids
            .iter()
            .enumerate()
            .filter(|(_, s)| s.name == name)
            .map(|(index, _)| (format!("solids[{index}]"), Target::Solid { index }));
        objects.chain(solids).take(2).collect()
    };
    let target = match named.as_slice() {
        [] => {
            return Err(MeasureError::NotFound {
                name: name.to_string(),
                file: file.to_path_buf(),
            });
        }
        [(first, _), (second, _)] => {
            return Err(MeasureError::Ambiguous {
                name: name.to_string(),
                first: first.clone(),
                second: second.clone(),
            });
        }
        [(_, target), ..] => target.clone(),
    };

    let mut members = Vec::new();
    let tree = match &target {
        Target::Object { index, .. } => {
            members.push(member(scene, *index, &format!("object {}", quoted(name)))?);
            Node::Leaf(0)
        }
        Target::Solid { index } => {
            solid_node(scene, &scene.solids[*index].tree, name, &mut members)?
        }
    };
    let bounds = tree.bounds(&members);
    let mut out = Measurement {
        name: name.to_string(),
        target,
        bounds: (bounds.min, bounds.max),
        grid: [0; 3],
        seed: opts.seed,
        inside: 0,
        volume: 0.0,
        volume_se: 0.0,
        centre: None,
    };
    if bounds.is_empty() {
        return Ok(out);
    }
    let ext = bounds.max - bounds.min;
    let n = grid(ext, opts.samples);
    let inside = |p: DVec3, key: u64| tree.contains(&members, p, key);
    let s = sample(&bounds, n, opts.seed, &inside);

    let total = (n[0] * n[1] * n[2]) as f64;
    let box_volume = ext.x * ext.y * ext.z;
    out.grid = n;
    out.inside = s.inside;
    out.volume = box_volume * s.inside as f64 / total;
    out.volume_se = box_volume / total * (s.vol_pairs as f64).sqrt();
    if s.inside > 0 {
        let count = s.inside as f64;
        let mut at = DVec3::ZERO;
        let mut se = DVec3::ZERO;
        for k in 0..3 {
            let c = s.first[k] / count;
            let var = (s.dxx[k] - 2.0 * c * s.dxi[k] + c * c * s.dii[k] as f64) / (count * count);
            at[k] = c;
            se[k] = var.max(0.0).sqrt();
        }
        out.centre = Some(Centre { at: at + (bounds.min + bounds.max) * 0.5, se });
    }
    Ok(out)
}
