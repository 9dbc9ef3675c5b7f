//! The two permutations of the renderer, named by what they mean.
//!
//! - [`bit_reversal`]: the order in which spatial strata are paired with sample indices (and
//!   so with time and lens strata), Appendix A's `permute`: "bit reversal, but mapped back
//!   onto 0-n". [`bit_reversal_original`] is the function as printed, kept for study and
//!   behind `hider.original.permute`.
//! - [`keyed`]: a pseudo-random permutation of `0..n` chosen by a 64-bit key, which
//!   scrambles the cells of a stratified set per set and per dimension ([`crate::Strata`]).
//!
//! Invariant: [`bit_reversal`] and [`keyed`] are bijections on `0..n` for every `n >= 1`.

/// Port of the original `permute(i, n)` as printed (reading `j = a + 1 - j`, appendix-a.md 2.11).
/// It is *not* a permutation for n in {12, 14, 20, 21, 24, 25, ...} (3.4); kept for study and
/// behind `Original::permute`. Results may fall outside `0..n`; callers must check.
pub fn bit_reversal_original(i: u32, n: u32) -> i64 {
    let mut i = i as i64;
    let n = n as i64;
    let mut j: i64 = 0;
    let mut b: i64 = 1;
    while b + b < n {
        b += b;
    }
    let mut a: i64 = 1;
    while b >= 1 {
        if i - b >= 0 {
            i -= b;
            j += a;
        }
        a += a;
        b /= 2;
    }
    if j >= n {
        j = a + 1 - j;
    }
    j
}

/// Bit-reversal order restricted to `0..n`: the `i`-th value of the sequence
/// `bitrev_k(0), bitrev_k(1), ...` (k = bits of the smallest power of two >= n) with the
/// values `>= n` skipped. For n a power of two this is plain k-bit reversal, the same as the
/// original; for other n it keeps the original's intent (successive indices land far apart)
/// and is a true permutation.
pub fn bit_reversal(i: u32, n: u32) -> u32 {
    assert!(i < n, "bit_reversal({i}, {n}) out of range");
    let k = n.next_power_of_two().trailing_zeros();
    let mut seen = 0;
    for q in 0..(1u32 << k) {
        let r = if k == 0 { 0 } else { q.reverse_bits() >> (32 - k) };
        if r < n {
            if seen == i {
                return r;
            }
            seen += 1;
        }
    }
    unreachable!("bit reversal is a bijection on 0..2^k, which contains 0..n")
}

/// Appendix A's `Location` (from `tablesinit`): for each sample `s` of an `nx x ny` pixel,
/// the lower-left corner `(x/nx, y/ny)` of the spatial stratum it is paired with. The strata
/// are enumerated x-major (`q = x * ny + y`) and stratum `q` goes to sample
/// [`bit_reversal`]`(q, nx * ny)`, or with `original` to [`bit_reversal_original`], which is
/// not a permutation for every grid: a sample it assigns no stratum keeps `(0, 0)` (the C left
/// it uninitialised). The hider's sample tables and the filter check of validation both take
/// the locations from here, so the filter table validation evaluates is the one rendered.
pub fn stratum_locations(nx: u32, ny: u32, original: bool) -> Vec<[f32; 2]> {
    let ns = nx * ny;
    let (fx, fy) = (nx as f32, ny as f32);
    let mut location = vec![[0.0f32; 2]; ns as usize];
    let mut q = 0;
    for x in 0..nx {
        for y in 0..ny {
            let t =
                if original { bit_reversal_original(q, ns) } else { bit_reversal(q, ns) as i64 };
            if (0..ns as i64).contains(&t) {
                location[t as usize] = [x as f32 / fx, y as f32 / fy];
            }
            q += 1;
        }
    }
    location
}

/// Position of `i` in a pseudo-random permutation of `0..n` keyed by `key`: a bijection
/// of the smallest power-of-two range holding `n`, walked until it lands below `n`
/// (cycle walking, so the restriction stays a bijection).
pub fn keyed(i: u32, n: u32, key: u64) -> u32 {
    debug_assert!(i < n);
    if n <= 1 {
        return 0;
    }
    let mask = u32::MAX >> (n - 1).leading_zeros();
    let (k0, k1) = (key as u32, (key >> 32) as u32);
    let shift = (32 - mask.leading_zeros()).div_ceil(2).max(1);
    let mut x = i;
    loop {
        // Each step is a bijection of 0..=mask: xor with a key, xorshift right, multiply
        // by an odd number, add; all taken modulo mask + 1.
        x ^= k0 & mask;
        x ^= x >> shift;
        x = x.wrapping_mul(k1 | 1) & mask;
        x = x.wrapping_add(k0 >> 7) & mask;
        x ^= x >> shift;
        x = x.wrapping_mul(0x2c1b_3c6d) & mask;
        if x < n {
            return x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bit_reversal_is_a_permutation_for_every_n_to_256() {
        for n in 1..=256 {
            let mut hit = vec![false; n as usize];
            for i in 0..n {
                let j = bit_reversal(i, n) as usize;
                assert!(!hit[j], "n = {n}: {j} twice");
                hit[j] = true;
            }
        }
    }

    #[test]
    fn bit_reversal_equals_original_for_powers_of_two() {
        for k in 0..8 {
            let n = 1 << k;
            for i in 0..n {
                assert_eq!(bit_reversal(i, n) as i64, bit_reversal_original(i, n), "n = {n}");
            }
        }
    }

    #[test]
    fn original_is_not_a_permutation_where_appendix_a_says() {
        let is_perm = |n: u32| {
            let mut hit = vec![false; n as usize];
            (0..n).all(|i| {
                let j = bit_reversal_original(i, n);
                (0..n as i64).contains(&j) && !std::mem::replace(&mut hit[j as usize], true)
            })
        };
        for n in [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 15, 16, 18, 32, 64] {
            assert!(is_perm(n), "n = {n} should be a permutation");
        }
        for n in [12, 14, 20, 21, 24, 25, 28, 30, 35, 36, 40, 42, 48, 49, 56] {
            assert!(!is_perm(n), "n = {n} should not be a permutation");
        }
    }

    #[test]
    fn default_grid_pairing_matches_appendix_a_table() {
        // 3.3: for 4x4, stratum q = x*4 + y goes to sample bit_reversal(q); sample s has
        // x = bitrev2(s mod 4), y = bitrev2(s div 4).
        let mut loc = [(0, 0); 16];
        for x in 0..4 {
            for y in 0..4 {
                loc[bit_reversal(x * 4 + y, 16) as usize] = (x, y);
            }
        }
        let xs: Vec<u32> = loc.iter().map(|l| l.0).collect();
        let ys: Vec<u32> = loc.iter().map(|l| l.1).collect();
        assert_eq!(xs, [0, 2, 1, 3, 0, 2, 1, 3, 0, 2, 1, 3, 0, 2, 1, 3]);
        assert_eq!(ys, [0, 0, 0, 0, 2, 2, 2, 2, 1, 1, 1, 1, 3, 3, 3, 3]);
    }

    #[test]
    fn keyed_is_a_permutation() {
        for n in [1, 2, 3, 5, 16, 17, 64, 100, 1000] {
            for key in [0, 1, 0xdead_beef_1234_5678] {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let p = keyed(i, n, key);
                    assert!(!seen[p as usize], "n {n} key {key}: {p} twice");
                    seen[p as usize] = true;
                }
            }
        }
    }
}
