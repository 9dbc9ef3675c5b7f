//! The shapes of every kind: quadrics, bilinear patches, meshes, patch meshes, NURBS and hyperboloids.

use super::Case;

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "sphere cut without Some", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, zmin: -0.5)", field: "objects[0].shape.zmin", at: Some((7, 53)) },
    Case { name: "unknown field in a shape", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, radius2: 2.0)", field: "objects[0].shape.radius2", at: Some((7, 47)) },
    Case { name: "missing required field in a shape", from: "Sphere(radius: 1.0)", to: "Sphere()", field: "objects[0].shape.radius", at: Some((7, 34)) },
    Case { name: "overflowing float", from: "radius: 1.0", to: "radius: 1e39", field: "objects[0].shape.radius", at: Some((7, 42)) },
    Case { name: "negative radius", from: "radius: 1.0", to: "radius: -1.0", field: "objects[0].shape.radius", at: Some((7, 42)) },
    Case { name: "sphere zmin above radius", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, zmin: Some(2.0))", field: "objects[0].shape.zmin", at: Some((7, 53)) },
    Case { name: "sphere zmax at zmin", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, zmin: Some(0.5), zmax: Some(0.5))", field: "objects[0].shape.zmax", at: Some((7, 70)) },
    Case { name: "sphere thetamax 0", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, thetamax: 0.0)", field: "objects[0].shape.thetamax", at: Some((7, 57)) },
    Case { name: "sphere thetamax above 360", from: "Sphere(radius: 1.0)", to: "Sphere(radius: 1.0, thetamax: 361.0)", field: "objects[0].shape.thetamax", at: Some((7, 57)) },
    Case { name: "cylinder zmax at zmin", from: "Sphere(radius: 1.0)", to: "Cylinder(radius: 1.0, zmin: 1.0, zmax: 1.0)", field: "objects[0].shape.zmax", at: Some((7, 66)) },
    Case { name: "cone height 0", from: "Sphere(radius: 1.0)", to: "Cone(height: 0.0, radius: 1.0)", field: "objects[0].shape.height", at: Some((7, 40)) },
    Case { name: "disk radius 0", from: "Sphere(radius: 1.0)", to: "Disk(radius: 0.0)", field: "objects[0].shape.radius", at: Some((7, 40)) },
    Case { name: "torus minor radius negative", from: "Sphere(radius: 1.0)", to: "Torus(major_radius: 1.0, minor_radius: -0.25)", field: "objects[0].shape.minor_radius", at: Some((7, 66)) },
    Case { name: "torus phimax below phimin", from: "Sphere(radius: 1.0)", to: "Torus(major_radius: 1.0, minor_radius: 0.25, phimin: 90.0, phimax: 45.0)", field: "objects[0].shape.phimax", at: Some((7, 94)) },
    Case { name: "torus tube sweep above 360", from: "Sphere(radius: 1.0)", to: "Torus(major_radius: 1.0, minor_radius: 0.25, phimin: -90.0, phimax: 290.0)", field: "objects[0].shape.phimax", at: Some((7, 95)) },
    Case { name: "mesh without faces", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0)], faces: [])", field: "objects[0].shape.faces", at: Some((7, 66)) },
    Case { name: "mesh index out of range", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 3]])", field: "objects[0].shape.faces[0][2]", at: Some((7, 108)) },
    Case { name: "mesh face with 5 indices", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2], [0, 1, 2, 0, 1]])", field: "objects[0].shape.faces[1]", at: Some((7, 112)) },
    Case { name: "mesh face with 2 indices", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1]])", field: "objects[0].shape.faces[0]", at: Some((7, 101)) },
    Case { name: "mesh colours length mismatch", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]], colors: Some([(1.0, 1.0, 1.0)]))", field: "objects[0].shape.colors", at: Some((7, 121)) },
    Case { name: "mesh NaN point", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, NaN, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]])", field: "objects[0].shape.points[1][1]", at: Some((7, 64)) },
    Case { name: "hyperboloid with equal points", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (1.0, 0.0, 0.0), point2: (1.0, 0.0, 0.0))", field: "objects[0].shape.point2", at: Some((7, 72)) },
    Case { name: "hyperboloid on the z axis", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (0.0, 0.0, -1.0), point2: (0.0, 0.0, 1.0))", field: "objects[0].shape.point2", at: Some((7, 73)) },
    Case { name: "hyperboloid thetamax 0", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (1.0, 0.0, -1.0), point2: (1.0, 0.0, 1.0), thetamax: 0.0)", field: "objects[0].shape.thetamax", at: Some((7, 100)) },
    Case { name: "hyperboloid NaN point", from: "Sphere(radius: 1.0)", to: "Hyperboloid(point1: (1.0, NaN, -1.0), point2: (1.0, 0.0, 1.0))", field: "objects[0].shape.point1[1]", at: Some((7, 53)) },
    Case { name: "bicubic patch mesh with 5 points along u", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 5, nv: 4, points: [])", field: "objects[0].shape.nu", at: Some((7, 56)) },
    Case { name: "periodic bezier mesh with 4 points along u", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, uwrap: Periodic, points: [])", field: "objects[0].shape.nu", at: Some((7, 56)) },
    Case { name: "periodic b-spline mesh with no points along v", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 0, vwrap: Periodic, vbasis: BSpline, points: [])", field: "objects[0].shape.nv", at: Some((7, 63)) },
    Case { name: "b-spline mesh whose step leaves points over", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 9, nv: 4, ubasis: BSpline, ustep: Some(2), points: [])", field: "objects[0].shape.nu", at: Some((7, 56)) },
    Case { name: "bilinear patch mesh with 1 point along v", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bilinear, nu: 2, nv: 1, points: [])", field: "objects[0].shape.nv", at: Some((7, 64)) },
    Case { name: "patch mesh step 0", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, ustep: Some(0), points: [])", field: "objects[0].shape.ustep", at: Some((7, 73)) },
    Case { name: "matrix basis without a step", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, vbasis: Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))), points: [])", field: "objects[0].shape.vstep", at: Some((7, 27)) },
    Case { name: "NaN in a basis matrix", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bicubic, nu: 4, nv: 4, ubasis: Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, NaN, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))), ustep: Some(1), points: [])", field: "objects[0].shape.ubasis[1][2]", at: Some((7, 115)) },
    Case { name: "patch mesh with too few points", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bilinear, nu: 2, nv: 2, points: [(0.0, 0.0, 0.0)])", field: "objects[0].shape.points", at: Some((7, 75)) },
    Case { name: "patch mesh inf point", from: "Sphere(radius: 1.0)", to: "PatchMesh(kind: Bilinear, nu: 2, nv: 2, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, inf)])", field: "objects[0].shape.points[3][2]", at: Some((7, 138)) },
    Case { name: "nurbs order 1", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 1, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.uorder", at: Some((7, 50)) },
    Case { name: "nurbs order above 16", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 17, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.vorder", at: Some((7, 119)) },
    Case { name: "nurbs with fewer points than its order", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 3, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.nu", at: Some((7, 39)) },
    Case { name: "nurbs with a knot too few", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.uknot", at: Some((7, 60)) },
    Case { name: "nurbs knots decreasing", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 0.5], umin: 0.0, umax: 0.5, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.uknot[3]", at: Some((7, 76)) },
    Case { name: "nurbs NaN knot", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, NaN, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.vknot[1]", at: Some((7, 135)) },
    Case { name: "nurbs umin before the valid range", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: -0.5, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.umin", at: Some((7, 88)) },
    Case { name: "nurbs vmax after the valid range", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 2.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.vmax", at: Some((7, 168)) },
    Case { name: "nurbs umax at umin", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.5, umax: 0.5, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.umax", at: Some((7, 99)) },
    Case { name: "nurbs weight 0", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 0.0)])", field: "objects[0].shape.points[3][3]", at: Some((7, 264)) },
    Case { name: "nurbs with too many points", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0), (2.0, 1.0, 0.0, 1.0)])", field: "objects[0].shape.points", at: Some((7, 181)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}
