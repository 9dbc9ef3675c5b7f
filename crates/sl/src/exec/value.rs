//! Values of the grid machine, structure-of-arrays: a uniform number is stored once, a varying
//! one as one lane per grid point (`w` floats per lane: 1 for float and boolean, 3 for triples,
//! 16 for matrices, lane-major so a triple is `[f32; 3]` per lane); strings are uniform; an
//! array is a list of element values. The active points are a [`Mask`].

use crate::types::{BaseType, Type};

/// A number of the grid: one lane (uniform) or one lane per point (varying).
#[derive(Debug, PartialEq)]
pub struct Num {
    /// Floats per lane: 1, 3 or 16.
    pub w: usize,
    /// One lane per grid point.
    pub varying: bool,
    /// `w` floats per lane, lane after lane.
    pub data: Vec<f32>,
}

impl Num {
    /// A uniform value.
    pub fn uniform(data: &[f32]) -> Num {
        Num { w: data.len(), varying: false, data: data.to_vec() }
    }

    /// A uniform float.
    pub fn scalar(v: f32) -> Num {
        Num { w: 1, varying: false, data: vec![v] }
    }

    /// Zeros: `n` lanes when varying.
    pub fn zeros(w: usize, varying: bool, n: usize) -> Num {
        Num { w, varying, data: super::pool::zeros(if varying { w * n } else { w }) }
    }

    /// The lane of point `i` (the one lane of a uniform value).
    #[inline]
    pub fn lane(&self, i: usize) -> &[f32] {
        if self.varying { &self.data[i * self.w..(i + 1) * self.w] } else { &self.data[..self.w] }
    }

    /// The lane of point `i`, writable.
    #[inline]
    pub fn lane_mut(&mut self, i: usize) -> &mut [f32] {
        let w = self.w;
        if self.varying { &mut self.data[i * w..(i + 1) * w] } else { &mut self.data[..w] }
    }

    /// The first component of point `i`'s lane.
    #[inline]
    pub fn f(&self, i: usize) -> f32 {
        if self.varying { self.data[i * self.w] } else { self.data[0] }
    }

    /// Point `i`'s lane as a triple (`w` must be 3; a float is broadcast).
    #[inline]
    pub fn v3(&self, i: usize) -> [f32; 3] {
        let l = self.lane(i);
        if l.len() >= 3 { [l[0], l[1], l[2]] } else { [l[0]; 3] }
    }

    /// This value with one lane per point (a uniform one is broadcast).
    pub fn to_varying(&self, n: usize) -> Num {
        if self.varying {
            return self.clone();
        }
        let lane = &self.data[..self.w];
        let total = self.w * n;
        let mut data = super::pool::take(total);
        if let [x] = *lane {
            data.resize(n, x);
        } else if n > 0 {
            // Doubling copies: a handful of block copies, not one per lane.
            data.extend_from_slice(lane);
            while data.len() < total {
                data.extend_from_within(..data.len().min(total - data.len()));
            }
        }
        Num { w: self.w, varying: true, data }
    }
}

impl Clone for Num {
    /// A copy in a buffer from the machine's pool (see `pool`).
    fn clone(&self) -> Num {
        super::pool::dup(self)
    }
}

/// A value: number, string, or array.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// Float, boolean, triple, matrix.
    Num(Num),
    /// A string (uniform only).
    Str(String),
    /// An array's elements.
    Array(Vec<Value>),
}

impl Value {
    /// The zero value of a type: numbers zero, strings empty, arrays of zeros.
    pub fn zero(ty: Type, varying: bool, n: usize) -> Value {
        let elem = |_| match ty.base {
            BaseType::String => Value::Str(String::new()),
            b => Value::Num(Num::zeros(width(b), varying, n)),
        };
        match ty.array {
            Some(len) => Value::Array((0..len.max(1)).map(elem).collect()),
            None => elem(0),
        }
    }

    /// The number (a string or array reads as a uniform 0).
    pub fn num(&self) -> &Num {
        match self {
            Value::Num(n) => n,
            _ => &ZERO,
        }
    }

    /// The string (a number reads as "").
    pub fn str(&self) -> &str {
        match self {
            Value::Str(s) => s,
            _ => "",
        }
    }

    /// Varying (any part).
    pub fn varying(&self) -> bool {
        match self {
            Value::Num(n) => n.varying,
            Value::Str(_) => false,
            Value::Array(v) => v.iter().any(Value::varying),
        }
    }
}

static ZERO: std::sync::LazyLock<Num> = std::sync::LazyLock::new(|| Num::scalar(0.0));

/// A uniform 0 (what a missing argument reads as).
pub static ZERO1: std::sync::LazyLock<Num> = std::sync::LazyLock::new(|| Num::scalar(0.0));

/// Floats per lane of a base type.
pub fn width(b: BaseType) -> usize {
    match b {
        BaseType::Matrix => 16,
        b if b.is_triple() => 3,
        _ => 1,
    }
}

/// The active points: a flag per point and the list of the active ones.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mask {
    /// One flag per point.
    pub on: Vec<bool>,
    /// The active points, ascending.
    pub idx: Vec<u32>,
}

impl Mask {
    /// Every point of an `n`-point grid.
    pub fn all(n: usize) -> Mask {
        Mask { on: vec![true; n], idx: (0..n as u32).collect() }
    }

    /// From flags.
    pub fn from_flags(on: Vec<bool>) -> Mask {
        let idx = on.iter().enumerate().filter(|(_, b)| **b).map(|(i, _)| i as u32).collect();
        Mask { on, idx }
    }

    /// No point is active.
    pub fn is_empty(&self) -> bool {
        self.idx.is_empty()
    }

    /// The active points where `keep(i)` holds.
    pub fn filter(&self, mut keep: impl FnMut(usize) -> bool) -> Mask {
        let mut on = vec![false; self.on.len()];
        let mut idx = Vec::with_capacity(self.idx.len());
        for &i in &self.idx {
            if keep(i as usize) {
                on[i as usize] = true;
                idx.push(i);
            }
        }
        Mask { on, idx }
    }

    /// The active points where the condition `c` is (`want`) true.
    pub fn when(&self, c: &Num, want: bool) -> Mask {
        self.filter(|i| (c.f(i) != 0.0) == want)
    }

    /// The active points.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.idx.iter().map(|&i| i as usize)
    }
}

/// The most arguments a lane function sees (a matrix constructor has 16). A `min` or `max`
/// of more values reads only the first 32 (`spline` does not go through here: any number of
/// knots).
pub const MAX_ARGS: usize = 32;

/// Applies `f` to the lanes of `args`: once when every argument is uniform (a uniform result),
/// else on every active point (inactive lanes of the result are 0).
pub fn map_n(
    n: usize,
    mask: &Mask,
    args: &[&Num],
    w_out: usize,
    mut f: impl FnMut(&[&[f32]], &mut [f32]),
) -> Num {
    let mut lanes: [&[f32]; MAX_ARGS] = [&[]; MAX_ARGS];
    let k = args.len().min(MAX_ARGS);
    if args.iter().all(|a| !a.varying) {
        let mut out = Num::zeros(w_out, false, n);
        for (j, a) in args.iter().take(k).enumerate() {
            lanes[j] = a.lane(0);
        }
        f(&lanes[..k], &mut out.data);
        return out;
    }
    let mut out = Num::zeros(w_out, true, n);
    for i in mask.iter() {
        for (j, a) in args.iter().take(k).enumerate() {
            lanes[j] = a.lane(i);
        }
        f(&lanes[..k], out.lane_mut(i));
    }
    out
}

/// A float function of floats, lane by lane.
pub fn map_f(n: usize, mask: &Mask, args: &[&Num], f: impl Fn(&[f32]) -> f32) -> Num {
    let mut xs = [0.0f32; MAX_ARGS];
    map_n(n, mask, args, 1, |l, o| {
        for (x, a) in xs.iter_mut().zip(l) {
            *x = a[0];
        }
        o[0] = f(&xs[..l.len()]);
    })
}

/// A componentwise function of same-width values (floats broadcast to the widest).
pub fn map_c(n: usize, mask: &Mask, args: &[&Num], f: impl Fn(&[f32]) -> f32) -> Num {
    let w = args.iter().map(|a| a.w).max().unwrap_or(1);
    let mut xs = [0.0f32; MAX_ARGS];
    map_n(n, mask, args, w, |l, o| {
        for (c, oc) in o.iter_mut().enumerate() {
            for (x, a) in xs.iter_mut().zip(l) {
                *x = if a.len() == 1 { a[0] } else { a[c] };
            }
            *oc = f(&xs[..l.len()]);
        }
    })
}

/// A componentwise function of one value, without the generic lane machinery (the common
/// case: negation, the one-argument math functions).
pub fn map_c1(n: usize, mask: &Mask, a: &Num, f: impl Fn(f32) -> f32) -> Num {
    if !a.varying {
        return Num { w: a.w, varying: false, data: a.data.iter().map(|&x| f(x)).collect() };
    }
    let w = a.w;
    let mut out = Num::zeros(w, true, n);
    if mask.idx.len() == n {
        for (o, &x) in out.data.iter_mut().zip(&a.data) {
            *o = f(x);
        }
    } else {
        for i in mask.iter() {
            for c in i * w..(i + 1) * w {
                out.data[c] = f(a.data[c]);
            }
        }
    }
    out
}

/// A componentwise function of two values (a float is broadcast to the other's width): the
/// arithmetic operators.
pub fn map_c2(n: usize, mask: &Mask, a: &Num, b: &Num, f: impl Fn(f32, f32) -> f32) -> Num {
    let w = a.w.max(b.w);
    let step = |x: &Num| usize::from(x.w != 1);
    let (ca, cb) = (step(a), step(b));
    if !a.varying && !b.varying {
        let data = (0..w).map(|c| f(a.data[c * ca], b.data[c * cb])).collect();
        return Num { w, varying: false, data };
    }
    match w {
        1 => return c2_fixed::<1>(n, mask, a, b, &f),
        3 => return c2_fixed::<3>(n, mask, a, b, &f),
        _ => {}
    }
    let (sa, sb) = (if a.varying { a.w } else { 0 }, if b.varying { b.w } else { 0 });
    let mut out = Num::zeros(w, true, n);
    if mask.idx.len() == n && sa == w && sb == w {
        for ((o, &x), &y) in out.data.iter_mut().zip(&a.data).zip(&b.data) {
            *o = f(x, y);
        }
        return out;
    }
    for i in mask.iter() {
        for c in 0..w {
            out.data[i * w + c] = f(a.data[i * sa + c * ca], b.data[i * sb + c * cb]);
        }
    }
    out
}

/// An operand of [`c2_fixed`] as `W`-wide lanes: a uniform lane (a float broadcast), a
/// varying value of width `W`, or a varying float broadcast to `W`.
#[derive(Clone, Copy)]
enum Lanes<'a, const W: usize> {
    Uniform([f32; W]),
    Wide(&'a [f32]),
    Float(&'a [f32]),
}

impl<'a, const W: usize> Lanes<'a, W> {
    fn of(x: &'a Num) -> Lanes<'a, W> {
        match (x.varying, x.w == 1) {
            (false, _) => {
                Lanes::Uniform(std::array::from_fn(|c| x.data[if x.w == 1 { 0 } else { c }]))
            }
            (true, false) => Lanes::Wide(&x.data),
            (true, true) => Lanes::Float(&x.data),
        }
    }
}

/// `f` on `W`-wide lanes of a varying result, each operand read in place (a uniform one is
/// not broadcast into a buffer first). One loop per pairing of operand kinds, so each is
/// a plain loop the compiler can unroll.
fn c2_fixed<const W: usize>(
    n: usize,
    mask: &Mask,
    a: &Num,
    b: &Num,
    f: &impl Fn(f32, f32) -> f32,
) -> Num {
    let mut out = Num::zeros(W, true, n);
    let full = mask.idx.len() == n;
    let o = &mut out.data;
    let wide = |d: &[f32], i: usize| -> [f32; W] { std::array::from_fn(|c| d[i * W + c]) };
    let flt = |d: &[f32], i: usize| -> [f32; W] { [d[i]; W] };
    match (Lanes::<W>::of(a), Lanes::<W>::of(b)) {
        (Lanes::Wide(x), Lanes::Wide(y)) => {
            lanes2(o, mask, full, |i| wide(x, i), |i| wide(y, i), f);
        }
        (Lanes::Wide(x), Lanes::Uniform(y)) => lanes2(o, mask, full, |i| wide(x, i), |_| y, f),
        (Lanes::Uniform(x), Lanes::Wide(y)) => lanes2(o, mask, full, |_| x, |i| wide(y, i), f),
        (Lanes::Wide(x), Lanes::Float(y)) => {
            lanes2(o, mask, full, |i| wide(x, i), |i| flt(y, i), f);
        }
        (Lanes::Float(x), Lanes::Wide(y)) => {
            lanes2(o, mask, full, |i| flt(x, i), |i| wide(y, i), f);
        }
        (Lanes::Float(x), Lanes::Float(y)) => {
            lanes2(o, mask, full, |i| flt(x, i), |i| flt(y, i), f);
        }
        (Lanes::Float(x), Lanes::Uniform(y)) => lanes2(o, mask, full, |i| flt(x, i), |_| y, f),
        (Lanes::Uniform(x), Lanes::Float(y)) => lanes2(o, mask, full, |_| x, |i| flt(y, i), f),
        (Lanes::Uniform(x), Lanes::Uniform(y)) => lanes2(o, mask, full, |_| x, |_| y, f),
    }
    out
}

#[inline(always)]
fn lanes2<const W: usize>(
    out: &mut [f32],
    mask: &Mask,
    full: bool,
    a: impl Fn(usize) -> [f32; W],
    b: impl Fn(usize) -> [f32; W],
    f: &impl Fn(f32, f32) -> f32,
) {
    let one = |i: usize, o: &mut [f32]| {
        let (x, y) = (a(i), b(i));
        for c in 0..W {
            o[c] = f(x[c], y[c]);
        }
    };
    if full {
        for (i, o) in out.chunks_exact_mut(W).enumerate() {
            one(i, o);
        }
    } else {
        for i in mask.iter() {
            one(i, &mut out[i * W..(i + 1) * W]);
        }
    }
}

/// Writes `src` into `dst` at the active points (a varying destination) or whole (a uniform
/// one, which takes the first active lane of a varying source).
pub fn store_num(dst: &mut Num, src: &Num, mask: &Mask, n: usize) {
    if !dst.varying {
        let i = mask.idx.first().map_or(0, |&i| i as usize);
        let lane = src.lane(i);
        if lane.len() == dst.w {
            dst.data.copy_from_slice(lane);
        } else if !lane.is_empty() {
            dst.data.iter_mut().for_each(|d| *d = lane[0]);
        }
        return;
    }
    if dst.data.len() != dst.w * n {
        *dst = dst.to_varying(n);
    }
    if src.varying && src.w == dst.w && mask.idx.len() == n {
        dst.data.copy_from_slice(&src.data);
        return;
    }
    for i in mask.iter() {
        let s = src.lane(i);
        let d = dst.lane_mut(i);
        if s.len() == d.len() {
            d.copy_from_slice(s);
        } else if !s.is_empty() {
            d.iter_mut().for_each(|x| *x = s[0]);
        }
    }
}

/// Writes a whole value (see [`store_num`]); strings and arrays element by element.
pub fn store(dst: &mut Value, src: &Value, mask: &Mask, n: usize) {
    match (dst, src) {
        (Value::Num(d), Value::Num(s)) => store_num(d, s, mask, n),
        // An open array formal (`float k[]`) takes the actual array whole.
        (Value::Array(d), Value::Array(s)) if d.len() != s.len() => *d = s.clone(),
        (Value::Array(d), Value::Array(s)) => {
            for (d, s) in d.iter_mut().zip(s) {
                store(d, s, mask, n);
            }
        }
        (d, s) => *d = s.clone(),
    }
}

/// How many floats of `v` at the active points are not finite.
pub fn count_nonfinite(v: &Num, mask: &Mask) -> u64 {
    let count = |d: &[f32]| d.iter().filter(|x| !x.is_finite()).count() as u64;
    if !v.varying || mask.idx.len() * v.w == v.data.len() {
        // Uniform, or every point active: the whole buffer in one pass.
        return count(&v.data);
    }
    mask.iter().map(|i| v.lane(i).iter().filter(|x| !x.is_finite()).count() as u64).sum()
}
