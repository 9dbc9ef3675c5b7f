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
//!
//! The scan is `mutate/scan.rs` (its spans are public: numbers, words, groups, elements), the
//! mutations of lists, groups and lines `mutate/structure.rs`, the numbers written in place
//! of numbers `mutate/number.rs`; the byte mutations and the choice among all of them are
//! here.

mod number;
mod scan;
mod structure;

pub use scan::{Group, elements, groups, numbers, words};

use crate::rng::Rng;
use structure::{
    crossover, delete_element, duplicate_element, line, nest_group, splice_group, swap_elements,
};

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
        let new = number::replacement(rng, &old);
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
