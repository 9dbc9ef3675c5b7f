//! Area lights with a visible surface: polygon shapes, one-sided emission and the link from
//! an object to the light it is the surface of, valid and invalid.

use std::path::Path;

use reyes_scene::{AreaShape, Light, parse};

fn scene(lights: &str, link: &str) -> String {
    format!(
        "Scene(image: (width: 8, height: 8),
  camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0)),
  lights: [{lights}],
  objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 1.0, 1.0)){link})])"
    )
}

const QUAD: &str = "Area(shape: Polygon(points: [(0.0, 2.0, 0.0), (2.0, 2.0, 0.0), (3.0, 2.0, 3.0), (0.0, 2.0, 1.0)]), one_sided: true)";

#[test]
fn a_polygon_light_with_its_surface_linked_is_valid() {
    let s = parse(
        &scene(QUAD, ", area_light: Some(0), emission: Some((1.0, 1.0, 1.0))"),
        Path::new("t.ron"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        matches!(&s.lights[0], Light::Area { shape: AreaShape::Polygon { points }, one_sided: true, .. } if points.len() == 4)
    );
    assert_eq!(s.objects[0].area_light, Some(0));
}

#[test]
fn bad_polygons_and_links_name_their_field() {
    let bent = "Area(shape: Polygon(points: [(0.0, 2.0, 0.0), (2.0, 2.0, 0.0), (2.0, 3.0, 2.0), (0.0, 2.0, 2.0)]))";
    let dart = "Area(shape: Polygon(points: [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (0.5, 0.0, 0.5), (0.0, 0.0, 2.0)]))";
    let two = "Area(shape: Polygon(points: [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0)]))";
    let point = "Point(from: (0.0, 5.0, 0.0))";
    for (lights, link, field, message) in [
        (bent, "", "lights[0].shape.points", "not planar"),
        (dart, "", "lights[0].shape.points", "not convex"),
        (two, "", "lights[0].shape.points", "at least 3 points"),
        (point, ", area_light: Some(0)", "objects[0].area_light", "not an Area light"),
        (QUAD, ", area_light: Some(3)", "objects[0].area_light", "out of range"),
    ] {
        let e = parse(&scene(lights, link), Path::new("t.ron")).unwrap_err().to_string();
        assert!(e.contains(field) && e.contains(message) && !e.contains('\n'), "{e}");
    }
}
