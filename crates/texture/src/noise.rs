//! Gradient noise: Perlin's construction on the integer lattice of 3-space, with its
//! gradients chosen by a hash, and its sum over octaves.
//!
//! `noise(p)` = sum over the 8 lattice corners `c` of the cell holding `p` of
//! `w(c) * g(c) . (p - c)`, where `g(c)` is one of the 12 vectors to the midpoints of a
//! cube's edges (`(+-1, +-1, 0)` and its permutations), picked by
//! `reyes_sampling::hash(NOISE_SEED, [c.x, c.y, c.z]) % 12`, and `w(c)` is the product over
//! the axes of the quintic fade `6x^5 - 15x^4 + 10x^3` of `1 - |p - c|` along that axis.
//!
//! Invariants: a pure function of `p` (and so of nothing else: every render, thread and
//! platform with IEEE `f32` gives the same value); 0 at every lattice point; continuous with
//! continuous first derivatives; `|noise(p)| <= NOISE_BOUND`: the weights are non-negative
//! and sum to 1, and each `|g . d| <= |d_a| + |d_b| <= 2` for the two non-zero components of
//! `g`, as every `|d_k| <= 1` inside the cell.

use reyes_sampling::hash;

/// Seed of the lattice hash (the noise is one fixed function).
const NOISE_SEED: u64 = 0x006e_6f69_7365;

/// A bound on `|noise(p)|` for every `p` (see the module).
pub const NOISE_BOUND: f32 = 2.0;

const GRADIENTS: [[f32; 3]; 12] = [
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, -1.0, 1.0],
    [0.0, 1.0, -1.0],
    [0.0, -1.0, -1.0],
];

fn fade(x: f32) -> f32 {
    x * x * x * (x * (x * 6.0 - 15.0) + 10.0)
}

/// Gradient noise at `p` (see the module); 0 for a non-finite point.
pub fn noise(p: [f32; 3]) -> f32 {
    if !p.iter().all(|v| v.is_finite()) {
        return 0.0;
    }
    // Cells far from the origin: keep the lattice integers in range.
    let p = p.map(|v| f64::from(v).clamp(-1e12, 1e12));
    let cell = p.map(f64::floor);
    let d = [(p[0] - cell[0]) as f32, (p[1] - cell[1]) as f32, (p[2] - cell[2]) as f32];
    let c = cell.map(|v| v as i64);
    let mut sum = 0.0f32;
    for corner in 0..8u32 {
        let o = [corner & 1, (corner >> 1) & 1, (corner >> 2) & 1];
        let mut w = 1.0f32;
        let mut dot = 0.0f32;
        let h = hash(
            NOISE_SEED,
            &[
                (c[0] + i64::from(o[0])) as u64,
                (c[1] + i64::from(o[1])) as u64,
                (c[2] + i64::from(o[2])) as u64,
            ],
        );
        let g = GRADIENTS[(h % 12) as usize];
        for k in 0..3 {
            let dk = d[k] - o[k] as f32;
            w *= fade(1.0 - dk.abs());
            dot += g[k] * dk;
        }
        sum += w * dot;
    }
    sum
}

/// `octaves` octaves of [`noise`]: `sum_k 0.5^k noise(2^k p)`, for `k` in `0..octaves`;
/// `|fbm| <= NOISE_BOUND * (2 - 2^(1 - octaves))`, [`fbm_bound`].
pub fn fbm(p: [f32; 3], octaves: u32) -> f32 {
    let (mut sum, mut amp, mut freq) = (0.0f32, 1.0f32, 1.0f32);
    for _ in 0..octaves {
        sum += amp * noise(p.map(|v| v * freq));
        amp *= 0.5;
        freq *= 2.0;
    }
    sum
}

/// The bound of [`fbm`] with `octaves` octaves.
pub fn fbm_bound(octaves: u32) -> f32 {
    (0..octaves).map(|k| NOISE_BOUND * 0.5f32.powi(k as i32)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zero_on_the_lattice_bounded_and_continuous() {
        assert_eq!(noise([3.0, -2.0, 7.0]), 0.0);
        let mut max = 0.0f32;
        let mut prev = noise([0.0, 0.3, 0.7]);
        for k in 1..20_000 {
            let x = k as f32 * 0.001;
            let v = noise([x, 0.3 + 0.5 * x, 0.7 - 0.25 * x]);
            assert!(v.abs() <= NOISE_BOUND);
            // Lipschitz: the gradient is bounded, so steps of 0.001 change it by little.
            assert!((v - prev).abs() < 0.02, "jump at {x}: {prev} -> {v}");
            prev = v;
            max = max.max(v.abs());
        }
        assert!(max > 0.3, "the noise varies: max {max}");
        assert_eq!(fbm([0.2, 0.4, 0.6], 1), noise([0.2, 0.4, 0.6]));
        assert_eq!(fbm_bound(3), 2.0 + 1.0 + 0.5);
    }
}
