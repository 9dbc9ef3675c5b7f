//! The modern sampler: an Owen-scrambled Sobol (0,2) sequence, scrambled by hashing
//! (Burley 2020, "Practical hash-based Owen scrambling"), one independent scramble per pixel
//! and per dimension pair (position, lens) and a scrambled van der Corput (0,1) sequence for
//! time.
//!
//! Why it stratifies: the first two Sobol dimensions (van der Corput, and the Pascal-matrix
//! dimension) form a (0,2)-sequence in base 2, so every aligned block of `2^m` consecutive
//! points is a (0,m,2)-net: each elementary interval `[i/2^a, (i+1)/2^a) x [j/2^b, (j+1)/2^b)`
//! with `a + b = m` holds exactly one point. In particular, when the pixel has `nx x ny` strata
//! with `nx = 2^a`, `ny = 2^b`, each stratum holds exactly one of the pixel's `NS = 2^m`
//! points, so every point can be given to the sample index whose stratum contains it.
//!
//! Owen (nested uniform) scrambling flips digit `k` of a coordinate by a random function of
//! the digits before it; it maps elementary intervals onto elementary intervals of the same
//! shape, so it keeps the net property while making each point uniformly distributed.
//! The hash below does this on bit-reversed integers: every bit of the result depends only on
//! the same and lower bits of the input (additions, multiplications, and `x ^= x * even`).
//! The same scramble applied to the point *index* maps aligned blocks of `2^m` indices onto
//! aligned blocks, so prefixes of the shuffled sequence stay nets (the progressive property).

use reyes_sampling::hash;

/// Base-2 Owen scrambling of a bit-reversed integer: bit `k` of the result depends only on
/// bits `0..=k` of `x` and on `seed`, and the map is a bijection. The Laine-Karras hash
/// improved by N. Vegdahl (2021), as used in Burley's scheme.
#[inline]
pub fn reversed_owen(mut x: u32, seed: u32) -> u32 {
    x ^= x.wrapping_mul(0x3d20_adea);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6c56);
    x ^= x.wrapping_mul(0x53a2_2864);
    x
}

/// Nested uniform (Owen) scrambling of a 32-digit binary fraction `x / 2^32`: digit `k`
/// (bit `31 - k`) is flipped by a hash of the digits before it.
#[inline]
pub fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    reversed_owen(x.reverse_bits(), seed).reverse_bits()
}

/// Sobol dimension 1 (the second): the Pascal generator matrix mod 2, as a 32-bit fraction.
#[inline]
pub fn sobol_dim1(mut i: u32) -> u32 {
    let mut v: u32 = 1 << 31;
    let mut x = 0;
    while i != 0 {
        if i & 1 != 0 {
            x ^= v;
        }
        i >>= 1;
        v ^= v >> 1;
    }
    x
}

/// The first two Sobol dimensions of point `i`, unscrambled, as 32-bit fractions: van der
/// Corput (bit reversal) and [`sobol_dim1`].
#[inline]
pub fn sobol_2d(i: u32) -> [u32; 2] {
    [i.reverse_bits(), sobol_dim1(i)]
}

/// Seeds of one scrambled (0,2) or (0,1) sequence: one for the index shuffle, one per
/// coordinate. Derived by hashing, so independent sequences need only different keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Scramble {
    index: u32,
    x: u32,
    y: u32,
}

impl Scramble {
    /// The scramble for `seed` and the integers `key` (e.g. dimension and global pixel).
    pub fn new(seed: u64, key: &[u64]) -> Scramble {
        let h = hash(seed, key);
        let h2 = hash(h, &[0x0e5c]);
        Scramble { index: h as u32, x: (h >> 32) as u32, y: h2 as u32 }
    }

    /// Point `i` of the Owen-scrambled, index-shuffled Sobol (0,2) sequence, as 32-bit
    /// fractions. For any `m`, points `0..2^m` form a (0,m,2)-net.
    #[inline]
    pub fn point_2d(&self, i: u32) -> [u32; 2] {
        let [x, y] = sobol_2d(nested_uniform_scramble(i, self.index));
        [nested_uniform_scramble(x, self.x), nested_uniform_scramble(y, self.y)]
    }

    /// Point `i` of the Owen-scrambled, index-shuffled van der Corput (0,1) sequence: for any
    /// `m`, points `0..2^m` put one point in each interval `[k/2^m, (k+1)/2^m)`.
    #[inline]
    pub fn point_1d(&self, i: u32) -> u32 {
        nested_uniform_scramble(nested_uniform_scramble(i, self.index).reverse_bits(), self.x)
    }
}

/// Generator matrix of a Sobol dimension as its 32 direction numbers (`v[c]` is column `c`,
/// a 32-bit fraction, for bit `c` of the index), built from the primitive polynomial of
/// degree `s` with inner coefficients `a` (Joe and Kuo's encoding) and initial odd numbers
/// `m`: the recurrence `m_i = 2 a_1 m_{i-1} ^ 4 a_2 m_{i-2} ^ ... ^ 2^s m_{i-s} ^ m_{i-s}`.
/// Every such matrix is upper triangular with a unit diagonal, so each dimension alone is a
/// (0,1)-sequence.
const fn directions(s: usize, a: u32, m: &[u32]) -> [u32; 32] {
    let mut mm = [0u64; 33];
    let mut i = 1;
    while i <= s {
        mm[i] = m[i - 1] as u64;
        i += 1;
    }
    while i <= 32 {
        let mut v = mm[i - s] ^ (mm[i - s] << s);
        let mut k = 1;
        while k < s {
            if (a >> (s - 1 - k)) & 1 == 1 {
                v ^= mm[i - k] << k;
            }
            k += 1;
        }
        mm[i] = v;
        i += 1;
    }
    let mut out = [0u32; 32];
    let mut c = 0;
    while c < 32 {
        // m_i / 2^i as a 32-bit fraction (m_i < 2^i).
        out[c] = ((mm[c + 1] << (31 - c)) & 0xffff_ffff) as u32;
        c += 1;
    }
    out
}

/// Sobol dimension 2 (the third): polynomial `x^2 + x + 1`, `m = 1, 3` (Joe and Kuo 2008,
/// the table every Sobol implementation shares).
pub const SOBOL_DIM2: [u32; 32] = directions(2, 1, &[1, 3]);
/// Sobol dimension 3 (the fourth): polynomial `x^3 + x + 1`, `m = 1, 3, 1`.
pub const SOBOL_DIM3: [u32; 32] = directions(3, 1, &[1, 3, 1]);
/// Sobol dimension 4 (the fifth): polynomial `x^3 + x^2 + 1`, `m = 1, 1, 1`.
pub const SOBOL_DIM4: [u32; 32] = directions(3, 2, &[1, 1, 1]);

/// Point `i` of the Sobol dimension with direction numbers `v`, as a 32-bit fraction.
#[inline]
pub fn sobol_dim(v: &[u32; 32], mut i: u32) -> u32 {
    let mut x = 0;
    let mut c = 0;
    while i != 0 {
        if i & 1 != 0 {
            x ^= v[c];
        }
        i >>= 1;
        c += 1;
    }
    x
}

/// One point of the joint sampler, as 32-bit fractions: position, time and lens.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JointPoint {
    /// Sobol dimensions 0 and 1: a (0,2)-sequence.
    pub xy: [u32; 2],
    /// Sobol dimension 2: with `xy`, the first three dimensions of one Sobol sequence.
    pub t: u32,
    /// Lens: Sobol dimensions 3 and 4. Each is a (0,1)-sequence, but the pair is not a
    /// (0,2)-sequence: a block need not put one point in every lens cell (for 4 x 4 cells it
    /// does not), so the sampler re-ranks `v` within each column of cells
    /// (`BucketSamples::generate`). Tried and measured worse on the defocused edge: the
    /// (0,2) pair of dimensions 0-1 at an index map of dimension 2 or 3 (a (0,2)-net, but
    /// correlated with the position digits: up to 2.9 times the error of a shuffled pairing
    /// at 256 samples).
    pub lens: [u32; 2],
    /// `lens[1]` before its scramble ([`JointScramble::scramble_lens_v`] gives it back), for
    /// re-ranking in the unscrambled digits.
    pub lens_v_raw: u32,
}

/// The scrambles of the joint sampler for one pixel: one index shuffle shared by every
/// dimension (so the dimensions stay one sequence) and one nested uniform scramble per
/// coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JointScramble {
    index: u32,
    coord: [u32; 5],
}

impl JointScramble {
    /// The scramble for `seed` and the integers `key` (e.g. the global pixel).
    pub fn new(seed: u64, key: &[u64]) -> JointScramble {
        let h = hash(seed, key);
        let h2 = hash(h, &[0x0e5c]);
        let h3 = hash(h, &[0x0e5d]);
        JointScramble {
            index: h as u32,
            coord: [(h >> 32) as u32, h2 as u32, (h2 >> 32) as u32, h3 as u32, (h3 >> 32) as u32],
        }
    }

    /// Points `0..2^m` of [`JointScramble::point`], into `out`, the same values computed
    /// faster: the shuffled indices of the block share their bits above `m`, and every Sobol
    /// dimension is linear over XOR, so that shared part is evaluated once and each point
    /// only over its low `m` bits.
    pub fn block(&self, m: u32, out: &mut Vec<JointPoint>) {
        out.clear();
        let low = ((1u64 << m) - 1) as u32;
        let high = nested_uniform_scramble(0, self.index) & !low;
        let dims = |j: u32| {
            [
                j.reverse_bits(),
                sobol_dim1(j),
                sobol_dim(&SOBOL_DIM2, j),
                sobol_dim(&SOBOL_DIM3, j),
                sobol_dim(&SOBOL_DIM4, j),
            ]
        };
        let base = dims(high);
        let c = &self.coord;
        for i in 0..=low {
            let j = nested_uniform_scramble(i, self.index);
            debug_assert_eq!(j & !low, high);
            let d = dims(j & low);
            let v = |k: usize| nested_uniform_scramble(base[k] ^ d[k], c[k]);
            let lens_v_raw = base[4] ^ d[4];
            out.push(JointPoint { xy: [v(0), v(1)], t: v(2), lens: [v(3), v(4)], lens_v_raw });
        }
    }

    /// Point `i` of the scrambled joint sequence. For any `m`, points `0..2^m` have `xy` a
    /// (0,m,2)-net, `(xy, t)` a (1,m,3)-net, and each of `t`, `lens[0]` and `lens[1]` one
    /// point in each `[k/2^m, (k+1)/2^m)`.
    #[inline]
    pub fn point(&self, i: u32) -> JointPoint {
        let j = nested_uniform_scramble(i, self.index);
        let [x, y] = sobol_2d(j);
        let t = sobol_dim(&SOBOL_DIM2, j);
        let (u, v) = (sobol_dim(&SOBOL_DIM3, j), sobol_dim(&SOBOL_DIM4, j));
        let c = &self.coord;
        JointPoint {
            xy: [nested_uniform_scramble(x, c[0]), nested_uniform_scramble(y, c[1])],
            t: nested_uniform_scramble(t, c[2]),
            lens: [nested_uniform_scramble(u, c[3]), nested_uniform_scramble(v, c[4])],
            lens_v_raw: v,
        }
    }

    /// The scramble of the lens's `v` (`lens[1]` of a point is this of its `lens_v_raw`).
    #[inline]
    pub fn scramble_lens_v(&self, v: u32) -> u32 {
        nested_uniform_scramble(v, self.coord[4])
    }
}

/// A 32-bit fraction as an `f32` in `[0, 1)`, keeping its leading 24 bits exactly, so the
/// stratum read from the float (`floor(u * 2^a)` for `a <= 24`) is the one read from the bits.
#[inline]
pub fn to_unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// A 32-bit fraction as an `f32` in `(0, 1)` on a grid of `2^-16` (the centre of its cell):
/// adding it to a pixel coordinate below 128 is exact, so a sample never rounds across a
/// stratum or pixel boundary.
#[inline]
pub fn to_unit_16(x: u32) -> f32 {
    ((x >> 16) as f32 + 0.5) * (1.0 / 65_536.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every elementary interval of area 2^-m holds exactly one of `pts`.
    fn is_02_net(pts: &[[u32; 2]], m: u32) -> bool {
        (0..=m).all(|a| {
            let b = m - a;
            let mut seen = vec![false; 1 << m];
            pts.iter().all(|p| {
                let cx = if a == 0 { 0 } else { p[0] >> (32 - a) };
                let cy = if b == 0 { 0 } else { p[1] >> (32 - b) };
                let c = ((cx << b) | cy) as usize;
                !std::mem::replace(&mut seen[c], true)
            })
        })
    }

    #[test]
    fn unscrambled_sobol_is_a_02_sequence() {
        for m in 0..=10 {
            for block in 0..4u32 {
                let pts: Vec<_> = (0..1u32 << m).map(|i| sobol_2d((block << m) + i)).collect();
                assert!(is_02_net(&pts, m), "m {m} block {block}");
            }
        }
    }

    #[test]
    fn scrambling_is_a_bijection_that_keeps_leading_digits_together() {
        // Points sharing their first k digits still share them after scrambling.
        for seed in [0u32, 1, 0xdead_beef] {
            let mut out: Vec<u32> =
                (0..1u32 << 12).map(|i| nested_uniform_scramble(i << 20, seed)).collect();
            for w in out.chunks(1 << 4) {
                assert!(w.iter().all(|&v| v >> 24 == w[0] >> 24));
            }
            out.sort();
            out.dedup();
            assert_eq!(out.len(), 1 << 12);
        }
    }

    #[test]
    fn scrambled_prefixes_are_nets() {
        for seed in 0..20u64 {
            let sc = Scramble::new(seed, &[7, seed * 3]);
            let pts: Vec<_> = (0..1024).map(|i| sc.point_2d(i)).collect();
            for m in 0..=10 {
                assert!(is_02_net(&pts[..1 << m], m), "seed {seed} m {m}");
            }
            let ts: Vec<u32> = (0..256).map(|i| sc.point_1d(i)).collect();
            for m in 0..=8u32 {
                let mut seen = vec![false; 1 << m];
                for &t in &ts[..1 << m] {
                    let k = if m == 0 { 0 } else { (t >> (32 - m)) as usize };
                    assert!(!std::mem::replace(&mut seen[k], true), "seed {seed} m {m}");
                }
            }
        }
    }

    #[test]
    fn float_conversion_keeps_the_stratum() {
        for x in [0u32, 1, 0x7fff_ffff, 0x8000_0000, u32::MAX, 0x1234_5678] {
            let u = to_unit(x);
            assert!((0.0..1.0).contains(&u));
            assert_eq!((u * 256.0) as u32, x >> 24);
            let v = to_unit_16(x);
            assert!(v > 0.0 && v < 1.0);
            assert_eq!((v * 256.0) as u32, x >> 24);
        }
    }

    #[test]
    fn direction_numbers_give_the_published_points() {
        // Sobol dimension 2 (Joe-Kuo d = 3): 0, 1/2, 3/4, 1/4, 3/8, 7/8, 5/8, 1/8.
        let want = [0.0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125];
        for (i, w) in want.iter().enumerate() {
            assert_eq!(sobol_dim(&SOBOL_DIM2, i as u32) as f64 / 4_294_967_296.0, *w);
        }
        // The Pascal dimension from the same recurrence is `sobol_dim1`.
        let pascal = directions(1, 0, &[1]);
        for i in 0..4096 {
            assert_eq!(sobol_dim(&pascal, i), sobol_dim1(i));
        }
    }

    #[test]
    fn a_block_is_its_points() {
        for seed in 0..8u64 {
            let sc = JointScramble::new(seed, &[seed, 1]);
            let mut out = Vec::new();
            for m in 0..=10u32 {
                sc.block(m, &mut out);
                assert_eq!(out.len(), 1 << m);
                for (i, p) in out.iter().enumerate() {
                    assert_eq!(*p, sc.point(i as u32), "seed {seed} m {m} point {i}");
                }
            }
        }
    }

    #[test]
    fn joint_prefixes_are_nets_in_every_dimension_group() {
        for seed in 0..12u64 {
            let sc = JointScramble::new(seed, &[3, seed]);
            let pts: Vec<_> = (0..1024).map(|i| sc.point(i)).collect();
            for m in 0..=10u32 {
                let block = &pts[..1 << m];
                let xy: Vec<_> = block.iter().map(|p| p.xy).collect();
                assert!(is_02_net(&xy, m), "seed {seed} m {m}: positions");
                let dims: [fn(&JointPoint) -> u32; 3] = [|p| p.t, |p| p.lens[0], |p| p.lens[1]];
                for (d, get) in dims.iter().enumerate() {
                    let mut seen = vec![false; 1 << m];
                    for p in block {
                        let k = if m == 0 { 0 } else { (get(p) >> (32 - m)) as usize };
                        assert!(
                            !std::mem::replace(&mut seen[k], true),
                            "seed {seed} m {m} dim {d}"
                        );
                    }
                }
            }
        }
    }

    /// The (x, y, t) points of a block of `2^m`: every elementary box of volume `2^(1-m)`
    /// holds exactly 2 points, i.e. a (1,m,3)-net, the quality of the first three Sobol
    /// dimensions (a (1,3)-sequence), which the scrambles keep.
    #[test]
    fn position_and_time_together_are_a_1_m_3_net() {
        for seed in 0..6u64 {
            let sc = JointScramble::new(seed, &[9]);
            for m in 1..=9u32 {
                let pts: Vec<_> = (0..1u32 << m).map(|i| sc.point(i)).collect();
                let k = m - 1;
                for a in 0..=k {
                    for b in 0..=k - a {
                        let c = k - a - b;
                        let mut count = vec![0u8; 1 << k];
                        let lead = |x: u32, d: u32| if d == 0 { 0 } else { x >> (32 - d) };
                        for p in &pts {
                            let cell = (lead(p.xy[0], a) << (b + c))
                                | (lead(p.xy[1], b) << c)
                                | lead(p.t, c);
                            count[cell as usize] += 1;
                        }
                        assert!(count.iter().all(|&n| n == 2), "seed {seed} m {m} ({a},{b},{c})");
                    }
                }
            }
        }
    }
}
