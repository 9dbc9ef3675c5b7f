//! `Curves`, `Points` and `Blobby` (RI Spec 3.2, 5.5 and 5.6) as the scene model's shapes,
//! with their primitive variables `P`, `width`, `constantwidth`, `N`, `Cs` and `Os` of every
//! storage class.
//!
//! Invariants: every count is checked against the request's arrays before anything is
//! indexed, each fault one error at the argument or parameter at fault (`file:line:col`);
//! curves take the current `Basis`'s v basis and step, as the Specification says; a blobby's
//! code stream is read by the scene crate's reader, whose fault names the code index.

use reyes_scene::blobby::Program;
use reyes_scene::curves::{self, CurveSpan};
use reyes_scene::{CurveType, Primvar, Shape, Wrap};

use super::frame::Machine;
use super::geometry;
use crate::{Class, Param, Request, RibError};

/// Values per storage class: `(uniform, varying, vertex)`.
type Counts = (usize, usize, usize);

/// A primitive variable of `n` floats per value, as the model's [`Primvar`] of its class,
/// each value made by `make` from its `n` floats. Facevarying counts as varying (a curve's
/// face-vertices are its segment ends).
fn primvar<T>(
    r: &Request,
    p: &Param,
    n: usize,
    (uniform, varying, vertex): Counts,
    make: impl Fn(&[f32]) -> T,
) -> Result<Primvar<T>, RibError> {
    let values = p.floats().ok_or_else(|| r.param_error(p, "must hold numbers"))?;
    let class = p.decl.as_ref().map_or(Class::Vertex, |d| d.class);
    let (want, name) = match class {
        Class::Constant => (1, "constant"),
        Class::Uniform => (uniform, "uniform"),
        Class::Varying | Class::FaceVarying => (varying, "varying"),
        Class::Vertex | Class::FaceVertex => (vertex, "vertex"),
    };
    if values.len() != want * n {
        return Err(r.param_error(
            p,
            format!(
                "{name} values: expected {want} of {n} number{} ({} numbers), got {} numbers",
                if n == 1 { "" } else { "s" },
                want * n,
                values.len()
            ),
        ));
    }
    let items: Vec<T> = values.chunks_exact(n).map(make).collect();
    Ok(match class {
        Class::Constant => Primvar::Constant(
            items.into_iter().next().ok_or_else(|| r.param_error(p, "a constant needs a value"))?,
        ),
        Class::Uniform => Primvar::Uniform(items),
        Class::Varying | Class::FaceVarying => Primvar::Varying(items),
        Class::Vertex | Class::FaceVertex => Primvar::Vertex(items),
    })
}

fn rgb(c: &[f32]) -> [f32; 3] {
    [c[0], c[1], c[2]]
}

/// The width of curves or points: `width` (any class) or `constantwidth`; 1 without either.
fn width(r: &Request, counts: Counts) -> Result<Primvar<f32>, RibError> {
    if let Some(p) = r.param("width") {
        return primvar(r, p, 1, counts, |c| c[0]);
    }
    if let Some(p) = r.param("constantwidth") {
        let v = p.floats().unwrap_or(&[]);
        return match v {
            [w] => Ok(Primvar::Constant(*w)),
            _ => Err(r.param_error(p, format!("is one number, got {}", v.len()))),
        };
    }
    Ok(Primvar::Constant(1.0))
}

/// `Cs` (unless constant, which the material takes) and `Os` of a primitive.
type Colours = (Option<Primvar<[f32; 3]>>, Option<Primvar<[f32; 3]>>);

fn colours(r: &Request, counts: Counts) -> Result<Colours, RibError> {
    let var = |name: &str, constant_to_material: bool| -> Result<_, RibError> {
        let Some(p) = r.param(name) else { return Ok(None) };
        let constant = p.decl.as_ref().is_some_and(|d| d.class == Class::Constant);
        if constant && constant_to_material {
            return Ok(None);
        }
        primvar(r, p, 3, counts, rgb).map(Some)
    };
    Ok((var("Cs", true)?, var("Os", false)?))
}

impl Machine {
    /// `Curves type [nvertices] wrap ...`.
    pub(super) fn curves(&mut self, r: &Request) -> Result<Shape, RibError> {
        let kind = match r.string(0).unwrap_or_default() {
            "linear" => CurveType::Linear,
            "cubic" => CurveType::Cubic,
            other => {
                return Err(
                    r.error(format!("type must be \"linear\" or \"cubic\", got \"{other}\""))
                );
            }
        };
        let wrap = match r.string(2).unwrap_or_default() {
            "nonperiodic" => Wrap::Nonperiodic,
            "periodic" => Wrap::Periodic,
            other => {
                return Err(r.error(format!(
                    "wrap must be \"periodic\" or \"nonperiodic\", got \"{other}\""
                )));
            }
        };
        let nvertices = r.ints(1).unwrap_or(&[]);
        if nvertices.is_empty() {
            return Err(r.error("nvertices must list at least one curve"));
        }
        let (_, _, vbasis, vstep) = self.attributes.basis;
        let step = curves::step(kind, &vbasis, Some(vstep));
        let mut spans: Vec<CurveSpan> = Vec::with_capacity(nvertices.len());
        let (mut first, mut first_varying) = (0, 0);
        for (c, &n) in nvertices.iter().enumerate() {
            let count = u32::try_from(n).map_err(|_| r.error(format!("nvertices[{c}] is {n}")))?;
            let segments = curves::segment_count(kind, wrap, count, step)
                .map_err(|e| r.error(format!("nvertices[{c}]: {e}")))?;
            spans.push(CurveSpan {
                first,
                points: count as usize,
                segments: segments as usize,
                first_varying,
            });
            first += count as usize;
            first_varying += curves::varying_count(wrap, segments) as usize;
        }
        let counts = curves::primvar_counts(&spans, wrap);
        let points = geometry::positions(r, counts.2)?;
        let width = width(r, counts)?;
        let normals = match r.param("N") {
            Some(p) => Some(primvar(r, p, 3, counts, rgb)?),
            None => None,
        };
        let (colors, opacities) = colours(r, counts)?;
        geometry::unused_primvars(
            r,
            &["P", "Pw", "width", "constantwidth", "N", "Cs", "Os"],
            &mut self.warnings,
        );
        Ok(Shape::Curves {
            kind,
            wrap,
            nvertices: nvertices.iter().map(|&n| n as u32).collect(),
            points,
            basis: vbasis,
            step: Some(vstep),
            width,
            normals,
            colors,
            opacities,
        })
    }

    /// `Points ...`: one disk per point of `P`.
    pub(super) fn points(&mut self, r: &Request) -> Result<Shape, RibError> {
        let p = r.param("P").ok_or_else(|| r.error("needs \"P\" positions"))?;
        let n = p.floats().map_or(0, <[f32]>::len) / 3;
        if n == 0 {
            return Err(r.param_error(p, "needs at least one point"));
        }
        let counts = (1, n, n);
        let points = geometry::positions(r, n)?;
        let width = width(r, counts)?;
        let (colors, opacities) = colours(r, counts)?;
        geometry::unused_primvars(
            r,
            &["P", "Pw", "width", "constantwidth", "Cs", "Os"],
            &mut self.warnings,
        );
        Ok(Shape::Points { points, width, colors, opacities })
    }

    /// `Blobby nleaf [code] [floats] [strings] ...`.
    pub(super) fn blobby(&mut self, r: &Request) -> Result<Shape, RibError> {
        let nleaf = r.int(0).unwrap_or(0);
        let code = r.ints(1).unwrap_or(&[]).to_vec();
        let floats = r.floats(2).unwrap_or(&[]).to_vec();
        let strings = r.strings(3).unwrap_or(&[]).to_vec();
        let program = Program::parse(&code, &floats, &strings)
            .map_err(|e| r.error(format!("{}[{}]: {}", e.array, e.index, e.message)))?;
        let leaves = program.leaf_count();
        if usize::try_from(nleaf).ok() != Some(leaves) {
            let w = r.warning(format!(
                "nleaf is {nleaf} but the code has {leaves} primitive fields: {leaves} is used"
            ));
            self.warnings.push(w);
        }
        if program.bound().is_none() {
            let w = r.warning(
                "no ellipsoid or segment field: the blobby has no bounded surface and is not drawn",
            );
            self.warnings.push(w);
        }
        if let Some(s) = strings.iter().find(|s| !s.is_empty()) {
            let w = r.warning(format!(
                "repelling ground plane depth map \"{s}\" is not read: the plane z = 0 of the primitive's space stands in for it"
            ));
            self.warn_once(format!("blobby depth map {s}"), w);
        }
        let (colors, opacities) = colours(r, (1, leaves, leaves))?;
        geometry::unused_primvars(r, &["Cs", "Os"], &mut self.warnings);
        Ok(Shape::Blobby { code, floats, strings, colors, opacities })
    }
}
