//! Triples lane by lane without the generic machinery of `value::map_n` (a slice per
//! argument per point): the common geometric functions (`normalize`, `faceforward`,
//! `reflect`, `.` and `^`) read each argument's lane as a `[f32; 3]` in place; `normalize`
//! and the lighting functions work a block of points at a time, component by component.

// Index loops over the blocks' lanes on purpose: fixed-length loops the compiler turns into
// vector instructions.
#![allow(clippy::needless_range_loop)]

use super::geom::V3;
use super::value::{Mask, Num};

/// Points per block.
pub(crate) const B: usize = 8;

/// One float per point of a block.
pub(crate) type Fs = [f32; B];

/// A triple per point of a block, component by component.
#[derive(Clone, Copy)]
pub(crate) struct T3(pub(crate) [Fs; 3]);

#[inline(always)]
pub(crate) fn dot(a: &T3, b: &T3) -> Fs {
    let mut o = [0.0; B];
    for j in 0..B {
        o[j] = a.0[0][j] * b.0[0][j] + a.0[1][j] * b.0[1][j] + a.0[2][j] * b.0[2][j];
    }
    o
}

#[inline(always)]
pub(crate) fn scale(a: &T3, k: &Fs) -> T3 {
    let mut o = *a;
    for c in 0..3 {
        for j in 0..B {
            o.0[c][j] = a.0[c][j] * k[j];
        }
    }
    o
}

#[inline(always)]
pub(crate) fn add(a: &T3, b: &T3) -> T3 {
    let mut o = *a;
    for c in 0..3 {
        for j in 0..B {
            o.0[c][j] = a.0[c][j] + b.0[c][j];
        }
    }
    o
}

#[inline(always)]
pub(crate) fn sub(a: &T3, b: &T3) -> T3 {
    let mut o = *a;
    for c in 0..3 {
        for j in 0..B {
            o.0[c][j] = a.0[c][j] - b.0[c][j];
        }
    }
    o
}

/// `geom::normalize` on each point: a zero vector stays as it is.
#[inline(always)]
pub(crate) fn normalize(a: &T3) -> T3 {
    let d = dot(a, a);
    let (mut l, mut k) = ([0.0; B], [0.0; B]);
    for j in 0..B {
        l[j] = d[j].sqrt();
        k[j] = 1.0 / l[j];
    }
    let mut o = *a;
    for c in 0..3 {
        for j in 0..B {
            o.0[c][j] = if l[j] > 0.0 { a.0[c][j] * k[j] } else { a.0[c][j] };
        }
    }
    o
}

/// `geom::reflect`: `i - 2 (i . n) n`.
#[inline(always)]
pub(crate) fn reflect(i: &T3, n: &T3) -> T3 {
    let mut d = dot(i, n);
    for x in &mut d {
        *x *= 2.0;
    }
    sub(i, &scale(n, &d))
}

/// A triple operand read at any point: uniform, or a lane per point (a float broadcast).
#[derive(Clone, Copy)]
pub(crate) enum Src<'a> {
    Uniform(V3),
    Lanes { data: &'a [f32], w: usize },
}

impl<'a> Src<'a> {
    pub(crate) fn of(x: &'a Num) -> Src<'a> {
        if x.varying { Src::Lanes { data: &x.data, w: x.w } } else { Src::Uniform(x.v3(0)) }
    }

    #[inline(always)]
    pub(crate) fn at(&self, i: usize) -> V3 {
        match *self {
            Src::Uniform(v) => v,
            Src::Lanes { data, w: 3 } => [data[3 * i], data[3 * i + 1], data[3 * i + 2]],
            Src::Lanes { data, w } if w > 3 => [data[w * i], data[w * i + 1], data[w * i + 2]],
            Src::Lanes { data, w } => [data[w * i]; 3],
        }
    }
}

/// The arguments' triples at point `i`.
#[inline(always)]
fn gather<const K: usize>(src: &[Src<'_>; K], i: usize) -> [V3; K] {
    let mut v = [[0.0; 3]; K];
    for k in 0..K {
        v[k] = src[k].at(i);
    }
    v
}

/// `f` of the arguments' triples at each active point: a triple per point, or one uniform
/// triple when every argument is uniform (inactive lanes are 0, as `map_n` leaves them).
pub(crate) fn map_v3<const K: usize>(
    n: usize,
    mask: &Mask,
    args: [&Num; K],
    f: impl Fn([V3; K]) -> V3,
) -> Num {
    if args.iter().all(|a| !a.varying) {
        return Num::uniform(&f(args.map(|a| a.v3(0))));
    }
    let src = args.map(Src::of);
    let mut out = Num::zeros(3, true, n);
    if mask.idx.len() == n {
        for (i, o) in out.data.chunks_exact_mut(3).enumerate() {
            o.copy_from_slice(&f(gather(&src, i)));
        }
    } else {
        for i in mask.iter() {
            out.data[3 * i..3 * i + 3].copy_from_slice(&f(gather(&src, i)));
        }
    }
    out
}

/// `f` of the arguments' triples at each active point, a float result (see [`map_v3`]).
pub(crate) fn map_v3_f<const K: usize>(
    n: usize,
    mask: &Mask,
    args: [&Num; K],
    f: impl Fn([V3; K]) -> f32,
) -> Num {
    if args.iter().all(|a| !a.varying) {
        return Num::scalar(f(args.map(|a| a.v3(0))));
    }
    let src = args.map(Src::of);
    let mut out = Num::zeros(1, true, n);
    if mask.idx.len() == n {
        for (i, o) in out.data.iter_mut().enumerate() {
            *o = f(gather(&src, i));
        }
    } else {
        for i in mask.iter() {
            out.data[i] = f(gather(&src, i));
        }
    }
    out
}

/// `normalize` at each active point: a block of [`B`] points at a time where the points are
/// consecutive (the square roots and divisions of a block run together), the same
/// operations as `geom::normalize`, so the same bits.
pub(crate) fn normalize_lanes(n: usize, mask: &Mask, a: &Num) -> Num {
    if !(a.varying && a.w == 3 && mask.idx.len() == n && a.data.len() == 3 * n) {
        return map_v3(n, mask, [a], |[x]| super::geom::normalize(x));
    }
    let mut out = Num::zeros(3, true, n);
    let blocks = n / B;
    for (o, x) in out.data.chunks_exact_mut(3 * B).zip(a.data.chunks_exact(3 * B)) {
        let mut t = T3([[0.0; B]; 3]);
        for j in 0..B {
            for c in 0..3 {
                t.0[c][j] = x[3 * j + c];
            }
        }
        let t = normalize(&t);
        for j in 0..B {
            for c in 0..3 {
                o[3 * j + c] = t.0[c][j];
            }
        }
    }
    for i in blocks * B..n {
        let x = [a.data[3 * i], a.data[3 * i + 1], a.data[3 * i + 2]];
        out.data[3 * i..3 * i + 3].copy_from_slice(&super::geom::normalize(x));
    }
    out
}
