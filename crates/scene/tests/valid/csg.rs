//! Constructive solid geometry: solids and their trees, closed operands, glass and Gouraud
//! objects.

use reyes_scene::{Csg, Interpolation, Solid};

use crate::{FULL, ok, reads_back};

/// Constructive solid geometry: a sphere minus a cylinder, a lens (intersection of two
/// spheres), a 3-deep nested tree, a closed cube mesh, and glass and Gouraud objects.
const CSG: &str = r#"
Scene(
  image: (width: 160, height: 120),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0)),
  hider: (original: (csg_order: true)),
  lights: [Ambient(intensity: 0.2), Distant(from: (1.0, 1.0, -1.0))],
  objects: [
    (name: "ball", shape: Sphere(radius: 1.0), material: Plastic(color: (0.8, 0.1, 0.1)),
     interpolation: Gouraud),
    (name: "hole", shape: Cylinder(radius: 0.4, zmin: -2.0, zmax: 2.0), material: Matte(color: (0.8, 0.8, 0.1))),
    (name: "left", shape: Sphere(radius: 2.0), transform: [Translate((-1.5, 0.0, 0.0))],
     material: Plastic(color: (0.9, 0.9, 0.9), opacity: (0.3, 0.3, 0.3)), glass: Some(0.25)),
    (name: "right", shape: Sphere(radius: 2.0, zmin: Some(-2.0), zmax: Some(3.0)),
     transform: [Translate((1.5, 0.0, 0.0))],
     material: Plastic(color: (0.9, 0.9, 0.9), opacity: (0.3, 0.3, 0.3)), glass: Some(0.25)),
    (name: "cube",
     shape: Mesh(points: [(-1.0, -1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, -1.0), (-1.0, 1.0, -1.0),
                          (-1.0, -1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, 1.0), (-1.0, 1.0, 1.0)],
                 faces: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]),
     material: Matte(color: (0.2, 0.2, 0.8))),
    (name: "ring", shape: Torus(major_radius: 1.0, minor_radius: 0.3, phimin: -90.0, phimax: 270.0),
     material: Matte(color: (0.2, 0.8, 0.2))),
    (name: "cone", shape: Cone(height: 2.0, radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5)),
     motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Translate((0.0, 1.0, 0.0))])]),
    (name: "pip", shape: Sphere(radius: 0.2), material: Matte(color: (0.5, 0.5, 0.5))),
    (name: "floor", shape: Disk(radius: 5.0), material: Matte(color: (0.5, 0.5, 0.5)), glass: Some(1.0)),
    (name: "floor", shape: Disk(radius: 6.0), material: Matte(color: (0.5, 0.5, 0.5)), glass: Some(0.0)),
    (shape: Disk(radius: 7.0), material: Matte(color: (0.5, 0.5, 0.5))),
    (shape: Disk(radius: 8.0), material: Matte(color: (0.5, 0.5, 0.5))),
  ],
  solids: [
    (name: "drilled", tree: Difference(Object("ball"), Object("hole"))),
    (name: "lens", tree: Intersection([Object("left"), Object("right")])),
    (name: "nested",
     tree: Difference(Union([Object("cube"), Intersection([Object("ring"), Object("cone")])]), Object("pip"))),
  ],
)
"#;

#[test]
fn csg_parses_with_the_expected_values() {
    let scene = ok(CSG);
    let object = |name: &str| Csg::Object(name.into());
    assert_eq!(
        scene.solids,
        vec![
            Solid {
                name: "drilled".into(),
                tree: Csg::Difference(Box::new(object("ball")), Box::new(object("hole"))),
            },
            Solid {
                name: "lens".into(),
                tree: Csg::Intersection(vec![object("left"), object("right")]),
            },
            Solid {
                name: "nested".into(),
                tree: Csg::Difference(
                    Box::new(Csg::Union(vec![
                        object("cube"),
                        Csg::Intersection(vec![object("ring"), object("cone")]),
                    ])),
                    Box::new(object("pip")),
                ),
            },
        ]
    );
    assert!(scene.hider.original.csg_order);
    assert_eq!(scene.objects[0].interpolation, Interpolation::Gouraud);
    assert_eq!(scene.objects[1].interpolation, Interpolation::Flat);
    assert_eq!(scene.objects[2].glass, Some(0.25));
    assert_eq!(scene.objects[1].glass, None);
    assert_eq!((scene.objects[8].glass, scene.objects[9].glass), (Some(1.0), Some(0.0)));
}

#[test]
fn csg_defaults_to_nothing() {
    let scene = ok(FULL);
    assert!(scene.solids.is_empty());
    assert!(!scene.hider.original.csg_order);
    assert_eq!(scene.objects[0].interpolation, Interpolation::Flat);
    assert_eq!(scene.objects[0].glass, None);
}

#[test]
fn csg_reads_back_from_what_ron_writes() {
    let scene = ok(CSG);
    reads_back(&scene);
}

/// More closed operands: n-ary trees, sphere cuts at or beyond the poles, a deforming closed
/// mesh, triangles and a quad with a repeated corner.
#[test]
fn closed_operands_are_accepted() {
    let tetra = "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)],
                      faces: [[0, 2, 1, 1], [0, 1, 3], [0, 0, 3, 2], [1, 2, 3], [3, 3, 3]])";
    let text = format!(
        r#"Scene(
      image: (width: 8, height: 8),
      camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),
      objects: [
        (name: "a", shape: Sphere(radius: 1.0, zmin: Some(-1.0), zmax: Some(1.0), thetamax: 360.0),
         material: Matte(color: (0.5, 0.5, 0.5))),
        (name: "b", shape: Sphere(radius: 1.0, zmin: Some(-5.0), zmax: Some(5.0)),
         material: Matte(color: (0.5, 0.5, 0.5))),
        (name: "c", shape: {tetra}, material: Matte(color: (0.5, 0.5, 0.5)),
         deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]),
                  (time: 1.0, points: [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0), (0.0, 0.0, 2.0)])]),
        (name: "d", shape: Cylinder(radius: 1.0, zmin: 0.0, zmax: 1.0, thetamax: 360.0),
         material: Matte(color: (0.5, 0.5, 0.5))),
        (name: "e", shape: Torus(major_radius: 2.0, minor_radius: 0.5), material: Matte(color: (0.5, 0.5, 0.5))),
      ],
      solids: [
        (tree: Union([Object("a"), Object("b"), Object("c")])),
        (tree: Intersection([Object("d"), Object("e")])),
      ],
    )"#
    );
    let scene = ok(&text);
    assert_eq!(scene.solids.len(), 2);
    assert_eq!(scene.solids[0].name, "");
}
