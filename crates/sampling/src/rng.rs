//! Deterministic pseudo-random numbers: the SplitMix64 mix, a hash for values that must
//! depend only on their inputs (bucket, pixel, sample, dimension), and SplitMix64 streams,
//! of which Appendix A's `drand()` is one.
//!
//! Invariant: nothing here has global state; the same seed gives the same numbers on every
//! thread and in every bucket order.

/// The golden-ratio increment of SplitMix64 (`2^64 / phi`, odd).
pub const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hash of a seed and a few integers.
#[inline]
pub fn hash(seed: u64, parts: &[u64]) -> u64 {
    let mut h = mix64(seed ^ GOLDEN);
    for &p in parts {
        h = mix64(h ^ p.wrapping_mul(GOLDEN));
    }
    h
}

/// A uniform f32 in [0, 1) from the top 24 bits of `x`.
#[inline]
pub fn unit(x: u64) -> f32 {
    (x >> 40) as f32 * (1.0 / 16_777_216.0)
}

/// A uniform f64 in [0, 1) from the top 53 bits of `x`.
#[inline]
pub fn unit_f64(x: u64) -> f64 {
    (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A SplitMix64 stream: the state advances by [`GOLDEN`] and each output is the state
/// [`mix64`]ed.
#[derive(Debug, Clone)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The stream whose state starts at `state` (the first output mixes `state + GOLDEN`).
    pub fn from_state(state: u64) -> SplitMix64 {
        SplitMix64 { state }
    }

    /// The output of the stream at `state` taken alone: `mix64(state + GOLDEN)`, the first
    /// number of [`SplitMix64::from_state`]`(state)`, for counter-based draws.
    #[inline]
    pub fn at(state: u64) -> u64 {
        mix64(state.wrapping_add(GOLDEN))
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN);
        mix64(self.state)
    }

    /// The next number in [0, 1), with 24 bits.
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        unit(self.next_u64())
    }

    /// The next number in [0, 1), with 53 bits.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        unit_f64(self.next_u64())
    }
}

/// Appendix A's `drand()`: a stream of uniform numbers in [0, 1), from a seed (the
/// SplitMix64 stream starting at the seed's mix).
#[derive(Debug, Clone)]
pub struct Drand {
    stream: SplitMix64,
}

impl Drand {
    /// A stream for `seed`.
    pub fn new(seed: u64) -> Drand {
        Drand { stream: SplitMix64::from_state(mix64(seed)) }
    }

    /// Next number in [0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        self.stream.next_f32()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drand_is_uniform_in_unit_interval() {
        let mut d = Drand::new(7);
        let n = 100_000;
        let mut bins = [0u32; 10];
        for _ in 0..n {
            let x = d.next_f32();
            assert!((0.0..1.0).contains(&x));
            bins[(x * 10.0) as usize] += 1;
        }
        // Each bin is Binomial(n, 0.1): sd = sqrt(n * 0.1 * 0.9) ~ 95; allow 5 sd.
        for b in bins {
            assert!((b as f64 - 10_000.0).abs() < 5.0 * 95.0, "{bins:?}");
        }
    }

    #[test]
    fn the_stream_is_splitmix64() {
        // The published first outputs of SplitMix64 seeded with 1234567.
        let mut s = SplitMix64::from_state(1_234_567);
        assert_eq!(s.next_u64(), 6_457_827_717_110_365_317);
        assert_eq!(s.next_u64(), 3_203_168_211_198_807_973);
        assert_eq!(SplitMix64::at(1_234_567), 6_457_827_717_110_365_317);
    }

    #[test]
    fn floats_lie_in_the_unit_interval() {
        for x in [0, 1, u64::MAX, 1 << 63] {
            assert!((0.0..1.0).contains(&unit(x)));
            assert!((0.0..1.0).contains(&unit_f64(x)));
        }
    }
}
