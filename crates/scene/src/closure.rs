//! Whether a shape bounds a solid: the one definition used by CSG validation and by
//! `reyes-render measure` (quadric sweeps and cuts, and the mesh edge rule).
//!
//! Invariant: the shape has passed validation (finite numbers, thetamax in (0, 360]).

use std::collections::HashMap;

use crate::model::{Faces, Shape, SubdivTag};

/// Whether a (valid) shape bounds a solid.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Closure {
    /// Bounds a solid.
    Closed,
    /// Not closed, and why.
    Open(String),
    /// A closed mesh whose faces do not agree on the outside.
    Misoriented(String),
}

/// Closure of a valid shape (one that passed validation). Quadrics: full sweeps, a sphere uncut (cuts at or
/// beyond the poles do not cut), a torus's whole tube; cylinders and cones are closed by end
/// caps in a solid. Disks, patches, patch meshes, NURBS and hyperboloids never are (a
/// wrapped patch mesh or a NURBS may bound a solid, but that is not proved). Meshes by [`mesh_closure`].
pub fn closure(shape: &Shape) -> Closure {
    let sweep = |kind: &str, thetamax: f32| {
        if thetamax == 360.0 {
            Closure::Closed
        } else {
            Closure::Open(format!("{kind} with thetamax {thetamax}"))
        }
    };
    match shape {
        Shape::Sphere { radius, zmin, zmax, thetamax } => {
            if let Some(z) = zmin
                && *z > -radius
            {
                return Closure::Open(format!("Sphere cut at zmin {z}"));
            }
            if let Some(z) = zmax
                && z < radius
            {
                return Closure::Open(format!("Sphere cut at zmax {z}"));
            }
            sweep("Sphere", *thetamax)
        }
        Shape::Cylinder { thetamax, .. } => sweep("Cylinder", *thetamax),
        Shape::Cone { thetamax, .. } => sweep("Cone", *thetamax),
        Shape::Paraboloid { thetamax, .. } => sweep("Paraboloid", *thetamax),
        Shape::Torus { phimin, phimax, thetamax, .. } => {
            let tube = f64::from(*phimax) - f64::from(*phimin);
            if tube != 360.0 {
                return Closure::Open(format!("Torus with phimax - phimin = {tube}"));
            }
            sweep("Torus", *thetamax)
        }
        Shape::Disk { .. } => Closure::Open("Disk".into()),
        Shape::BilinearPatch { .. } => Closure::Open("BilinearPatch".into()),
        // Open surfaces: no attempt is made to prove a wrapped mesh or a NURBS closed.
        Shape::Hyperboloid { .. } => Closure::Open("Hyperboloid".into()),
        Shape::PatchMesh { .. } => Closure::Open("PatchMesh".into()),
        Shape::NuPatch { .. } => Closure::Open("NuPatch".into()),
        Shape::Mesh { faces, .. } => mesh_closure(faces),
        // Ribbons and disks bound nothing; a blobby's level set of a bounded field does.
        Shape::Curves { .. } => Closure::Open("Curves".into()),
        Shape::Points { .. } => Closure::Open("Points".into()),
        Shape::Blobby { .. } => Closure::Closed,
        // Read into a Mesh or SubdivisionMesh before anything asks.
        Shape::MeshFile { .. } => Closure::Open("MeshFile (not read)".into()),
        // The limit surface of a closed control mesh is closed; a hole opens it.
        Shape::SubdivisionMesh { faces, tags, .. } => {
            if tags.iter().any(|t| matches!(t, SubdivTag::Hole { faces } if !faces.is_empty())) {
                Closure::Open("SubdivisionMesh with a hole".into())
            } else {
                mesh_closure(faces)
            }
        }
    }
}

/// Whether a (valid) shape bounds a solid on its own, outside any CSG solid: as [`closure`],
/// but cylinders, cones and paraboloids, which only a solid's end caps close, are open tubes
/// whose insides show through their ends (what back-face culling needs to know).
pub fn closed_alone(shape: &Shape) -> bool {
    !matches!(shape, Shape::Cylinder { .. } | Shape::Cone { .. } | Shape::Paraboloid { .. })
        && closure(shape) == Closure::Closed
}

/// The faces along one undirected mesh edge.
#[derive(Debug, Default)]
struct EdgeUse {
    /// How many faces have the edge.
    faces: usize,
    /// The first two of them, each with the direction it runs along the edge.
    first: Vec<(usize, (u32, u32))>,
}

/// A mesh is closed when every edge is shared by exactly two faces, and consistently
/// oriented when those two faces run along it in opposite directions. A face first drops
/// repeated consecutive indices (`[0, 1, 1, 2]` is the triangle `[0, 1, 2]`); one left with
/// fewer than 3 points has no area and is ignored, one that still repeats a point is an error.
/// Faces and their edges are visited in order, so the edge reported is the first bad one.
fn mesh_closure(faces: &Faces) -> Closure {
    let mut polygons: Vec<(usize, Vec<u32>)> = Vec::with_capacity(faces.len());
    for (f, face) in faces.iter().enumerate() {
        let mut v: Vec<u32> = Vec::with_capacity(face.len());
        for &i in face {
            if v.last() != Some(&i) {
                v.push(i);
            }
        }
        while v.len() > 1 && v.first() == v.last() {
            v.pop();
        }
        if v.len() < 3 {
            continue;
        }
        if let Some(&p) =
            v.iter().enumerate().find_map(|(k, p)| v[k + 1..].contains(p).then_some(p))
        {
            return Closure::Open(format!("Mesh: faces[{f}] passes through point {p} twice"));
        }
        polygons.push((f, v));
    }
    if polygons.is_empty() {
        return Closure::Open("Mesh: no face has an area".into());
    }
    let edges = |v: &[u32]| -> Vec<(u32, u32)> {
        (0..v.len()).map(|k| (v[k], v[(k + 1) % v.len()])).collect()
    };
    let key = |(a, b): (u32, u32)| (a.min(b), a.max(b));
    let mut uses: HashMap<(u32, u32), EdgeUse> = HashMap::new();
    for (f, v) in &polygons {
        for e in edges(v) {
            let entry = uses.entry(key(e)).or_default();
            entry.faces += 1;
            if entry.first.len() < 2 {
                entry.first.push((*f, e));
            }
        }
    }
    for (f, v) in &polygons {
        for e @ (a, b) in edges(v) {
            let n = uses.get(&key(e)).map_or(0, |u| u.faces);
            if n == 1 {
                return Closure::Open(format!(
                    "Mesh: edge ({a}, {b}) of faces[{f}] belongs to no other face"
                ));
            }
            if n > 2 {
                return Closure::Open(format!("Mesh: edge ({a}, {b}) is shared by {n} faces"));
            }
        }
    }
    for (_, v) in &polygons {
        for e in edges(v) {
            if let Some(used) = uses.get(&key(e))
                && let [(f, d), (g, d2)] = used.first.as_slice()
                && d == d2
            {
                let (a, b) = *d;
                return Closure::Misoriented(format!(
                    "Mesh: faces[{f}] and faces[{g}] both run along edge ({a}, {b}) from point \
                     {a} to point {b}"
                ));
            }
        }
    }
    Closure::Closed
}
