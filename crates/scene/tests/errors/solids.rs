//! CSG solids: their number, operators, operands and depth.

use std::path::Path;

use reyes_scene::parse;

use super::{BASE, Case, FILE};

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "solid with a bare object", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(name: \"lonely\", tree: Object(\"ball\"))],\n)", field: "solids[0].tree", at: Some((10, 35)) },
    Case { name: "union with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\")]))],\n)", field: "solids[0].tree", at: Some((11, 19)) },
    Case { name: "empty intersection", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([]))],\n)", field: "solids[0].tree", at: Some((11, 19)) },
    Case { name: "nested union with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Union([Object(\"ball\")]), Object(\"hole\")))],\n)", field: "solids[0].tree[0]", at: Some((11, 30)) },
    Case { name: "unknown operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hoel\")))],\n)", field: "solids[0].tree[1]", at: Some((11, 46)) },
    Case { name: "ambiguous operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"ball\", shape: Sphere(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"hole\"), Object(\"ball\")]))],\n)", field: "solids[0].tree[1]", at: Some((11, 42)) },
    Case { name: "unnamed operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (shape: Sphere(radius: 3.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"\")))],\n)", field: "solids[0].tree[1]", at: Some((11, 46)) },
    Case { name: "object used twice in one solid", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"hole\"), Object(\"ball\")]))],\n)", field: "solids[0].tree[2]", at: Some((11, 58)) },
    Case { name: "object used by two solids", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"cap\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hole\"))), (tree: Intersection([Object(\"cap\"), Object(\"ball\")]))],\n)", field: "solids[1].tree[1]", at: Some((11, 100)) },
    Case { name: "disk operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"plate\")))],\n)", field: "solids[0].tree[1]", at: Some((11, 46)) },
    Case { name: "bilinear patch operand", from: "  ],\n)", to: "    (name: \"sheet\", shape: BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"sheet\"), Object(\"ball\")]))],\n)", field: "solids[0].tree[0]", at: Some((10, 26)) },
    Case { name: "sphere cut at zmax operand", from: "  ],\n)", to: "    (name: \"dome\", shape: Sphere(radius: 1.0, zmax: Some(0.5)), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([Object(\"ball\"), Object(\"dome\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 49)) },
    Case { name: "sphere cut at zmin operand", from: "  ],\n)", to: "    (name: \"dome\", shape: Sphere(radius: 1.0, zmin: Some(-0.5), zmax: Some(2.0)), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([Object(\"ball\"), Object(\"dome\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 49)) },
    Case { name: "partial sphere operand", from: "  ],\n)", to: "    (name: \"wedge\", shape: Sphere(radius: 2.0, thetamax: 270.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"wedge\"), Object(\"ball\")))],\n)", field: "solids[0].tree[0]", at: Some((10, 30)) },
    Case { name: "partial cylinder operand", from: "  ],\n)", to: "    (name: \"trough\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0, thetamax: 180.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"trough\")))],\n)", field: "solids[0].tree[1]", at: Some((10, 46)) },
    Case { name: "partial cone operand", from: "  ],\n)", to: "    (name: \"fan\", shape: Cone(height: 2.0, radius: 0.5, thetamax: 90.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"fan\")))],\n)", field: "solids[0].tree[1]", at: Some((10, 46)) },
    Case { name: "torus with a partial tube", from: "  ],\n)", to: "    (name: \"arch\", shape: Torus(major_radius: 1.0, minor_radius: 0.25, phimax: 180.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"arch\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "torus with a partial sweep", from: "  ],\n)", to: "    (name: \"arch\", shape: Torus(major_radius: 1.0, minor_radius: 0.25, phimin: -90.0, phimax: 270.0, thetamax: 90.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"arch\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "open mesh operand", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [0, 3, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "mesh edge shared by three faces", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 1, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "inconsistently oriented mesh", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "mesh face through a point twice", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 0, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "mesh of degenerate faces", from: "  ],\n)", to: "    (name: \"tet\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 0, 1], [2, 2, 2]]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "open operand deep in a tree", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"cap\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Union([Object(\"ball\"), Intersection([Object(\"hole\"), Object(\"plate\")])]), Object(\"cap\")))],\n)", field: "solids[0].tree[0][1][1]", at: Some((12, 83)) },
    Case { name: "difference with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\")))],\n)", field: "solids[0].tree", at: Some((11, 44)) },
    Case { name: "unknown CSG operator", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Xor([Object(\"ball\"), Object(\"hole\")]))],\n)", field: "solids[0].tree", at: Some((11, 19)) },
    Case { name: "union without a list", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union(Object(\"ball\"), Object(\"hole\")))],\n)", field: "solids[0].tree[0]", at: Some((11, 25)) },
    Case { name: "operand name without quotes", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"plate\", shape: Disk(radius: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(ball), Object(\"hole\")))],\n)", field: "solids[0].tree[0]", at: Some((11, 37)) },
    Case { name: "solid without a tree", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(name: \"nothing\")],\n)", field: "solids[0].tree", at: Some((10, 28)) },
    Case { name: "unknown field in a solid", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hole\")), op: 3)],\n)", field: "solids[0].op", at: Some((10, 63)) },
    Case { name: "hyperboloid operand", from: "  ],\n)", to: "    (name: \"hyp\", shape: Hyperboloid(point1: (1.0, 0.0, -1.0), point2: (1.0, 0.0, 1.0)), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"hyp\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "wrapped patch mesh operand", from: "  ],\n)", to: "    (name: \"tube\", shape: PatchMesh(kind: Bilinear, nu: 3, nv: 2, uwrap: Periodic, points: [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), (1.0, 0.0, 1.0), (0.0, 1.0, 1.0), (-1.0, 0.0, 1.0)]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"tube\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    Case { name: "nurbs operand", from: "  ],\n)", to: "    (name: \"sheet\", shape: NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)]), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Union([Object(\"ball\"), Object(\"sheet\")]))],\n)", field: "solids[0].tree[1]", at: Some((10, 42)) },
    // Added with the hardening of #20.
    Case { name: "solid name not a string", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(name: 3, tree: Difference(Object(\"ball\"), Object(\"hole\")))],\n)", field: "solids[0].name", at: Some((10, 19)) },
    Case { name: "solids not a list", from: "  ],\n)", to: "  ],\n  solids: (tree: Union([])),\n)", field: "solids", at: Some((9, 11)) },
    Case { name: "intersection with one operand", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Intersection([Object(\"ball\")]))],\n)", field: "solids[0].tree", at: Some((10, 19)) },
    Case { name: "difference with three operands", from: "  ],\n)", to: "    (name: \"hole\", shape: Cylinder(radius: 0.5, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (name: \"cap\", shape: Sphere(radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],\n  solids: [(tree: Difference(Object(\"ball\"), Object(\"hole\"), Object(\"cap\")))],\n)", field: "solids[0].tree[2]", at: Some((11, 62)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}

/// A scene with `solids` made of `count` copies of `solid`, after the base scene's objects.
fn with_solids(solid: &str, count: usize) -> String {
    let list = vec![solid; count].join(",\n    ");
    BASE.replacen("  ],\n)", &format!("  ],\n  solids: [\n    {list}\n  ],\n)"), 1)
}

/// At most 65535 solids: one more is rejected at `solids`, before any solid is looked at.
#[test]
fn the_number_of_solids_is_limited() {
    let e = parse(&with_solids("(tree: Union([]))", 65536), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some("scenes/bad.ron:9:11: solids: at most 65535 solids are allowed, got 65536")
    );
    // At the limit the count passes and the first solid is checked.
    let e = parse(&with_solids("(tree: Union([]))", 65535), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some("scenes/bad.ron:10:12: solids[0].tree: Union needs at least 2 operands, got 0")
    );
}

/// At most 32768 leaves in one solid (2 * 32768 - 2 slot ids fit the renderer's `u16`),
/// counted before any leaf is resolved.
#[test]
fn the_number_of_leaves_in_a_solid_is_limited() {
    let tree = |n: usize| format!("(tree: Union([{}]))", vec!["Object(\"x\")"; n].join(", "));
    let e = parse(&with_solids(&tree(32769), 1), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some(
            "scenes/bad.ron:10:12: solids[0].tree: a solid may use at most 32768 objects, got 32769"
        )
    );
    let e = parse(&with_solids(&tree(32768), 1), Path::new(FILE)).err();
    assert_eq!(
        e.map(|e| e.to_string()).as_deref(),
        Some("scenes/bad.ron:10:19: solids[0].tree[0]: no object is named \"x\"")
    );
}

/// Solids are checked after every object, each tree in pre-order: an operator before its
/// operands, operands left to right.
#[test]
fn solids_are_checked_after_objects_in_pre_order() {
    let text = with_solids(
        "(tree: Difference(Intersection([Object(\"nope\"), Object(\"ball\")]), Union([Object(\"ball\")])))",
        1,
    );
    let shown = |text: &str| parse(text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        shown(&text).as_deref(),
        Some("scenes/bad.ron:10:37: solids[0].tree[0][0]: no object is named \"nope\"")
    );
    let bad_object = text.replacen("material:", "glass: Some(2.0), material:", 1);
    assert_eq!(
        shown(&bad_object).as_deref(),
        Some("scenes/bad.ron:7:55: objects[0].glass: must be in [0, 1], got 2")
    );
    // With that name fixed, the second use of "ball" in the first operand comes before the
    // one-operand Union that is the second.
    let text = text.replacen("Object(\"nope\")", "Object(\"ball\")", 1);
    assert_eq!(
        shown(&text).as_deref(),
        Some(
            "scenes/bad.ron:10:53: solids[0].tree[0][1]: object \"ball\" is already used by solids[0] (at solids[0].tree[0][0])"
        )
    );
}

/// Object names in messages are escaped and clipped, so a message stays short and one line.
#[test]
fn operand_names_in_messages_are_clipped_and_escaped() {
    let long = "n".repeat(10_000);
    let text = with_solids(&format!("(tree: Union([Object(\"{long}\"), Object(\"ball\")]))"), 1);
    let e = parse(&text, Path::new(FILE)).err().unwrap_or_else(|| panic!("accepted"));
    assert!(e.to_string().chars().count() < 200, "{e}");
    assert_eq!(e.field, "solids[0].tree[0]");
    let text = with_solids("(tree: Union([Object(\"a\\nb\"), Object(\"ball\")]))", 1);
    let e = parse(&text, Path::new(FILE)).err().unwrap_or_else(|| panic!("accepted"));
    assert_eq!(e.message, "no object is named \"a\\nb\"");
}
