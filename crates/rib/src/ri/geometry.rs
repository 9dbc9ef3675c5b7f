//! Geometric primitives of RIB (Spec 3.2, 5) as the scene model's shapes: the quadrics,
//! polygons (convex, concave and with holes) and bilinear patches, with their primitive
//! variables `P` and `Cs` of every storage class.
//!
//! Invariants: a primitive's counts are checked against its parameter lengths before anything
//! is indexed, so a malformed primitive is an error naming the request and the parameter,
//! never a panic; polygons are split into the model's triangles and quads without adding
//! vertices, so neighbouring faces stay welded; when per-face or per-face-vertex colours ask
//! for it, vertices are duplicated per face (positions unchanged, so no crack opens).

use reyes_scene::{Faces, Rgb, Shape, V3};

use crate::{Class, Param, Request, RequestKind, RibError, Warning};

/// Where a primitive variable's values go: one per primitive, per face, per vertex, or per
/// face-vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Counts {
    /// Faces (1 for a single polygon or patch).
    pub uniform: usize,
    /// Vertices (`varying` and `vertex` count the same on polygons).
    pub vertex: usize,
    /// Face-vertices (the sum of the faces' vertex counts).
    pub facevarying: usize,
}

/// The number of values of `p` expected for its class under `counts`.
fn expected(class: Class, counts: Counts) -> usize {
    match class {
        Class::Constant => 1,
        Class::Uniform => counts.uniform,
        Class::Varying | Class::Vertex => counts.vertex,
        Class::FaceVarying | Class::FaceVertex => counts.facevarying,
    }
}

/// The values of a float-typed parameter in groups of `n`, checked against the counts of its
/// class; None if the primitive does not have it.
pub(crate) fn groups<'a>(
    r: &Request,
    p: &'a Param,
    n: usize,
    counts: Counts,
) -> Result<(Class, &'a [f32]), RibError> {
    let values = p.floats().ok_or_else(|| r.param_error(p, "must hold numbers"))?;
    let class = p.decl.as_ref().map(|d| d.class).unwrap_or(Class::Vertex);
    let want = expected(class, counts) * n;
    if values.len() != want {
        return Err(r.param_error(
            p,
            format!(
                "{} {} values for {} {}: expected {want}, got {}",
                class.name(),
                if n == 1 { "float".to_string() } else { format!("{n}-component") },
                expected(class, counts),
                match class {
                    Class::Constant => "primitive",
                    Class::Uniform => "faces",
                    Class::FaceVarying | Class::FaceVertex => "face-vertices",
                    _ => "vertices",
                },
                values.len()
            ),
        ));
    }
    Ok((class, values))
}

/// A polygon mesh in RIB's terms, before it becomes a model mesh.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PolyMesh {
    /// Vertex positions.
    pub points: Vec<V3>,
    /// Each face's outline: vertex indices.
    pub faces: Faces,
    /// The holes of the faces that have them: `(face, loops)`, in face order.
    pub holes: Vec<(usize, Vec<Vec<u32>>)>,
}

impl PolyMesh {
    /// The vertex count of every loop of every face (the face-vertices).
    fn corners(&self) -> usize {
        self.faces.indices().len()
            + self.holes.iter().flat_map(|(_, h)| h).map(Vec::len).sum::<usize>()
    }
}

/// The positions `P` (or `Pw`, divided through) of a primitive with `vertices` vertices.
pub(crate) fn positions(r: &Request, vertices: usize) -> Result<Vec<V3>, RibError> {
    let counts = Counts { uniform: 1, vertex: vertices, facevarying: vertices };
    if let Some(p) = r.param("P") {
        let (_, v) = groups(r, p, 3, counts)?;
        return Ok(v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect());
    }
    if let Some(p) = r.param("Pw") {
        let (_, v) = groups(r, p, 4, counts)?;
        return v
            .chunks_exact(4)
            .enumerate()
            .map(|(i, c)| {
                if c[3] == 0.0 || !c[3].is_finite() {
                    Err(r.param_error(p, format!("point {i} has weight {}", c[3])))
                } else {
                    Ok([c[0] / c[3], c[1] / c[3], c[2] / c[3]])
                }
            })
            .collect();
    }
    Err(r.error("needs \"P\" (or \"Pw\") positions"))
}

/// The mesh of `PointsGeneralPolygons` (and, with one loop per face, `PointsPolygons`;
/// with one face, `Polygon` and `GeneralPolygon`): `nloops` per face (`None`: one loop per
/// face, each face one entry of `nvertices`), `nvertices` per loop, `vertices` the indices
/// (`None`: `0, 1, 2, ...`). The faces are built flat, straight from the request's arrays.
pub(crate) fn poly_mesh(
    r: &Request,
    nloops: Option<&[i32]>,
    nvertices: &[i32],
    vertices: Option<&[i32]>,
) -> Result<PolyMesh, RibError> {
    let sum = |v: &[i32], what: &str| -> Result<usize, RibError> {
        let mut total = 0usize;
        for (i, &n) in v.iter().enumerate() {
            if n < 1 {
                return Err(r.error(format!("{what}[{i}] must be at least 1, got {n}")));
            }
            total = total.saturating_add(n as usize);
        }
        Ok(total)
    };
    let loops = match nloops {
        Some(nloops) => sum(nloops, "nloops")?,
        None => nvertices.len(),
    };
    if loops != nvertices.len() {
        return Err(r.error(format!(
            "nloops adds up to {loops} loops but nvertices has {} entries",
            nvertices.len()
        )));
    }
    for (i, &n) in nvertices.iter().enumerate() {
        if n < 3 {
            return Err(r.error(format!("nvertices[{i}] must be at least 3, got {n}")));
        }
    }
    let corners = sum(nvertices, "nvertices")?;
    if u32::try_from(corners).is_err() {
        return Err(r.error(format!(
            "nvertices adds up to {corners} vertices, more than a mesh holds ({})",
            u32::MAX
        )));
    }
    // The number of points the indices reach; every index checked before any is used.
    let npoints = match vertices {
        Some(v) => {
            if v.len() != corners {
                return Err(r.error(format!(
                    "nvertices adds up to {corners} vertices but vertices has {} entries",
                    v.len()
                )));
            }
            let mut max = None;
            for (i, &k) in v.iter().enumerate() {
                let k = u32::try_from(k)
                    .map_err(|_| r.error(format!("vertices[{i}] is negative ({k})")))?;
                max = max.max(Some(k));
            }
            max.map_or(0, |k| k as usize + 1)
        }
        None => corners,
    };
    let points = positions(r, npoints)?;
    // The loop of `n` vertices from face-vertex `k`: its (checked) indices, or `k, k + 1, ...`.
    let loop_at =
        |k: usize, n: usize| (k..k + n).map(move |j| vertices.map_or(j as u32, |v| v[j] as u32));
    let faces_count = nloops.map_or(nvertices.len(), <[i32]>::len);
    let mut faces = Faces::with_capacity(faces_count, corners);
    let mut holes = Vec::new();
    let (mut l, mut k) = (0usize, 0usize);
    for f in 0..faces_count {
        let nl = nloops.map_or(1, |nloops| nloops[f] as usize);
        let n = nvertices[l] as usize;
        faces.push_iter(loop_at(k, n));
        k += n;
        l += 1;
        if nl > 1 {
            let mut face_holes = Vec::with_capacity(nl - 1);
            for _ in 1..nl {
                let n = nvertices[l] as usize;
                face_holes.push(loop_at(k, n).collect());
                k += n;
                l += 1;
            }
            holes.push((f, face_holes));
        }
    }
    Ok(PolyMesh { points, faces, holes })
}

/// Colours `Cs` of a mesh, as the model needs them: one per vertex. Constant colours come
/// back as `(Some(c), None)` (a material colour); per-face and per-face-vertex colours unweld
/// the mesh (`mesh` is rewritten with one vertex per face-vertex).
pub(crate) fn mesh_colors(
    r: &Request,
    mesh: &mut PolyMesh,
) -> Result<(Option<Rgb>, Option<Vec<Rgb>>), RibError> {
    let Some(p) = r.param("Cs") else { return Ok((None, None)) };
    let counts = Counts {
        uniform: mesh.faces.len(),
        vertex: mesh.points.len(),
        facevarying: mesh.corners(),
    };
    let (class, v) = groups(r, p, 3, counts)?;
    let rgb: Vec<Rgb> = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    match class {
        Class::Constant => Ok((Some(rgb[0]), None)),
        Class::Varying | Class::Vertex => Ok((None, Some(rgb))),
        Class::Uniform | Class::FaceVarying | Class::FaceVertex => {
            // One vertex per face-vertex, so each face carries its own colours. Face-vertices
            // run face by face: a face's outline, then its holes.
            let mut points = Vec::with_capacity(counts.facevarying);
            let mut colors = Vec::with_capacity(counts.facevarying);
            let mut fv = 0usize;
            let mut holes = mesh.holes.iter_mut().peekable();
            for f in 0..mesh.faces.len() {
                let mut unweld = |lp: &mut [u32]| {
                    for k in lp {
                        points.push(mesh.points[*k as usize]);
                        colors.push(if class == Class::Uniform { rgb[f] } else { rgb[fv] });
                        *k = (points.len() - 1) as u32;
                        fv += 1;
                    }
                };
                unweld(&mut mesh.faces[f]);
                if holes.peek().is_some_and(|(hf, _)| *hf == f)
                    && let Some((_, h)) = holes.next()
                {
                    h.iter_mut().for_each(|lp| unweld(lp));
                }
            }
            mesh.points = points;
            Ok((None, Some(colors)))
        }
    }
}

/// Checks the counts of the standard primitive variables a polygon mesh may carry, whether or
/// not the model uses them yet, so a mismatched length is an error naming the parameter.
pub(crate) fn check_primvars(r: &Request, mesh: &PolyMesh) -> Result<(), RibError> {
    let counts = Counts {
        uniform: mesh.faces.len(),
        vertex: mesh.points.len(),
        facevarying: mesh.corners(),
    };
    for (name, n) in [("N", 3), ("Np", 3), ("Os", 3), ("st", 2), ("s", 1), ("t", 1)] {
        if let Some(p) = r.param(name) {
            groups(r, p, n, counts)?;
        }
    }
    Ok(())
}

/// The `vertex` or `varying` normals `N` and texture coordinates `st` of a polygon mesh, one
/// per point (the model's `Mesh` `normals` and `st`); `None` for either when absent or of
/// another class (left to [`unused_primvars`]'s warning). Counts are checked as
/// [`check_primvars`] checks them.
#[allow(clippy::type_complexity)]
pub(crate) fn vertex_normals_and_st(
    r: &Request,
    mesh: &PolyMesh,
) -> Result<(Option<Vec<[f32; 3]>>, Option<Vec<[f32; 2]>>), RibError> {
    let counts = Counts {
        uniform: mesh.faces.len(),
        vertex: mesh.points.len(),
        facevarying: mesh.corners(),
    };
    let per_point = |class: Class| matches!(class, Class::Vertex | Class::Varying);
    let normals = match r.param("N") {
        Some(p) => match groups(r, p, 3, counts)? {
            (class, v) if per_point(class) => {
                Some(v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
            }
            _ => None,
        },
        None => None,
    };
    let st = match r.param("st") {
        Some(p) => match groups(r, p, 2, counts)? {
            (class, v) if per_point(class) => {
                Some(v.chunks_exact(2).map(|c| [c[0], c[1]]).collect())
            }
            _ => None,
        },
        None => None,
    };
    Ok((normals, st))
}

/// What [`repair_normals`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum NormalRepair {
    /// Every normal was usable.
    Sound,
    /// `count` normals (the first at point `first`) were zero or not finite and were
    /// recomputed from the faces around their points.
    Recomputed { count: usize, first: usize },
    /// As above, but a point's faces have no area to take a normal from: the mesh's normals
    /// are to be dropped (it shades by its faces' own normals).
    Dropped { count: usize, first: usize },
}

/// True for a normal that cannot be normalised: zero, too short to square in single
/// precision, or not finite.
fn unusable(n: &[f32; 3]) -> bool {
    let l2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    !(l2.is_finite() && l2 >= f32::MIN_POSITIVE)
}

/// Replaces the unusable per-point normals of `mesh` (zero or not finite: exporters write
/// them at degenerate points) by the normal the geometry gives: the sum of the normals of
/// the faces around the point (on their outline or one of their holes), each weighted by
/// its area (Newell's method over the face's outline) and turned to agree with the usable
/// normals the face's other points carry. A
/// point on no face gets (0, 0, 1), which nothing reads. When the faces around a point have
/// no area, no normal can be taken from them: the result says the mesh's normals are to be
/// dropped.
pub(crate) fn repair_normals(mesh: &PolyMesh, normals: &mut [[f32; 3]]) -> NormalRepair {
    let bad: Vec<usize> = (0..normals.len()).filter(|&i| unusable(&normals[i])).collect();
    let (count, first) = match bad.first() {
        None => return NormalRepair::Sound,
        Some(&first) => (bad.len(), first),
    };
    let p = |k: u32| {
        let q = mesh.points[k as usize];
        [f64::from(q[0]), f64::from(q[1]), f64::from(q[2])]
    };
    let mut sums = vec![[0.0f64; 3]; normals.len()];
    let mut on_a_face = vec![false; normals.len()];
    let mut holes = mesh.holes.iter().peekable();
    for (f, face) in mesh.faces.iter().enumerate() {
        // The face's points: its outline's and its holes'.
        let face_holes = match holes.peek() {
            Some((hf, _)) if *hf == f => holes.next().map(|(_, h)| h.as_slice()).unwrap_or(&[]),
            _ => &[],
        };
        let around: Vec<u32> = face.iter().chain(face_holes.iter().flatten()).copied().collect();
        if !around.iter().any(|&k| unusable(&normals[k as usize])) {
            continue;
        }
        // Newell's normal: twice the face's area along its normal, in the winding's sense.
        let mut n = [0.0f64; 3];
        for (i, &k) in face.iter().enumerate() {
            let (a, b) = (p(k), p(face[(i + 1) % face.len()]));
            n[0] += (a[1] - b[1]) * (a[2] + b[2]);
            n[1] += (a[2] - b[2]) * (a[0] + b[0]);
            n[2] += (a[0] - b[0]) * (a[1] + b[1]);
        }
        let given: [f64; 3] = around
            .iter()
            .map(|&k| normals[k as usize])
            .filter(|g| !unusable(g))
            .fold([0.0; 3], |s, g| std::array::from_fn(|c| s[c] + f64::from(g[c])));
        let sense =
            if n[0] * given[0] + n[1] * given[1] + n[2] * given[2] < 0.0 { -1.0 } else { 1.0 };
        for &k in &around {
            let k = k as usize;
            on_a_face[k] = true;
            for c in 0..3 {
                sums[k][c] += sense * n[c];
            }
        }
    }
    for &i in &bad {
        if !on_a_face[i] {
            normals[i] = [0.0, 0.0, 1.0];
            continue;
        }
        let s = sums[i];
        let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        let n = s.map(|c| (c / len) as f32);
        if len == 0.0 || len.is_nan() || unusable(&n) {
            return NormalRepair::Dropped { count, first };
        }
        normals[i] = n;
    }
    NormalRepair::Recomputed { count, first }
}

/// True if the mesh's `Cs` is per face or per face-vertex, so [`mesh_colors`] unwelds its
/// points (and per-point `N` and `st` are dropped, with the warning of an unused variable).
pub(crate) fn colors_unweld(r: &Request) -> bool {
    r.param("Cs")
        .and_then(|p| p.decl.as_ref())
        .is_some_and(|d| matches!(d.class, Class::Uniform | Class::FaceVarying | Class::FaceVertex))
}

/// Warnings for the primitive variables of `r` that the model does not carry yet.
pub(crate) fn unused_primvars(r: &Request, used: &[&str], warnings: &mut Vec<Warning>) {
    for p in &r.params {
        if used.contains(&p.name.as_str()) {
            continue;
        }
        // Polygon requests use vertex or varying N and st in some cases; other primitives never.
        let polygons = matches!(
            r.kind,
            RequestKind::Polygon
                | RequestKind::GeneralPolygon
                | RequestKind::PointsPolygons
                | RequestKind::PointsGeneralPolygons
        );
        let what = match p.name.as_str() {
            "N" | "Np" if polygons => {
                "only vertex or varying N on a polygon mesh without per-face colours is used: faces shade by their own normals"
            }
            "N" | "Np" => "not used on this primitive: it shades by its own surface normals",
            "st" | "s" | "t" if polygons => {
                "only vertex or varying st on a polygon mesh without per-face colours is used: texture maps read the surface parameters (u, v)"
            }
            "st" | "s" | "t" => {
                "not used on this primitive: texture maps read the surface parameters (u, v)"
            }
            "Os" => "per-vertex opacity is not supported: the Opacity attribute is used",
            _ => "primitive variable ignored",
        };
        warnings.push(Warning {
            at: r.param_location(p),
            message: format!("{}: \"{}\": {what}", r.name(), p.name),
        });
    }
}

/// The model mesh of `mesh`: faces of 3 or 4 vertices. Convex faces of more vertices are
/// fanned into triangles from their first vertex; concave faces and faces with holes are
/// triangulated by ear clipping (holes bridged into the outline first). A mesh of triangles
/// and quads alone keeps its faces as they are.
pub(crate) fn to_model_mesh(
    r: &Request,
    mesh: PolyMesh,
    colors: Option<Vec<Rgb>>,
) -> Result<Shape, RibError> {
    let PolyMesh { points, faces, holes } = mesh;
    if holes.is_empty() && faces.iter().all(|outline| outline.len() <= 4) {
        return Ok(Shape::Mesh { points, faces, colors, normals: None, st: None });
    }
    let mut holes = holes.into_iter().peekable();
    let mut out = Faces::with_capacity(faces.len(), faces.indices().len());
    for (f, outline) in faces.iter().enumerate() {
        let face_holes = match holes.peek() {
            Some((hf, _)) if *hf == f => holes.next().map(|(_, h)| h).unwrap_or_default(),
            _ => Vec::new(),
        };
        if face_holes.is_empty() && outline.len() <= 4 {
            out.push(outline);
            continue;
        }
        let mut loops = vec![outline.to_vec()];
        loops.extend(face_holes);
        match crate::ri::triangulate::face(&points, &loops) {
            Some(tris) => out.extend(tris),
            None => {
                return Err(r.error(format!(
                    "face {f} cannot be triangulated (degenerate, or its loops cross)"
                )));
            }
        }
    }
    Ok(Shape::Mesh { points, faces: out, colors, normals: None, st: None })
}

/// A quadric's shape, with its optional `zmin`/`zmax` cuts in the model's form.
pub(crate) fn sphere(radius: f32, zmin: f32, zmax: f32, thetamax: f32) -> Shape {
    // RenderMan clamps the cuts to the sphere; a negative radius turns it inside out, which
    // two-sided shading does not see: its absolute value is the sphere.
    let r = radius.abs();
    let (lo, hi) = (zmin.min(zmax).max(-r), zmin.max(zmax).min(r));
    Shape::Sphere {
        radius: r,
        zmin: (lo > -r).then_some(lo),
        zmax: (hi < r).then_some(hi),
        thetamax,
    }
}
