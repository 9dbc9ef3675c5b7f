//! `SubdivisionMesh "catmull-clark"` (Spec 3.2, 5.5; the tags as PRMan defines them) as the
//! model's [`Shape::SubdivisionMesh`].
//!
//! The request is `SubdivisionMesh scheme nvertices vertices [tags nargs intargs floatargs]`.
//! Each tag takes `nargs[2 i]` integers and `nargs[2 i + 1]` floats from the running
//! positions of `intargs` and `floatargs` (PRMan's three counts per tag, the third for string
//! arguments, are accepted when every string count is 0). The tags:
//!
//! | tag | integers | floats | model |
//! |---|---|---|---|
//! | `interpolateboundary` | none, or one: 0 off, 1 on, 2 edges only | none | `InterpolateBoundary` (2 also keeps the boundary's valence-2 corners sharp, with a warning) |
//! | `crease` | a chain of 2 or more points | one sharpness, or one per edge | one `Crease` per run of equal sharpness |
//! | `corner` | points | one sharpness, or one per point | one `Corner` per sharpness |
//! | `hole` | faces | none | `Hole` |
//!
//! Other tags of PRMan (`facevaryinginterpolateboundary`, `creasemethod`, `smoothtriangles`,
//! ...) are skipped with a warning. Primitive variables: `P` (or `Pw`); `Cs` of class
//! `vertex` or `varying` as the shape's colours (`constant` is the material colour, as for
//! polygons); `st` of class `facevarying` or `facevertex` as the shape's facevarying `st`,
//! and of class `vertex` or `varying` gathered to the face corners (so interpolated
//! bilinearly over each control face rather than subdivided with the points, with a
//! warning). Everything the model checks (indices in range, a manifold and consistently
//! oriented mesh, crease chains along edges) is left to scene validation, which reports it
//! at this request.

use reyes_scene::{Rgb, Shape, SubdivTag};

use super::geometry::{self, Counts, PolyMesh};
use crate::{Class, Request, RibError, Warning};

/// The model shape of a `SubdivisionMesh` request; `None` (with a warning) for a scheme
/// other than Catmull-Clark.
pub(crate) fn shape(r: &Request, warnings: &mut Vec<Warning>) -> Result<Option<Shape>, RibError> {
    let scheme = r.string(0).unwrap_or("");
    if scheme != "catmull-clark" {
        warnings.push(r.warning(format!(
            "scheme \"{scheme}\" is not supported (only \"catmull-clark\"): skipped"
        )));
        return Ok(None);
    }
    let nvertices = r.ints(1).unwrap_or(&[]);
    let mesh = geometry::poly_mesh(r, None, nvertices, Some(r.ints(2).unwrap_or(&[])))?;
    let tags = tags(r, warnings)?;
    let counts = Counts {
        uniform: mesh.faces.len(),
        vertex: mesh.points.len(),
        facevarying: corners(&mesh),
    };
    let colors = colors(r, counts, warnings)?;
    let st = st(r, &mesh, counts, warnings)?;
    geometry::unused_primvars(r, &["P", "Pw", "Cs", "st"], warnings);
    let PolyMesh { points, faces, .. } = mesh;
    Ok(Some(Shape::SubdivisionMesh { points, faces, tags, colors, st }))
}

fn corners(mesh: &PolyMesh) -> usize {
    mesh.faces.indices().len()
}

/// The per-point colours of a vertex or varying `Cs` (constant `Cs` is the material's).
fn colors(
    r: &Request,
    counts: Counts,
    warnings: &mut Vec<Warning>,
) -> Result<Option<Vec<Rgb>>, RibError> {
    let Some(p) = r.param("Cs") else { return Ok(None) };
    let (class, v) = geometry::groups(r, p, 3, counts)?;
    Ok(match class {
        Class::Vertex | Class::Varying => {
            Some(v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
        }
        Class::Constant => None,
        Class::Uniform | Class::FaceVarying | Class::FaceVertex => {
            warnings.push(Warning {
                at: r.param_location(p),
                message: format!(
                    "SubdivisionMesh: \"Cs\" of class {} is not supported (vertex or varying only): ignored",
                    class.name()
                ),
            });
            None
        }
    })
}

/// The facevarying texture coordinates of `st`.
fn st(
    r: &Request,
    mesh: &PolyMesh,
    counts: Counts,
    warnings: &mut Vec<Warning>,
) -> Result<Option<Vec<[f32; 2]>>, RibError> {
    let Some(p) = r.param("st") else { return Ok(None) };
    let (class, v) = geometry::groups(r, p, 2, counts)?;
    let pairs: Vec<[f32; 2]> = v.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    let warn = |what: &str, warnings: &mut Vec<Warning>| {
        warnings.push(Warning {
            at: r.param_location(p),
            message: format!("SubdivisionMesh: \"st\" of class {}: {what}", class.name()),
        });
    };
    Ok(match class {
        Class::FaceVarying | Class::FaceVertex => Some(pairs),
        Class::Vertex | Class::Varying => {
            warn("interpolated bilinearly over each control face, not subdivided", warnings);
            Some(mesh.faces.indices().iter().map(|&k| pairs[k as usize]).collect())
        }
        Class::Constant | Class::Uniform => {
            warn("not supported (facevarying, vertex or varying only): ignored", warnings);
            None
        }
    })
}

/// Reads `count` entries from `values` at `*at`, or names what is missing.
fn take<'a, T>(
    r: &Request,
    values: &'a [T],
    at: &mut usize,
    count: usize,
    what: &str,
    tag: &str,
) -> Result<&'a [T], RibError> {
    let end = at.saturating_add(count);
    let got = values.get(*at..end).ok_or_else(|| {
        r.error(format!("{tag}: asks for {what} {}..{end}, but it has {}", *at, values.len()))
    })?;
    *at = end;
    Ok(got)
}

/// The sharpness at `i` of `floats`: one value for all, or one per item.
fn sharpness(r: &Request, floats: &[f32], i: usize, tag: &str) -> Result<f32, RibError> {
    let s = if floats.len() == 1 { floats[0] } else { floats[i] };
    if s.is_nan() || s < 0.0 {
        return Err(r.error(format!("{tag}: sharpness must be a number >= 0, got {s}")));
    }
    Ok(s)
}

/// The model's tags of the request's `tags nargs intargs floatargs`.
fn tags(r: &Request, warnings: &mut Vec<Warning>) -> Result<Vec<SubdivTag>, RibError> {
    let names = r.strings(3).unwrap_or(&[]);
    let nargs = r.ints(4).unwrap_or(&[]);
    let ints = r.ints(5).unwrap_or(&[]);
    let floats = r.floats(6).unwrap_or(&[]);
    let per = if nargs.len() == 2 * names.len() {
        2
    } else if nargs.len() == 3 * names.len() {
        if let Some(k) = (0..names.len()).find(|&k| nargs[3 * k + 2] != 0) {
            return Err(
                r.error(format!("tag {k} (\"{}\"): string arguments are not supported", names[k]))
            );
        }
        3
    } else {
        return Err(r.error(format!(
            "nargs has {} entries for {} tags: expected 2 per tag (integers, floats)",
            nargs.len(),
            names.len()
        )));
    };
    let index = |k: usize, v: i32, what: &str| -> Result<u32, RibError> {
        u32::try_from(v)
            .map_err(|_| r.error(format!("tag {k} (\"{}\"): {what} {v} is negative", names[k])))
    };
    let (mut ai, mut af) = (0usize, 0usize);
    let mut out = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let label = format!("tag {k} (\"{name}\")");
        let tag = label.as_str();
        let (ni, nf) = (nargs[per * k], nargs[per * k + 1]);
        let count = |n: i32| {
            usize::try_from(n)
                .map_err(|_| r.error(format!("tag {k} (\"{name}\"): nargs entry {n} is negative")))
        };
        let (ni, nf) = (count(ni)?, count(nf)?);
        let iv = take(r, ints, &mut ai, ni, "intargs", tag)?;
        let fv = take(r, floats, &mut af, nf, "floatargs", tag)?;
        let bad = |what: &str| r.error(format!("{tag}: {what}"));
        match name.as_str() {
            "interpolateboundary" => match iv {
                [] | [1] => out.push(SubdivTag::InterpolateBoundary),
                [0] => {}
                [2] => {
                    warnings.push(r.warning(
                        "interpolateboundary 2 (edges only) also keeps the boundary's corners sharp",
                    ));
                    out.push(SubdivTag::InterpolateBoundary);
                }
                _ => return Err(bad("takes no integer or one of 0, 1, 2")),
            },
            "crease" => {
                if iv.len() < 2 || !(fv.len() == 1 || fv.len() == iv.len() - 1) {
                    return Err(bad(
                        "takes a chain of 2 or more points and one sharpness, or one per edge",
                    ));
                }
                let chain: Vec<u32> =
                    iv.iter().map(|&v| index(k, v, "point")).collect::<Result<_, _>>()?;
                // One crease per run of edges of equal sharpness.
                let mut start = 0;
                for e in 0..chain.len() - 1 {
                    let s = sharpness(r, fv, e, tag)?;
                    let last = e + 2 == chain.len();
                    if last || sharpness(r, fv, e + 1, tag)? != s {
                        out.push(SubdivTag::Crease {
                            vertices: chain[start..e + 2].to_vec(),
                            sharpness: s,
                        });
                        start = e + 1;
                    }
                }
            }
            "corner" => {
                if iv.is_empty() || !(fv.len() == 1 || fv.len() == iv.len()) {
                    return Err(bad("takes points and one sharpness, or one per point"));
                }
                for (i, &v) in iv.iter().enumerate() {
                    let (v, s) = (index(k, v, "point")?, sharpness(r, fv, i, tag)?);
                    match out.last_mut() {
                        Some(SubdivTag::Corner { vertices, sharpness })
                            if i > 0 && *sharpness == s =>
                        {
                            vertices.push(v);
                        }
                        _ => out.push(SubdivTag::Corner { vertices: vec![v], sharpness: s }),
                    }
                }
            }
            "hole" => {
                if !fv.is_empty() {
                    return Err(bad("takes faces and no floats"));
                }
                let faces = iv.iter().map(|&v| index(k, v, "face")).collect::<Result<_, _>>()?;
                out.push(SubdivTag::Hole { faces });
            }
            other => warnings.push(r.warning(format!("tag \"{other}\" is not supported: ignored"))),
        }
    }
    Ok(out)
}
