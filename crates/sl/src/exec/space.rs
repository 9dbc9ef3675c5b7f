//! Coordinate systems and colour spaces.
//!
//! Matrices are 4x4, row by row, and act on row vectors as the Specification's do:
//! `p' = [x y z 1] M` (so `translate` fills the last row). The caller gives, for each named
//! space, the matrix taking a point in that space to "current" ([`Spaces`]). Colours are RGB
//! internally; `hsv`, `hsl`, `xyz` (CIE XYZ of linear Rec. 709 primaries, D65 white), `xyY`
//! and `YIQ` convert to and from it.

use std::collections::HashMap;

use crate::types::BaseType;

use super::value::{Mask, Num, map_n};
use super::{ExecError, GridContext};

/// A 4x4 matrix, row by row.
pub type Mat = [f32; 16];

/// The identity.
pub const IDENTITY: Mat = [1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.];

/// The named coordinate systems of a grid: each name's matrix from that space to "current".
/// "current" is the identity; "shader", "object", "world", "camera" not given are the identity
/// too (a test grid needs none); any other name not given is an error of the run.
#[derive(Debug, Clone, Default)]
pub struct Spaces {
    /// Name to the matrix taking that space's points to "current".
    pub to_current: HashMap<String, Mat>,
    /// The camera's near and far clipping distances: `depth(P)` is 0 at near and 1 at far
    /// (without them, `depth` is the camera-space z).
    pub clipping: Option<(f32, f32)>,
}

impl Spaces {
    /// Adds a space.
    pub fn with(mut self, name: &str, m: Mat) -> Spaces {
        self.to_current.insert(name.to_string(), m);
        self
    }

    /// The matrix from space `name` to "current".
    pub fn get(&self, name: &str) -> Option<Mat> {
        if let Some(m) = self.to_current.get(name) {
            return Some(*m);
        }
        matches!(name, "current" | "shader" | "object" | "world" | "camera" | "")
            .then_some(IDENTITY)
    }
}

/// `a * b`.
pub fn mat_mul(a: &Mat, b: &Mat) -> Mat {
    let mut o = [0.0; 16];
    for r in 0..4 {
        for c in 0..4 {
            o[r * 4 + c] = (0..4).map(|k| a[r * 4 + k] * b[k * 4 + c]).sum();
        }
    }
    o
}

/// The inverse by Gauss-Jordan elimination with partial pivoting; a singular matrix gives
/// non-finite entries (IEEE division by a zero pivot), never a panic.
pub fn mat_inverse(m: &Mat) -> Mat {
    let mut a = [[0.0f64; 8]; 4];
    for r in 0..4 {
        for c in 0..4 {
            a[r][c] = m[r * 4 + c] as f64;
        }
        a[r][4 + r] = 1.0;
    }
    for col in 0..4 {
        let p =
            (col..4).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).unwrap_or(col);
        a.swap(col, p);
        let d = a[col][col];
        for x in a[col].iter_mut() {
            *x /= d;
        }
        for r in 0..4 {
            if r != col {
                let f = a[r][col];
                if f != 0.0 {
                    let row = a[col];
                    for (x, y) in a[r].iter_mut().zip(row) {
                        *x -= f * y;
                    }
                }
            }
        }
    }
    let mut o = [0.0; 16];
    for r in 0..4 {
        for c in 0..4 {
            o[r * 4 + c] = a[r][4 + c] as f32;
        }
    }
    o
}

/// The transpose.
pub fn mat_transpose(m: &Mat) -> Mat {
    let mut o = [0.0; 16];
    for r in 0..4 {
        for c in 0..4 {
            o[c * 4 + r] = m[r * 4 + c];
        }
    }
    o
}

/// The determinant (by cofactors of the first row).
pub fn mat_det(m: &Mat) -> f32 {
    let a = |r: usize, c: usize| m[r * 4 + c] as f64;
    let det3 = |c0: usize, c1: usize, c2: usize| {
        a(1, c0) * (a(2, c1) * a(3, c2) - a(2, c2) * a(3, c1))
            - a(1, c1) * (a(2, c0) * a(3, c2) - a(2, c2) * a(3, c0))
            + a(1, c2) * (a(2, c0) * a(3, c1) - a(2, c1) * a(3, c0))
    };
    (a(0, 0) * det3(1, 2, 3) - a(0, 1) * det3(0, 2, 3) + a(0, 2) * det3(0, 1, 3)
        - a(0, 3) * det3(0, 1, 2)) as f32
}

/// A point through `m` (with the homogeneous divide).
pub fn xform_point(m: &Mat, p: [f32; 3]) -> [f32; 3] {
    let c = |j: usize| p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + m[12 + j];
    let w = c(3);
    let w = if w == 1.0 || w == 0.0 { 1.0 } else { w };
    [c(0) / w, c(1) / w, c(2) / w]
}

/// A vector through `m` (no translation).
pub fn xform_vector(m: &Mat, p: [f32; 3]) -> [f32; 3] {
    let c = |j: usize| p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j];
    [c(0), c(1), c(2)]
}

/// A normal through `m`: by the transposed inverse.
pub fn xform_normal(m: &Mat, p: [f32; 3]) -> [f32; 3] {
    xform_vector(&mat_transpose(&mat_inverse(m)), p)
}

fn mat3(m: [[f32; 3]; 3], c: [f32; 3]) -> [f32; 3] {
    [0, 1, 2].map(|r| m[r][0] * c[0] + m[r][1] * c[1] + m[r][2] * c[2])
}

fn mat3_inverse(m: [[f32; 3]; 3]) -> [[f32; 3]; 3] {
    let mut big = IDENTITY;
    for r in 0..3 {
        for c in 0..3 {
            big[r * 4 + c] = m[r][c];
        }
    }
    let i = mat_inverse(&big);
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| i[r * 4 + c]))
}

const RGB_TO_XYZ: [[f32; 3]; 3] =
    [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]];
const RGB_TO_YIQ: [[f32; 3]; 3] =
    [[0.299, 0.587, 0.114], [0.596, -0.274, -0.322], [0.211, -0.523, 0.312]];

fn hue_to_rgb(h: f32) -> [f32; 3] {
    let h = (h - h.floor()) * 6.0;
    [
        ((h - 3.0).abs() - 1.0).clamp(0.0, 1.0),
        (2.0 - (h - 2.0).abs()).clamp(0.0, 1.0),
        (2.0 - (h - 4.0).abs()).clamp(0.0, 1.0),
    ]
}

/// A colour in space `name` to RGB (`None`: an unknown colour space).
pub fn color_to_rgb(name: &str, c: [f32; 3]) -> Option<[f32; 3]> {
    Some(match name {
        "rgb" => c,
        "hsv" => {
            let [h, s, v] = c;
            hue_to_rgb(h).map(|x| v * (1.0 - s + s * x))
        }
        "hsl" => {
            let [h, s, l] = c;
            let chroma = (1.0 - (2.0 * l - 1.0).abs()) * s;
            hue_to_rgb(h).map(|x| l + chroma * (x - 0.5))
        }
        "xyz" | "XYZ" => mat3(mat3_inverse(RGB_TO_XYZ), c),
        "xyY" => {
            let [x, y, yy] = c;
            if y == 0.0 {
                [0.0; 3]
            } else {
                mat3(mat3_inverse(RGB_TO_XYZ), [x * yy / y, yy, (1.0 - x - y) * yy / y])
            }
        }
        "YIQ" | "yiq" => mat3(mat3_inverse(RGB_TO_YIQ), c),
        _ => return None,
    })
}

/// An RGB colour to space `name`.
pub fn rgb_to_color(name: &str, c: [f32; 3]) -> Option<[f32; 3]> {
    let [r, g, b] = c;
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let d = max - min;
    let hue = || {
        if d == 0.0 {
            0.0
        } else if max == r {
            ((g - b) / d / 6.0).rem_euclid(1.0)
        } else if max == g {
            ((b - r) / d + 2.0) / 6.0
        } else {
            ((r - g) / d + 4.0) / 6.0
        }
    };
    Some(match name {
        "rgb" => c,
        "hsv" => [hue(), if max == 0.0 { 0.0 } else { d / max }, max],
        "hsl" => {
            let l = (max + min) / 2.0;
            let s = if d == 0.0 { 0.0 } else { d / (1.0 - (2.0 * l - 1.0).abs()) };
            [hue(), s, l]
        }
        "xyz" | "XYZ" => mat3(RGB_TO_XYZ, c),
        "xyY" => {
            let [x, y, z] = mat3(RGB_TO_XYZ, c);
            let s = x + y + z;
            if s == 0.0 { [0.0; 3] } else { [x / s, y / s, y] }
        }
        "YIQ" | "yiq" => mat3(RGB_TO_YIQ, c),
        _ => return None,
    })
}

impl GridContext<'_> {
    pub(crate) fn space(&self, name: &str) -> Result<Mat, ExecError> {
        self.spaces
            .get(name)
            .ok_or_else(|| self.err_at(format!("unknown coordinate system \"{name}\"")))
    }

    /// A value of type `base` in space `name`, taken to "current" (colours: to RGB).
    pub(crate) fn in_space(
        &self,
        name: &str,
        base: BaseType,
        v: &Num,
        mask: &Mask,
    ) -> Result<Num, ExecError> {
        let n = self.n;
        if base == BaseType::Color {
            if color_to_rgb(name, [0.0; 3]).is_none() {
                return Err(self.err_at(format!("unknown colour space \"{name}\"")));
            }
            return Ok(map_n(n, mask, &[v], 3, |l, o| {
                let c = [l[0][0], l[0][1], l[0][2]];
                o.copy_from_slice(&color_to_rgb(name, c).unwrap_or(c));
            }));
        }
        let m = self.space(name)?;
        Ok(transform_num(base, &m, v, n, mask))
    }
}

/// A value of type `base` through matrix `m` (points, vectors, normals; matrices are
/// multiplied: `v * m`).
pub(crate) fn transform_num(base: BaseType, m: &Mat, v: &Num, n: usize, mask: &Mask) -> Num {
    let nm = if base == BaseType::Normal { mat_transpose(&mat_inverse(m)) } else { *m };
    match base {
        BaseType::Matrix => map_n(n, mask, &[v], 16, |l, o| {
            let x: Mat = l[0].try_into().unwrap_or(IDENTITY);
            o.copy_from_slice(&mat_mul(&x, m));
        }),
        b if b.is_spatial() => map_n(n, mask, &[v], 3, |l, o| {
            let p = [l[0][0], l[0][1], l[0][2]];
            let r = match b {
                BaseType::Point => xform_point(m, p),
                _ => xform_vector(&nm, p),
            };
            o.copy_from_slice(&r);
        }),
        _ => v.clone(),
    }
}
