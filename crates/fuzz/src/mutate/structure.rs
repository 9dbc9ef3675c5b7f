//! Structure-aware mutations (on the spans of `scan.rs`): list elements deleted, duplicated
//! (a few times, or hundreds) and swapped; groups and list elements spliced in from another
//! corpus input; a group nested inside itself; lines deleted, duplicated, swapped or spliced
//! in (RIB requests are lines); a crossover of two inputs. Each returns whether it changed
//! anything; `false` leaves the buffer as it was, and the caller falls back to a byte
//! mutation.

use std::ops::Range;

use super::scan::{Group, elements, groups, is_word};
use crate::rng::Rng;

/// A group with at least one element, and its elements.
fn pick_list(rng: &mut Rng, buf: &[u8]) -> Option<(Group, Vec<Range<usize>>)> {
    let gs = groups(buf);
    for _ in 0..4 {
        let g = *rng.pick(gs.as_slice().get(..).filter(|s| !s.is_empty())?);
        let els = elements(buf, g);
        if !els.is_empty() {
            return Some((g, els));
        }
    }
    None
}

/// The separator of a group's elements: `, ` when they are comma-separated, else a space.
fn separator(buf: &[u8], g: Group, els: &[Range<usize>]) -> &'static [u8] {
    let between = match els {
        [a, b, ..] => &buf[a.end..b.start],
        _ => &buf[g.inner()],
    };
    if between.contains(&b',') || buf[g.inner()].ends_with(b",") { b", " } else { b" " }
}

pub(super) fn delete_element(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
    let Some((g, els)) = pick_list(rng, buf) else { return false };
    let k = rng.below(els.len());
    let end = els.get(k + 1).map_or(els[k].end, |n| n.start);
    buf.drain(els[k].start..end);
    let _ = g;
    true
}

pub(super) fn duplicate_element(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
    let Some((g, els)) = pick_list(rng, buf) else { return false };
    let sep = separator(buf, g, &els);
    let e = rng.pick(&els).clone();
    let copies = if rng.one_in(16) { 1 + rng.below(512) } else { 1 + rng.small(8) };
    let mut ins = Vec::new();
    for _ in 0..copies {
        ins.extend_from_slice(sep);
        ins.extend_from_slice(&buf[e.clone()]);
    }
    buf.splice(e.end..e.end, ins);
    true
}

pub(super) fn swap_elements(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
    let Some((_, els)) = pick_list(rng, buf) else { return false };
    if els.len() < 2 {
        return false;
    }
    let i = rng.below(els.len());
    let j = (i + 1 + rng.below(els.len() - 1)) % els.len();
    let (a, b) =
        if i < j { (els[i].clone(), els[j].clone()) } else { (els[j].clone(), els[i].clone()) };
    let mut out = Vec::with_capacity(buf.len());
    out.extend_from_slice(&buf[..a.start]);
    out.extend_from_slice(&buf[b.clone()]);
    out.extend_from_slice(&buf[a.end..b.start]);
    out.extend_from_slice(&buf[a.clone()]);
    out.extend_from_slice(&buf[b.end..]);
    *buf = out;
    true
}

/// Replaces a group, or one element of a list, by a group or an element of `other` opened by
/// the same bracket: the fields of one scene in the place of another's.
pub(super) fn splice_group(rng: &mut Rng, buf: &mut Vec<u8>, other: &[u8]) -> bool {
    let mine = groups(buf);
    let theirs = groups(other);
    if mine.is_empty() || theirs.is_empty() {
        return false;
    }
    let g = *rng.pick(&mine);
    let same: Vec<Group> =
        theirs.iter().copied().filter(|t| other[t.open] == buf[g.open]).collect();
    let Some(&t) = same.get(rng.below(same.len().max(1))) else { return false };
    if rng.one_in(2) {
        let els = elements(other, t);
        let mine_els = elements(buf, g);
        if !els.is_empty() && !mine_els.is_empty() {
            let src = rng.pick(&els).clone();
            let dst = rng.pick(&mine_els).clone();
            let piece = other[src].to_vec();
            if rng.one_in(2) {
                buf.splice(dst, piece);
            } else {
                let sep = separator(buf, g, &mine_els);
                let mut ins = sep.to_vec();
                ins.extend_from_slice(&piece);
                buf.splice(dst.end..dst.end, ins);
            }
            return true;
        }
    }
    buf.splice(g.span(), other[t.span()].iter().copied());
    true
}

/// Puts a copy of a group in the place of a group inside it, one to eight times over (now and
/// then hundreds): the same structure nested deeper (CSG trees, attribute blocks, arrays of
/// arrays). A word just before a bracket goes with its group (`Union(...)`).
pub(super) fn nest_group(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
    let start = |g: &Group| {
        let mut s = g.open;
        while s > 0 && is_word(buf[s - 1]) {
            s -= 1;
        }
        s
    };
    let gs = groups(buf);
    let pairs: Vec<(Range<usize>, Range<usize>)> = gs
        .iter()
        .flat_map(|a| {
            gs.iter()
                .filter(move |b| b.open > a.open && b.close < a.close)
                .map(move |b| (start(a)..a.close + 1, start(b)..b.close + 1))
        })
        .take(4096)
        .collect();
    if pairs.is_empty() {
        return false;
    }
    let (outer, inner) = rng.pick(&pairs).clone();
    let prefix = buf[outer.start..inner.start].to_vec();
    let suffix = buf[inner.end..outer.end].to_vec();
    let most = if rng.one_in(8) { 256 } else { 8 };
    let levels = 1 + rng.small(most);
    let mut mid = buf[outer.clone()].to_vec();
    for _ in 0..levels {
        if mid.len() > 1 << 16 {
            break;
        }
        let mut next = prefix.clone();
        next.extend_from_slice(&mid);
        next.extend_from_slice(&suffix);
        mid = next;
    }
    buf.splice(outer, mid);
    true
}

/// Deletes, duplicates or swaps a line, or inserts a line of `other`: RIB requests are lines.
pub(super) fn line(rng: &mut Rng, buf: &mut Vec<u8>, other: &[u8]) -> bool {
    let lines = line_spans(buf);
    if lines.is_empty() {
        return false;
    }
    let l = rng.pick(&lines).clone();
    match rng.below(4) {
        0 => {
            buf.drain(l);
        }
        1 => {
            let copy = buf[l.clone()].to_vec();
            let copies = if rng.one_in(16) { 1 + rng.below(256) } else { 1 };
            let ins: Vec<u8> = (0..copies).flat_map(|_| copy.iter().copied()).collect();
            buf.splice(l.start..l.start, ins);
        }
        2 => {
            let m = rng.pick(&lines).clone();
            if m == l {
                return false;
            }
            let (a, b) = if l.start < m.start { (l, m) } else { (m, l) };
            let mut out = Vec::with_capacity(buf.len());
            out.extend_from_slice(&buf[..a.start]);
            out.extend_from_slice(&buf[b.clone()]);
            out.extend_from_slice(&buf[a.end..b.start]);
            out.extend_from_slice(&buf[a]);
            out.extend_from_slice(&buf[b.end..]);
            *buf = out;
        }
        _ => {
            let theirs = line_spans(other);
            if theirs.is_empty() {
                return false;
            }
            let piece = other[rng.pick(&theirs).clone()].to_vec();
            buf.splice(l.start..l.start, piece);
        }
    }
    true
}

/// The lines of `text`, each with its newline.
fn line_spans(text: &[u8]) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &c) in text.iter().enumerate() {
        if c == b'\n' {
            out.push(start..i + 1);
            start = i + 1;
        }
    }
    if start < text.len() {
        out.push(start..text.len());
    }
    out
}

/// The head of `buf` up to a random point, then the tail of `other` from another.
pub(super) fn crossover(rng: &mut Rng, buf: &mut Vec<u8>, other: &[u8]) -> bool {
    if buf.is_empty() || other.is_empty() {
        return false;
    }
    let a = rng.below(buf.len());
    let b = rng.below(other.len());
    buf.truncate(a);
    buf.extend_from_slice(&other[b..]);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nesting_deepens_a_group_inside_itself() {
        let t = b"U([U(A), B])".to_vec();
        let mut found = false;
        for s in 0..50 {
            let mut b = t.clone();
            if nest_group(&mut Rng::new(s), &mut b) && b.starts_with(b"U([U([U(A), B]), B])") {
                found = true;
            }
        }
        assert!(found);
    }
}
