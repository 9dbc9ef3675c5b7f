//! Vector helpers and the Specification's geometric formulas (15.2).

/// A triple.
pub type V3 = [f32; 3];

/// `a . b`.
pub fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a ^ b`.
pub fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `length(a)`.
pub fn length(a: V3) -> f32 {
    dot(a, a).sqrt()
}

/// `normalize(a)`: a zero vector stays zero (no NaN).
pub fn normalize(a: V3) -> V3 {
    let l = length(a);
    if l > 0.0 { scale(a, 1.0 / l) } else { a }
}

/// `a * k`.
pub fn scale(a: V3, k: f32) -> V3 {
    a.map(|x| x * k)
}

/// `a + b`.
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `faceforward(n, i, nref)`: `n` flipped to face against `i` (by the sign of `-i . nref`).
pub fn faceforward(n: V3, i: V3, nref: V3) -> V3 {
    if dot(i, nref) > 0.0 { scale(n, -1.0) } else { n }
}

/// `reflect(i, n)`: `i - 2 (i . n) n`.
pub fn reflect(i: V3, n: V3) -> V3 {
    sub(i, scale(n, 2.0 * dot(i, n)))
}

/// `refract(i, n, eta)`: the refracted direction by Snell's law (`i`, `n` unit), zero on
/// total internal reflection.
pub fn refract(i: V3, n: V3, eta: f32) -> V3 {
    let idn = dot(i, n);
    let k = 1.0 - eta * eta * (1.0 - idn * idn);
    if k < 0.0 { [0.0; 3] } else { sub(scale(i, eta), scale(n, eta * idn + k.sqrt())) }
}

/// `fresnel(i, n, eta, Kr, Kt, R, T)`: the unpolarised Fresnel reflectance of a dielectric
/// (the average of the s and p terms), `Kt = 1 - Kr`, `R` the reflected and `T` the refracted
/// direction. `i` and `n` are normalised here; `n` faces against `i`.
pub fn fresnel(i: V3, n: V3, eta: f32) -> (f32, f32, V3, V3) {
    let i = normalize(i);
    let n = normalize(n);
    let r = reflect(i, n);
    let t = refract(i, n, eta);
    let cos_i = (-dot(i, n)).clamp(-1.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return (1.0, 0.0, r, t);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let ci = cos_i.abs();
    // eta = n1 / n2.
    let rs = (eta * ci - cos_t) / (eta * ci + cos_t);
    let rp = (ci - eta * cos_t) / (ci + eta * cos_t);
    let kr = (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0);
    (kr, 1.0 - kr, r, t)
}

/// `ptlined(a, b, p)`: the distance from `p` to the segment `ab`.
pub fn ptlined(a: V3, b: V3, p: V3) -> f32 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let t = if l2 > 0.0 { (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0) } else { 0.0 };
    length(sub(p, add(a, scale(ab, t))))
}

/// Rotation matrix (row-vector convention) by `angle` radians about the axis `axis`.
pub fn rotation(angle: f32, axis: V3) -> [f32; 16] {
    let [x, y, z] = normalize(axis);
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    // Column-vector rotation R; row vectors use its transpose.
    let r = [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ];
    let mut m = super::space::IDENTITY;
    for (i, row) in r.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            m[j * 4 + i] = *v;
        }
    }
    m
}
