//! RenderMan blobby implicit surfaces (`RiBlobby`), shared by validation and the dicer: the
//! code stream read into a [`Program`], the field and its gradient, the per-field blend of
//! colours, a bound, and a coarse polygon mesh of the surface on which the dicer dices.
//!
//! The field (RenderMan Interface 3.2, "Implicit surfaces", and PRMan's application note on
//! blobbies): every primitive field is the bump `F(R) = (1 - R^2)^3` for `R < 1` (0 beyond)
//! of a distance `R` in its own space: an ellipsoid (1001) is the unit sphere under its 4x4
//! matrix, a segment (1002) the points within `radius` of a segment under its matrix. A
//! constant (1000) is its value everywhere. A repelling ground plane (1003, with a depth-map
//! name, and 1004, without) is PRMan's `repulsion(z)` of the height `z` above the plane
//! `z = 0` of the primitive's space (a depth map is not read: its plane stands in for it).
//! Operators combine earlier results: 0 add, 1 multiply, 2 maximum, 3 minimum (each with a
//! count of operands), 4 subtract (`a - b` of `4 a b`), 5 divide, 6 negate, 7 identity. The
//! surface is the level set `field = THRESHOLD` (27/64, PRMan's and Aqsis's: a lone ellipsoid's
//! surface is its matrix's image of the sphere of radius 1/2).
//!
//! Invariants: [`Program::parse`] checks every opcode, operand count and index, so a parsed
//! program never indexes out of range; evaluation is in `f64` and finite for finite input
//! (a singular matrix contributes no field); the coarse mesh's vertices lie on the surface
//! (to the root finder's tolerance) and its triangles wind so that `(b - a) x (c - a)` points
//! out of the solid (where the field is below the threshold), which is `-grad`.

use glam::{DMat3, DMat4, DVec3};

/// The level of the surface: `F` at `R = 1/2`, `(3/4)^3`.
pub const THRESHOLD: f64 = 27.0 / 64.0;

/// Most cells of the coarse mesh's lattice along one axis.
const MAX_CELLS: usize = 48;

/// One instruction, its operands resolved.
#[derive(Debug, Clone, PartialEq)]
enum Op {
    Constant(f64),
    /// The inverse of the matrix carrying the unit sphere onto the ellipsoid.
    Ellipsoid(DMat4),
    /// Segment `a`-`b` of `radius`, in the space of the inverse matrix `inv`.
    Segment {
        a: DVec3,
        b: DVec3,
        radius: f64,
        inv: DMat4,
    },
    /// PRMan's repulsion parameters `A, B, C, D`.
    Repeller([f64; 4]),
    Add(Vec<usize>),
    Multiply(Vec<usize>),
    Max(Vec<usize>),
    Min(Vec<usize>),
    Subtract(usize, usize),
    Divide(usize, usize),
    Negate(usize),
    Identity(usize),
}

/// A blobby's code stream, checked and ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    ops: Vec<Op>,
    /// Instruction index of each primitive field (opcode >= 1000), in order.
    leaves: Vec<usize>,
    /// Object-space bound of the bounded primitive fields' supports.
    bound: Option<(DVec3, DVec3)>,
    /// Smallest feature: half the smallest semi-axis of an ellipsoid or radius of a segment
    /// (object space), the scale of the coarse lattice.
    feature: f64,
    /// Where the bounded fields are not 0: a lattice of cells over `bound`, each listing
    /// the instructions of the fields whose support box meets it (see [`Program::eval`]).
    cells: LeafGrid,
    /// Primitive fields without bounded support (constants, repellers), evaluated everywhere.
    unbounded: Vec<u32>,
    /// The operators, in order.
    operators: Vec<usize>,
    /// Per instruction, its place in `operators` (`usize::MAX` for a primitive field).
    slot: Vec<usize>,
    /// Per operator, for a sum of primitive fields only (the usual last instruction), which
    /// instructions it adds: it then adds the fields near the point, not all of them.
    sums: Vec<Option<Vec<bool>>>,
}

/// Cells per axis of [`LeafGrid`].
const GRID: usize = 32;

/// The bounded primitive fields that may be non-zero in each cell of a lattice over the
/// program's bound.
#[derive(Debug, Clone, Default, PartialEq)]
struct LeafGrid {
    lo: DVec3,
    /// Cells per unit length along each axis.
    scale: DVec3,
    cells: Vec<Vec<u32>>,
}

impl LeafGrid {
    /// The list of the cell holding `p`; `None` outside the lattice (where every bounded
    /// field is 0).
    fn at(&self, p: DVec3) -> Option<&[u32]> {
        if self.cells.is_empty() {
            return None;
        }
        let c = (p - self.lo) * self.scale;
        if c.min_element().is_nan() || c.min_element() < 0.0 || c.max_element() >= GRID as f64 {
            return None;
        }
        let i = |x: f64| (x as usize).min(GRID - 1);
        self.cells.get((i(c.z) * GRID + i(c.y)) * GRID + i(c.x)).map(Vec::as_slice)
    }
}

/// A code stream fault: the index in `code` (or, with `floats`, in `floats`) and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CodeError {
    /// Which array: `"code"` or `"strings"`.
    pub array: &'static str,
    /// The index in it.
    pub index: usize,
    /// Why.
    pub message: String,
}

fn bump(s: f64) -> (f64, f64) {
    // F(s) = (1 - s)^3 of s = R^2, and dF/ds.
    if s >= 1.0 {
        (0.0, 0.0)
    } else {
        let a = 1.0 - s;
        (a * a * a, -3.0 * a * a)
    }
}

/// PRMan's repulsion and its derivative in `z`.
fn repulsion(z: f64, [a, b, c, d]: [f64; 4]) -> (f64, f64) {
    if z >= a || a <= 0.0 {
        return (0.0, 0.0);
    }
    let z = z.max(1e-6);
    let bump = |r: f64| {
        if r <= 0.0 || r >= 2.0 {
            (0.0, 0.0)
        } else {
            let v = (((6.0 - r) * r - 12.0) * r + 8.0) * r * r * r;
            let dv = ((((30.0 - 6.0 * r) * r - 48.0) * r + 24.0) * r) * r;
            (v, dv)
        }
    };
    let ease = |r: f64| {
        if r <= 0.0 {
            (0.0, 0.0)
        } else if r >= 1.0 {
            (1.0, 0.0)
        } else {
            (r * r * (3.0 - 2.0 * r), 6.0 * r * (1.0 - r))
        }
    };
    let (bv, bd) = if c > 0.0 { bump(z / c) } else { (0.0, 0.0) };
    let (bd, inner) = (if c > 0.0 { bd / c } else { 0.0 }, d * bv - b / z);
    let dinner = d * bd + b / (z * z);
    let (e, ed) = ease(z / a);
    (inner * (1.0 - e), dinner * (1.0 - e) - inner * ed / a)
}

impl Program {
    /// Reads a code stream, checking every opcode, operand and index.
    pub fn parse(code: &[i32], floats: &[f32], strings: &[String]) -> Result<Program, CodeError> {
        let err = |index: usize, message: String| CodeError { array: "code", index, message };
        let mut ops = Vec::new();
        let mut leaves = Vec::new();
        let mut starts = Vec::new();
        let mut i = 0;
        let operand = |i: usize| -> Result<i32, CodeError> {
            code.get(i).copied().ok_or_else(|| {
                err(i, format!("the code ends inside an instruction (operand {i} is missing)"))
            })
        };
        let floats_at = |k: i32, n: usize, at: usize| -> Result<Vec<f64>, CodeError> {
            let k =
                usize::try_from(k).ok().filter(|&k| k + n <= floats.len()).ok_or_else(|| {
                    err(
                        at,
                        format!(
                            "float index {k} needs {n} floats from there, but floats has {}",
                            floats.len()
                        ),
                    )
                })?;
            Ok(floats[k..k + n].iter().map(|&x| f64::from(x)).collect())
        };
        let matrix = |m: &[f64]| {
            let a = DMat4::from_cols_array(&std::array::from_fn(|k| m[k]));
            if a.determinant().abs() > 1e-300 && a.is_finite() { a.inverse() } else { DMat4::ZERO }
        };
        while i < code.len() {
            let at = i;
            let op = code[i];
            i += 1;
            let reference = |j: usize, done: usize| -> Result<usize, CodeError> {
                let r = operand(j)?;
                usize::try_from(r).ok().filter(|&r| r < done).ok_or_else(|| {
                    err(
                        j,
                        format!(
                            "operand {r} must name an earlier instruction (0 to {}), got {r}",
                            done as i64 - 1
                        ),
                    )
                })
            };
            let done = ops.len();
            let next = match op {
                1000 => {
                    let v = floats_at(operand(i)?, 1, i)?;
                    i += 1;
                    Op::Constant(v[0])
                }
                1001 => {
                    let m = floats_at(operand(i)?, 16, i)?;
                    i += 1;
                    Op::Ellipsoid(matrix(&m))
                }
                1002 => {
                    let f = floats_at(operand(i)?, 23, i)?;
                    i += 1;
                    Op::Segment {
                        a: DVec3::new(f[0], f[1], f[2]),
                        b: DVec3::new(f[3], f[4], f[5]),
                        radius: f[6],
                        inv: matrix(&f[7..23]),
                    }
                }
                1003 => {
                    let s = operand(i)?;
                    if usize::try_from(s).ok().filter(|&s| s < strings.len()).is_none() {
                        return Err(err(
                            i,
                            format!(
                                "string index {s} is out of range (strings has {})",
                                strings.len()
                            ),
                        ));
                    }
                    let f = floats_at(operand(i + 1)?, 4, i + 1)?;
                    i += 2;
                    Op::Repeller([f[0], f[1], f[2], f[3]])
                }
                1004 => {
                    let f = floats_at(operand(i)?, 4, i)?;
                    i += 1;
                    Op::Repeller([f[0], f[1], f[2], f[3]])
                }
                0..=3 => {
                    let n = operand(i)?;
                    if n < 1 {
                        return Err(err(
                            i,
                            format!("an operator needs at least 1 operand, got {n}"),
                        ));
                    }
                    let list = (0..n as usize)
                        .map(|k| reference(i + 1 + k, done))
                        .collect::<Result<Vec<_>, _>>()?;
                    i += 1 + n as usize;
                    match op {
                        0 => Op::Add(list),
                        1 => Op::Multiply(list),
                        2 => Op::Max(list),
                        _ => Op::Min(list),
                    }
                }
                4 | 5 => {
                    let (a, b) = (reference(i, done)?, reference(i + 1, done)?);
                    i += 2;
                    if op == 4 { Op::Subtract(a, b) } else { Op::Divide(a, b) }
                }
                6 | 7 => {
                    let a = reference(i, done)?;
                    i += 1;
                    if op == 6 { Op::Negate(a) } else { Op::Identity(a) }
                }
                other => {
                    return Err(err(
                        at,
                        format!(
                            "unknown blobby opcode {other} (primitive fields are 1000 to 1004, operators 0 to 7)"
                        ),
                    ));
                }
            };
            if op >= 1000 {
                leaves.push(ops.len());
            }
            if let Op::Segment { radius, .. } = &next
                && !(*radius > 0.0 && radius.is_finite())
            {
                return Err(err(at, format!("a segment's radius must be > 0, got {radius}")));
            }
            starts.push(at);
            ops.push(next);
        }
        if ops.is_empty() {
            return Err(err(0, "the code holds no instruction".into()));
        }
        let mut program = Program {
            ops,
            leaves,
            bound: None,
            feature: f64::INFINITY,
            cells: LeafGrid::default(),
            unbounded: Vec::new(),
            operators: Vec::new(),
            slot: Vec::new(),
            sums: Vec::new(),
        };
        program.measure();
        program.slot = vec![usize::MAX; program.ops.len()];
        for (s, &k) in program.operators.iter().enumerate() {
            program.slot[k] = s;
        }
        program.sums = program
            .operators
            .iter()
            .map(|&k| match &program.ops[k] {
                Op::Add(list) if list.iter().all(|&i| program.slot[i] == usize::MAX) => {
                    let mut member = vec![false; program.ops.len()];
                    let mut distinct = true;
                    for &i in list {
                        distinct &= !std::mem::replace(&mut member[i], true);
                    }
                    distinct.then_some(member)
                }
                _ => None,
            })
            .collect();
        Ok(program)
    }

    /// The number of primitive fields (RenderMan's `nleaf`).
    pub fn leaf_count(&self) -> usize {
        self.leaves.len()
    }

    /// The bound and the smallest feature of the bounded fields.
    fn measure(&mut self) {
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        let mut feature = f64::INFINITY;
        let mut boxes: Vec<(usize, DVec3, DVec3)> = Vec::new();
        let mut grow = |m: DMat4, corners: [DVec3; 2]| {
            let (mut blo, mut bhi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            for k in 0..8 {
                let c = DVec3::new(
                    if k & 1 == 0 { corners[0].x } else { corners[1].x },
                    if k & 2 == 0 { corners[0].y } else { corners[1].y },
                    if k & 4 == 0 { corners[0].z } else { corners[1].z },
                );
                let p = m.transform_point3(c);
                blo = blo.min(p);
                bhi = bhi.max(p);
            }
            lo = lo.min(blo);
            hi = hi.max(bhi);
            (blo, bhi)
        };
        for (k, op) in self.ops.iter().enumerate() {
            let (inv, local) = match op {
                Op::Ellipsoid(inv) => (*inv, [DVec3::splat(-1.0), DVec3::splat(1.0)]),
                Op::Segment { a, b, radius, inv } => {
                    (*inv, [a.min(*b) - *radius, a.max(*b) + *radius])
                }
                Op::Constant(_) | Op::Repeller(_) => {
                    self.unbounded.push(k as u32);
                    continue;
                }
                _ => {
                    self.operators.push(k);
                    continue;
                }
            };
            if inv == DMat4::ZERO {
                continue;
            }
            let m = inv.inverse();
            let (blo, bhi) = grow(m, local);
            boxes.push((k, blo, bhi));
            // Half the smallest semi-axis: the smallest singular value of the linear part.
            let l = DMat3::from_mat4(m);
            let smallest = smallest_singular(l);
            let scale = match op {
                Op::Segment { radius, .. } => *radius,
                _ => 1.0,
            };
            feature = feature.min(0.5 * smallest * scale);
        }
        self.bound = (lo.x <= hi.x).then_some((lo, hi));
        self.feature = feature;
        if let Some((lo, hi)) = self.bound {
            let size = (hi - lo).max(DVec3::splat(1e-12 * (1.0 + hi.abs().max_element())));
            let scale = DVec3::splat(GRID as f64) / size;
            let mut cells = vec![Vec::new(); GRID * GRID * GRID];
            let cell = |x: f64| (x.max(0.0) as usize).min(GRID - 1);
            for (k, blo, bhi) in boxes {
                let (a, b) = ((blo - lo) * scale, (bhi - lo) * scale);
                for z in cell(a.z)..=cell(b.z) {
                    for y in cell(a.y)..=cell(b.y) {
                        for x in cell(a.x)..=cell(b.x) {
                            cells[(z * GRID + y) * GRID + x].push(k as u32);
                        }
                    }
                }
            }
            self.cells = LeafGrid { lo, scale, cells };
        }
    }

    /// The value and gradient of primitive field `op` at `p` (operators give zeros).
    fn leaf(&self, op: &Op, p: DVec3) -> (f64, DVec3) {
        match op {
            Op::Constant(c) => (*c, DVec3::ZERO),
            Op::Ellipsoid(inv) => {
                let q = inv.transform_point3(p);
                let (f, df) = bump(q.length_squared());
                (f, DMat3::from_mat4(*inv).transpose() * (q * (2.0 * df)))
            }
            Op::Segment { a, b, radius, inv } => {
                let q = inv.transform_point3(p);
                let ab = *b - *a;
                let t = if ab.length_squared() > 0.0 {
                    ((q - *a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let d = (q - (*a + ab * t)) / *radius;
                let (f, df) = bump(d.length_squared());
                (f, DMat3::from_mat4(*inv).transpose() * (d * (2.0 * df / *radius)))
            }
            Op::Repeller(params) => {
                let (f, df) = repulsion(p.z, *params);
                (f, DVec3::new(0.0, 0.0, df))
            }
            _ => (0.0, DVec3::ZERO),
        }
    }

    /// The object-space box holding every point where a bounded primitive field is not 0
    /// (`None` if there is none): where the surface lies, unless constants or negations
    /// raise the field above the threshold elsewhere.
    pub fn bound(&self) -> Option<(DVec3, DVec3)> {
        self.bound
    }

    /// The field and its gradient at `p`. Only the bounded fields whose support box holds
    /// `p` (its cell's list) are evaluated; every other one is exactly 0 there, and a sum of
    /// fields adds the ones near `p` alone.
    pub fn eval(&self, p: DVec3) -> (f64, DVec3) {
        let near = self.cells.at(p).unwrap_or(&[]);
        let finite = |r: (f64, DVec3)| {
            if r.0.is_finite() && r.1.is_finite() { r } else { (0.0, DVec3::ZERO) }
        };
        // A primitive field's value: computed where it may be non-zero.
        let leaf = |k: usize| -> (f64, DVec3) {
            let k32 = k as u32;
            if near.binary_search(&k32).is_ok() || self.unbounded.contains(&k32) {
                finite(self.leaf(&self.ops[k], p))
            } else {
                (0.0, DVec3::ZERO)
            }
        };
        let mut done: Vec<(f64, DVec3)> = Vec::with_capacity(self.operators.len());
        let value = |k: usize, done: &[(f64, DVec3)]| {
            if self.slot[k] == usize::MAX { leaf(k) } else { done[self.slot[k]] }
        };
        for (s, &k) in self.operators.iter().enumerate() {
            let r = match (&self.ops[k], &self.sums[s]) {
                (Op::Add(_), Some(member)) => near
                    .iter()
                    .chain(&self.unbounded)
                    .filter(|&&i| member[i as usize])
                    .map(|&i| finite(self.leaf(&self.ops[i as usize], p)))
                    .fold((0.0, DVec3::ZERO), |(f, g), (a, b)| (f + a, g + b)),
                (Op::Add(list), None) => list.iter().fold((0.0, DVec3::ZERO), |(f, g), &i| {
                    let (a, b) = value(i, &done);
                    (f + a, g + b)
                }),
                (Op::Multiply(list), _) => list.iter().fold((1.0, DVec3::ZERO), |(f, g), &i| {
                    let (a, b) = value(i, &done);
                    (f * a, g * a + b * f)
                }),
                (Op::Max(list), _) => list
                    .iter()
                    .map(|&i| value(i, &done))
                    .reduce(|a, b| if b.0 > a.0 { b } else { a })
                    .unwrap_or_default(),
                (Op::Min(list), _) => list
                    .iter()
                    .map(|&i| value(i, &done))
                    .reduce(|a, b| if b.0 < a.0 { b } else { a })
                    .unwrap_or_default(),
                (Op::Subtract(a, b), _) => {
                    let ((fa, ga), (fb, gb)) = (value(*a, &done), value(*b, &done));
                    (fa - fb, ga - gb)
                }
                (Op::Divide(a, b), _) => {
                    let ((fa, ga), (fb, gb)) = (value(*a, &done), value(*b, &done));
                    if fb == 0.0 {
                        (0.0, DVec3::ZERO)
                    } else {
                        (fa / fb, (ga * fb - gb * fa) / (fb * fb))
                    }
                }
                (Op::Negate(a), _) => {
                    let (f, g) = value(*a, &done);
                    (-f, -g)
                }
                (Op::Identity(a), _) => value(*a, &done),
                _ => (0.0, DVec3::ZERO),
            };
            done.push(finite(r));
        }
        value(self.ops.len() - 1, &done)
    }

    /// The field at `p`.
    pub fn field(&self, p: DVec3) -> f64 {
        self.eval(p).0
    }

    /// The weights of the primitive fields at `p` for blending their colours: each bounded
    /// field's value over their sum (all equal where none reaches `p`).
    pub fn leaf_weights(&self, p: DVec3) -> Vec<f64> {
        let mut w = vec![0.0; self.leaves.len()];
        let near = self.cells.at(p).unwrap_or(&[]);
        for &k in near {
            if let Ok(slot) = self.leaves.binary_search(&(k as usize)) {
                w[slot] = self.leaf(&self.ops[k as usize], p).0.max(0.0);
            }
        }
        let sum: f64 = w.iter().sum();
        if sum > 0.0 {
            w.iter_mut().for_each(|x| *x /= sum);
        } else if !w.is_empty() {
            let n = w.len() as f64;
            w.iter_mut().for_each(|x| *x = 1.0 / n);
        }
        w
    }

    /// `p` moved onto the surface along the field's gradient (Newton's method on
    /// `field = THRESHOLD`, each step at most `reach`); `p` itself where the gradient
    /// vanishes. Deterministic: the same `p` gives the same point.
    pub fn project(&self, p: DVec3, reach: f64) -> DVec3 {
        let mut q = p;
        for _ in 0..12 {
            let (f, g) = self.eval(q);
            let gg = g.length_squared();
            if gg <= 1e-300 {
                break;
            }
            if (f - THRESHOLD).abs() <= 1e-10 {
                break;
            }
            let mut step = g * ((THRESHOLD - f) / gg);
            let len = step.length();
            if len > reach {
                step *= reach / len;
            }
            q += step;
            if len <= 1e-12 * (1.0 + q.length()) {
                break;
            }
        }
        q
    }

    /// The outward unit normal at `p` (`-grad`, normalised; +z where it vanishes).
    pub fn normal(&self, p: DVec3) -> DVec3 {
        (-self.eval(p).1).try_normalize().unwrap_or(DVec3::Z)
    }
}

/// The smallest singular value of `m` (the square root of the smallest eigenvalue of
/// `m^T m`, by the characteristic cubic).
fn smallest_singular(m: DMat3) -> f64 {
    let a = m.transpose() * m;
    // Eigenvalues of a symmetric 3x3 (Smith's method).
    let p1 = a.x_axis.y.powi(2) + a.x_axis.z.powi(2) + a.y_axis.z.powi(2);
    let q = (a.x_axis.x + a.y_axis.y + a.z_axis.z) / 3.0;
    let p2 =
        (a.x_axis.x - q).powi(2) + (a.y_axis.y - q).powi(2) + (a.z_axis.z - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p <= 1e-300 {
        return q.max(0.0).sqrt();
    }
    let b = (a - DMat3::from_diagonal(DVec3::splat(q))) * (1.0 / p);
    let r = (b.determinant() / 2.0).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let smallest = q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    smallest.max(0.0).sqrt()
}

mod mesh;
#[cfg(test)]
mod tests;
