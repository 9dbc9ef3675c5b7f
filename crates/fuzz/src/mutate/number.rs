//! The numbers a number mutation writes: extremes of every kind (zeros, denormals, the ends
//! of `f32`, `u32`, `i32` and `u64`, NaN and infinities, sizes just past a power of two), a
//! neighbour of the old value, or a random value, written so that both scene formats read
//! them back.

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

/// What to write in place of the number `old`: an extreme (half the time), a value near it,
/// or a random number of its kind (integer or not).
pub(super) fn replacement(rng: &mut Rng, old: &str) -> String {
    match rng.below(4) {
        0 | 1 => rng.pick(INTERESTING).to_string(),
        2 => nudge(rng, old),
        _ => random_number(rng, is_integer(old)),
    }
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
