//! Surfaces and their placement: the [`Shape`] of an object and the [`Transform`] steps
//! that carry it to world space.
//!
//! Invariant: quadrics sweep around the object's z axis, angles are in degrees.

use serde::{Deserialize, Serialize};

use super::{Rgb, V3};

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
    /// Polygon mesh of triangles and quads (planar or not).
    Mesh {
        /// Vertex positions.
        points: Vec<V3>,
        /// Faces: 3 or 4 indices into `points`, in order around the face.
        faces: Vec<Vec<u32>>,
        /// Optional per-vertex colours (same length as `points`), multiplying the material colour.
        #[serde(default)]
        colors: Option<Vec<Rgb>>,
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
        }
    }
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
