//! Each supported request, mapped onto the scene model: the values land where the model
//! expects them, with RenderMan's conventions (camera space as the world, row-vector
//! matrices, transformations applied object side first, motion fitted to the shutter).

use glam::{DVec3, Vec3};
use reyes_scene::{
    Csg, Faces, FilterKind, HiderMethod, Light, Material, Object, Scene, Shape, object_to_world,
};

use super::{rib, scene, world};

/// Where the object's transform at shutter open takes the object-space point `p`.
fn place(o: &Object, p: [f32; 3]) -> Vec3 {
    object_to_world(&o.transform).project_point3(Vec3::from(p))
}

fn close(a: Vec3, b: [f32; 3]) -> bool {
    (a - Vec3::from(b)).length() < 1e-5
}

#[test]
fn options_land_in_image_camera_and_hider() {
    let s = scene(
        "Format 320 200 1
         Projection \"perspective\" \"fov\" [35]
         Clipping 0.5 200
         Shutter 0.25 0.75
         DepthOfField 4 0.5 10
         PixelSamples 3 5
         PixelFilter \"catmull-rom\" 3 2
         Hider \"raytrace\" \"jitter\" [0]
         Option \"limits\" \"bucketsize\" [32 8]
         Option \"limits\" \"gridsize\" [64]
         WorldBegin Sphere 1 -1 1 360 WorldEnd",
    );
    assert_eq!((s.image.width, s.image.height), (320, 200));
    assert_eq!(s.camera.fov, 35.0);
    assert_eq!((s.camera.hither, s.camera.yon), (0.5, 200.0));
    assert_eq!((s.camera.shutter.open, s.camera.shutter.close), (0.25, 0.75));
    let lens = s.camera.lens.unwrap();
    assert_eq!((lens.f_stop, lens.focal_length, lens.focal_distance), (4.0, 0.5, 10.0));
    assert_eq!(s.hider.pixel_samples, (3, 5));
    assert_eq!(s.hider.filter.kind, FilterKind::RiCatmullRom);
    assert_eq!((s.hider.filter.width, s.hider.filter.y_width()), (3.0, 2.0));
    assert_eq!(s.hider.method, HiderMethod::RayTrace);
    assert!(!s.hider.jitter);
    assert_eq!(s.hider.bucket_size, (32, 8));
    assert_eq!(s.hider.max_grid_size, 64);
    // The camera is the model's canonical one: RenderMan's camera space is the world.
    assert_eq!(
        (s.camera.eye, s.camera.look_at, s.camera.up),
        ([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0])
    );
}

#[test]
fn the_specification_defaults_apply() {
    let s = scene("Projection \"perspective\" WorldBegin Sphere 1 -1 1 360 WorldEnd");
    assert_eq!((s.image.width, s.image.height), (640, 480));
    assert_eq!(s.camera.fov, 90.0);
    assert_eq!(s.hider.pixel_samples, (2, 2));
    assert_eq!(s.hider.filter.kind, FilterKind::RiGaussian);
    assert_eq!((s.hider.filter.width, s.hider.filter.y_width()), (2.0, 2.0));
    assert!(s.camera.lens.is_none());
    assert_eq!(s.camera.shutter.open, s.camera.shutter.close);
}

#[test]
fn the_camera_transformation_places_the_world_in_camera_space() {
    // Camera 5 units back, turned 90 degrees about y: the world origin is 5 ahead, and the
    // world's +x axis turns as RenderMan's Rotate turns it.
    let s = scene(
        "Format 64 48 1 Projection \"perspective\" \"fov\" [40]
         Translate 0 0 5 Rotate 90 0 1 0
         WorldBegin
           Translate 1 0 0 Sphere 0.5 -0.5 0.5 360
         WorldEnd",
    );
    let o = &s.objects[0];
    let p = place(o, [0.0; 3]);
    // Rotate 90 about y takes +x to -z (right-hand rule matrix), so the sphere sits at
    // z = 5 - 1 = 4.
    assert!(close(p, [0.0, 0.0, 4.0]), "{p}");
}

#[test]
fn transformations_apply_object_side_first_and_blocks_restore_them() {
    let s = scene(&world(
        "Translate 0 0 10
         TransformBegin
           Rotate 90 0 0 1 Translate 2 0 0
           Sphere 1 -1 1 360
         TransformEnd
         AttributeBegin
           Scale 2 2 2 Sphere 1 -1 1 360
         AttributeEnd
         ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  0 3 0 1]
         Sphere 1 -1 1 360
         Identity Translate 0 0 7 Sphere 1 -1 1 360
         Transform [1 0 0 0  0 1 0 0  0 0 1 0  1 1 20 1] Sphere 1 -1 1 360",
    ));
    // Translate 2 first, then Rotate 90 about z: (2, 0) -> (0, 2); then z + 10.
    assert!(close(place(&s.objects[0], [0.0; 3]), [0.0, 2.0, 10.0]));
    assert!(close(place(&s.objects[1], [1.0, 0.0, 0.0]), [2.0, 0.0, 10.0]));
    // The row-vector matrix's last row is a translation, applied before Translate 0 0 10.
    assert!(close(place(&s.objects[2], [0.0; 3]), [0.0, 3.0, 10.0]));
    assert!(close(place(&s.objects[3], [0.0; 3]), [0.0, 0.0, 7.0]));
    assert!(close(place(&s.objects[4], [0.0; 3]), [1.0, 1.0, 20.0]));
}

#[test]
fn quadrics_keep_every_parameter() {
    let s = scene(&world(
        "Translate 0 0 10
         Sphere 2 -1 1.5 300
         Cylinder 1 -1 2 180
         Cone 2 0.5 270
         Disk 0.5 1.5 90
         Paraboloid 1 0.2 2 360
         Torus 2 0.5 -90 90 320
         Sphere 1 -5 5 360",
    ));
    let shapes: Vec<&Shape> = s.objects.iter().map(|o| &o.shape).collect();
    assert_eq!(
        *shapes[0],
        Shape::Sphere { radius: 2.0, zmin: Some(-1.0), zmax: Some(1.5), thetamax: 300.0 }
    );
    assert_eq!(*shapes[1], Shape::Cylinder { radius: 1.0, zmin: -1.0, zmax: 2.0, thetamax: 180.0 });
    assert_eq!(*shapes[2], Shape::Cone { height: 2.0, radius: 0.5, thetamax: 270.0 });
    assert_eq!(*shapes[3], Shape::Disk { height: 0.5, radius: 1.5, thetamax: 90.0 });
    assert_eq!(*shapes[4], Shape::Paraboloid { rmax: 1.0, zmin: 0.2, zmax: 2.0, thetamax: 360.0 });
    assert_eq!(
        *shapes[5],
        Shape::Torus {
            major_radius: 2.0,
            minor_radius: 0.5,
            phimin: -90.0,
            phimax: 90.0,
            thetamax: 320.0
        }
    );
    // Cuts beyond the sphere are clamped to it, as RenderMan does.
    assert_eq!(*shapes[6], Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 });
}

#[test]
fn polygons_of_any_shape_become_triangles_and_quads_over_their_own_points() {
    let s = scene(&world(
        "Translate 0 0 5
         Polygon \"P\" [0 0 0  1 0 0  1 1 0  0 1 0]
         Polygon \"P\" [0 0 0  2 0 0  2 1 0  1 1 0  1 2 0  0 2 0]
         GeneralPolygon [4 4] \"P\" [0 0 0 4 0 0 4 4 0 0 4 0  1 1 0 1 3 0 3 3 0 3 1 0]
         PointsPolygons [3 3] [0 1 2  0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]",
    ));
    let faces = |o: &Object| match &o.shape {
        Shape::Mesh { faces, points, .. } => (Vec::<Vec<u32>>::from(faces), points.len()),
        other => panic!("{other:?}"),
    };
    assert_eq!(faces(&s.objects[0]), (vec![vec![0, 1, 2, 3]], 4));
    let (l, n) = faces(&s.objects[1]);
    assert_eq!((l.len(), n), (4, 6), "an L hexagon: four triangles over its six points");
    let (holed, n) = faces(&s.objects[2]);
    assert_eq!(n, 8);
    assert!(holed.iter().all(|f| f.len() == 3) && holed.len() == 8, "{holed:?}");
    assert_eq!(faces(&s.objects[3]), (vec![vec![0, 1, 2], vec![0, 2, 3]], 4));
}

#[test]
fn colours_of_every_class() {
    let s = scene(&world(
        "Translate 0 0 5
         Color [0.5 0.5 0.5]
         PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]
           \"varying color Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]
         PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]
           \"uniform color Cs\" [1 0 0  0 0 1]
         Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"constant color Cs\" [0.2 0.3 0.4]",
    ));
    match &s.objects[0].shape {
        Shape::Mesh { colors: Some(c), .. } => assert_eq!(c[1], [0.0, 1.0, 0.0]),
        other => panic!("{other:?}"),
    }
    match &s.objects[1].shape {
        // Per-face colours: each face gets its own three vertices.
        Shape::Mesh { colors: Some(c), points, faces, .. } => {
            assert_eq!(
                (points.len(), faces),
                (6, &Faces::from(vec![vec![0, 1, 2], vec![3, 4, 5]]))
            );
            assert_eq!((c[0], c[5]), ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]));
        }
        other => panic!("{other:?}"),
    }
    // No Surface: RenderMan's defaultsurface, on the constant colour.
    assert_eq!(
        s.objects[2].material,
        Material::DefaultSurface { color: [0.2, 0.3, 0.4], opacity: [1.0; 3], ka: 0.2, kd: 0.8 }
    );
}

#[test]
fn face_varying_colours_unweld_each_face_outline_first_then_its_holes() {
    // A square with a square hole, then a triangle on two of its corners.
    let cs: Vec<String> = (0..11).map(|k| format!("{} 0 1", k as f32 / 8.0)).collect();
    let s = scene(&world(&format!(
        "Translate 0 0 5
         PointsGeneralPolygons [2 1] [4 4 3] [0 1 2 3  4 5 6 7  0 1 8]
           \"P\" [0 0 0 4 0 0 4 4 0 0 4 0  1 1 0 1 3 0 3 3 0 3 1 0  2 -2 0]
           \"facevarying color Cs\" [{}]
         PointsGeneralPolygons [1 1] [3 4] [0 1 2  1 3 4 2] \"P\" [0 0 0 1 0 0 1 1 0 2 0 0 2 1 0]",
        cs.join("  ")
    )));
    let Shape::Mesh { points, faces, colors: Some(colors), .. } = &s.objects[0].shape else {
        panic!("{:?}", s.objects[0].shape)
    };
    let original = [[0, 0], [4, 0], [4, 4], [0, 4], [1, 1], [1, 3], [3, 3], [3, 1], [2, -2]];
    let corner_of = [0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 8];
    assert_eq!(points.len(), 11, "one vertex per face-vertex");
    for (k, &c) in corner_of.iter().enumerate() {
        let [x, y] = original[c].map(|v| v as f32);
        assert_eq!((points[k], colors[k]), ([x, y, 0.0], [k as f32 / 8.0, 0.0, 1.0]), "{k}");
    }
    // The holed square: eight triangles over its own eight vertices; the triangle as it is.
    assert_eq!(faces.len(), 9, "{faces:?}");
    assert!(faces.iter().take(8).all(|f| f.len() == 3 && f.iter().all(|&i| i < 8)), "{faces:?}");
    assert_eq!(&faces[8], &[8, 9, 10]);
    // Triangles and quads without holes are kept as they are.
    match &s.objects[1].shape {
        Shape::Mesh { faces, colors: None, .. } => {
            assert_eq!(*faces, Faces::from(vec![vec![0, 1, 2], vec![1, 3, 4, 2]]));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn standard_shaders_and_their_parameters() {
    let s = scene(&world(
        "LightSource \"ambientlight\" 1 \"intensity\" [0.2] \"lightcolor\" [1 0.5 0.5]
         LightSource \"distantlight\" 2 \"from\" [0 0 0] \"to\" [0 0 1]
         Translate 0 0 5
         LightSource \"pointlight\" 3 \"from\" [1 2 3] \"intensity\" [7]
         Color [0.1 0.2 0.3] Opacity [0.5 0.5 0.5]
         Surface \"plastic\" \"Ka\" [0.5] \"Kd\" [0.6] \"Ks\" [0.7] \"roughness\" [0.2] \"specularcolor\" [1 0 0]
         Sphere 1 -1 1 360
         Surface \"matte\" \"Kd\" [0.25] Sphere 1 -1 1 360
         Surface \"constant\" Sphere 1 -1 1 360
         Surface \"plastic\" Sphere 1 -1 1 360",
    ));
    assert_eq!(s.lights[0], Light::Ambient { color: [1.0, 0.5, 0.5], intensity: 0.2 });
    assert_eq!(
        s.lights[1],
        Light::Distant {
            from: [0.0; 3],
            to: [0.0, 0.0, 1.0],
            color: [1.0; 3],
            intensity: 1.0,
            shadows: false
        }
    );
    // The point light's "from" is in the current space: Translate 0 0 5 moves it.
    assert_eq!(
        s.lights[2],
        Light::Point { from: [1.0, 2.0, 8.0], color: [1.0; 3], intensity: 7.0, shadows: false }
    );
    assert_eq!(
        s.objects[0].material,
        Material::Plastic {
            color: [0.1, 0.2, 0.3],
            opacity: [0.5; 3],
            ka: 0.5,
            kd: 0.6,
            ks: 0.7,
            roughness: 0.2,
            specular_color: [1.0, 0.0, 0.0]
        }
    );
    assert_eq!(
        s.objects[1].material,
        Material::Matte { color: [0.1, 0.2, 0.3], opacity: [0.5; 3], ka: 1.0, kd: 0.25 }
    );
    assert_eq!(
        s.objects[2].material,
        Material::Constant { color: [0.1, 0.2, 0.3], opacity: [0.5; 3] }
    );
    // The Specification's defaults of plastic.
    match s.objects[3].material {
        Material::Plastic { ka, kd, ks, roughness, specular_color, .. } => {
            assert_eq!((ka, kd, ks, roughness, specular_color), (1.0, 0.5, 0.5, 0.1, [1.0; 3]));
        }
        ref other => panic!("{other:?}"),
    }
}

#[test]
fn unknown_shaders_stand_in_with_one_warning_and_fail_when_strict() {
    let text = world("Surface \"wood\" Sphere 1 -1 1 360 Sphere 1 -1 1 360");
    let loaded = rib(&text).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(w.iter().filter(|m| m.contains("\"wood\"")).count(), 1, "{w:?}");
    assert!(w[0].starts_with("test.rib:4:1: warning: Surface: unknown shader \"wood\""), "{w:?}");
    assert!(matches!(loaded.frames[0].scene.objects[0].material, Material::Plastic { .. }));
    let strict = reyes_rib::load(
        reyes_rib::Source::from_bytes("test.rib", text.into_bytes()),
        &reyes_rib::RiOptions { strict: true, ..Default::default() },
    );
    assert_eq!(
        strict.unwrap_err().to_string(),
        "test.rib:4:1: Surface: unknown surface shader \"wood\" (--strict)"
    );
}

#[test]
fn motion_blocks_become_keys_fitted_to_the_shutter() {
    let s = scene(
        "Format 64 48 1 Projection \"perspective\" \"fov\" [40] Shutter 0 1
         WorldBegin
           Translate 0 0 10
           MotionBegin [0 2] Translate 0 0 0 Translate 4 0 0 MotionEnd
           Sphere 1 -1 1 360
           MotionBegin [0 1]
             Polygon \"P\" [0 0 0 1 0 0 1 1 0]
             Polygon \"P\" [0 0 0 1 0 0 1 2 0]
           MotionEnd
         WorldEnd",
    );
    let o = &s.objects[0];
    // Keys at 0 and 2 seen through the shutter [0, 1]: at 1 it has moved half way.
    assert_eq!(o.motion.len(), 2);
    assert_eq!((o.motion[0].time, o.motion[1].time), (0.0, 1.0));
    let at = |k: usize| object_to_world(&o.motion[k].transform).project_point3(Vec3::ZERO);
    assert!(
        close(at(0), [0.0, 0.0, 10.0]) && close(at(1), [2.0, 0.0, 10.0]),
        "{} {}",
        at(0),
        at(1)
    );
    let d = &s.objects[1].deform;
    assert_eq!(d.len(), 2);
    assert_eq!((d[0].time, d[1].time, d[1].points[2]), (0.0, 1.0, [1.0, 2.0, 0.0]));
}

#[test]
fn a_moving_camera_becomes_camera_keys() {
    let s = scene(
        "Format 64 48 1 Projection \"perspective\" \"fov\" [40] Shutter 0 1
         MotionBegin [0 1] Translate 0 0 0 Translate -1 0 0 MotionEnd
         WorldBegin Translate 0 0 5 Sphere 1 -1 1 360 WorldEnd",
    );
    let m = &s.camera.motion;
    assert_eq!(m.len(), 2);
    assert_eq!(m[0].eye, [0.0; 3]);
    // The world moves -1 in x relative to the camera: the camera moves +1.
    assert!((Vec3::from(m[1].eye) - Vec3::X).length() < 1e-6, "{:?}", m[1].eye);
    assert!((Vec3::from(m[1].look_at) - Vec3::new(1.0, 0.0, 1.0)).length() < 1e-6);
}

#[test]
fn solids_become_csg_trees_over_named_leaves() {
    let s = scene(&world(
        "Translate 0 0 8
         Attribute \"identifier\" \"name\" [\"bite\"]
         SolidBegin \"difference\"
           SolidBegin \"primitive\" Sphere 1.4 -1.4 1.4 360 SolidEnd
           SolidBegin \"union\"
             SolidBegin \"primitive\" Translate 0.5 0.5 -1 Sphere 1 -1 1 360 SolidEnd
             SolidBegin \"primitive\" Translate -0.5 0.5 -1 Sphere 1 -1 1 360 SolidEnd
           SolidEnd
         SolidEnd
         SolidBegin \"primitive\" Sphere 1 -1 1 360 SolidEnd",
    ));
    assert_eq!(s.solids.len(), 1);
    assert_eq!(s.solids[0].name, "bite");
    let Csg::Difference(a, b) = &s.solids[0].tree else { panic!("{:?}", s.solids[0].tree) };
    let Csg::Object(first) = a.as_ref() else { panic!() };
    let Csg::Union(rest) = b.as_ref() else { panic!() };
    assert_eq!(rest.len(), 2);
    assert!(s.objects.iter().any(|o| &o.name == first));
    // The lone primitive solid at the end is an ordinary object.
    assert_eq!(s.objects.len(), 4);
}

#[test]
fn instances_replay_their_definition_under_the_current_transformation() {
    let s = scene(&world(
        "ObjectBegin 1 Translate 1 0 0 Sphere 0.5 -0.5 0.5 360 ObjectEnd
         ObjectBegin \"pair\" ObjectInstance 1 Translate 0 1 0 ObjectInstance 1 ObjectEnd
         Translate 0 0 10 ObjectInstance \"pair\"
         Translate 0 0 5 ObjectInstance 1",
    ));
    let at: Vec<Vec3> = s.objects.iter().map(|o| place(o, [0.0; 3])).collect();
    assert_eq!(at.len(), 3);
    assert!(
        close(at[0], [1.0, 0.0, 10.0])
            && close(at[1], [1.0, 1.0, 10.0])
            && close(at[2], [1.0, 0.0, 15.0]),
        "{at:?}"
    );
}

#[test]
fn frames_render_one_scene_each_and_restore_their_options() {
    let text = "Format 64 48 1 Projection \"perspective\" \"fov\" [40]
        FrameBegin 1 PixelSamples 4 4 WorldBegin Sphere 1 -1 1 360 WorldEnd FrameEnd
        FrameBegin 2 WorldBegin Translate 0 0 3 Sphere 1 -1 1 360 WorldEnd FrameEnd
        FrameBegin 3 Format 32 32 1 WorldBegin Sphere 1 -1 1 360 WorldEnd FrameEnd";
    let all = rib(text).unwrap();
    let numbers: Vec<Option<i32>> = all.frames.iter().map(|f| f.number).collect();
    assert_eq!(numbers, [Some(1), Some(2), Some(3)]);
    assert_eq!(all.frames[0].scene.hider.pixel_samples, (4, 4));
    assert_eq!(all.frames[1].scene.hider.pixel_samples, (2, 2), "FrameEnd restores the options");
    assert_eq!(all.frames[2].scene.image.width, 32);
    let some = reyes_rib::load(
        reyes_rib::Source::from_bytes("t.rib", text.as_bytes().to_vec()),
        &reyes_rib::RiOptions { frames: Some(vec![(2, 3)]), ..Default::default() },
    )
    .unwrap();
    assert_eq!(some.frames.iter().map(|f| f.number).collect::<Vec<_>>(), [Some(2), Some(3)]);
}

#[test]
fn coordinate_systems_and_attributes() {
    let s = scene(&world(
        "Translate 0 0 9 CoordinateSystem \"table\" Identity
         CoordSysTransform \"table\" Matte 1
         Attribute \"identifier\" \"name\" [\"ball\"] Sphere 1 -1 1 360",
    ));
    let o = &s.objects[0];
    assert!(close(place(o, [0.0; 3]), [0.0, 0.0, 9.0]));
    assert!(o.matte);
    assert_eq!(o.name, "ball");
}

#[test]
fn archives_are_read_relative_to_the_including_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("parts")).unwrap();
    std::fs::write(dir.path().join("parts/ball.rib"), "Sphere 1 -1 1 360\n").unwrap();
    std::fs::write(
        dir.path().join("lamp.rib"),
        "Procedural \"DelayedReadArchive\" [\"parts/ball.rib\"] [-1 1 -1 1 -1 1]\n",
    )
    .unwrap();
    let main = dir.path().join("main.rib");
    std::fs::write(
        &main,
        world("Translate 0 0 5 ReadArchive \"parts/ball.rib\" ReadArchive \"lamp.rib\""),
    )
    .unwrap();
    let loaded = reyes_rib::load_scene_file(&main, &Default::default()).unwrap();
    assert_eq!(loaded.frames[0].scene.objects.len(), 2);
}

#[test]
fn the_same_scene_from_ron_and_from_rib_is_the_same_model() {
    let from_rib = scene(
        "Format 64 48 1 Projection \"perspective\" \"fov\" [40] PixelSamples 4 4
         PixelFilter \"box\" 1 1 Clipping 0.1 1000 Shutter 0 1
         WorldBegin
           LightSource \"ambientlight\" 1 \"intensity\" [0.15]
           Surface \"matte\" Color [0.5 0.25 1] Translate 0 0 10 Sphere 1 -1 1 360
         WorldEnd",
    );
    let from_ron = reyes_scene::parse(
        "Scene(image: (width: 64, height: 48),
           camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0), fov: 40.0, hither: 0.1, yon: 1000.0),
           hider: (pixel_samples: (4, 4), filter: (kind: RiBox, width: 1.0, height: Some(1.0))),
           lights: [Ambient(intensity: 0.15)],
           objects: [(shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.25, 1.0)),
                      transform: [Translate((0.0, 0.0, 10.0))])])",
        std::path::Path::new("t.ron"),
    )
    .unwrap();
    // The transforms are the same map (one as a matrix), everything else equal.
    let p = DVec3::new(0.3, -0.2, 0.7);
    let m = |s: &Scene| object_to_world(&s.objects[0].transform).as_dmat4().transform_point3(p);
    assert!((m(&from_rib) - m(&from_ron)).length() < 1e-6);
    let mut a = from_rib.clone();
    a.objects[0].transform = from_ron.objects[0].transform.clone();
    assert_eq!(a, from_ron);
}

#[test]
fn the_worked_example_of_docs_rib_md_loads_without_a_warning() {
    let doc = include_str!("../../../../docs/rib.md");
    let example = doc.split("### A worked example").nth(1).expect("the worked example");
    let block = example.split("```rib\n").nth(1).and_then(|b| b.split("```").next()).unwrap();
    let loaded = rib(block).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let s = &loaded.frames[0].scene;
    assert_eq!((s.objects.len(), s.lights.len()), (2, 2));
    match s.lights[1] {
        Light::Spot { cone_angle, .. } => assert!((cone_angle - 22.918).abs() < 1e-3),
        ref other => panic!("{other:?}"),
    }
}

#[test]
fn display_lines_with_output_variables_become_aov_layers() {
    use reyes_scene::{AovFilter, AovSource};
    let text = format!(
        "Display \"main.exr\" \"openexr\" \"rgba\"\n\
         Display \"+n.exr\" \"openexr\" \"varying normal N\"\n\
         Display \"+id.exr\" \"openexr\" \"id\" \"string filter\" \"nearest\"\n\
         Display \"+depth.exr\" \"openexr\" \"z\" \"string filter\" \"min\"\n\
         Display \"+diffuse.exr\" \"openexr\" \"color __diffuse\" \"string filter\" \"gaussian\"\n\
         Display \"+copy.png\" \"file\" \"rgba\"\n{}",
        world("Sphere 1 -1 1 360")
    );
    let loaded = rib(&text).unwrap_or_else(|e| panic!("{e}"));
    let frame = &loaded.frames[0];
    let aovs: Vec<_> = frame.scene.outputs.aovs.iter().map(|a| (a.source, a.filter)).collect();
    assert_eq!(
        aovs,
        [
            (AovSource::N, None),
            (AovSource::ObjectId, Some(AovFilter::Nearest)),
            (AovSource::Z, Some(AovFilter::Min)),
            (AovSource::Diffuse, None),
        ]
    );
    // Only the image display is an extra file; the variables are layers of the main output.
    let extras: Vec<_> =
        frame.displays.iter().filter(|d| d.extra).map(|d| d.name.as_str()).collect();
    assert_eq!(extras, ["copy.png"]);
}

/// The cube of side 2 as RIB's `nvertices vertices P` of a `SubdivisionMesh`.
const CUBE: &str = "[4 4 4 4 4 4] [0 2 3 1 4 5 7 6 0 1 5 4 2 6 7 3 0 4 6 2 1 3 7 5]
    \"P\" [-1 -1 -1 1 -1 -1 -1 1 -1 1 1 -1 -1 -1 1 1 -1 1 -1 1 1 1 1 1]";

#[test]
fn a_subdivision_mesh_keeps_its_faces_tags_and_primitive_variables() {
    use reyes_scene::SubdivTag;
    let cube = CUBE.split_once(" \"P\"").unwrap();
    let text = world(&format!(
        "Translate 0 0 6
         SubdivisionMesh \"catmull-clark\" {}
           [\"crease\" \"crease\" \"corner\" \"hole\" \"interpolateboundary\" \"creasemethod\"]
           [3 1  3 2  2 2  1 0  0 0  0 0]
           [0 1 3  4 5 7  6 2  5]
           [2.5  1 4  0.5 3]
           \"P\" {}
           \"vertex color Cs\" [0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1]
           \"facevarying float[2] st\" [{}]",
        cube.0,
        cube.1,
        (0..24).map(|i| format!("{} 0", i)).collect::<Vec<_>>().join(" ")
    ));
    let loaded = rib(&text).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("SubdivisionMesh: tag \"creasemethod\" is not supported"), "{w:?}");
    let s = &loaded.frames[0].scene;
    let Shape::SubdivisionMesh { points, faces, tags, colors, st } = &s.objects[0].shape else {
        panic!("{:?}", s.objects[0].shape)
    };
    assert_eq!(points.len(), 8);
    assert_eq!(points[7], [1.0, 1.0, 1.0]);
    assert_eq!(faces.get(1), Some(&[4, 5, 7, 6][..]));
    assert_eq!(
        tags,
        &vec![
            // One sharpness for the chain.
            SubdivTag::Crease { vertices: vec![0, 1, 3], sharpness: 2.5 },
            // One sharpness per edge: one crease per edge of its own sharpness.
            SubdivTag::Crease { vertices: vec![4, 5], sharpness: 1.0 },
            SubdivTag::Crease { vertices: vec![5, 7], sharpness: 4.0 },
            // One sharpness per corner point.
            SubdivTag::Corner { vertices: vec![6], sharpness: 0.5 },
            SubdivTag::Corner { vertices: vec![2], sharpness: 3.0 },
            SubdivTag::Hole { faces: vec![5] },
            SubdivTag::InterpolateBoundary,
        ]
    );
    assert_eq!(colors.as_ref().map(|c| c[3]), Some([1.0, 1.0, 0.0]));
    let st = st.as_ref().unwrap();
    assert_eq!((st.len(), st[23]), (24, [23.0, 0.0]));
}

#[test]
fn subdivision_mesh_st_and_cs_of_other_classes() {
    // Vertex st is gathered to the face corners; per-face Cs is ignored with a warning; a
    // constant Cs is the material colour.
    let cube = CUBE.split_once(" \"P\"").unwrap();
    let text = world(&format!(
        "SubdivisionMesh \"catmull-clark\" {} \"P\" {} \"vertex float[2] st\" [{}] \"uniform color Cs\" [{}]
         SubdivisionMesh \"catmull-clark\" {} \"P\" {} \"constant color Cs\" [0.25 0.5 1]",
        cube.0,
        cube.1,
        (0..8).map(|i| format!("{i} {}", 10 * i)).collect::<Vec<_>>().join(" "),
        ["1 0 0"; 6].join(" "),
        cube.0,
        cube.1,
    ));
    let loaded = rib(&text).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w.iter().any(|m| m.contains("\"st\" of class vertex: interpolated bilinearly")),
        "{w:?}"
    );
    assert!(w.iter().any(|m| m.contains("\"Cs\" of class uniform is not supported")), "{w:?}");
    let s = &loaded.frames[0].scene;
    let Shape::SubdivisionMesh { st: Some(st), colors: None, .. } = &s.objects[0].shape else {
        panic!("{:?}", s.objects[0].shape)
    };
    // Face 1 is [4 5 7 6]: its corners take those points' st.
    assert_eq!(&st[4..8], &[[4.0, 40.0], [5.0, 50.0], [7.0, 70.0], [6.0, 60.0]]);
    match &s.objects[1].material {
        Material::DefaultSurface { color, .. } => assert_eq!(*color, [0.25, 0.5, 1.0]),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_subdivision_mesh_in_a_motion_block_deforms_and_other_schemes_are_skipped() {
    let cube = CUBE.split_once(" \"P\"").unwrap();
    let moved: String = cube.1.replace("1 1 1]", "1 1 3]");
    let text = format!(
        "Shutter 0 1\n{}",
        world(&format!(
            "MotionBegin [0 1]
               SubdivisionMesh \"catmull-clark\" {0} \"P\" {1}
               SubdivisionMesh \"catmull-clark\" {0} \"P\" {2}
             MotionEnd
             SubdivisionMesh \"loop\" [3] [0 1 2] \"P\" [0 0 0 1 0 0 0 1 0]",
            cube.0, cube.1, moved
        ))
    );
    let loaded = rib(&text).unwrap();
    let w: Vec<String> = loaded.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("SubdivisionMesh: scheme \"loop\" is not supported"), "{w:?}");
    let s = &loaded.frames[0].scene;
    assert_eq!(s.objects.len(), 1);
    let d = &s.objects[0].deform;
    assert_eq!(d.len(), 2);
    assert_eq!((d[0].points[7], d[1].points[7]), ([1.0, 1.0, 1.0], [1.0, 1.0, 3.0]));
}

/// Vertex (or varying) `N` and `st` of a polygon mesh become the model mesh's per-point
/// `normals` and `st`, value for value and unwarned; per-face colours unweld the points, so
/// then they are dropped with a warning naming the variable; facevarying `st` is warned of.
#[test]
fn polygon_normals_and_st_map_onto_the_mesh() {
    let loaded = rib(&world(
        "PointsPolygons [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]
           \"N\" [0 0 -1  0.1 0 -1  0.1 0.1 -1  0 0.1 -1]
           \"varying float[2] st\" [0 0  1 0  1 1  0 1]
         PointsPolygons [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]
           \"N\" [0 0 -1  0 0 -1  0 0 -1] \"uniform color Cs\" [1 0 0]
         PointsPolygons [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]
           \"facevarying float[2] st\" [0 0  1 0  1 1]",
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    let s = &loaded.frames[0].scene;
    let Shape::Mesh { normals: Some(n), st: Some(st), .. } = &s.objects[0].shape else {
        panic!("{:?}", s.objects[0].shape)
    };
    assert_eq!(n, &vec![[0.0, 0.0, -1.0], [0.1, 0.0, -1.0], [0.1, 0.1, -1.0], [0.0, 0.1, -1.0]]);
    assert_eq!(st, &vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    for k in [1, 2] {
        let Shape::Mesh { normals: None, st: None, .. } = &s.objects[k].shape else {
            panic!("{:?}", s.objects[k].shape)
        };
    }
    let warned: Vec<String> = loaded.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(warned.len(), 2, "{warned:?}");
    assert!(warned[0].contains("\"N\": only vertex or varying N"), "{warned:?}");
    assert!(warned[1].contains("\"st\": only vertex or varying st"), "{warned:?}");
}
