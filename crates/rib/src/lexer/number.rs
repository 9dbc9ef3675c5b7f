//! RIB numbers (Spec 3.2 Appendix C.2), and the byte classes that end names and numbers: an optional sign, digits with an embedded period, a
//! trailing exponent, or both, converted to `f32` (and `i32` for the integer forms) without
//! allocating.
//!
//! Invariant: every conversion is correctly rounded; text that is not of the form is rejected
//! before any conversion.

use super::Num;

/// Byte classes: delimiters end names and numbers.
const fn delimiters() -> [bool; 256] {
    let mut t = [false; 256];
    let mut b = 0;
    while b < 256 {
        t[b] = matches!(
            b as u8,
            b' ' | b'\t' | b'\r' | b'\n' | 0x0b | 0x0c | b'[' | b']' | b'"' | b'#'
        ) || b >= 0x80
            || b < 0x20
            || b == 0x7f;
        b += 1;
    }
    t
}
pub(super) static DELIM: [bool; 256] = delimiters();

/// True if `b` can start a number.
pub(super) fn is_number_start(b: u8) -> bool {
    b.is_ascii_digit() || matches!(b, b'+' | b'-' | b'.')
}

/// Why a number's text was rejected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NumError {
    /// Not of the RIB number form.
    Malformed,
    /// Of the form, but not a finite `f32`.
    OutOfRange,
}

/// Exact powers of ten in `f32` (10^10 = 2^10 · 5^10 and 5^10 < 2^24).
const POW10: [f32; 11] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10];

/// Converts a RIB number's text (Spec C.2: optional sign, digits with an embedded period, a
/// trailing exponent, or both) without allocating.
///
/// Correctly rounded: when the decimal mantissa fits in 24 bits and the power of ten is at most
/// 10^10 both are exact `f32`s and one multiply or divide rounds once (Clinger's fast path);
/// otherwise the already validated text goes to `core`'s `f32` parser (Eisel-Lemire, also
/// allocation-free).
pub(crate) fn parse_number(text: &[u8]) -> Result<Num, NumError> {
    let mut i = 0;
    let neg = match text.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    let mut mant: u64 = 0;
    let mut truncated = false;
    let mut exp10: i32 = 0;
    let int_start = i;
    while i < text.len() && text[i].is_ascii_digit() {
        if mant < 100_000_000_000_000_000 {
            mant = mant * 10 + u64::from(text[i] - b'0');
        } else {
            truncated = true;
        }
        i += 1;
    }
    let mut digits = i - int_start;
    let mut int_form = true;
    if i < text.len() && text[i] == b'.' {
        int_form = false;
        i += 1;
        let frac_start = i;
        while i < text.len() && text[i].is_ascii_digit() {
            if mant < 100_000_000_000_000_000 {
                mant = mant * 10 + u64::from(text[i] - b'0');
                exp10 -= 1;
            } else {
                truncated = true;
            }
            i += 1;
        }
        digits += i - frac_start;
    }
    if digits == 0 {
        return Err(NumError::Malformed);
    }
    if i < text.len() && (text[i] == b'e' || text[i] == b'E') {
        int_form = false;
        i += 1;
        let eneg = match text.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let exp_start = i;
        let mut e: i32 = 0;
        while i < text.len() && text[i].is_ascii_digit() {
            e = (e * 10 + i32::from(text[i] - b'0')).min(100_000);
            i += 1;
        }
        if i == exp_start {
            return Err(NumError::Malformed);
        }
        exp10 += if eneg { -e } else { e };
    }
    if i != text.len() {
        return Err(NumError::Malformed);
    }
    if int_form && !truncated {
        let limit = if neg { 1u64 << 31 } else { (1u64 << 31) - 1 };
        let f = if neg { -(mant as f32) } else { mant as f32 };
        let i = (mant <= limit)
            .then(|| if neg { (mant as i64).wrapping_neg() as i32 } else { mant as i32 });
        return Ok(Num { f, i, int_form: true });
    }
    let f = if !truncated && mant <= 1 << 24 && (-10..=10).contains(&exp10) {
        let m = mant as f32;
        let v = if exp10 >= 0 { m * POW10[exp10 as usize] } else { m / POW10[(-exp10) as usize] };
        if neg { -v } else { v }
    } else {
        let s = std::str::from_utf8(text).map_err(|_| NumError::Malformed)?;
        s.parse::<f32>().map_err(|_| NumError::Malformed)?
    };
    if !f.is_finite() {
        return Err(NumError::OutOfRange);
    }
    Ok(Num { f, i: None, int_form })
}

/// Message for a number where an integer was required.
pub(crate) fn not_an_int(n: Num) -> String {
    if n.int_form {
        format!("integer {} is out of range", n.f)
    } else {
        format!("expected an integer, got {}", n.f)
    }
}
