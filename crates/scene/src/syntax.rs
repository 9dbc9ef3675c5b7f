//! Turns ron's syntax and type errors (and invalid UTF-8) into one-line [`SceneError`]s.
//!
//! Invariants: the position is ron's span start, moved forward over whitespace and comments
//! onto the offending token when ron's span starts before it; the field path is that of the
//! innermost value containing the position (plus the field name for unknown, missing and
//! duplicate fields); messages are short, lower-case, single-line and clipped in length.

use std::path::Path;

use ron::error::{Error as RonError, SpannedError};

use crate::error::{SceneError, clip};
use crate::locate::{Pos, SourceMap, join};

/// Longest message or field path kept, in characters.
const MAX_LEN: usize = 240;

/// The [`SceneError`] for a failed `ron` deserialisation of `text`.
pub(crate) fn from_ron(text: &str, file: &Path, err: &SpannedError) -> SceneError {
    let map = SourceMap::scan(text);
    let start = Pos { line: err.span.start.line, col: err.span.start.col };
    let end = Pos { line: err.span.end.line, col: err.span.end.col };
    // ron reports a missing separator or closer from the token before it; point at what
    // stands where the separator was expected instead.
    let expects_separator = matches!(
        err.code,
        RonError::ExpectedComma
            | RonError::ExpectedArrayEnd
            | RonError::ExpectedStructLikeEnd
            | RonError::ExpectedMapEnd
            | RonError::ExpectedOptionEnd
    );
    let pos = match (&err.code, map.unclosed_comment) {
        (RonError::UnclosedBlockComment, Some(comment)) => comment,
        _ if expects_separator => map.snap(end, Pos::MAX),
        _ => map.snap(start, end),
    };
    // ron reports some number errors from inside the number (after a sign, at the point of
    // `1.5` read as an integer): the error is about the whole number, so point at its start.
    let number = map.number_around(pos);
    let read = number.map_or(0, |(start, _)| pos.col.saturating_sub(start.col));
    let pos = number.map_or(pos, |(start, _)| start);
    let at_eof = map.is_past_last_token(pos);
    let field = if is_document_level(&err.code) {
        String::new()
    } else {
        let base = map.path_for(pos);
        match &err.code {
            RonError::NoSuchStructField { found, .. } => join(&base, found),
            RonError::MissingStructField { field, .. }
            | RonError::DuplicateStructField { field, .. } => join(&base, field),
            RonError::ExpectedMapColon => map.field_before(pos).unwrap_or(base),
            _ => base,
        }
    };
    let message = match number {
        Some((_, text)) => describe_number(&err.code, text, read, expects_separator),
        None => None,
    };
    let message = message.unwrap_or_else(|| describe(&err.code, at_eof));
    SceneError {
        file: file.to_path_buf(),
        line: Some(pos.line),
        col: Some(pos.col),
        field: clip(&field, MAX_LEN),
        message: clip(&message, MAX_LEN),
    }
}

/// The [`SceneError`] for a file whose bytes are not UTF-8; `valid` is the valid prefix.
pub(crate) fn invalid_utf8(file: &Path, valid: &str) -> SceneError {
    let line = 1 + valid.matches('\n').count();
    let col = 1 + valid.rsplit('\n').next().map_or(0, |last| last.chars().count());
    SceneError {
        file: file.to_path_buf(),
        line: Some(line),
        col: Some(col),
        field: String::new(),
        message: "the file is not valid UTF-8".into(),
    }
}

/// Errors about the document as a whole, where naming a field would mislead.
fn is_document_level(code: &RonError) -> bool {
    matches!(
        code,
        RonError::Eof
            | RonError::TrailingCharacters
            | RonError::UnclosedBlockComment
            | RonError::UnclosedLineComment
            | RonError::Utf8Error(_)
            | RonError::ExpectedAttribute
            | RonError::ExpectedAttributeEnd
            | RonError::NoSuchExtension(_)
            | RonError::ExceededRecursionLimit
    )
}

/// What is wrong with the number `text` that ron stopped reading after `read` characters:
/// a negative or too large integer, a fraction or exponent where an integer is due (`640.5`,
/// `4e0`), or something that is not a number at all (`35.0deg`); `None` to describe the
/// error as usual. `stopped_early` is true for the errors ron gives after a value, which are
/// about the number only when ron stopped inside it.
fn describe_number(
    code: &RonError,
    text: &str,
    read: usize,
    stopped_early: bool,
) -> Option<String> {
    let shown = clip(text, 40);
    let rest = text.chars().nth(read);
    let integer_then = |rest: Option<char>| matches!(rest, Some('.' | 'e' | 'E'));
    let read_an_integer = read > 0
        && text
            .chars()
            .take(read)
            .enumerate()
            .all(|(i, c)| c.is_ascii_digit() || c == '_' || (i == 0 && matches!(c, '+' | '-')));
    match code {
        RonError::IntegerOutOfBounds if text.starts_with('-') => {
            Some(format!("must be a non-negative integer, got {shown}"))
        }
        RonError::IntegerOutOfBounds => {
            Some(format!("integer out of range for this field, got {shown}"))
        }
        RonError::InvalidIntegerDigit { digit, .. } if integer_then(Some(*digit)) => {
            Some(format!("expected an integer, got {shown}"))
        }
        RonError::InvalidIntegerDigit { .. } => Some(format!("`{shown}` is not an integer")),
        _ if stopped_early && read > 0 && read < text.chars().count() => {
            Some(if read_an_integer && integer_then(rest) {
                format!("expected an integer, got {shown}")
            } else {
                format!("`{shown}` is not a number")
            })
        }
        _ => None,
    }
}

/// `a, b or c`, with each name in backticks.
fn one_of(names: &[&str]) -> String {
    match names {
        [] => "nothing".into(),
        [one] => format!("`{one}`"),
        [init @ .., last] => {
            let init: Vec<String> = init.iter().map(|n| format!("`{n}`")).collect();
            format!("{} or `{last}`", init.join(", "))
        }
    }
}

/// A short, human, one-line description of a ron error.
fn describe(code: &RonError, at_eof: bool) -> String {
    match code {
        RonError::ExpectedComma if at_eof => {
            "unexpected end of file, expected `,` or a closing bracket".into()
        }
        RonError::ExpectedComma => "expected `,` or a closing bracket".into(),
        RonError::Eof => "unexpected end of file".into(),
        RonError::TrailingCharacters => "unexpected text after the scene".into(),
        RonError::ExpectedOption => "expected `Some(...)` or `None`".into(),
        RonError::ExceededRecursionLimit => "nesting is too deep".into(),
        RonError::IntegerOutOfBounds => "integer out of range for this field".into(),
        RonError::NoSuchStructField { expected, found, .. } => {
            format!("unknown field `{found}`, expected {}", one_of(expected))
        }
        RonError::MissingStructField { field, .. } => format!("missing required field `{field}`"),
        RonError::DuplicateStructField { field, .. } => format!("field `{field}` given twice"),
        RonError::NoSuchEnumVariant { expected, found, .. } => {
            format!("unknown variant `{found}`, expected {}", one_of(expected))
        }
        RonError::InvalidValueForType { expected, found } => {
            format!("expected {expected}, found {found}")
        }
        RonError::ExpectedDifferentLength { expected, found } => {
            format!(
                "expected {expected}, found {found} element{}",
                if *found == 1 { "" } else { "s" }
            )
        }
        other => lower_first(&other.to_string()),
    }
}

fn lower_first(s: &str) -> String {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) => c.to_lowercase().chain(chars).collect(),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alternatives() {
        assert_eq!(one_of(&[]), "nothing");
        assert_eq!(one_of(&["a"]), "`a`");
        assert_eq!(one_of(&["a", "b", "c"]), "`a`, `b` or `c`");
    }

    #[test]
    fn utf8_position() {
        let e = invalid_utf8(Path::new("f.ron"), "ab\ncdé");
        assert_eq!((e.line, e.col), (Some(2), Some(4)));
    }
}
