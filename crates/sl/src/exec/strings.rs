//! String functions (`concat`, `format`, `printf`, `match`, `shadername`) and `spline`.
//!
//! Strings are uniform: `format` of a varying value formats its first active point; `printf`
//! with a varying argument writes one line per active point. `match` is a small regular
//! expression matcher written here: literals, `.`, `[...]` (ranges, `^` negation), `*`, `+`,
//! `?`, `^`, `$`, `\` escapes; it finds the pattern anywhere in the subject. Strings a run
//! makes are at most [`MAX_STRING`] bytes.

use crate::ir::Expr;
use crate::types::BaseType;

use super::value::{Mask, Num, Value};
use super::{ExecError, GridContext};

impl GridContext<'_> {
    pub(crate) fn string_fn(
        &mut self,
        name: &str,
        args: &[Expr],
        vals: &[Value],
        mask: &Mask,
    ) -> Result<Value, ExecError> {
        let first = mask.idx.first().map_or(0, |&i| i as usize);
        Ok(match name {
            "concat" => Value::Str(cap(vals.iter().map(Value::str).collect())),
            "shadername" => Value::Str(self.shader.name.clone()),
            "match" => {
                let hit = regex_find(vals[0].str().as_bytes(), vals[1].str().as_bytes());
                Value::Num(Num::scalar(if hit { 1.0 } else { 0.0 }))
            }
            "format" => Value::Str(cap(format_at(vals[0].str(), &args[1..], &vals[1..], first))),
            _ => {
                let lanes: Vec<usize> = if vals.iter().any(Value::varying) {
                    mask.iter().collect()
                } else {
                    vec![first]
                };
                for i in lanes {
                    let line = cap(format_at(vals[0].str(), &args[1..], &vals[1..], i));
                    if self.printed.len() < 10_000 {
                        self.printed.push(line);
                    }
                }
                Value::Num(Num::scalar(0.0))
            }
        })
    }

    /// `spline([basis,] x, knots...)` or with an array of knots.
    pub(crate) fn spline(&mut self, args: &[Expr], vals: &[Value], w: usize, mask: &Mask) -> Value {
        let has_basis = args.first().is_some_and(|a| a.ty.base == BaseType::String);
        let basis = if has_basis { vals[0].str().to_string() } else { "catmull-rom".into() };
        let rest = &vals[usize::from(has_basis)..];
        let x = rest[0].num().clone();
        let knots: Vec<Num> = match rest.get(1) {
            Some(Value::Array(a)) if rest.len() == 2 => a.iter().map(|v| v.num().clone()).collect(),
            _ => rest[1..].iter().map(|v| v.num().clone()).collect(),
        };
        let mut refs: Vec<&Num> = vec![&x];
        refs.extend(knots.iter());
        let n = self.n;
        let uniform = refs.iter().all(|r| !r.varying);
        let mut out = Num::zeros(w, !uniform, n);
        let lanes: Vec<usize> = if uniform { vec![0] } else { mask.iter().collect() };
        let mut ks: Vec<f32> = Vec::with_capacity(knots.len());
        for i in lanes {
            let xv = x.f(i);
            for c in 0..w {
                ks.clear();
                ks.extend(knots.iter().map(|k| {
                    let l = k.lane(i);
                    if l.len() == 1 { l[0] } else { l[c] }
                }));
                let v = spline1(&basis, xv, &ks);
                if uniform {
                    out.data[c] = v;
                } else {
                    out.lane_mut(i)[c] = v;
                }
            }
        }
        Value::Num(out)
    }
}

/// The longest string a run makes (1 MiB): `s = concat(s, s)` in a loop cannot exhaust
/// memory; longer results are cut (at a character boundary).
pub const MAX_STRING: usize = 1 << 20;

fn cap(mut s: String) -> String {
    if s.len() > MAX_STRING {
        let mut k = MAX_STRING;
        while !s.is_char_boundary(k) {
            k -= 1;
        }
        s.truncate(k);
    }
    s
}

/// One component of a spline through knots `k` at `x` in [0, 1] (clamped).
pub fn spline1(basis: &str, x: f32, k: &[f32]) -> f32 {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    if k.len() < 4 {
        return k.first().copied().unwrap_or(0.0);
    }
    if basis == "linear" {
        let nseg = k.len() - 3;
        let s = x * nseg as f32;
        let seg = (s as usize).min(nseg - 1);
        let t = s - seg as f32;
        return k[seg + 1] * (1.0 - t) + k[seg + 2] * t;
    }
    let (m, step): ([[f32; 4]; 4], usize) = match basis {
        "bezier" => {
            ([[-1., 3., -3., 1.], [3., -6., 3., 0.], [-3., 3., 0., 0.], [1., 0., 0., 0.]], 3)
        }
        "bspline" | "b-spline" => (
            [
                [-1. / 6., 3. / 6., -3. / 6., 1. / 6.],
                [3. / 6., -6. / 6., 3. / 6., 0.],
                [-3. / 6., 0., 3. / 6., 0.],
                [1. / 6., 4. / 6., 1. / 6., 0.],
            ],
            1,
        ),
        "hermite" => {
            ([[2., 1., -2., 1.], [-3., -2., 3., -1.], [0., 1., 0., 0.], [1., 0., 0., 0.]], 2)
        }
        _ => (
            [[-0.5, 1.5, -1.5, 0.5], [1., -2.5, 2., -0.5], [-0.5, 0., 0.5, 0.], [0., 1., 0., 0.]],
            1,
        ),
    };
    let nseg = (k.len() - 4) / step + 1;
    let s = x * nseg as f32;
    let seg = (s as usize).min(nseg - 1);
    let t = s - seg as f32;
    let p = &k[seg * step..seg * step + 4];
    let tv = [t * t * t, t * t, t, 1.0];
    (0..4).map(|r| tv[r] * (0..4).map(|c| m[r][c] * p[c]).sum::<f32>()).sum()
}

fn format_at(fmt: &str, args: &[Expr], vals: &[Value], lane: usize) -> String {
    let mut out = String::new();
    let mut it = vals.iter().zip(args);
    let b = fmt.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] != b'%' {
            let ch = fmt[i..].chars().next().unwrap_or('?');
            out.push(ch);
            i += ch.len_utf8();
            continue;
        }
        let start = i;
        i += 1;
        while i < b.len() && b"-+ #0123456789.".contains(&b[i]) {
            i += 1;
        }
        let spec = &fmt[start + 1..i];
        let Some(ch) = fmt[i..].chars().next() else { break };
        i += ch.len_utf8();
        let conv = if ch.is_ascii() { ch as u8 } else { b'?' };
        // Flags `-` (left) and `0` (zero padding), a width and a precision, each capped so a
        // hostile format cannot ask for a huge string.
        let prec = spec.split('.').nth(1).and_then(|p| p.parse::<usize>().ok()).map(|p| p.min(64));
        let head = spec.split('.').next().unwrap_or("");
        let left = head.contains('-');
        let digits = head.trim_start_matches(['-', '+', ' ', '#', '0']);
        let zero = head.trim_start_matches(['-', '+', ' ', '#']).starts_with('0') && !left;
        let width = digits.parse::<usize>().unwrap_or(0).min(256);
        let pad = |t: String, numeric: bool| {
            let len = t.chars().count();
            if len >= width {
                t
            } else if left {
                format!("{t}{}", " ".repeat(width - len))
            } else if zero && numeric {
                let (sign, rest) =
                    if let Some(r) = t.strip_prefix('-') { ("-", r) } else { ("", &t[..]) };
                format!("{sign}{}{rest}", "0".repeat(width - len))
            } else {
                format!("{}{t}", " ".repeat(width - len))
            }
        };
        if conv == b'%' {
            out.push('%');
            continue;
        }
        let Some((v, _)) = it.next() else { continue };
        let f = |x: f32| {
            let t = match (conv, prec) {
                (b'd' | b'i', _) => format!("{}", x as i64),
                (b'e', Some(p)) => format!("{x:.p$e}"),
                (b'e', None) => format!("{x:e}"),
                (_, Some(p)) => format!("{x:.p$}"),
                (b'f', None) => format!("{x:.6}"),
                _ => format!("{x}"),
            };
            pad(t, true)
        };
        match v {
            Value::Str(s) => out.push_str(&pad(s.clone(), false)),
            Value::Num(x) => {
                let l = x.lane(lane);
                let parts: Vec<String> = l.iter().map(|&c| f(c)).collect();
                out.push_str(&parts.join(" "));
            }
            Value::Array(a) => {
                let parts: Vec<String> = a.iter().map(|e| f(e.num().f(lane))).collect();
                out.push_str(&parts.join(" "));
            }
        }
    }
    out
}

/// Whether pattern `p` matches somewhere in `s`.
/// The search gives up (no match) after `4 * (2^20 + len)` steps, so a pattern like
/// `a*a*a*a*b` cannot stall a grid (a plain pattern over a long subject stays well inside).
pub fn regex_find(p: &[u8], s: &[u8]) -> bool {
    let mut steps = 4 * ((1u64 << 20) + s.len() as u64);
    if let Some(rest) = p.strip_prefix(b"^") {
        return match_here(rest, s, &mut steps, 0);
    }
    (0..=s.len()).any(|k| match_here(p, &s[k..], &mut steps, 0))
}

/// One pattern atom: its length in the pattern, and whether it takes byte `c`.
fn atom(p: &[u8], c: u8) -> (usize, bool) {
    match p[0] {
        b'.' => (1, true),
        b'\\' if p.len() > 1 => (2, p[1] == c),
        b'[' => {
            let mut i = 1;
            let neg = p.get(1) == Some(&b'^');
            if neg {
                i += 1;
            }
            let mut hit = false;
            let mut first = true;
            while i < p.len() && (p[i] != b']' || first) {
                first = false;
                if i + 2 < p.len() && p[i + 1] == b'-' && p[i + 2] != b']' {
                    hit |= (p[i]..=p[i + 2]).contains(&c);
                    i += 3;
                } else {
                    hit |= p[i] == c;
                    i += 1;
                }
            }
            ((i + 1).min(p.len()), hit != neg)
        }
        x => (1, x == c),
    }
}

fn match_here(p: &[u8], s: &[u8], steps: &mut u64, depth: u32) -> bool {
    // Each level matches one atom: a pattern of more than 2000 atoms does not match (and
    // cannot overflow the stack).
    if *steps == 0 || depth > 2000 {
        return false;
    }
    *steps -= 1;
    if p.is_empty() {
        return true;
    }
    if p == b"$" {
        return s.is_empty();
    }
    let (len, _) = atom(p, 0);
    let rep = p.get(len).copied();
    let takes = |c: u8| atom(p, c).1;
    match rep {
        Some(b'*' | b'+' | b'?') => {
            let rest = &p[len + 1..];
            let mut k = 0;
            let max = if rep == Some(b'?') { 1 } else { s.len() };
            while k < s.len() && k < max && takes(s[k]) {
                k += 1;
            }
            let min = usize::from(rep == Some(b'+'));
            (min..=k).rev().any(|j| match_here(rest, &s[j..], steps, depth + 1))
        }
        _ => !s.is_empty() && takes(s[0]) && match_here(&p[len..], &s[1..], steps, depth + 1),
    }
}
