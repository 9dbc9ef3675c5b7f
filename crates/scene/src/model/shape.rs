//! Surfaces and their placement: the [`Shape`] of an object and the [`Transform`] steps
//! that carry it to world space.
//!
//! Invariant: quadrics sweep around the object's z axis, angles are in degrees; control
//! points of patch meshes and NURBS are listed u-major (u varies fastest), as RenderMan
//! lists them.

use serde::{Deserialize, Serialize};

use super::hair::default_width;
use super::{CurveType, Faces, Primvar, Rgb, V3};

fn deg360() -> f32 {
    360.0
}

/// Shapes. Quadrics follow RenderMan: they sweep around the object's z axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shape {
    /// Sphere of `radius`, cut to `zmin..zmax`, swept through `thetamax` degrees.
    Sphere {
        /// Radius (> 0).
        radius: f32,
        /// Lower cut (default `-radius`).
        #[serde(default)]
        zmin: Option<f32>,
        /// Upper cut (default `radius`).
        #[serde(default)]
        zmax: Option<f32>,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Open cylinder of `radius` from `zmin` to `zmax`.
    Cylinder {
        /// Radius (> 0).
        radius: f32,
        /// Bottom.
        zmin: f32,
        /// Top (> zmin).
        zmax: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Cone with base of `radius` at z = 0 and apex at z = `height`.
    Cone {
        /// Height (!= 0).
        height: f32,
        /// Base radius (> 0).
        radius: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Disk of `radius` in the plane z = `height`, facing +z.
    Disk {
        /// Plane offset.
        #[serde(default)]
        height: f32,
        /// Radius (> 0).
        radius: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Torus around the z axis.
    Torus {
        /// Distance from the z axis to the tube centre (> 0).
        major_radius: f32,
        /// Tube radius (> 0).
        minor_radius: f32,
        /// Start of the tube angle, degrees.
        #[serde(default)]
        phimin: f32,
        /// End of the tube angle, degrees (> phimin, at most phimin + 360).
        #[serde(default = "deg360")]
        phimax: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// RenderMan paraboloid: radius `rmax` at `zmax`, `r = rmax * sqrt(z / zmax)`, cut to
    /// `zmin..zmax`.
    Paraboloid {
        /// Radius at `zmax` (> 0).
        rmax: f32,
        /// Lower cut (>= 0).
        #[serde(default)]
        zmin: f32,
        /// Top (> zmin).
        zmax: f32,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// Bilinear patch. Corners in RenderMan order: (u,v) = (0,0), (1,0), (0,1), (1,1).
    BilinearPatch {
        /// The four corners.
        points: [V3; 4],
    },
    /// RenderMan hyperboloid (`RiHyperboloid`): the surface swept by turning the segment
    /// `point1 -> point2` about the z axis through `thetamax` degrees. `u` is the sweep
    /// (`theta = u * thetamax`, from +x towards +y), `v` runs along the segment.
    Hyperboloid {
        /// Start of the segment (`v = 0`).
        point1: V3,
        /// End of the segment (`v = 1`); != `point1`.
        point2: V3,
        /// Sweep angle in degrees, (0, 360].
        #[serde(default = "deg360")]
        thetamax: f32,
    },
    /// RenderMan patch mesh (`RiPatchMesh`; `RiPatch` is the mesh of one patch): an
    /// `nu x nv` grid of control points, `points[j * nu + i]` at column `i` (u), row `j` (v),
    /// cut into sub-patches by the basis steps (see [`PatchType`], [`Basis`]).
    PatchMesh {
        /// `Bilinear` or `Bicubic` (RenderMan's `type` argument).
        kind: PatchType,
        /// Control points along u.
        nu: u32,
        /// Control points along v.
        nv: u32,
        /// Whether the mesh wraps around in u.
        #[serde(default)]
        uwrap: Wrap,
        /// Whether the mesh wraps around in v.
        #[serde(default)]
        vwrap: Wrap,
        /// The `nu * nv` control points, u-major.
        points: Vec<V3>,
        /// Basis along u (`RiBasis`'s `ubasis`; bicubic only).
        #[serde(default)]
        ubasis: Basis,
        /// Step along u between sub-patches; `None`: the standard step of `ubasis`.
        #[serde(default)]
        ustep: Option<u32>,
        /// Basis along v.
        #[serde(default)]
        vbasis: Basis,
        /// Step along v; `None`: the standard step of `vbasis`.
        #[serde(default)]
        vstep: Option<u32>,
    },
    /// RenderMan NURBS patch (`RiNuPatch`), rational, with optional trim loops
    /// (`RiTrimCurve`). Knot vectors have `n + order` entries; the surface is drawn over
    /// `[umin, umax] x [vmin, vmax]`, less the trimmed region.
    NuPatch {
        /// Control points along u.
        nu: u32,
        /// Order along u (degree + 1), >= 2.
        uorder: u32,
        /// Knots along u: `nu + uorder` non-decreasing values.
        uknot: Vec<f32>,
        /// Start of the drawn u range, `>= uknot[uorder - 1]`.
        umin: f32,
        /// End of the drawn u range, `> umin`, `<= uknot[nu]`.
        umax: f32,
        /// Control points along v.
        nv: u32,
        /// Order along v.
        vorder: u32,
        /// Knots along v: `nv + vorder` values.
        vknot: Vec<f32>,
        /// Start of the drawn v range.
        vmin: f32,
        /// End of the drawn v range.
        vmax: f32,
        /// The `nu * nv` homogeneous control points `(x, y, z, w)` (RenderMan's `Pw`; the
        /// point is `(x/w, y/w, z/w)`, `w > 0`; `P` is `w = 1`), u-major.
        points: Vec<[f32; 4]>,
        /// Trim loops in the patch's `(u, v)` parameter space (`RiTrimCurve`), each a closed
        /// chain of curves; the region inside an odd number of loops is removed (the
        /// Specification's, PRMan's `"trimcurve" "sense" "inside"`). Empty: untrimmed.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        trim: Vec<TrimLoop>,
        /// Keep the region inside the loops and remove the rest instead (PRMan's
        /// `Attribute "trimcurve" "sense" "outside"`).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        trim_outside: bool,
    },
    /// Polygon mesh: triangles, quads (planar or not) and larger convex polygons (fanned
    /// into triangles around their first index).
    Mesh {
        /// Vertex positions.
        points: Vec<V3>,
        /// Faces: 3 or more indices into `points`, in order around the face (written as a
        /// list of lists, `[[0, 1, 2, 3], [3, 2, 4]]`; held flat, see [`Faces`]). A face of
        /// more than four indices must be convex: it is drawn as the fan of triangles
        /// `(0, k, k + 1)`.
        faces: Faces,
        /// Optional per-vertex colours (same length as `points`), multiplying the material colour.
        #[serde(default)]
        colors: Option<Vec<Rgb>>,
        /// Optional per-point shading normals (same length as `points`, non-zero), in object
        /// space: the mesh then shades smoothly, each face interpolating its corners' normals
        /// (bilinearly over a quad, barycentrically over a triangle). They are oriented to
        /// the side the face winds towards; they are not keyed by deformation (a deforming
        /// mesh keeps these normals at every time).
        #[serde(default)]
        normals: Option<Vec<V3>>,
        /// Optional per-point texture coordinates (same length as `points`), interpolated
        /// over each face as the normals are; texture maps are looked up at them instead of
        /// the face's own `(u, v)`.
        #[serde(default)]
        st: Option<Vec<[f32; 2]>>,
    },
    /// A polygon mesh read from an OBJ or PLY file when the scene is loaded
    /// ([`crate::parse`]): it becomes a [`Shape::Mesh`] (or, with `subdivision`, a
    /// [`Shape::SubdivisionMesh`]) before validation, so no later stage sees it.
    MeshFile {
        /// The file (`.obj` or `.ply`), relative to the scene file's folder unless absolute.
        path: String,
        /// Read the mesh as the control mesh of a Catmull-Clark subdivision surface
        /// (its normals are then ignored; its texture coordinates become facevarying `st`).
        #[serde(default)]
        subdivision: bool,
        /// Only the faces of this OBJ group or object (by name); `None`: every face.
        #[serde(default)]
        group: Option<String>,
    },
    /// Catmull-Clark subdivision surface (`RiSubdivisionMesh "catmull-clark"`): the limit
    /// surface of a control mesh of polygons of any size, with RenderMan's tags.
    SubdivisionMesh {
        /// Control points (RenderMan's vertex `P`).
        points: Vec<V3>,
        /// Faces: 3 or more indices into `points`, in order around the face, consistently
        /// oriented (`[[0, 1, 2, 3], [3, 2, 4]]`).
        faces: Faces,
        /// Tags (`interpolateboundary`, `crease`, `corner`, `hole`).
        #[serde(default)]
        tags: Vec<SubdivTag>,
        /// Optional per-point colours (vertex `Cs`), subdivided with the points.
        #[serde(default)]
        colors: Option<Vec<Rgb>>,
        /// Optional texture coordinates, facevarying: one per face corner, face after face
        /// (as many as the face indices), interpolated bilinearly over each face.
        #[serde(default)]
        st: Option<Vec<[f32; 2]>>,
    },
    /// RenderMan curves (`RiCurves`): `nvertices.len()` curves, linear or cubic in `basis`,
    /// each a ribbon of `width` (object space) along the curve. With `normals` the ribbon
    /// faces them; without, it turns to face the camera at every point (docs/geometry.md,
    /// "Curves").
    Curves {
        /// `Linear` or `Cubic`.
        kind: CurveType,
        /// Whether each curve closes on itself.
        #[serde(default)]
        wrap: Wrap,
        /// Control points of each curve (linear: at least 2, or 3 periodic; cubic: 4 + a
        /// multiple of the step, or a multiple of it periodic).
        nvertices: Vec<u32>,
        /// Every curve's control points, curve after curve.
        points: Vec<V3>,
        /// The cubic basis (ignored by linear curves).
        #[serde(default)]
        basis: Basis,
        /// Step between segments; `None`: the basis's standard step.
        #[serde(default)]
        step: Option<u32>,
        /// Width (> 0) along the curves: `Constant` (RenderMan's `constantwidth`), or per
        /// curve, segment end or control point. Default 1.
        #[serde(default = "default_width")]
        width: Primvar<f32>,
        /// Normals the ribbon faces (`N`); `None`: the ribbon faces the camera.
        #[serde(default)]
        normals: Option<Primvar<V3>>,
        /// Colours multiplying the material colour (`Cs`).
        #[serde(default)]
        colors: Option<Primvar<Rgb>>,
        /// Opacities multiplying the material opacity (`Os`).
        #[serde(default)]
        opacities: Option<Primvar<Rgb>>,
    },
    /// RenderMan points (`RiPoints`): each point a disk of `width` (object space) facing
    /// the camera.
    Points {
        /// Centres.
        points: Vec<V3>,
        /// Diameter (> 0): `Constant` (`constantwidth`) or one per point. Default 1.
        #[serde(default = "default_width")]
        width: Primvar<f32>,
        /// Colours multiplying the material colour (`Cs`), one per point or constant.
        #[serde(default)]
        colors: Option<Primvar<Rgb>>,
        /// Opacities multiplying the material opacity (`Os`).
        #[serde(default)]
        opacities: Option<Primvar<Rgb>>,
    },
    /// A RenderMan blobby implicit surface (`RiBlobby`): the level set at the Specification's
    /// threshold of the field the code stream computes (docs/geometry.md, "Blobby").
    Blobby {
        /// The instruction stream: primitive fields (1000 constant, 1001 ellipsoid, 1002
        /// segment, 1003 repelling ground plane, 1004 plane) and operators (0 add, 1
        /// multiply, 2 maximum, 3 minimum, 4 subtract, 5 divide, 6 negate, 7 identity).
        code: Vec<i32>,
        /// The floats the instructions index.
        floats: Vec<f32>,
        /// The strings the instructions index (depth-map names).
        #[serde(default)]
        strings: Vec<String>,
        /// Colours multiplying the material colour (`Cs`), one per primitive field or constant.
        #[serde(default)]
        colors: Option<Primvar<Rgb>>,
        /// Opacities multiplying the material opacity (`Os`).
        #[serde(default)]
        opacities: Option<Primvar<Rgb>>,
    },
}

/// A tag of a [`Shape::SubdivisionMesh`] (the tags of `RiSubdivisionMesh`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum SubdivTag {
    /// The boundary is interpolated: boundary edges are infinitely sharp creases and
    /// boundary points of one face are corners. Without it, the faces along the boundary
    /// only shape their neighbours and are not drawn.
    InterpolateBoundary,
    /// A crease along the chain of edges `vertices[i] - vertices[i + 1]`, of `sharpness`
    /// (DeRose, Kass and Truong 1998: sharp for that many subdivision steps, then smooth;
    /// `inf` or any value of 20 and more is infinitely sharp).
    Crease {
        /// The chain of points, each edge an edge of the mesh.
        vertices: Vec<u32>,
        /// Sharpness, >= 0.
        sharpness: f32,
    },
    /// Corners: each listed point is kept sharp for `sharpness` steps.
    Corner {
        /// The points.
        vertices: Vec<u32>,
        /// Sharpness, >= 0.
        sharpness: f32,
    },
    /// Faces that are not drawn (they still shape their neighbours).
    Hole {
        /// The faces.
        faces: Vec<u32>,
    },
}

impl Shape {
    /// The variant's name as RON spells it (`"Sphere"`, `"Mesh"`, ...), for messages.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Sphere { .. } => "Sphere",
            Shape::Cylinder { .. } => "Cylinder",
            Shape::Cone { .. } => "Cone",
            Shape::Disk { .. } => "Disk",
            Shape::Torus { .. } => "Torus",
            Shape::Paraboloid { .. } => "Paraboloid",
            Shape::BilinearPatch { .. } => "BilinearPatch",
            Shape::Mesh { .. } => "Mesh",
            Shape::MeshFile { .. } => "MeshFile",
            Shape::Hyperboloid { .. } => "Hyperboloid",
            Shape::PatchMesh { .. } => "PatchMesh",
            Shape::NuPatch { .. } => "NuPatch",
            Shape::SubdivisionMesh { .. } => "SubdivisionMesh",
            Shape::Curves { .. } => "Curves",
            Shape::Points { .. } => "Points",
            Shape::Blobby { .. } => "Blobby",
        }
    }
}

/// The kind of a [`Shape::PatchMesh`]: RenderMan's `"bilinear"` or `"bicubic"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum PatchType {
    /// Sub-patches of 2 x 2 points, interpolated bilinearly (the basis is ignored).
    Bilinear,
    /// Sub-patches of 4 x 4 points in the mesh's bases.
    Bicubic,
}

/// Whether a patch mesh wraps around in one direction (RenderMan's `"periodic"` and
/// `"nonperiodic"`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Wrap {
    /// The mesh ends at its last control point (the default).
    #[default]
    Nonperiodic,
    /// The control points wrap around: the last sub-patch reuses the first points.
    Periodic,
}

/// A cubic basis of `RiBasis`: the matrix `M` of `P(u, v) = U M G M^T V^T` with
/// `U = (u^3, u^2, u, 1)`. Each named basis has its standard step (`RiBezierStep` ...).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub enum Basis {
    /// `RiBezierBasis`, step 3 (the default).
    #[default]
    Bezier,
    /// `RiBSplineBasis` (uniform cubic B-spline), step 1.
    BSpline,
    /// `RiCatmullRomBasis`, step 1.
    CatmullRom,
    /// `RiHermiteBasis` (points `P0, T0, P1, T1`), step 2.
    Hermite,
    /// `RiPowerBasis` (the identity: points are the coefficients of `u^3 .. 1`), step 4.
    Power,
    /// An explicit matrix, rows written top to bottom as `RtBasis` (`M[row][column]`); it
    /// has no standard step, so the mesh must give one.
    Matrix([[f32; 4]; 4]),
}

/// One step of an object's transform.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Transform {
    /// Move by a vector.
    Translate(V3),
    /// Rotate by `angle` degrees about `axis` (right-hand rule in a left-handed world, as RenderMan).
    Rotate {
        /// Degrees.
        angle: f32,
        /// Axis (non-zero).
        axis: V3,
    },
    /// Scale per axis (no zero factor).
    Scale(V3),
    /// A 4x4 matrix, rows written top to bottom, acting on column vectors `(x, y, z, 1)`.
    Matrix([[f32; 4]; 4]),
}

/// One closed trim loop of a [`Shape::NuPatch`]: its curves, end to end.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrimLoop {
    /// The curves in order; the loop closes from the last curve's end to the first's start.
    pub curves: Vec<TrimCurve>,
}

/// One curve of a trim loop: a rational NURBS curve in the patch's parameter space
/// (`RiTrimCurve`'s `order`, `knot`, `min`, `max`, `n` and `u`, `v`, `w` of one curve).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrimCurve {
    /// Order (degree + 1), `2..=16`.
    pub order: u32,
    /// `points.len() + order` non-decreasing knots.
    pub knot: Vec<f32>,
    /// Start of the drawn parameter range, `>= knot[order - 1]`.
    pub min: f32,
    /// End of the drawn parameter range, `> min`, `<= knot[n]`.
    pub max: f32,
    /// Homogeneous control points `(u w, v w, w)`, `w > 0`: the point is `(u, v)`.
    pub points: Vec<[f32; 3]>,
}
