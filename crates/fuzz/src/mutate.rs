//! Mutations of scene text, structure-aware and byte-level.
//!
//! Both scene formats are text made of numbers, words, quoted strings and bracketed lists, so
//! one light scan of that shape (no parser: the input may be anything) serves both: numbers
//! are replaced by extremes (0, -1, 1e30, NaN, infinities, denormals, integers at the edges of
//! `u32`, `i32`, `u64`) or nudged; list elements are deleted, duplicated (a few times, or
//! hundreds) and swapped; lists and lines are spliced in from other corpus inputs; a list is
//! nested inside itself (recursion depth); words are replaced by words of the corpus. Byte
//! mutations (bit flips, random bytes, deletions, copies, truncation) cover what the scan
//! cannot see: broken tokens, binary RIB, invalid UTF-8.
//!
//! Invariant: a mutation is a pure function of the generator's state, the input and the
//! corpus, and never yields more than `max_len` bytes.

use std::ops::Range;

use crate::rng::Rng;

/// Numbers worth trying in any numeric field.
const INTERESTING: &[&str] = &[
    "0",
    "-0",
    "1",
    "-1",
    "2",
    "3",
    "0.0",
    "-0.0",
    "0.5",
    "-0.5",
    "1.0",
    "-1.0",
    "0.1",
    "1e-7",
    "1e-30",
    "1e-38",
    "1.1754942e-38",
    "1e-45",
    "1e-300",
    "1e7",
    "1e9",
    "1e15",
    "1e30",
    "-1e30",
    "1e38",
    "3.4028235e38",
    "-3.4028235e38",
    "1e39",
    "-1e39",
    "1e300",
    "NaN",
    "inf",
    "-inf",
    "16",
    "64",
    "65",
    "90",
    "180",
    "360",
    "361",
    "-360",
    "255",
    "256",
    "1024",
    "1025",
    "4096",
    "65535",
    "65536",
    "1000000",
    "16777217",
    "2147483647",
    "2147483648",
    "-2147483648",
    "-2147483649",
    "4294967295",
    "4294967296",
    "9007199254740993",
    "9223372036854775807",
    "18446744073709551615",
    "18446744073709551616",
    "99999999999999999999999999",
];

/// Single bytes worth writing anywhere.
const BYTES: &[u8] = b"\0\x01\x7f\x80\xff\n\r\t \"\\()[]{},:;#-+.eE0123456789";

/// The mutator: the words to splice in, and the size bound.
#[derive(Debug, Clone)]
pub struct Mutator {
    dict: Vec<Vec<u8>>,
    max_len: usize,
}

impl Mutator {
    /// A mutator whose dictionary is every word and short quoted string of `corpus` plus
    /// `extra`; results are cut to `max_len` bytes.
    pub fn new(corpus: &[Vec<u8>], extra: &[&str], max_len: usize) -> Mutator {
        let mut dict: Vec<Vec<u8>> = extra.iter().map(|s| s.as_bytes().to_vec()).collect();
        for input in corpus {
            for r in words(input) {
                if r.len() <= 64 {
                    dict.push(input[r].to_vec());
                }
            }
        }
        dict.sort();
        dict.dedup();
        if dict.is_empty() {
            dict.push(b"0".to_vec());
        }
        Mutator { dict, max_len }
    }

    /// How many words the dictionary holds.
    pub fn dict_len(&self) -> usize {
        self.dict.len()
    }

    /// A mutant of `input`: one to eight mutations stacked; `others` (the corpus) gives the
    /// material of splices and may be empty.
    pub fn mutate(&self, rng: &mut Rng, input: &[u8], others: &[Vec<u8>]) -> Vec<u8> {
        let mut out = input.to_vec();
        let rounds = 1 + rng.small(8);
        for _ in 0..rounds {
            self.once(rng, &mut out, others);
            out.truncate(self.max_len);
        }
        out
    }

    /// One mutation, structure-aware (most of the time) or on bytes.
    fn once(&self, rng: &mut Rng, buf: &mut Vec<u8>, others: &[Vec<u8>]) {
        let other = if others.is_empty() { &buf.clone() } else { &others[rng.below(others.len())] };
        let done = match rng.below(16) {
            0..=3 => self.number(rng, buf),
            4 => delete_element(rng, buf),
            5 => duplicate_element(rng, buf),
            6 => swap_elements(rng, buf),
            7 => splice_group(rng, buf, other),
            8 => nest_group(rng, buf),
            9 => line(rng, buf, other),
            10 => self.word(rng, buf),
            11 => crossover(rng, buf, other),
            _ => false,
        };
        if !done {
            self.byte(rng, buf);
        }
    }

    /// Replaces a number by an extreme, a neighbour or a random value.
    fn number(&self, rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
        let spans = numbers(buf);
        if spans.is_empty() {
            return false;
        }
        let span = rng.pick(&spans).clone();
        let old = std::str::from_utf8(&buf[span.clone()]).unwrap_or("0").to_string();
        let new = match rng.below(4) {
            0 | 1 => rng.pick(INTERESTING).to_string(),
            2 => nudge(rng, &old),
            _ => random_number(rng, is_integer(&old)),
        };
        buf.splice(span, new.bytes());
        true
    }

    /// Replaces a word by a dictionary word, or inserts one before a word.
    fn word(&self, rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
        let spans = words(buf);
        let new = rng.pick(&self.dict).clone();
        if spans.is_empty() {
            let at = rng.below(buf.len() + 1);
            buf.splice(at..at, new);
            return true;
        }
        let span = rng.pick(&spans).clone();
        if rng.one_in(3) {
            let mut ins = new;
            ins.push(b' ');
            buf.splice(span.start..span.start, ins);
        } else {
            buf.splice(span, new);
        }
        true
    }

    /// A byte-level mutation.
    fn byte(&self, rng: &mut Rng, buf: &mut Vec<u8>) {
        let n = buf.len();
        match rng.below(9) {
            0 if n > 0 => {
                let i = rng.below(n);
                buf[i] ^= 1 << rng.below(8);
            }
            1 if n > 0 => {
                let i = rng.below(n);
                buf[i] = *rng.pick(BYTES);
            }
            2 => {
                let at = rng.below(n + 1);
                let len = 1 + rng.small(8);
                let bytes: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
                buf.splice(at..at, bytes);
            }
            3 if n > 0 => {
                let start = rng.below(n);
                let len = 1 + rng.small(n - start);
                buf.drain(start..(start + len).min(n));
            }
            4 if n > 0 => {
                let start = rng.below(n);
                let len = 1 + rng.small(n - start);
                let copy = buf[start..(start + len).min(n)].to_vec();
                let at = rng.below(n + 1);
                buf.splice(at..at, copy);
            }
            5 if n > 0 => buf.truncate(rng.below(n)),
            6 => {
                let at = rng.below(n + 1);
                let word = rng.pick(&self.dict).clone();
                buf.splice(at..at, word);
            }
            _ => {
                let at = rng.below(n + 1);
                buf.insert(at, *rng.pick(BYTES));
            }
        }
    }
}

/// True if `c` may continue a word.
fn is_word(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// The spans of the numbers in `text`: an optional sign, digits and a point, an optional
/// exponent; not inside a word (`Fig7`). Also `NaN` and `inf` standing alone.
pub fn numbers(text: &[u8]) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let prev_word = i > 0 && (is_word(text[i - 1]) || text[i - 1] == b'.');
        let start = i;
        let mut j = i;
        if matches!(text[j], b'-' | b'+') {
            j += 1;
        }
        let digits_at = |k: usize| k < text.len() && text[k].is_ascii_digit();
        let lead = digits_at(j) || (j < text.len() && text[j] == b'.' && digits_at(j + 1));
        if prev_word || !lead {
            if !prev_word
                && (text[i..].starts_with(b"NaN") || text[i..].starts_with(b"inf"))
                && !text.get(i + 3).is_some_and(|&c| is_word(c))
            {
                out.push(i..i + 3);
                i += 3;
                continue;
            }
            i += 1;
            continue;
        }
        while j < text.len() && (text[j].is_ascii_digit() || text[j] == b'.') {
            j += 1;
        }
        if j < text.len() && matches!(text[j], b'e' | b'E') {
            let mut k = j + 1;
            if k < text.len() && matches!(text[k], b'-' | b'+') {
                k += 1;
            }
            if digits_at(k) {
                j = k;
                while digits_at(j) {
                    j += 1;
                }
            }
        }
        out.push(start..j);
        i = j;
    }
    out
}

/// The spans of the words (identifiers) and quoted strings of `text`.
pub fn words(text: &[u8]) -> Vec<Range<usize>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        let c = text[i];
        if c == b'"' {
            let end = string_end(text, i);
            out.push(i..end);
            i = end;
        } else if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < text.len() && is_word(text[i]) {
                i += 1;
            }
            out.push(start..i);
        } else if c.is_ascii_digit() {
            while i < text.len() && (is_word(text[i]) || text[i] == b'.') {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The index just past the string that opens at `start` (a `"`), or the end of the text.
fn string_end(text: &[u8], start: usize) -> usize {
    let mut i = start + 1;
    while i < text.len() {
        match text[i] {
            b'\\' => i += 2,
            b'"' => return i + 1,
            _ => i += 1,
        }
    }
    text.len()
}

/// A bracketed list: the indices of its opening and closing brackets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Group {
    /// The opening bracket.
    pub open: usize,
    /// The closing bracket.
    pub close: usize,
}

impl Group {
    /// The whole group, brackets included.
    pub fn span(&self) -> Range<usize> {
        self.open..self.close + 1
    }

    /// Between the brackets.
    pub fn inner(&self) -> Range<usize> {
        self.open + 1..self.close
    }
}

/// Every balanced `(...)`, `[...]` and `{...}` of `text`, strings skipped, in order of their
/// opening bracket.
pub fn groups(text: &[u8]) -> Vec<Group> {
    let mut out = Vec::new();
    let mut stack: Vec<(u8, usize)> = Vec::new();
    let mut i = 0;
    while i < text.len() {
        match text[i] {
            b'"' => {
                i = string_end(text, i);
                continue;
            }
            c @ (b'(' | b'[' | b'{') => stack.push((c, i)),
            c @ (b')' | b']' | b'}') => {
                let want = match c {
                    b')' => b'(',
                    b']' => b'[',
                    _ => b'{',
                };
                if let Some(depth) = stack.iter().rposition(|&(o, _)| o == want) {
                    let (_, open) = stack[depth];
                    stack.truncate(depth);
                    out.push(Group { open, close: i });
                }
            }
            _ => {}
        }
        i += 1;
    }
    out.sort_by_key(|g| g.open);
    out
}

/// The elements of a group: its top-level comma-separated items (RON), or, when it has no
/// top-level comma, its white-space-separated items (RIB arrays). Each span is trimmed.
pub fn elements(text: &[u8], g: Group) -> Vec<Range<usize>> {
    let inner = g.inner();
    let mut cuts = Vec::new();
    let mut depth = 0i32;
    let mut i = inner.start;
    let mut commas = false;
    while i < inner.end {
        match text[i] {
            b'"' => {
                i = string_end(text, i).min(inner.end);
                continue;
            }
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            b',' if depth == 0 => {
                commas = true;
                cuts.push((i, true));
            }
            c if depth == 0 && c.is_ascii_whitespace() => cuts.push((i, false)),
            _ => {}
        }
        i += 1;
    }
    let mut out = Vec::new();
    let mut start = inner.start;
    for (at, comma) in cuts.into_iter().filter(|&(_, c)| c == commas) {
        let _ = comma;
        push_trimmed(text, start..at, &mut out);
        start = at + 1;
    }
    push_trimmed(text, start..inner.end, &mut out);
    out
}

fn push_trimmed(text: &[u8], r: Range<usize>, out: &mut Vec<Range<usize>>) {
    let mut s = r.start;
    let mut e = r.end;
    while s < e && text[s].is_ascii_whitespace() {
        s += 1;
    }
    while e > s && text[e - 1].is_ascii_whitespace() {
        e -= 1;
    }
    if s < e {
        out.push(s..e);
    }
}

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

fn delete_element(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
    let Some((g, els)) = pick_list(rng, buf) else { return false };
    let k = rng.below(els.len());
    let end = els.get(k + 1).map_or(els[k].end, |n| n.start);
    buf.drain(els[k].start..end);
    let _ = g;
    true
}

fn duplicate_element(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
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

fn swap_elements(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
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
fn splice_group(rng: &mut Rng, buf: &mut Vec<u8>, other: &[u8]) -> bool {
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
fn nest_group(rng: &mut Rng, buf: &mut Vec<u8>) -> bool {
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
fn line(rng: &mut Rng, buf: &mut Vec<u8>, other: &[u8]) -> bool {
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
fn crossover(rng: &mut Rng, buf: &mut Vec<u8>, other: &[u8]) -> bool {
    if buf.is_empty() || other.is_empty() {
        return false;
    }
    let a = rng.below(buf.len());
    let b = rng.below(other.len());
    buf.truncate(a);
    buf.extend_from_slice(&other[b..]);
    true
}

fn is_integer(s: &str) -> bool {
    !s.contains(['.', 'e', 'E', 'N', 'i'])
}

/// A value near `old`: negated, doubled, halved, off by one, or scaled by a power of ten.
fn nudge(rng: &mut Rng, old: &str) -> String {
    if is_integer(old) {
        let v: i128 = old.parse().unwrap_or(0);
        let v = match rng.below(5) {
            0 => v + 1,
            1 => v - 1,
            2 => -v,
            3 => v.saturating_mul(2),
            _ => v / 2,
        };
        return v.to_string();
    }
    let v: f64 = old.parse().unwrap_or(0.0);
    let v = match rng.below(7) {
        0 => -v,
        1 => v * 2.0,
        2 => v / 2.0,
        3 => v + 1.0,
        4 => v - 1.0,
        5 => v * 10f64.powi(rng.below(40) as i32),
        _ => v * 10f64.powi(-(rng.below(40) as i32)),
    };
    format_float(v)
}

/// A random number: an integer of random magnitude, or a float.
fn random_number(rng: &mut Rng, integer: bool) -> String {
    let bits = rng.below(64);
    let magnitude = rng.next_u64() >> (63 - bits);
    if integer {
        if rng.one_in(4) { format!("-{magnitude}") } else { magnitude.to_string() }
    } else {
        let x = (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
        format_float(x * 10f64.powi(rng.below(12) as i32 - 4))
    }
}

/// A float written so both scene formats read it back (`1.0`, `1e30`, `NaN`, `inf`).
fn format_float(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{v:?}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(text: &[u8], spans: &[Range<usize>]) -> Vec<String> {
        spans.iter().map(|r| String::from_utf8_lossy(&text[r.clone()]).into_owned()).collect()
    }

    #[test]
    fn numbers_are_found_outside_words_with_signs_points_and_exponents() {
        let t = b"Fig7 (x: -1.5e-3, y: 2) [3 .5 +4] NaN inf info";
        assert_eq!(texts(t, &numbers(t)), ["-1.5e-3", "2", "3", ".5", "+4", "NaN", "inf"]);
    }

    #[test]
    fn words_include_quoted_strings_with_escapes() {
        let t = br#"Sphere "a \" b" 1 x_2"#;
        assert_eq!(texts(t, &words(t)), ["Sphere", r#""a \" b""#, "x_2"]);
    }

    #[test]
    fn groups_match_brackets_and_skip_strings() {
        let t = br#"A([1, (2)], ")") ]"#;
        let gs = groups(t);
        let spans: Vec<Range<usize>> = gs.iter().map(Group::span).collect();
        assert_eq!(texts(t, &spans), [r#"([1, (2)], ")")"#, "[1, (2)]", "(2)"]);
    }

    #[test]
    fn elements_split_on_top_level_commas_else_on_white_space() {
        let t = b"[(1, 2), (3, 4), ] [1 2  3]";
        let gs = groups(t);
        assert_eq!(texts(t, &elements(t, gs[0])), ["(1, 2)", "(3, 4)"]);
        let rib = gs.iter().find(|g| t[g.open] == b'[' && g.open > 0).copied().unwrap();
        assert_eq!(texts(t, &elements(t, rib)), ["1", "2", "3"]);
    }

    #[test]
    fn mutants_differ_stay_bounded_and_repeat_for_a_seed() {
        let seed =
            b"Scene(image: (width: 64, height: 48), objects: [(shape: Sphere(radius: 1.0))])";
        let corpus = vec![seed.to_vec()];
        let m = Mutator::new(&corpus, &["None"], 200);
        let run = |s| {
            let mut rng = Rng::new(s);
            (0..200).map(|_| m.mutate(&mut rng, seed, &corpus)).collect::<Vec<_>>()
        };
        let a = run(1);
        assert_eq!(a, run(1));
        assert!(a.iter().all(|x| x.len() <= 200));
        let changed = a.iter().filter(|x| x.as_slice() != seed).count();
        assert!(changed > 150, "{changed} of 200 changed");
        let distinct: std::collections::HashSet<&Vec<u8>> = a.iter().collect();
        assert!(distinct.len() > 100, "{} distinct", distinct.len());
    }

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
