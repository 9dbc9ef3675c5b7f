//! The hider's 8-lane inside test, the innermost part of the visibility stage's hot loop
//! ([`super::Bucket::scan`]): a micropolygon's candidate samples gathered into a [`Batch`] on
//! the stack ([`Candidate`], one kind per path), the vertices placed relative to [`LANES`]
//! samples at once ([`Place`], one per path), and the test itself ([`inside_mask`]).
//! Invariants: every lane computes exactly the operations of the scalar test
//! ([`crate::inside::inside_xy`]) and of [`Place::one`], which places one hit's vertices for
//! its visible point; nothing here allocates.

use super::SliceSample;

/// Samples tested together by the batched inside test: a multiple of 4 so the lanes fill
/// whole SSE/NEON registers.
pub(super) const LANES: usize = 8;

/// Capacity of a [`Batch`] in samples: one batch of [`LANES`]. (Larger buffers, filled
/// branch-free, measured no faster.)
const BUF: usize = LANES;

/// Candidate samples of one micropolygon, gathered from its scan ranges and tested [`LANES`] at
/// a time (structure of arrays on the stack: no allocation). Entry `i < fill` is sample `n[i]`
/// (`pixel*NS + s`) at bucket-local `(x[i], y[i])` — for a lens, minus the depth-independent
/// shift `l * Dof_b` — with lens shift at depth 1 `(ax[i], ay[i])` (paths D and M with a lens)
/// and motion fraction `alpha[i]` (path M). Entries are appended in scan order and tested in
/// that order, as soon as the batch is [full](Batch::full); so `fill < BUF` at every append.
#[derive(Clone, Copy)]
pub(super) struct Batch {
    pub(super) fill: usize,
    pub(super) x: [f32; BUF],
    pub(super) y: [f32; BUF],
    pub(super) ax: [f32; BUF],
    pub(super) ay: [f32; BUF],
    pub(super) alpha: [f32; BUF],
    pub(super) n: [u32; BUF],
    /// Samples tested and visible points created, for the statistics.
    pub(super) tests: u64,
    pub(super) hits: u64,
}

impl Batch {
    pub(super) fn new() -> Batch {
        Batch {
            fill: 0,
            x: [f32::NAN; BUF],
            y: [f32::NAN; BUF],
            ax: [0.0; BUF],
            ay: [0.0; BUF],
            alpha: [0.0; BUF],
            n: [0; BUF],
            tests: 0,
            hits: 0,
        }
    }

    /// Append a sample; returns its entry.
    #[inline(always)]
    fn push(&mut self, x: f32, y: f32, n: usize) -> usize {
        let i = self.fill & (BUF - 1);
        self.x[i] = x;
        self.y[i] = y;
        self.n[i] = n as u32;
        self.fill = i + 1;
        i
    }

    /// Append a slice-ordered sample; returns its entry.
    #[inline(always)]
    fn push_sample(&mut self, r: &SliceSample) -> usize {
        let i = self.fill & (BUF - 1);
        self.x[i] = r.x;
        self.y[i] = r.y;
        self.ax[i] = r.ax;
        self.ay[i] = r.ay;
        self.n[i] = r.n;
        self.fill = i + 1;
        i
    }

    /// True when the batch must be tested before the next append.
    #[inline(always)]
    pub(super) fn full(&self) -> bool {
        self.fill == BUF
    }
}

/// How a path places the micropolygon's vertices relative to a batch's samples: lane by lane
/// for the test (vectorised), and for one entry on a hit. Both must compute exactly the same
/// values, operation for operation.
pub(super) trait Place {
    /// `x[j][l]`, `y[j][l]`: vertex `j` relative to the sample of entry `base + l`.
    fn lanes(&self, b: &Batch, base: usize) -> ([[f32; LANES]; 4], [[f32; LANES]; 4]);
    /// Vertices relative to the sample of entry `i`, with their depths.
    fn one(&self, b: &Batch, i: usize) -> [[f32; 3]; 4];
}

/// `LANES` entries of a batch array from `base`.
#[inline(always)]
fn lanes(a: &[f32; BUF], base: usize) -> &[f32; LANES] {
    a[base..base + LANES].try_into().unwrap()
}

/// Path P: the vertices translated to the sample.
pub(super) struct PlacePinhole {
    pub(super) vx: [f32; 4],
    pub(super) vy: [f32; 4],
    pub(super) vz: [f32; 4],
}

impl Place for PlacePinhole {
    #[inline(always)]
    fn lanes(&self, b: &Batch, base: usize) -> ([[f32; LANES]; 4], [[f32; LANES]; 4]) {
        let (bx, by) = (lanes(&b.x, base), lanes(&b.y, base));
        let mut x = [[0.0; LANES]; 4];
        let mut y = [[0.0; LANES]; 4];
        for j in 0..4 {
            for l in 0..LANES {
                x[j][l] = self.vx[j] - bx[l];
                y[j][l] = self.vy[j] - by[l];
            }
        }
        (x, y)
    }
    #[inline(always)]
    fn one(&self, b: &Batch, i: usize) -> [[f32; 3]; 4] {
        let mut v = [[0.0; 3]; 4];
        for (j, v) in v.iter_mut().enumerate() {
            *v = [self.vx[j] - b.x[i], self.vy[j] - b.y[i], self.vz[j]];
        }
        v
    }
}

/// Path D: each vertex also shifted by the lens offset over its depth.
pub(super) struct PlaceLens {
    pub(super) vx: [f32; 4],
    pub(super) vy: [f32; 4],
    pub(super) vz: [f32; 4],
    pub(super) inv_z: [f32; 4],
}

impl Place for PlaceLens {
    #[inline(always)]
    fn lanes(&self, b: &Batch, base: usize) -> ([[f32; LANES]; 4], [[f32; LANES]; 4]) {
        let (bx, by) = (lanes(&b.x, base), lanes(&b.y, base));
        let (ax, ay) = (lanes(&b.ax, base), lanes(&b.ay, base));
        let mut x = [[0.0; LANES]; 4];
        let mut y = [[0.0; LANES]; 4];
        for j in 0..4 {
            for l in 0..LANES {
                x[j][l] = self.vx[j] - bx[l] + ax[l] * self.inv_z[j];
                y[j][l] = self.vy[j] - by[l] + ay[l] * self.inv_z[j];
            }
        }
        (x, y)
    }
    #[inline(always)]
    fn one(&self, b: &Batch, i: usize) -> [[f32; 3]; 4] {
        let mut v = [[0.0; 3]; 4];
        for (j, v) in v.iter_mut().enumerate() {
            *v = [
                self.vx[j] - b.x[i] + b.ax[i] * self.inv_z[j],
                self.vy[j] - b.y[i] + b.ay[i] * self.inv_z[j],
                self.vz[j],
            ];
        }
        v
    }
}

/// Path M: the vertices moved to the sample's time, then (`LENS`) shifted by the lens offset
/// over their depth at that time, then translated to the sample.
///
/// With `WARP` (perspective-correct motion, Appendix A's `ALPHABETA`), a vertex whose depth
/// changes over the segment is moved in x and y by `beta * speed` instead of `alpha * speed`,
/// `beta = alpha z1 / z(alpha) = alpha / (alpha + (1 - alpha) z0/z1)`: the raster path of a
/// point moving linearly in eye space from depth z0 to z1, whose projection is
/// `(X0 + alpha dX) / (Z0 + alpha dZ)`. Depth itself stays linear in `alpha`. A vertex whose
/// depth does not change takes `beta = alpha` exactly.
pub(super) struct PlaceMoving<const LENS: bool, const WARP: bool> {
    pub(super) v: [[f32; 4]; 3],
    pub(super) speed: [[f32; 4]; 3],
    /// Depth of each vertex at the segment's end (`WARP` only).
    pub(super) z1: [f32; 4],
}

impl<const LENS: bool, const WARP: bool> PlaceMoving<LENS, WARP> {
    /// The fraction of its raster displacement vertex `j` has made at `alpha`, and its depth.
    #[inline(always)]
    fn beta(&self, j: usize, a: f32) -> (f32, f32) {
        let pz = self.v[2][j] + a * self.speed[2][j];
        if WARP && self.speed[2][j] != 0.0 { (a * self.z1[j] / pz, pz) } else { (a, pz) }
    }
}

impl<const LENS: bool, const WARP: bool> Place for PlaceMoving<LENS, WARP> {
    #[inline(always)]
    fn lanes(&self, b: &Batch, base: usize) -> ([[f32; LANES]; 4], [[f32; LANES]; 4]) {
        let (bx, by) = (lanes(&b.x, base), lanes(&b.y, base));
        let (ax, ay) = (lanes(&b.ax, base), lanes(&b.ay, base));
        let alpha = lanes(&b.alpha, base);
        let mut x = [[0.0; LANES]; 4];
        let mut y = [[0.0; LANES]; 4];
        for j in 0..4 {
            for l in 0..LANES {
                let (a, pz) = self.beta(j, alpha[l]);
                let mut px = self.v[0][j] + a * self.speed[0][j];
                let mut py = self.v[1][j] + a * self.speed[1][j];
                if LENS {
                    px += ax[l] / pz;
                    py += ay[l] / pz;
                }
                x[j][l] = px - bx[l];
                y[j][l] = py - by[l];
            }
        }
        (x, y)
    }
    #[inline(always)]
    fn one(&self, b: &Batch, i: usize) -> [[f32; 3]; 4] {
        let mut v = [[0.0; 3]; 4];
        for (j, v) in v.iter_mut().enumerate() {
            let (a, pz) = self.beta(j, b.alpha[i]);
            let mut px = self.v[0][j] + a * self.speed[0][j];
            let mut py = self.v[1][j] + a * self.speed[1][j];
            if LENS {
                px += b.ax[i] / pz;
                py += b.ay[i] / pz;
            }
            *v = [px - b.x[i], py - b.y[i], pz];
        }
        v
    }
}

/// The bit mask of the lanes whose vertices `(x[j][l], y[j][l])` (relative to the sample)
/// enclose the origin: [`crate::inside::inside_xy`] lane by lane, in lane-major form so the compiler keeps
/// lanes in vector registers; every lane computes exactly what the scalar test computes
/// (same products, same comparisons), as the tests check.
// `!(t < 0.0)` on purpose: a NaN counts as "up" there, as in `inside`.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
#[inline(always)]
pub(super) fn inside_mask(x: &[[f32; LANES]; 4], y: &[[f32; LANES]; 4]) -> u32 {
    // 0 or !0 per lane.
    let m = |b: bool| (b as u32).wrapping_neg();
    let mut up = [[0u32; LANES]; 4];
    for l in 0..LANES {
        let y0_up = m(y[0][l] > 0.0);
        for j in 0..4 {
            let t = y[j][l];
            up[j][l] = (y0_up & m(!(t < 0.0))) | (!y0_up & m(t > 0.0));
        }
    }
    let mut parity = [0u32; LANES];
    for i in 0..4 {
        let j = (i + 1) & 3;
        for l in 0..LANES {
            let a = x[i][l] * y[j][l];
            let b = y[i][l] * x[j][l];
            let crosses = (up[j][l] & m(a > b)) | (!up[j][l] & m(b > a));
            parity[l] ^= (up[i][l] ^ up[j][l]) & crosses;
        }
    }
    let mut mask = 0;
    for (l, p) in parity.iter().enumerate() {
        mask |= (p >> 31) << l;
    }
    mask
}

/// One candidate sample as a path's rows yield it, and how it enters a [`Batch`].
pub(super) trait Candidate {
    /// Append to the batch (`fill < BUF`), with every field the path's [`Place`] reads.
    fn append(self, b: &mut Batch);
    /// Its list index `pixel*NS + s`.
    fn n(&self) -> usize;
}

/// Path P: position and list index `pixel*NS + s`, read from
/// [`BucketSamples`](crate::samples::BucketSamples).
pub(super) struct PinholeSample {
    pub(super) x: f32,
    pub(super) y: f32,
    pub(super) n: usize,
}

impl Candidate for PinholeSample {
    #[inline(always)]
    fn append(self, b: &mut Batch) {
        b.push(self.x, self.y, self.n);
    }
    #[inline(always)]
    fn n(&self) -> usize {
        self.n
    }
}

/// Path D: a lens-slice sample as recorded.
impl Candidate for &SliceSample {
    #[inline(always)]
    fn append(self, b: &mut Batch) {
        b.push_sample(self);
    }
    #[inline(always)]
    fn n(&self) -> usize {
        self.n as usize
    }
}

/// Path M: a time-slice sample within the micropolygon's segment, with its motion fraction.
pub(super) struct MovingSample<'r> {
    pub(super) r: &'r SliceSample,
    pub(super) alpha: f32,
}

impl Candidate for MovingSample<'_> {
    #[inline(always)]
    fn append(self, b: &mut Batch) {
        let l = b.push_sample(self.r);
        b.alpha[l] = self.alpha;
    }
    #[inline(always)]
    fn n(&self) -> usize {
        self.r.n as usize
    }
}
