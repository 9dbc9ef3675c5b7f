//! Deterministic pseudo-random numbers: Appendix A's `drand()` as a seeded stream, and a hash
//! for values that must depend only on their inputs (bucket, pixel, sample, dimension).
//!
//! Invariant: nothing here has global state; the same seed gives the same numbers on every
//! thread and in every bucket order.

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
    let mut h = mix64(seed ^ 0x9e37_79b9_7f4a_7c15);
    for &p in parts {
        h = mix64(h ^ p.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    }
    h
}

/// A uniform f32 in [0, 1) from the top 24 bits of `x`.
#[inline]
pub fn unit(x: u64) -> f32 {
    (x >> 40) as f32 * (1.0 / 16_777_216.0)
}

/// Appendix A's `drand()`: a stream of uniform numbers in [0, 1), from a seed.
#[derive(Debug, Clone)]
pub struct Drand {
    state: u64,
}

impl Drand {
    /// A stream for `seed`.
    pub fn new(seed: u64) -> Drand {
        Drand { state: mix64(seed) }
    }

    /// Next number in [0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        self.state = self.state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        unit(mix64(self.state))
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
}
