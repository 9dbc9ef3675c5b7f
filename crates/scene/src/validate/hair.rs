//! The rules of curves, points and blobbies: counts of control points and primitive
//! variables by storage class, widths, and the blobby code stream.
//!
//! Invariant: no check can panic; counts are summed in `usize` from `u32` values.

use super::primitives::{Check, each, fail, finite_all, finite_each, positive};
use crate::blobby::Program;
use crate::curves::{self, CurveSpan};
use crate::model::{Basis, CurveType, Primvar, Rgb, Shape};

/// The counts of each storage class: `(uniform, varying, vertex)`.
type Counts = (usize, usize, usize);

/// `var` has as many values as its class asks under `counts`.
fn count<T>(path: &str, var: &Primvar<T>, (uniform, varying, vertex): Counts) -> Check {
    let (want, what) = match var {
        Primvar::Constant(_) => return Ok(()),
        Primvar::Uniform(_) => (uniform, "uniform"),
        Primvar::Varying(_) => (varying, "varying"),
        Primvar::Vertex(_) => (vertex, "vertex"),
    };
    let got = var.values().len();
    if got != want {
        return fail(path, format!("{what} values: expected {want}, got {got}"));
    }
    Ok(())
}

fn widths(path: &str, width: &Primvar<f32>, counts: Counts) -> Check {
    count(path, width, counts)?;
    let values = width.values();
    let at = |i: usize| match width {
        Primvar::Constant(_) => path.to_string(),
        _ => format!("{path}[{i}]"),
    };
    for (i, &w) in values.iter().enumerate() {
        if !(w.is_finite() && w > 0.0) {
            positive(&at(i), w)?;
        }
    }
    Ok(())
}

fn vectors(path: &str, var: &Primvar<[f32; 3]>, counts: Counts) -> Check {
    count(path, var, counts)?;
    match var {
        Primvar::Constant(v) => finite_all(path, v),
        _ => finite_each(path, var.values()),
    }
}

fn colours(path: &str, var: &Option<Primvar<Rgb>>, counts: Counts, opacity: bool) -> Check {
    let Some(var) = var else { return Ok(()) };
    vectors(path, var, counts)?;
    if opacity {
        let check = |p: &str, v: f32| {
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                fail(p, format!("must be in [0, 1], got {v}"))
            }
        };
        for (i, c) in var.values().iter().enumerate() {
            let p = match var {
                Primvar::Constant(_) => path.to_string(),
                _ => format!("{path}[{i}]"),
            };
            each(&p, c, check)?;
        }
    }
    Ok(())
}

/// A `Curves` shape.
pub(super) fn curves(at: &str, shape: &Shape) -> Check {
    let Shape::Curves {
        kind,
        wrap,
        nvertices,
        points,
        basis,
        step,
        width,
        normals,
        colors,
        opacities,
    } = shape
    else {
        return Ok(());
    };
    let field = |name: &str| format!("{at}.{name}");
    if *kind == CurveType::Cubic {
        if let Basis::Matrix(m) = basis {
            for (r, row) in m.iter().enumerate() {
                finite_all(&format!("{at}.basis[{r}]"), row)?;
            }
        }
        match curves::step(*kind, basis, *step) {
            0 if step.is_none() => {
                return fail(field("step"), "a matrix basis has no standard step: give one");
            }
            0 => return fail(field("step"), "must be at least 1, got 0"),
            _ => {}
        }
    }
    if nvertices.is_empty() {
        return fail(field("nvertices"), "must hold at least one curve");
    }
    let spans: Vec<CurveSpan> = curves::spans(shape)
        .map_err(|(c, why)| super::Issue { path: format!("{at}.nvertices[{c}]"), message: why })?;
    let (uniform, varying, vertex) = curves::primvar_counts(&spans, *wrap);
    if points.len() != vertex {
        return fail(
            field("points"),
            format!("expected {vertex} points (the sum of nvertices), got {}", points.len()),
        );
    }
    finite_each(&field("points"), points)?;
    let counts = (uniform, varying, vertex);
    widths(&field("width"), width, counts)?;
    if let Some(n) = normals {
        vectors(&field("normals"), n, counts)?;
    }
    colours(&field("colors"), colors, counts, false)?;
    colours(&field("opacities"), opacities, counts, true)?;
    Ok(())
}

/// A `Points` shape.
pub(super) fn points(at: &str, shape: &Shape) -> Check {
    let Shape::Points { points, width, colors, opacities } = shape else { return Ok(()) };
    let field = |name: &str| format!("{at}.{name}");
    if points.is_empty() {
        return fail(field("points"), "must hold at least one point");
    }
    finite_each(&field("points"), points)?;
    let counts = (1, points.len(), points.len());
    widths(&field("width"), width, counts)?;
    colours(&field("colors"), colors, counts, false)?;
    colours(&field("opacities"), opacities, counts, true)
}

/// A `Blobby` shape: its code stream, floats and per-field values.
pub(super) fn blobby(at: &str, shape: &Shape) -> Check {
    let Shape::Blobby { code, floats, strings, colors, opacities } = shape else {
        return Ok(());
    };
    finite_all(&format!("{at}.floats"), floats)?;
    let program = Program::parse(code, floats, strings).map_err(|e| super::Issue {
        path: format!("{at}.{}[{}]", e.array, e.index),
        message: e.message,
    })?;
    let leaves = program.leaf_count();
    let counts = (1, leaves, leaves);
    colours(&format!("{at}.colors"), colors, counts, false)?;
    colours(&format!("{at}.opacities"), opacities, counts, true)
}
