//! An object's name, transforms, material of every kind, motion and deformation keys, glass, interpolation, shading rate and light set.

use std::path::Path;

use reyes_scene::parse;

use super::{BASE, Case, FILE};

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "matrix written with brackets", from: "material:", to: "transform: [Matrix([[1.0, 0.0, 0.0, 0.0]])], material:", field: "objects[0].transform[0]", at: Some((7, 67)) },
    Case { name: "rotate about a zero axis", from: "material:", to: "transform: [Rotate(angle: 30.0, axis: (0.0, 0.0, 0.0))], material:", field: "objects[0].transform[0].axis", at: Some((7, 86)) },
    Case { name: "scale by zero", from: "material:", to: "transform: [Translate((1.0, 0.0, 0.0)), Scale((2.0, 0.0, 2.0))], material:", field: "objects[0].transform[1][1]", at: Some((7, 100)) },
    Case { name: "projective matrix", from: "material:", to: "transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 1.0, 1.0)))], material:", field: "objects[0].transform[0][3]", at: Some((7, 134)) },
    Case { name: "singular matrix", from: "material:", to: "transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0)))], material:", field: "objects[0].transform[0]", at: Some((7, 60)) },
    Case { name: "material colour above 1", from: "(0.8, 0.1, 0.1)", to: "(0.8, 1.5, 0.1)", field: "objects[0].material.color[1]", at: Some((7, 77)) },
    Case { name: "material opacity negative", from: "(0.8, 0.1, 0.1))", to: "(0.8, 0.1, 0.1), opacity: (1.0, 1.0, -0.5))", field: "objects[0].material.opacity[2]", at: Some((7, 108)) },
    Case { name: "plastic roughness 0", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Plastic(color: (0.8, 0.1, 0.1), roughness: 0.0)", field: "objects[0].material.roughness", at: Some((7, 101)) },
    Case { name: "negative kd", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Matte(color: (0.8, 0.1, 0.1), kd: -1.0)", field: "objects[0].material.kd", at: Some((7, 92)) },
    Case { name: "transform motion with one key", from: "material:", to: "motion: [(time: 0.0, transform: [Translate((1.0, 0.0, 0.0))])], material:", field: "objects[0].motion", at: Some((7, 56)) },
    Case { name: "transform motion key outside the shutter", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.5, transform: [Translate((1.0, 0.0, 0.0))])], material:", field: "objects[0].motion[1].time", at: Some((7, 92)) },
    Case { name: "transform motion keys out of order", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 0.7, transform: []), (time: 0.5, transform: [])], material:", field: "objects[0].motion[2].time", at: Some((7, 120)) },
    Case { name: "transform motion inf time", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: inf, transform: [])], material:", field: "objects[0].motion[1].time", at: Some((7, 92)) },
    Case { name: "transform motion NaN translate", from: "material:", to: "motion: [(time: 0.0, transform: [Translate((0.0, NaN, 0.0))]), (time: 1.0, transform: [])], material:", field: "objects[0].motion[0].transform[0][1]", at: Some((7, 97)) },
    Case { name: "transform motion rotate about a zero axis", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Rotate(angle: 90.0, axis: (0.0, 0.0, 0.0))])], material:", field: "objects[0].motion[1].transform[0].axis", at: Some((7, 135)) },
    Case { name: "transform motion scale by zero", from: "material:", to: "motion: [(time: 0.0, transform: [Translate((1.0, 0.0, 0.0)), Scale((1.0, 1.0, 0.0))]), (time: 1.0, transform: [])], material:", field: "objects[0].motion[0].transform[1][2]", at: Some((7, 126)) },
    Case { name: "transform motion projective matrix", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.5, 0.0, 0.0, 1.0)))])], material:", field: "objects[0].motion[1].transform[0][3]", at: Some((7, 183)) },
    Case { name: "transform motion singular matrix", from: "material:", to: "motion: [(time: 0.0, transform: []), (time: 1.0, transform: [Matrix(((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)))])], material:", field: "objects[0].motion[1].transform[0]", at: Some((7, 109)) },
    Case { name: "deformation of a sphere", from: "material:", to: "deform: [(time: 0.0, points: []), (time: 1.0, points: [])], material:", field: "objects[0].deform", at: Some((7, 56)) },
    Case { name: "deformation with one key", from: "Sphere(radius: 1.0)", to: "BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)])]", field: "objects[0].deform", at: Some((7, 128)) },
    Case { name: "deformation of a patch with 3 points", from: "0.1))),\n", to: "0.1))),\n    (shape: BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), material: Matte(color: (0.5, 0.5, 0.5)),\n     deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]),\n              (time: 1.0, points: [(0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (0.0, 1.0, 1.0)])]),\n", field: "objects[1].deform[1].points", at: Some((10, 35)) },
    Case { name: "deformation of a mesh with too many points", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[0].points", at: Some((7, 143)) },
    Case { name: "deformation key outside the shutter", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]), (time: 2.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[1].time", at: Some((7, 204)) },
    Case { name: "deformation keys out of order", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]), (time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[1].time", at: Some((7, 204)) },
    Case { name: "deformation NaN point", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 2]]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (NaN, 1.0, 0.0)])]", field: "objects[0].deform[1].points[2][0]", at: Some((7, 253)) },
    Case { name: "deformation points written as a tuple", from: "Sphere(radius: 1.0)", to: "BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), deform: [(time: 0.0, points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), (time: 1.0, points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)))]", field: "objects[0].deform[0].points", at: Some((7, 149)) },
    Case { name: "glass above 1", from: "material:", to: "glass: Some(1.5), material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "glass negative", from: "material:", to: "glass: Some(-0.25), material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "glass NaN", from: "material:", to: "glass: Some(NaN), material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "glass without Some", from: "material:", to: "glass: 0.5, material:", field: "objects[0].glass", at: Some((7, 55)) },
    Case { name: "unknown interpolation", from: "material:", to: "interpolation: Phong, material:", field: "objects[0].interpolation", at: Some((7, 63)) },
    Case { name: "deformation of a nurbs with 3 points", from: "Sphere(radius: 1.0)", to: "NuPatch(nu: 2, uorder: 2, uknot: [0.0, 0.0, 1.0, 1.0], umin: 0.0, umax: 1.0, nv: 2, vorder: 2, vknot: [0.0, 0.0, 1.0, 1.0], vmin: 0.0, vmax: 1.0, points: [(0.0, 0.0, 0.0, 1.0), (1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 0.0, 1.0)]), deform: [(time: 0.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)])]", field: "objects[0].deform[1].points", at: Some((7, 392)) },
    Case { name: "object shading rate 0", from: "material:", to: "shading_rate: Some(0.0), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "object shading rate negative", from: "material:", to: "shading_rate: Some(-0.5), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "object flatness negative", from: "material:", to: "flatness: Some(-1.0), material:", field: "objects[0].flatness", at: Some((7, 58)) },
    Case { name: "object motion factor negative", from: "material:", to: "motion_factor: Some(-2.0), material:", field: "objects[0].motion_factor", at: Some((7, 63)) },
    Case { name: "object motion factor NaN", from: "material:", to: "motion_factor: Some(NaN), material:", field: "objects[0].motion_factor", at: Some((7, 63)) },
    Case { name: "object focus factor negative", from: "material:", to: "focus_factor: Some(-1.0), material:", field: "objects[0].focus_factor", at: Some((7, 62)) },
    Case { name: "object shading rate NaN", from: "material:", to: "shading_rate: Some(NaN), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "light set index out of range", from: "material:", to: "lights: Some([0, 2]), material:", field: "objects[0].lights[1]", at: Some((7, 65)) },
    Case { name: "light set with a light twice", from: "material:", to: "lights: Some([1, 0, 1]), material:", field: "objects[0].lights[2]", at: Some((7, 68)) },
    Case { name: "light set without Some", from: "material:", to: "lights: [0], material:", field: "objects[0].lights", at: Some((7, 56)) },
    Case { name: "metal without colour", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(roughness: 0.2)", field: "objects[0].material.color", at: Some((7, 78)) },
    Case { name: "metal roughness 0", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), roughness: 0.0)", field: "objects[0].material.roughness", at: Some((7, 99)) },
    Case { name: "metal colour above 1", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 1.5, 0.1))", field: "objects[0].material.color[1]", at: Some((7, 77)) },
    Case { name: "metal ks negative", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), ks: -0.5)", field: "objects[0].material.ks", at: Some((7, 92)) },
    Case { name: "metal with kd", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), kd: 0.5)", field: "objects[0].material.kd", at: Some((7, 88)) },
    // Added with the hardening of #20.
    Case { name: "constant colour negative", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Constant(color: (0.8, -1.5, 0.1))", field: "objects[0].material.color[1]", at: Some((7, 80)) },
    Case { name: "constant opacity NaN", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Constant(color: (0.8, 0.1, 0.1), opacity: (1.0, NaN, 1.0))", field: "objects[0].material.opacity[1]", at: Some((7, 106)) },
    Case { name: "constant with kd", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Constant(color: (0.8, 0.1, 0.1), kd: 1.0)", field: "objects[0].material.kd", at: Some((7, 91)) },
    Case { name: "matte ka NaN", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Matte(color: (0.8, 0.1, 0.1), ka: NaN)", field: "objects[0].material.ka", at: Some((7, 92)) },
    Case { name: "plastic ks negative", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Plastic(color: (0.8, 0.1, 0.1), ks: -0.5)", field: "objects[0].material.ks", at: Some((7, 94)) },
    Case { name: "plastic specular colour above 1", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Plastic(color: (0.8, 0.1, 0.1), specular_color: (1.0, 2.0, 1.0))", field: "objects[0].material.specular_color[1]", at: Some((7, 112)) },
    Case { name: "plastic ka infinite", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Plastic(color: (0.8, 0.1, 0.1), ka: inf)", field: "objects[0].material.ka", at: Some((7, 94)) },
    Case { name: "plastic roughness NaN", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Plastic(color: (0.8, 0.1, 0.1), roughness: NaN)", field: "objects[0].material.roughness", at: Some((7, 101)) },
    Case { name: "metal opacity above 1", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Metal(color: (0.8, 0.1, 0.1), opacity: (1.0, 1.0, 1.5))", field: "objects[0].material.opacity[2]", at: Some((7, 108)) },
    Case { name: "default surface kd negative", from: "Matte(color: (0.8, 0.1, 0.1))", to: "DefaultSurface(color: (1.0, 1.0, 1.0), kd: -0.5)", field: "objects[0].material.kd", at: Some((7, 101)) },
    Case { name: "default surface colour NaN", from: "Matte(color: (0.8, 0.1, 0.1))", to: "DefaultSurface(color: (NaN, 1.0, 1.0))", field: "objects[0].material.color[0]", at: Some((7, 81)) },
    Case { name: "default surface opacity negative", from: "Matte(color: (0.8, 0.1, 0.1))", to: "DefaultSurface(color: (1.0, 1.0, 1.0), opacity: (1.0, -1.0, 1.0))", field: "objects[0].material.opacity[1]", at: Some((7, 112)) },
    Case { name: "unknown material", from: "Matte(color: (0.8, 0.1, 0.1))", to: "Glossy(color: (0.8, 0.1, 0.1))", field: "objects[0].material", at: Some((7, 58)) },
    Case { name: "colour with 2 channels", from: "(0.8, 0.1, 0.1)", to: "(0.8, 0.1)", field: "objects[0].material.color", at: Some((7, 80)) },
    Case { name: "object without a material", from: ", material: Matte(color: (0.8, 0.1, 0.1))", to: "", field: "objects[0].material", at: Some((7, 46)) },
    Case { name: "object without a shape", from: "shape: Sphere(radius: 1.0), ", to: "", field: "objects[0].shape", at: Some((7, 59)) },
    Case { name: "rotate NaN angle", from: "material:", to: "transform: [Rotate(angle: NaN, axis: (0.0, 1.0, 0.0))], material:", field: "objects[0].transform[0].angle", at: Some((7, 74)) },
    Case { name: "rotate infinite axis", from: "material:", to: "transform: [Rotate(angle: 30.0, axis: (0.0, inf, 0.0))], material:", field: "objects[0].transform[0].axis[1]", at: Some((7, 92)) },
    Case { name: "matrix NaN", from: "material:", to: "transform: [Matrix(((1.0, NaN, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0)))], material:", field: "objects[0].transform[0][0][1]", at: Some((7, 74)) },
    Case { name: "translate infinite", from: "material:", to: "transform: [Translate((inf, 0.0, 0.0))], material:", field: "objects[0].transform[0][0]", at: Some((7, 71)) },
    Case { name: "scale NaN", from: "material:", to: "transform: [Scale((1.0, NaN, 1.0))], material:", field: "objects[0].transform[0][1]", at: Some((7, 72)) },
    Case { name: "unknown transform", from: "material:", to: "transform: [Shear((1.0, 0.0, 0.0))], material:", field: "objects[0].transform[0]", at: Some((7, 60)) },
    Case { name: "transform not a list", from: "material:", to: "transform: Translate((1.0, 0.0, 0.0)), material:", field: "objects[0].transform", at: Some((7, 59)) },
    Case { name: "matte not a bool", from: "material:", to: "matte: 1, material:", field: "objects[0].matte", at: Some((7, 55)) },
    Case { name: "name not a string", from: "name: \"ball\"", to: "name: 3", field: "objects[0].name", at: Some((7, 12)) },
    Case { name: "unknown field in an object", from: "material:", to: "colour: 3, material:", field: "objects[0].colour", at: Some((7, 48)) },
    Case { name: "transform motion key unknown field", from: "material:", to: "motion: [(time: 0.0, transform: [], scale: 2.0), (time: 1.0, transform: [])], material:", field: "objects[0].motion[0].scale", at: Some((7, 84)) },
    Case { name: "transform motion key without time", from: "material:", to: "motion: [(transform: []), (time: 1.0, transform: [])], material:", field: "objects[0].motion[0].time", at: Some((7, 71)) },
    Case { name: "deformation NaN time", from: "Sphere(radius: 1.0)", to: "BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0))), deform: [(time: NaN, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]), (time: 1.0, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)])]", field: "objects[0].deform[0].time", at: Some((7, 136)) },
    Case { name: "object shading rate infinite", from: "material:", to: "shading_rate: Some(inf), material:", field: "objects[0].shading_rate", at: Some((7, 62)) },
    Case { name: "light set of negative index", from: "material:", to: "lights: Some([-1]), material:", field: "objects[0].lights[0]", at: Some((7, 62)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}

/// Object and deformation keys are checked against the camera's shutter, wherever it is.
#[test]
fn object_keys_follow_the_shutter() {
    let with = |shutter: &str, motion: &str| {
        let text = BASE
            .replacen("yon: 100.0)", &format!("yon: 100.0, shutter: {shutter})"), 1)
            .replacen("material:", &format!("motion: [{motion}], material:"), 1);
        parse(&text, Path::new(FILE)).map(|_| ()).map_err(|e| e.to_string())
    };
    let keys = |a: &str, b: &str| {
        format!("(time: {a}, transform: []), (time: {b}, transform: [Translate((1.0, 0.0, 0.0))])")
    };
    #[rustfmt::skip]
    let cases = [
        // Keys at both ends of a shifted shutter are inside it; outside it they are not.
        ("(open: 1.0, close: 2.0)", ("1.0", "2.0"), None),
        ("(open: 1.0, close: 2.0)", ("0.0", "2.0"), Some("scenes/bad.ron:7:64: objects[0].motion[0].time: motion key time 0 is outside the shutter [1, 2]")),
        ("(open: 1.0, close: 2.0)", ("1.0", "2.5"), Some("scenes/bad.ron:7:92: objects[0].motion[1].time: motion key time 2.5 is outside the shutter [1, 2]")),
        // A closed shutter (no blur): every key at the opening time, none after.
        ("(open: 0.5, close: 0.5)", ("0.5", "0.5"), None),
        ("(open: 0.5, close: 0.5)", ("0.5", "0.75"), Some("scenes/bad.ron:7:92: objects[0].motion[1].time: motion key time 0.75 is outside the shutter [0.5, 0.5]")),
        // An open shutter needs strictly increasing times.
        ("(open: 0.0, close: 1.0)", ("0.5", "0.5"), Some("scenes/bad.ron:7:92: objects[0].motion[1].time: keys must be in increasing time order, got 0.5 after 0.5")),
    ];
    for (shutter, (a, b), error) in cases {
        let want = error.map_or(Ok(()), |e| Err(e.to_string()));
        assert_eq!(with(shutter, &keys(a, b)), want, "shutter {shutter}, keys at {a} and {b}");
    }
}
