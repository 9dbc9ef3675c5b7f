//! Unit tests of the blobby field, its reader and its coarse mesh.
use super::*;

fn translate(x: f32, y: f32, z: f32) -> Vec<f32> {
    vec![1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, x, y, z, 1.0]
}

#[test]
fn a_lone_sphere_has_radius_one_half() {
    let p = Program::parse(&[1001, 0], &translate(0.0, 0.0, 0.0), &[]).unwrap();
    let r = p.project(DVec3::new(0.3, 0.0, 0.0), 0.1).length();
    assert!((r - 0.5).abs() < 1e-9, "{r}");
    assert!((p.field(DVec3::new(0.0, 0.5, 0.0)) - THRESHOLD).abs() < 1e-12);
    let n = p.normal(DVec3::new(0.0, 0.5, 0.0));
    assert!(n.distance(DVec3::Y) < 1e-9);
}

#[test]
fn gradients_match_differences() {
    let mut floats = translate(-0.4, 0.0, 0.0);
    floats.extend(translate(0.4, 0.1, 0.0));
    floats.extend([0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.4]);
    floats.extend(translate(0.0, 0.0, 0.2));
    let code =
        [1001, 0, 1001, 16, 1002, 32, 0, 2, 0, 1, 1, 2, 2, 1, 2, 2, 3, 4, 4, 5, 2, 0, 2, 6, 3];
    let p = Program::parse(&code, &floats, &[]).unwrap();
    for q in [DVec3::new(0.1, 0.2, 0.05), DVec3::new(-0.3, 0.1, 0.1), DVec3::new(0.2, 0.6, 0.2)] {
        let (_, g) = p.eval(q);
        let e = 1e-6;
        let d = DVec3::new(
            p.field(q + DVec3::X * e) - p.field(q - DVec3::X * e),
            p.field(q + DVec3::Y * e) - p.field(q - DVec3::Y * e),
            p.field(q + DVec3::Z * e) - p.field(q - DVec3::Z * e),
        ) / (2.0 * e);
        assert!(g.distance(d) < 1e-5 * (1.0 + d.length()), "{g} {d}");
    }
}

#[test]
fn bad_code_names_its_place() {
    let f = translate(0.0, 0.0, 0.0);
    let e = Program::parse(&[1001, 0, 1010, 0], &f, &[]).unwrap_err();
    assert_eq!(e.index, 2);
    assert!(e.message.contains("unknown blobby opcode 1010"), "{}", e.message);
    let e = Program::parse(&[1001, 4], &f, &[]).unwrap_err();
    assert_eq!(e.index, 1);
    let e = Program::parse(&[1001, 0, 0, 2, 0, 1], &f, &[]).unwrap_err();
    assert_eq!(e.index, 5);
    let e = Program::parse(&[1001], &f, &[]).unwrap_err();
    assert_eq!(e.index, 1);
}

#[test]
fn the_coarse_mesh_lies_on_the_surface_and_winds_out() {
    let p = Program::parse(&[1001, 0], &translate(0.0, 0.0, 0.0), &[]).unwrap();
    let (points, tris, _) = p.coarse_mesh();
    assert!(tris.len() > 20);
    for q in &points {
        assert!((q.length() - 0.5).abs() < 1e-6, "{q}");
    }
    let mut volume = 0.0;
    for t in &tris {
        let [a, b, c] = t.map(|i| points[i as usize]);
        assert!((b - a).cross(c - a).dot(a + b + c) > 0.0);
        volume += a.dot(b.cross(c)) / 6.0;
    }
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    assert!(volume > 0.6 * exact && volume <= exact, "{volume} {exact}");
}
