//! The light scan of scene text that the structure-aware mutations work on: numbers, words
//! and quoted strings, bracketed groups and their elements. No parser: it accepts any bytes
//! (unbalanced brackets, unterminated strings, invalid UTF-8) and finds what it can.
//! Invariant: every span it returns lies inside the text, and spans of one kind are in
//! order and do not overlap (groups nest).

use std::ops::Range;

/// True if `c` may continue a word.
pub(super) fn is_word(c: u8) -> bool {
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
}
