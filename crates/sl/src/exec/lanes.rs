//! Triples lane by lane without the generic machinery of `value::map_n` (a slice per
//! argument per point): the common geometric functions (`normalize`, `faceforward`,
//! `reflect`, `.` and `^`) read each argument's lane as a `[f32; 3]` in place.

use super::geom::V3;
use super::value::{Mask, Num};

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
            o.copy_from_slice(&f(src.map(|s| s.at(i))));
        }
    } else {
        for i in mask.iter() {
            out.data[3 * i..3 * i + 3].copy_from_slice(&f(src.map(|s| s.at(i))));
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
            *o = f(src.map(|s| s.at(i)));
        }
    } else {
        for i in mask.iter() {
            out.data[i] = f(src.map(|s| s.at(i)));
        }
    }
    out
}
