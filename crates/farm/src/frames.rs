//! Frame lists: the frames a run renders, `1-100` or `1,3,5-9` as text.
//!
//! Invariant: a list holds inclusive ranges, each with its start at most its end.

use std::str::FromStr;

/// Frame numbers to render: inclusive ranges, in the order given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrameList(pub Vec<(i32, i32)>);

impl FromStr for FrameList {
    type Err = String;

    /// Numbers and inclusive ranges separated by commas (`1-100`, `1,3,5-9`).
    fn from_str(s: &str) -> Result<FrameList, String> {
        let bad = || format!("expected frame numbers and ranges like 1-100 or 1,3,5-9, got '{s}'");
        s.split(',')
            .map(|part| {
                let part = part.trim();
                let (a, b) = match part.split_once('-').filter(|(a, _)| !a.is_empty()) {
                    Some((a, b)) => (a.trim(), b.trim()),
                    None => (part, part),
                };
                let (a, b): (i32, i32) =
                    (a.parse().map_err(|_| bad())?, b.parse().map_err(|_| bad())?);
                if a > b { Err(bad()) } else { Ok((a, b)) }
            })
            .collect::<Result<_, _>>()
            .map(FrameList)
    }
}

impl FrameList {
    /// The frame numbers, in order, each once.
    pub fn numbers(&self) -> Vec<i32> {
        let mut v: Vec<i32> = self.0.iter().flat_map(|&(a, b)| a..=b).collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_parse_and_number_their_frames() {
        let l: FrameList = "5-7, 1,6".parse().unwrap();
        assert_eq!(l.0, [(5, 7), (1, 1), (6, 6)]);
        assert_eq!(l.numbers(), [1, 5, 6, 7]);
        assert_eq!("-3".parse::<FrameList>().unwrap().0, [(-3, -3)]);
        assert!("3-1".parse::<FrameList>().is_err());
        assert!("x".parse::<FrameList>().is_err());
    }
}
