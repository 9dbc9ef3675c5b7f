//! RenderMan's cameras, lights, materials and higher-order geometry through RIB: the mapping
//! onto the model, the Basis matrices against a direct evaluation of the Specification's
//! formula, and quadric silhouettes rendered under an orthographic camera against their exact
//! areas.

use reyes_render::{RenderOptions, render};
use reyes_scene::{Basis, Light, Material, Projection, Shape};

use super::{scene, world};

#[test]
fn orthographic_projection_screen_window_and_frame_aspect() {
    let s = scene("Format 64 32 1 ScreenWindow -4 4 -2 2 WorldBegin Sphere 1 -1 1 360 WorldEnd");
    assert_eq!(s.camera.projection, Projection::Orthographic, "RenderMan's default projection");
    assert_eq!(s.camera.screen_window, Some([-4.0, 4.0, -2.0, 2.0]));
    let s = scene(
        "Format 64 32 1 FrameAspectRatio 0.5 Projection \"perspective\" WorldBegin Sphere 1 -1 1 360 WorldEnd",
    );
    assert_eq!(s.camera.projection, Projection::Perspective);
    assert_eq!(s.camera.screen_window, Some([-1.0, 1.0, -2.0, 2.0]));
    let s = scene(&world("Sphere 1 -1 1 360"));
    assert_eq!(s.camera.screen_window, None, "no ScreenWindow: the model's default");
}

#[test]
fn spot_lights_metal_and_the_default_surface() {
    let s = scene(&world(
        "LightSource \"spotlight\" 1 \"from\" [0 5 0] \"to\" [0 0 0] \"coneangle\" [0.5] \"conedeltaangle\" [0.1] \"beamdistribution\" [3] \"intensity\" [20]
         LightSource \"spotlight\" 2
         Surface \"metal\" \"roughness\" [0.3] Sphere 1 -1 1 360
         Surface \"shinymetal\" \"Ks\" [0.5] Sphere 1 -1 1 360
         Surface \"defaultsurface\" Sphere 1 -1 1 360",
    ));
    match s.lights[0] {
        Light::Spot { from, to, cone_angle, cone_delta, beam_distribution, intensity, .. } => {
            assert_eq!(
                (from, to, beam_distribution, intensity),
                ([0.0, 5.0, 0.0], [0.0; 3], 3.0, 20.0)
            );
            assert!((cone_angle - 0.5f32.to_degrees()).abs() < 1e-4, "radians become degrees");
            assert!((cone_delta - 0.1f32.to_degrees()).abs() < 1e-4);
        }
        ref other => panic!("{other:?}"),
    }
    // The Specification's defaults: 30 and 5 degrees, beam 2, from the origin down +z.
    match s.lights[1] {
        Light::Spot { from, to, cone_angle, cone_delta, beam_distribution, .. } => {
            assert_eq!((from, to, beam_distribution), ([0.0; 3], [0.0, 0.0, 1.0], 2.0));
            assert!((cone_angle - 30.0).abs() < 1e-4 && (cone_delta - 5.0).abs() < 1e-4);
        }
        ref other => panic!("{other:?}"),
    }
    assert_eq!(
        s.objects[0].material,
        Material::Metal { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, ks: 1.0, roughness: 0.3 }
    );
    assert_eq!(
        s.objects[1].material,
        Material::Metal { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, ks: 0.5, roughness: 0.1 }
    );
    assert_eq!(
        s.objects[2].material,
        Material::DefaultSurface { color: [1.0; 3], opacity: [1.0; 3], ka: 0.2, kd: 0.8 }
    );
}

#[test]
fn shading_rate_and_light_sets_are_per_object() {
    let s = scene(&world(
        "LightSource \"ambientlight\" 1 \"intensity\" [0.1]
         LightSource \"distantlight\" 2
         ShadingRate 4 Sphere 1 -1 1 360
         AttributeBegin
           ShadingRate 0.5 Illuminate 2 0
           LightSource \"pointlight\" \"lamp\" \"from\" [0 3 0]
           Sphere 1 -1 1 360
         AttributeEnd
         Sphere 1 -1 1 360
         Illuminate \"lamp\" 1 Sphere 1 -1 1 360",
    ));
    assert_eq!(s.hider.shading_rate, 4.0);
    let rates: Vec<Option<f32>> = s.objects.iter().map(|o| o.shading_rate).collect();
    assert_eq!(rates, [None, Some(0.5), None, None]);
    let lights: Vec<Option<Vec<u32>>> = s.objects.iter().map(|o| o.lights.clone()).collect();
    // The lamp, declared inside the attribute block, is off after it until Illuminate.
    assert_eq!(lights, [Some(vec![0, 1]), Some(vec![0, 2]), Some(vec![0, 1]), None]);
}

#[test]
fn geometric_approximation_flatness_is_per_object() {
    let s = scene(&world(
        "Sphere 1 -1 1 360
         AttributeBegin
           GeometricApproximation \"flatness\" 0.5
           Sphere 1 -1 1 360
           GeometricApproximation \"motionfactor\" 1
           Sphere 1 -1 1 360
         AttributeEnd
         Sphere 1 -1 1 360",
    ));
    let flatness: Vec<Option<f32>> = s.objects.iter().map(|o| o.flatness).collect();
    assert_eq!(flatness, [None, Some(0.5), Some(0.5), None]);
}

#[test]
fn geometric_approximation_motion_and_focus_factors_are_per_object() {
    let s = scene(&world(
        "Sphere 1 -1 1 360
         AttributeBegin
           GeometricApproximation \"motionfactor\" 1
           Sphere 1 -1 1 360
           GeometricApproximation \"FocusFactor\" 2.5
           Sphere 1 -1 1 360
         AttributeEnd
         Sphere 1 -1 1 360",
    ));
    let factors: Vec<(Option<f32>, Option<f32>)> =
        s.objects.iter().map(|o| (o.motion_factor, o.focus_factor)).collect();
    assert_eq!(factors, [(None, None), (Some(1.0), None), (Some(1.0), Some(2.5)), (None, None)]);
}

/// `U M G M^T V^T` of the Specification at `(u, v)`, written out for one coordinate: `m` as
/// RtBasis stores it (rows), `g` the 4 x 4 control values, `g[j][i]` at u-index i, v-index j.
fn spec_patch(m: &[[f64; 4]; 4], g: &[[f64; 4]; 4], u: f64, v: f64) -> f64 {
    let uu = [u * u * u, u * u, u, 1.0];
    let vv = [v * v * v, v * v, v, 1.0];
    // Row vector U M and V M; the patch is (U M) G^T (V M)^T with G indexed [u][v].
    let um: Vec<f64> = (0..4).map(|c| (0..4).map(|r| uu[r] * m[r][c]).sum()).collect();
    let vm: Vec<f64> = (0..4).map(|c| (0..4).map(|r| vv[r] * m[r][c]).sum()).collect();
    (0..4).map(|i| (0..4).map(|j| um[i] * g[j][i] * vm[j]).sum::<f64>()).sum()
}

#[test]
fn patch_meshes_take_the_current_basis_as_the_specification_evaluates_it() {
    // A 4 x 4 net with distinct heights, under b-spline by name and by its 16 numbers.
    let heights: Vec<f32> =
        (0..16).map(|k| ((k * 7) % 5) as f32 * 0.3 - (k / 4) as f32 * 0.1).collect();
    let mut pts = String::new();
    for j in 0..4 {
        for i in 0..4 {
            pts.push_str(&format!("{} {} {} ", i as f32, j as f32, heights[4 * j + i]));
        }
    }
    let bspline = [
        [-1.0 / 6.0, 3.0 / 6.0, -3.0 / 6.0, 1.0 / 6.0],
        [3.0 / 6.0, -6.0 / 6.0, 3.0 / 6.0, 0.0],
        [-3.0 / 6.0, 0.0, 3.0 / 6.0, 0.0],
        [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    ];
    let as_numbers: String = bspline.iter().flatten().map(|x: &f64| format!("{x} ")).collect();
    for basis in
        ["\"b-spline\" 1 \"b-spline\" 1".to_string(), format!("[{as_numbers}] 1 [{as_numbers}] 1")]
    {
        let s = scene(&world(&format!(
            "Basis {basis} PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"nonperiodic\" \"P\" [{pts}]"
        )));
        let shape = &s.objects[0].shape;
        match shape {
            Shape::PatchMesh { ubasis, ustep, vstep, .. } => {
                assert!(matches!(ubasis, Basis::BSpline | Basis::Matrix(_)));
                assert_eq!((*ustep, *vstep), (Some(1), Some(1)));
            }
            other => panic!("{other:?}"),
        }
        let patches = reyes_scene::patches::bezier_patches(shape, None);
        assert_eq!(patches.len(), 1);
        let g: [[f64; 4]; 4] =
            std::array::from_fn(|j| std::array::from_fn(|i| f64::from(heights[4 * j + i])));
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.9, 0.1)] {
            let z = patches[0].eval(u, v).p.z;
            let want = spec_patch(&bspline, &g, u, v);
            assert!((z - want).abs() < 1e-5, "{basis} at ({u}, {v}): {z} vs {want}");
        }
    }
}

#[test]
fn hyperboloids_and_nurbs_keep_their_parameters() {
    let s = scene(&world(
        "Hyperboloid 1 0 -1 0.5 0.5 1 270
         NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1  2 0 0 2  0 1 0 1  1 1 0 1]",
    ));
    assert_eq!(
        s.objects[0].shape,
        Shape::Hyperboloid { point1: [1.0, 0.0, -1.0], point2: [0.5, 0.5, 1.0], thetamax: 270.0 }
    );
    match &s.objects[1].shape {
        Shape::NuPatch { nu, uorder, uknot, points, .. } => {
            assert_eq!((*nu, *uorder, uknot.clone()), (2, 2, vec![0.0, 0.0, 1.0, 1.0]));
            assert_eq!(points[1], [2.0, 0.0, 0.0, 2.0], "homogeneous Pw as written");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn deforming_patch_meshes_keep_their_topology() {
    let s = scene(
        "Projection \"perspective\" Shutter 0 1 WorldBegin Translate 0 0 5
         MotionBegin [0 1]
           Patch \"bicubic\" \"P\" [0 0 0 1 0 0 2 0 0 3 0 0  0 1 0 1 1 0 2 1 0 3 1 0  0 2 0 1 2 0 2 2 0 3 2 0  0 3 0 1 3 0 2 3 0 3 3 0]
           Patch \"bicubic\" \"P\" [0 0 1 1 0 0 2 0 0 3 0 0  0 1 0 1 1 0 2 1 0 3 1 0  0 2 0 1 2 0 2 2 0 3 2 0  0 3 0 1 3 0 2 3 0 3 3 0]
         MotionEnd
         WorldEnd",
    );
    let d = &s.objects[0].deform;
    assert_eq!(d.len(), 2);
    assert_eq!((d[0].points[0], d[1].points[0]), ([0.0; 3], [0.0, 0.0, 1.0]));
}

/// Summed alpha of a render: the covered area in pixels.
fn coverage(text: &str) -> f64 {
    let s = scene(text);
    let film = render(&s, &RenderOptions::default()).unwrap().film;
    film.rgba().iter().map(|p| f64::from(p[3])).sum()
}

// Under an orthographic camera with ScreenWindow -2 2 -2 2 on 64 x 64 pixels a unit is 16
// pixels whatever the depth, so a silhouette's area in pixels is exact: 256 times its area
// in the plane. Tolerance: the pixels the outline cuts (fewer than 260 here) each carry a
// stratified 4 x 4 estimate of standard deviation at most sqrt(7)/32 = 0.083, so the sum's
// deviation is at most 0.083 sqrt(260) = 1.3 px^2; the flat micropolygons (about a pixel at
// shading rate 1) cut each curved outline by at most its sagitta, L^2 / 8R = 1/128 px for
// R = 16 px, under 1 px^2 along the longest outline. 6 px^2 is four deviations plus that.
const TOLERANCE: f64 = 6.0;

fn ortho(body: &str) -> String {
    format!(
        "Format 64 64 1 ScreenWindow -2 2 -2 2 PixelSamples 4 4 PixelFilter \"box\" 1 1
         WorldBegin Translate 0 0 5 {body} WorldEnd"
    )
}

#[test]
fn quadric_silhouettes_cover_their_exact_areas() {
    let px = 256.0;
    let pi = std::f64::consts::PI;
    let cases = [
        ("sphere", "Sphere 1 -1 1 360", pi * px),
        ("disk", "Disk 0 1.5 360", pi * 2.25 * px),
        ("half disk", "Disk 0 1.5 180", pi * 2.25 / 2.0 * px),
        // Side-on: the cylinder is a 2 x 2 rectangle, the cone a triangle of base 2 and
        // height 1.5, the paraboloid the region under r = sqrt(z/1.5) (area 4/3 r h).
        ("cylinder", "Rotate 90 1 0 0 Cylinder 1 -1 1 360", 4.0 * px),
        ("cone", "Rotate -90 1 0 0 Translate 0 0 -0.75 Cone 1.5 1 360", 1.5 * px),
        (
            "paraboloid",
            "Rotate -90 1 0 0 Translate 0 0 -0.75 Paraboloid 1 0 1.5 360",
            4.0 / 3.0 * 1.5 * px,
        ),
        // Face-on, the torus is an annulus between R - r and R + r.
        ("torus", "Torus 1.2 0.4 0 360 360", pi * (1.6f64.powi(2) - 0.8f64.powi(2)) * px),
        // A hyperboloid of two equal radii is a cylinder.
        ("hyperboloid", "Rotate 90 1 0 0 Hyperboloid 1 0 -1 1 0 1 360", 4.0 * px),
    ];
    let mut report = Vec::new();
    for (what, body, area) in cases {
        let got = coverage(&ortho(body));
        report.push(format!("{what} {:+.2}", got - area));
        assert!((got - area).abs() < TOLERANCE, "{what}: {got:.2} px^2 against {area:.2}");
    }
    eprintln!("coverage minus exact area, px^2: {}", report.join(", "));
}
