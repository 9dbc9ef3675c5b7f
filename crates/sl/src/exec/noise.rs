//! Noise, written for this project: gradient noise on the integer lattice in 1 to 4
//! dimensions. Each lattice corner gets a pseudo-random gradient (components uniform in
//! [-1, 1] in steps of 1/127.5, 8-bit fields of an integer hash of the corner); the value is the sum over the cell's corners
//! of each gradient dotted with the offset to the corner, blended by the quintic
//! `6t^5 - 15t^4 + 10t^3` (so the result and its first two derivatives are continuous). It is
//! 0 at every lattice point and symmetric about 0 (a gradient and its negation are equally
//! likely), so `0.5 + 0.5 * clamp(1.5 n, -1, 1)` lies in [0, 1] with mean 0.5. The periodic
//! form wraps the lattice coordinates modulo the (rounded) period before hashing. `cellnoise`
//! hashes the cell; colours, points and vectors take three values with distinct seeds.

/// Mixes 32 bits (multiply by odd constants, fold the high bits down).
pub fn mix(mut x: u32) -> u32 {
    x = x.wrapping_add(0x6a09_e667);
    x ^= x >> 15;
    x = x.wrapping_mul(0x9e37_79b1);
    x ^= x >> 13;
    x = x.wrapping_mul(0xc2b2_ae3d);
    x ^= x >> 16;
    x
}

fn hash_cell(cell: &[i32], seed: u32) -> u32 {
    let mut h = mix(seed.wrapping_mul(0x2545_f491));
    for &c in cell {
        h = mix(h ^ (c as u32));
    }
    h
}

fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// Signed gradient noise at `x` (1 to 4 coordinates), periodic in each coordinate whose
/// `period` is at least 1.
pub fn gradient(x: &[f32], period: Option<&[f32]>, seed: u32) -> f32 {
    let d = x.len().min(4);
    let mut base = [0i32; 4];
    let mut frac = [0.0f32; 4];
    let mut per = [0i32; 4];
    for k in 0..d {
        let f = x[k].floor();
        // Far from the origin the lattice coordinate saturates (no overflow, no panic).
        base[k] = f.clamp(-1.0e9, 1.0e9) as i32;
        frac[k] = if x[k].is_finite() { x[k] - f } else { 0.0 };
        per[k] = period.and_then(|p| p.get(k)).map_or(0, |p| p.round().clamp(0.0, 1.0e9) as i32);
    }
    let mut fades = [0.0f32; 4];
    for k in 0..d {
        fades[k] = fade(frac[k]);
    }
    let mut sum = 0.0;
    for corner in 0..(1u32 << d) {
        let mut cell = [0i32; 4];
        let mut weight = 1.0;
        let mut offs = [0.0f32; 4];
        for k in 0..d {
            let bit = ((corner >> k) & 1) as i32;
            let mut c = base[k].wrapping_add(bit);
            if per[k] >= 1 {
                c = c.rem_euclid(per[k]);
            }
            cell[k] = c;
            offs[k] = frac[k] - bit as f32;
            weight *= if bit == 1 { fades[k] } else { 1.0 - fades[k] };
        }
        let h = hash_cell(&cell[..d], seed);
        let mut dotp = 0.0;
        // Gradient components: 8-bit fields of one hash, each mapped onto [-1, 1] (a field
        // and its complement give opposite components, so the noise is symmetric about 0).
        for (k, off) in offs.iter().take(d).enumerate() {
            let g = ((h >> (8 * k)) & 0xff) as f32 / 127.5 - 1.0;
            dotp += g * off;
        }
        sum += weight * dotp;
    }
    if sum.is_finite() { sum } else { 0.0 }
}

/// `noise`/`pnoise` in [0, 1].
pub fn noise01(x: &[f32], period: Option<&[f32]>, seed: u32) -> f32 {
    0.5 + 0.5 * (1.5 * gradient(x, period, seed)).clamp(-1.0, 1.0)
}

/// `cellnoise` in [0, 1): constant on each unit cell.
pub fn cellnoise(x: &[f32], seed: u32) -> f32 {
    let mut cell = [0i32; 4];
    let d = x.len().min(4);
    for k in 0..d {
        cell[k] = x[k].floor().clamp(-1.0e9, 1.0e9) as i32;
    }
    (hash_cell(&cell[..d], seed.wrapping_add(77)) >> 8) as f32 / (1u32 << 24) as f32
}

/// A uniform random number in [0, 1) from a 64-bit state.
pub fn random01(state: u64) -> f32 {
    let h = mix((state as u32) ^ mix((state >> 32) as u32));
    (h >> 8) as f32 / (1u32 << 24) as f32
}
