//! One bucket's samples: position, time and lens position of sample `s` of every pixel,
//! computed once per bucket from the tables with Appendix A's indexing (appendix-a.md 3.2):
//!
//! ```text
//! i = 7*s + 2*pixel          (pixel = y*XPerBucket + x, bucket-local)
//! position = (x + Location[s].x + XJitter[ox+i],  y + Location[s].y + YJitter[oy+i+1])
//! time     = tau/NS + TJitter[ot+i+2]              (tau: the sample's time stratum)
//! lens     = lens stratum + (LXJitter[olx+i+3], LYJitter[oly+i+4])
//! ```
//!
//! with `ox..oly` in 0..=22 drawn per bucket. Invariants: arrays are pixel-major
//! (`k = pixel*NS + s`, the index of every per-sample array of the hider: visible-point
//! lists, colours, depths), so a micropolygon's scan, which reads a few pixels for every
//! sample index in turn, reads each pixel's samples in order, a cache line serving 16 of them
//! (sample-major, `s*P + pixel`, read one line per sample from arrays of `4 NS P` bytes, which
//! at 64x64 samples left the inside test waiting on memory: docs/performance.md); sample `s`
//! of every pixel lies in spatial stratum `Location[s]` (for every pattern but
//! [`Pattern::Random`], which is unstratified by definition: the hider's scan ranges come
//! from each slice's actual reach, so it stays correct, only slower); the samples of time
//! slice `tau` all have times in `[tau/NS, (tau+1)/NS)`.
//!
//! [`Pattern::Sobol`] does not read the tables: each pixel gets its own Owen-scrambled Sobol
//! (0,2) point set for position and another for the lens, and a scrambled (0,1) set for time
//! (see [`owen`]); each position point goes to the sample whose stratum holds it.

pub mod owen;

use reyes_sampling::{hash, unit};

use crate::tables::{Table, Tables};
use owen::{JointScramble, Scramble, to_unit, to_unit_16};
pub use reyes_sampling::ShutterShape;

/// Spatial pattern (FIGS. 3, 5, 6, 7 of the patent).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pattern {
    /// FIG. 3: the regular grid of stratum centres (Appendix A `jitter off`).
    Regular,
    /// FIG. 5: one random point per stratum, the same pattern in every pixel of the image.
    Fig5,
    /// FIG. 6: a new random point anywhere in each stratum of every pixel (Appendix A `jitter on`).
    #[default]
    Fig6,
    /// FIG. 7: the FIG. 5 reference pattern plus a random offset of at most a quarter stratum.
    Fig7,
    /// Pure random: each sample uniform anywhere in its pixel, new in every pixel, with no
    /// stratification (the baseline the patent improves on). Times and lens positions are
    /// still made as for FIG. 6 (stratified, paired as asked).
    Random,
    /// Modern: per pixel, an Owen-scrambled Sobol (0,2) point set (Burley 2020), every point
    /// given to the sample whose stratum holds it; time from a scrambled (0,1) set and the
    /// lens from another scrambled (0,2) set, each with its own scramble per pixel and paired
    /// with the positions as for FIG. 6. Needs `nx` and `ny` to be powers of two and a
    /// one-to-one `Location`; otherwise FIG. 6 is used instead.
    Sobol,
    /// Joint: per pixel, one Owen-scrambled Sobol sequence over position, time and lens
    /// together ([`owen::JointScramble`]): dimensions 0-2 are (x, y, t), a (1,m,3)-net, and
    /// the lens is a (0,m,2)-net on an index map of dimension 3, so a moving or defocused edge,
    /// whose integrand couples position with time or lens, is stratified jointly. The net
    /// picks each sample's spatial stratum, time and lens cell; within its stratum the point
    /// sits where correlated multi-jittered sampling (Kensler 2013) puts it, which is more
    /// even than the net's own offsets (measured in docs/sampling.md). Power-of-two `nx` and
    /// `ny` and a one-to-one `Location` only; otherwise FIG. 6 is used instead.
    SobolJoint,
}

/// For [`Pattern::Sobol`]: `(a, b, cells)` with `nx = 2^a`, `ny = 2^b` and `cells[cx << b | cy]`
/// the sample index whose stratum is cell `(cx, cy)`; `None` when that is not possible
/// (a side not a power of two, or the original `permute`'s non-bijective `Location`).
pub fn sobol_cells(tables: &Tables) -> Option<(u32, u32, Vec<u32>)> {
    if !(tables.nx.is_power_of_two() && tables.ny.is_power_of_two()) {
        return None;
    }
    let (a, b) = (tables.nx.trailing_zeros(), tables.ny.trailing_zeros());
    let mut cells = vec![u32::MAX; tables.ns as usize];
    for (s, loc) in tables.location.iter().enumerate() {
        let cx = (loc[0] * tables.nx as f32).round() as u32;
        let cy = (loc[1] * tables.ny as f32).round() as u32;
        let c = ((cx << b) | cy) as usize;
        if cells[c] != u32::MAX {
            return None;
        }
        cells[c] = s as u32;
    }
    Some((a, b, cells))
}

/// The leading `bits` binary digits of a 32-bit fraction.
#[inline]
fn leading(x: u32, bits: u32) -> u32 {
    ((x as u64) >> (32 - bits)) as u32
}

/// How a time is chosen within its stratum (patent FIGS. 13-15, the temporal counterparts of
/// the spatial FIGS. 5-7). With jitter off every pattern gives the stratum's centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TimePattern {
    /// FIG. 13: one pseudo-random time per stratum, the same in every pixel.
    Fig13,
    /// FIG. 14: a new pseudo-random time anywhere in the stratum for every pixel (Appendix A).
    #[default]
    Fig14,
    /// FIG. 15: a FIG. 13 reference time plus a pseudo-random shift of at most a quarter stratum.
    Fig15,
}

/// How sample indices are paired with time and lens strata.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pairing {
    /// Each pixel pairs its samples with time and lens strata through its own pseudo-random
    /// permutations, so time and lens are uncorrelated with sub-pixel position.
    #[default]
    Decorrelated,
    /// Appendix A: sample s has time stratum s and lens stratum `Location[s]`, in every pixel
    /// (time is tied to sub-pixel rows, lens to sub-pixel position: appendix-a.md 3.3, 3.8).
    Original,
}

/// Shape of the lens samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LensShape {
    /// Stratified lens cells mapped onto the unit disk by the concentric square-to-disk map.
    #[default]
    Disk,
    /// Appendix A's "kludge": the square `[-0.5/NS, 1 - 0.5/NS)^2`, uncentred, with sample s
    /// always in lens cell `Location[s]`, so lens position follows screen position (3.8).
    OriginalSquare,
}

/// A bucket's samples, reused from bucket to bucket.
#[derive(Debug, Default, Clone)]
pub struct BucketSamples {
    /// Bucket-local x of sample k = pixel*NS + s.
    pub x: Vec<f32>,
    /// Bucket-local y.
    pub y: Vec<f32>,
    /// Shutter time in [0, 1).
    pub t: Vec<f32>,
    /// Lens x in lens-radius units.
    pub lx: Vec<f32>,
    /// Lens y.
    pub ly: Vec<f32>,
    /// `by_time[pixel*NS + tau]`: the sample index s of that pixel whose time is in slice tau.
    pub by_time: Vec<u32>,
    /// `by_lens[pixel*NS + lambda]`: the sample index s of that pixel in lens stratum lambda.
    pub by_lens: Vec<u32>,
    /// Per lens slice: (min lx, max lx, min ly, max ly) of its samples.
    pub lens_range: Vec<[f32; 4]>,
    /// Per lens slice: reach of its samples' positions, as `reach_space`.
    pub reach_lens: Vec<[f32; 4]>,
    /// Per spatial slice s: (min x offset, max x offset, min y offset, max y offset) of the
    /// slice's samples from their pixel's corner, for scan ranges.
    pub reach_space: Vec<[f32; 4]>,
    /// The same per time slice.
    pub reach_time: Vec<[f32; 4]>,
}

/// Offset of a FIG. 7 sample from its reference point, at most this fraction of a stratum.
const FIG7_REACH: f32 = 0.25;

/// Concentric map of the unit square onto the unit disk (Shirley and Chiu, 1997): keeps
/// strata compact and area-preserving.
fn concentric_disk(u: f32, v: f32) -> (f32, f32) {
    let a = 2.0 * u - 1.0;
    let b = 2.0 * v - 1.0;
    if a == 0.0 && b == 0.0 {
        return (0.0, 0.0);
    }
    let (r, phi) = if a.abs() > b.abs() {
        (a, std::f32::consts::FRAC_PI_4 * (b / a))
    } else {
        (b, std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (a / b))
    };
    (r * phi.cos(), r * phi.sin())
}

/// Fill `perm` with a pseudo-random permutation of 0..n determined by `key`.
fn shuffle(perm: &mut [u32], seed: u64, key: &[u64]) {
    for (i, p) in perm.iter_mut().enumerate() {
        *p = i as u32;
    }
    let base = hash(seed, key);
    for i in (1..perm.len()).rev() {
        let j = (hash(base, &[i as u64]) % (i as u64 + 1)) as usize;
        perm.swap(i, j);
    }
}

/// Everything sample generation needs besides the tables.
#[derive(Debug, Clone, Copy)]
pub struct SampleSpec {
    /// Spatial pattern.
    pub pattern: Pattern,
    /// Time pairing.
    pub time_pairing: Pairing,
    /// Time pattern within each stratum.
    pub time_pattern: TimePattern,
    /// Shutter shape.
    pub shutter: ShutterShape,
    /// Lens shape (and lens pairing: decorrelated for the disk, Appendix A's for the square).
    pub lens_shape: LensShape,
    /// Seed.
    pub seed: u64,
}

/// Which sample dimensions a bucket will read. Positions are always made; times and lens
/// positions only when asked for (their values do not depend on whether the other is made).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Needs {
    /// Times, time slices and their reach (path M).
    pub time: bool,
    /// Lens positions, lens slices and their ranges (paths D and M with a lens).
    pub lens: bool,
}

impl Needs {
    /// Every dimension.
    pub const ALL: Needs = Needs { time: true, lens: true };
}

impl BucketSamples {
    /// Compute the samples of bucket number `bucket` whose top-left pixel is raster
    /// (`left`, `top`) and whose size is `bw` x `bh`.
    #[allow(clippy::too_many_arguments)]
    pub fn generate(
        &mut self,
        tables: &Tables,
        spec: &SampleSpec,
        bucket: usize,
        left: i32,
        top: i32,
        bw: u32,
        bh: u32,
        needs: Needs,
    ) {
        let ns = tables.ns as usize;
        let p_count = (bw * bh) as usize;
        let n = ns * p_count;
        for v in [&mut self.x, &mut self.y, &mut self.t, &mut self.lx, &mut self.ly] {
            v.clear();
            v.resize(n, 0.0);
        }
        self.by_time.clear();
        self.by_time.resize(n, 0);
        self.by_lens.clear();
        self.by_lens.resize(n, 0);
        let (fx, fy, fns) = (tables.nx as f32, tables.ny as f32, ns as f32);
        // Per-bucket random start offsets 0..22 into each table (`(int)(23*drand())`).
        let off: [usize; 5] = std::array::from_fn(|k| {
            (hash(spec.seed, &[0xb0c7, bucket as u64, k as u64]) % 23) as usize
        });
        let mut time_perm = vec![0u32; ns];
        let mut lens_perm = vec![0u32; ns];
        // The modern sampler's per-pixel point sets, indexed by sample index s (position),
        // time stratum tau and lens cell lambda.
        let sobol = match spec.pattern {
            Pattern::Sobol | Pattern::SobolJoint => sobol_cells(tables),
            _ => None,
        };
        let pattern = match spec.pattern {
            Pattern::Sobol | Pattern::SobolJoint if sobol.is_none() => Pattern::Fig6,
            p => p,
        };
        let joint = pattern == Pattern::SobolJoint;
        // The joint sampler's sample index, raw lens point and lens order per net point j.
        let (mut joint_s, mut joint_lens, mut joint_order) = match joint {
            true => (vec![0u32; ns], vec![[0u32; 3]; ns], vec![0u32; ns]),
            false => (Vec::new(), Vec::new(), Vec::new()),
        };
        let mut joint_points = Vec::with_capacity(if joint { ns } else { 0 });
        let (mut cmj_x, mut cmj_y) =
            (vec![0u32; tables.nx as usize], vec![0u32; tables.ny as usize]);
        let (mut net_xy, mut net_t, mut net_l) = match sobol {
            Some(_) => (vec![[0.0f32; 2]; ns], vec![0.0f32; ns], vec![[0.0f32; 2]; ns]),
            None => (Vec::new(), Vec::new(), Vec::new()),
        };
        let m = ns.trailing_zeros();
        for py in 0..bh {
            for px in 0..bw {
                let pixel = (py * bw + px) as usize;
                let gx = (left + px as i32) as i64 as u64;
                let gy = (top + py as i32) as i64 as u64;
                match spec.time_pairing {
                    _ if !needs.time || joint => {}
                    Pairing::Original => {
                        for (s, tp) in time_perm.iter_mut().enumerate() {
                            *tp = s as u32;
                        }
                    }
                    Pairing::Decorrelated => shuffle(&mut time_perm, spec.seed, &[0x7173, gx, gy]),
                }
                match spec.lens_shape {
                    _ if !needs.lens || joint => {}
                    LensShape::OriginalSquare => {
                        for (s, lp) in lens_perm.iter_mut().enumerate() {
                            *lp = s as u32;
                        }
                    }
                    LensShape::Disk => shuffle(&mut lens_perm, spec.seed, &[0x1e75, gx, gy]),
                }
                if let (true, Some((a, b, cells))) = (joint, &sobol) {
                    let (a, b) = (*a, *b);
                    let cell = |p: [u32; 2]| {
                        (
                            leading(p[0], a),
                            leading(p[1], b),
                            cells[((leading(p[0], a) << b) | leading(p[1], b)) as usize],
                        )
                    };
                    let sc = JointScramble::new(spec.seed, &[0x501a, gx, gy]);
                    shuffle(&mut cmj_x, spec.seed, &[0xc31a, gx, gy]);
                    shuffle(&mut cmj_y, spec.seed, &[0xc31b, gx, gy]);
                    let (ny, fine) = (tables.ny as u64, 32 - m);
                    sc.block(m, &mut joint_points);
                    for (j, p) in joint_points.iter().enumerate() {
                        let j = j as u32;
                        let (cx, cy, s) = cell(p.xy);
                        // Correlated multi-jitter within the stratum: column cx's points take
                        // the x sub-strata perm_y(row), row cy's the y sub-strata perm_x(col).
                        let h = hash(spec.seed, &[0xc31c, gx, gy, j as u64]);
                        let fx = ((cx as u64 * ny + cmj_y[cy as usize] as u64) << fine)
                            | ((h as u32) >> m) as u64;
                        let fy = ((cy as u64 * (1u64 << a) + cmj_x[cx as usize] as u64) << fine)
                            | (((h >> 32) as u32) >> m) as u64;
                        let s = s as usize;
                        net_xy[s] = [to_unit_16(fx as u32), to_unit_16(fy as u32)];
                        joint_s[j as usize] = s as u32;
                        joint_lens[j as usize] = [p.lens[0], p.lens[1], p.lens_v_raw];
                        if needs.time {
                            let tau = match spec.time_pairing {
                                Pairing::Decorrelated => leading(p.t, m) as usize,
                                Pairing::Original => s,
                            };
                            // The net's time, moved into stratum tau (the identity unless the
                            // original pairing asks for stratum s).
                            let bits = ((tau as u64) << fine) | (p.t.wrapping_shl(m) >> m) as u64;
                            time_perm[s] = tau as u32;
                            net_t[tau] = to_unit(bits as u32);
                        }
                    }
                    if needs.lens {
                        // Lens cells: u's column is exact (dimension 3 is a (0,1)-sequence, so
                        // each column of cells holds 2^b points); within a column the points
                        // are ranked by their v stratum before v's scramble (ties in a hashed
                        // order), the k-th takes row k with its own offset, and only then is
                        // v scrambled: one point per lens cell. The rank must not look at the
                        // offset: ranking two points of one stratum by their full v sent the
                        // lower offset down a row and the higher one up, pushing lens points
                        // apart and the circle of confusion out (+0.02 px on a 3-px radius at
                        // 16 samples, issue #36). Ranked after the scramble, which stratum a
                        // crowded column pushes into depended on where the scramble put the
                        // empty one, and lens v took a correlation with time (-0.016 over
                        // 65,536 samples); scrambled afterwards, every digit of the final v is
                        // flipped at random whatever the rank did, so each point is uniform in
                        // its cell and v is independent of the other dimensions.
                        for (j, o) in joint_order.iter_mut().enumerate() {
                            *o = j as u32;
                        }
                        let key = |j: u32| {
                            let [u, _, v] = joint_lens[j as usize];
                            let tie = hash(spec.seed, &[0x1e7a, gx, gy, j as u64]) as u32;
                            ((leading(u, a) as u64) << 48)
                                | ((leading(v, b) as u64) << 32)
                                | tie as u64
                        };
                        joint_order.sort_by_key(|&j| key(j)); // stable: ties in j order
                        for (rank, &j) in joint_order.iter().enumerate() {
                            let (s, [u, v, v_raw]) =
                                (joint_s[j as usize] as usize, joint_lens[j as usize]);
                            let row = rank as u64 & ((1u64 << b) - 1);
                            let (col, row) = match spec.lens_shape {
                                LensShape::Disk => (leading(u, a) as u64, row),
                                LensShape::OriginalSquare => {
                                    // Appendix A: lens cell Location[s], the net's offsets in it.
                                    let loc = tables.location[s];
                                    (
                                        (loc[0] * tables.nx as f32).round() as u64,
                                        (loc[1] * tables.ny as f32).round() as u64,
                                    )
                                }
                            };
                            let u = (col << (32 - a)) | (u.wrapping_shl(a) >> a) as u64;
                            let v = match spec.lens_shape {
                                LensShape::Disk => sc.scramble_lens_v(
                                    ((row << (32 - b)) | (v_raw.wrapping_shl(b) >> b) as u64)
                                        as u32,
                                ) as u64,
                                LensShape::OriginalSquare => {
                                    (row << (32 - b)) | (v.wrapping_shl(b) >> b) as u64
                                }
                            };
                            let lambda = match spec.lens_shape {
                                LensShape::Disk => {
                                    let row = leading(v as u32, b) as u64;
                                    cells[((col << b) | row) as usize] as usize
                                }
                                LensShape::OriginalSquare => s,
                            };
                            lens_perm[s] = lambda as u32;
                            net_l[lambda] = [to_unit(u as u32), to_unit(v as u32)];
                        }
                    }
                } else if let Some((a, b, cells)) = &sobol {
                    let cell = |p: [u32; 2]| {
                        cells[((leading(p[0], *a) << b) | leading(p[1], *b)) as usize]
                    };
                    let space = Scramble::new(spec.seed, &[0x50b0, gx, gy]);
                    for j in 0..ns as u32 {
                        let p = space.point_2d(j);
                        net_xy[cell(p) as usize] = [to_unit_16(p[0]), to_unit_16(p[1])];
                    }
                    if needs.time {
                        let time = Scramble::new(spec.seed, &[0x71e5, gx, gy]);
                        for j in 0..ns as u32 {
                            let t = time.point_1d(j);
                            net_t[leading(t, m) as usize] = to_unit(t);
                        }
                    }
                    if needs.lens {
                        let lens = Scramble::new(spec.seed, &[0x1e25, gx, gy]);
                        for j in 0..ns as u32 {
                            let p = lens.point_2d(j);
                            net_l[cell(p) as usize] = [to_unit(p[0]), to_unit(p[1])];
                        }
                    }
                }
                for s in 0..ns {
                    let i = 7 * s + 2 * pixel;
                    let k = pixel * ns + s;
                    let loc = tables.location[s];
                    let (jx, jy) = match pattern {
                        Pattern::Random | Pattern::Sobol | Pattern::SobolJoint => (0.0, 0.0), // not read
                        Pattern::Regular | Pattern::Fig6 => {
                            (tables.get(Table::X, off[0] + i), tables.get(Table::Y, off[1] + i + 1))
                        }
                        Pattern::Fig5 => {
                            (tables.get(Table::X, 7 * s), tables.get(Table::Y, 7 * s + 1))
                        }
                        Pattern::Fig7 => {
                            let r = |refj: f32, jit: f32, cells: f32| {
                                let refu = refj * cells; // [0, 1) of the stratum
                                let offu = 2.0 * jit * cells - 1.0; // [-1, 1)
                                (FIG7_REACH + (1.0 - 2.0 * FIG7_REACH) * refu + FIG7_REACH * offu)
                                    / cells
                            };
                            (
                                r(
                                    tables.get(Table::X, 7 * s),
                                    tables.get(Table::X, off[0] + i),
                                    fx,
                                ),
                                r(
                                    tables.get(Table::Y, 7 * s + 1),
                                    tables.get(Table::Y, off[1] + i + 1),
                                    fy,
                                ),
                            )
                        }
                    };
                    match pattern {
                        Pattern::Random => {
                            let h = hash(spec.seed, &[0x7a4d, gx, gy, s as u64]);
                            self.x[k] = px as f32 + unit(h);
                            self.y[k] = py as f32 + unit(h << 24);
                        }
                        Pattern::Sobol | Pattern::SobolJoint => {
                            self.x[k] = px as f32 + net_xy[s][0];
                            self.y[k] = py as f32 + net_xy[s][1];
                        }
                        _ => {
                            self.x[k] = px as f32 + loc[0] + jx;
                            self.y[k] = py as f32 + loc[1] + jy;
                        }
                    }
                    let tau = time_perm[s] as usize;
                    if needs.time {
                        // Stratified in [tau/NS, (tau+1)/NS), then warped by the shutter shape.
                        let u = if sobol.is_some() {
                            net_t[tau]
                        } else {
                            let own = tables.get(Table::T, off[2] + i + 2);
                            let jt = match spec.time_pattern {
                                TimePattern::Fig14 => own,
                                TimePattern::Fig13 => tables.get(Table::T, 7 * tau + 2),
                                TimePattern::Fig15 => {
                                    let refu = tables.get(Table::T, 7 * tau + 2) * fns;
                                    let offu = 2.0 * own * fns - 1.0;
                                    (FIG7_REACH
                                        + (1.0 - 2.0 * FIG7_REACH) * refu
                                        + FIG7_REACH * offu)
                                        / fns
                                }
                            };
                            tau as f32 / fns + jt
                        };
                        self.t[k] = spec.shutter.warp(u.min(1.0));
                        self.by_time[pixel * ns + tau] = s as u32;
                    }
                    if !needs.lens {
                        continue;
                    }
                    let jlx = tables.get(Table::LensX, off[3] + i + 3);
                    let jly = tables.get(Table::LensY, off[4] + i + 4);
                    let lambda = lens_perm[s] as usize;
                    self.by_lens[pixel * ns + lambda] = s as u32;
                    let lens_cell = tables.location[lambda];
                    let (lx, ly) = match spec.lens_shape {
                        _ if sobol.is_some() => {
                            let [u, v] = net_l[lambda];
                            match spec.lens_shape {
                                LensShape::OriginalSquare => (u - 0.5 / fns, v - 0.5 / fns),
                                LensShape::Disk => concentric_disk(u, v),
                            }
                        }
                        LensShape::OriginalSquare => {
                            (lens_cell[0] - 0.5 / fns + jlx, lens_cell[1] - 0.5 / fns + jly)
                        }
                        LensShape::Disk => concentric_disk(
                            (lens_cell[0] + jlx).min(1.0),
                            (lens_cell[1] + jly).min(1.0),
                        ),
                    };
                    self.lx[k] = lx;
                    self.ly[k] = ly;
                }
            }
        }
        const EMPTY: [f32; 4] =
            [f32::INFINITY, f32::NEG_INFINITY, f32::INFINITY, f32::NEG_INFINITY];
        let grow = |r: &mut [f32; 4], x: f32, y: f32| {
            r[0] = r[0].min(x);
            r[1] = r[1].max(x);
            r[2] = r[2].min(y);
            r[3] = r[3].max(y);
        };
        // Every slice's ranges over its pixels, each slice seeing the pixels in increasing
        // order (as a slice-by-slice loop would), while the arrays are read in their order.
        for r in [&mut self.reach_space, &mut self.reach_time, &mut self.reach_lens] {
            r.clear();
            r.resize(ns, EMPTY);
        }
        self.lens_range.clear();
        self.lens_range.resize(ns, EMPTY);
        for pixel in 0..p_count {
            let (px, py) = ((pixel as u32 % bw) as f32, (pixel as u32 / bw) as f32);
            let base = pixel * ns;
            for slice in 0..ns {
                let ks = base + slice;
                grow(&mut self.reach_space[slice], self.x[ks] - px, self.y[ks] - py);
                if needs.time {
                    let kt = base + self.by_time[ks] as usize;
                    grow(&mut self.reach_time[slice], self.x[kt] - px, self.y[kt] - py);
                }
                if needs.lens {
                    let kl = base + self.by_lens[ks] as usize;
                    grow(&mut self.reach_lens[slice], self.x[kl] - px, self.y[kl] - py);
                    grow(&mut self.lens_range[slice], self.lx[kl], self.ly[kl]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(pattern: Pattern, pairing: Pairing) -> SampleSpec {
        SampleSpec {
            pattern,
            time_pairing: pairing,
            time_pattern: TimePattern::Fig14,
            shutter: ShutterShape::Uniform,
            lens_shape: LensShape::Disk,
            seed: 5,
        }
    }

    fn make(pattern: Pattern, pairing: Pairing, nx: u32, ny: u32) -> (Tables, BucketSamples) {
        let t = Tables::new(nx, ny, 64, pattern != Pattern::Regular, 5, false, false);
        let mut b = BucketSamples::default();
        b.generate(&t, &spec(pattern, pairing), 3, 16, 8, 8, 8, Needs::ALL);
        (t, b)
    }

    #[test]
    fn every_pattern_puts_one_sample_in_each_stratum_of_every_pixel() {
        for pattern in [Pattern::Regular, Pattern::Fig5, Pattern::Fig6, Pattern::Fig7] {
            let (t, b) = make(pattern, Pairing::Decorrelated, 4, 3);
            for pixel in 0..64usize {
                let (px, py) = ((pixel % 8) as f32, (pixel / 8) as f32);
                let mut seen = [false; 12];
                for s in 0..12 {
                    let k = pixel * 12 + s;
                    let cx = ((b.x[k] - px) * 4.0).floor();
                    let cy = ((b.y[k] - py) * 3.0).floor();
                    assert!((0.0..4.0).contains(&cx) && (0.0..3.0).contains(&cy), "{pattern:?}");
                    assert_eq!([cx / 4.0, cy / 3.0], t.location[s]);
                    let q = (cx * 3.0 + cy) as usize;
                    assert!(!seen[q]);
                    seen[q] = true;
                }
            }
        }
    }

    #[test]
    fn fig5_repeats_the_pattern_and_fig6_does_not() {
        let (_, b5) = make(Pattern::Fig5, Pairing::Original, 2, 2);
        let (_, b6) = make(Pattern::Fig6, Pairing::Original, 2, 2);
        let frac = |b: &BucketSamples, k: usize, p: usize| b.x[k] - (p % 8) as f32;
        for s in 0..4 {
            let first5 = frac(&b5, s, 0);
            let first6 = frac(&b6, s, 0);
            // Equal up to the rounding of `x + frac - x` at x < 8 (a few ulps of 8).
            assert!((1..64).all(|p| (frac(&b5, p * 4 + s, p) - first5).abs() < 4e-6));
            assert!((1..64).any(|p| (frac(&b6, p * 4 + s, p) - first6).abs() > 1e-3));
        }
    }

    #[test]
    fn time_slices_hold_their_stratum() {
        for pairing in [Pairing::Original, Pairing::Decorrelated] {
            let (_, b) = make(Pattern::Fig6, pairing, 4, 4);
            for tau in 0..16 {
                for pixel in 0..64 {
                    let s = b.by_time[pixel * 16 + tau] as usize;
                    let t = b.t[pixel * 16 + s];
                    assert!(t >= tau as f32 / 16.0 && t < (tau + 1) as f32 / 16.0);
                }
            }
        }
    }

    #[test]
    fn disk_lens_is_in_the_unit_disk_and_centred() {
        let (_, b) = make(Pattern::Fig6, Pairing::Decorrelated, 4, 4);
        let n = b.lx.len() as f32;
        let (mut mx, mut my) = (0.0, 0.0);
        for k in 0..b.lx.len() {
            assert!(b.lx[k].hypot(b.ly[k]) <= 1.0 + 1e-6);
            mx += b.lx[k] / n;
            my += b.ly[k] / n;
        }
        // 1024 stratified samples of a centred disk: the mean is far inside 0.05.
        assert!(mx.abs() < 0.05 && my.abs() < 0.05, "{mx} {my}");
    }
}
