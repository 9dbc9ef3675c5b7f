//! CSG operands, interpolation and glass: micropolygons of an operand carry its
//! `(tree, slot)` from `CsgSetup`, others `(0, 0)`; cylinders, cones and paraboloids used as
//! operands are closed by end caps lying in their planes and facing out of the solid;
//! `Gouraud` and `glass` objects carry their flags; objects in no solid dice exactly as before.
//!
//! Orientation is tested through the micropolygon winding, the one place the dicer keeps it
//! (colours come from face-forwarded normals): every micropolygon is carried back to object
//! space (raster -> camera -> world -> object), and its vector area
//! `(v2 - v0) x (v3 - v1) / 2` — the direction from which vertices 0-1-2-3 are seen
//! counter-clockwise, which the dicer makes the surface's geometric normal — must point out
//! of the solid. (One pre-existing exception, kept so existing scenes dice unchanged: the
//! side of a cone of negative height winds inward although its geometric normal, used for
//! shading, is outward; the tests expect exactly that. Nothing downstream reads winding.)

mod common;

use common::{camera, dice, object, scene, signed_area, sphere};
use glam::{Mat4, Vec3};
use reyes_dice::{CameraSetup, CsgSetup, Diced};
use reyes_hider::{Micropolygon, flags};
use reyes_scene::object_to_world;
use reyes_scene::{Csg, Interpolation, Object, Scene, Shape, Solid, Transform};

fn leaf(name: &str) -> Csg {
    Csg::Object(name.to_string())
}

fn solid(tree: Csg) -> Solid {
    Solid { name: String::new(), tree }
}

fn at(x: f32, y: f32, z: f32) -> Vec<Transform> {
    vec![Transform::Translate([x, y, z])]
}

/// A wide strip of the x axis seen from z = -12: world x maps to raster x.
fn strip(objects: Vec<Object>) -> Scene {
    scene(320, 80, camera([0.0, 0.0, -12.0], [0.0; 3], 40.0, None), objects)
}

/// Raster `(x, y, z)` back to world space.
struct Unproject {
    setup: CameraSetup,
    camera_to_world: Mat4,
}

impl Unproject {
    fn new(scene: &Scene) -> Unproject {
        let setup = CameraSetup::new(scene);
        let camera_to_world = setup.world_to_camera().inverse();
        Unproject { setup, camera_to_world }
    }

    fn world(&self, v: [f32; 3]) -> Vec3 {
        let size = self.setup.image_size();
        let k = self.setup.pixels_per_unit();
        let z = v[2];
        let p = Vec3::new((v[0] - 0.5 * size.x) * z / k, (0.5 * size.y - v[1]) * z / k, z);
        self.camera_to_world.transform_point3(p)
    }

    /// World-space centroid of a micropolygon.
    fn centroid(&self, mp: &Micropolygon) -> Vec3 {
        mp.v.iter().map(|v| self.world(*v)).sum::<Vec3>() / 4.0
    }
}

/// The object with the nearest x centre (objects laid out along world x).
fn nearest(centres: &[f32], x: f32) -> usize {
    let d = |i: usize| (centres[i] - x).abs();
    (0..centres.len()).min_by(|&a, &b| d(a).total_cmp(&d(b))).unwrap_or(0)
}

#[test]
fn operands_carry_their_tree_and_slot_and_others_zero() {
    let xs = [-7.5_f32, -4.5, -1.5, 1.5, 4.5, 7.5];
    let cyl = Shape::Cylinder { radius: 0.6, zmin: -0.8, zmax: 0.8, thetamax: 360.0 };
    let objects = vec![
        object(sphere(0.9), at(xs[0], 0.0, 0.0)).named("a"),
        object(cyl.clone(), at(xs[1], 0.0, 0.0)).named("plain"),
        object(cyl, at(xs[2], 0.0, 0.0)).named("b"),
        object(Shape::Cone { height: 1.2, radius: 0.8, thetamax: 360.0 }, at(xs[3], 0.0, 0.0))
            .named("c"),
        object(
            Shape::Paraboloid { rmax: 0.8, zmin: 0.2, zmax: 1.2, thetamax: 360.0 },
            at(xs[4], 0.0, 0.0),
        )
        .named("d"),
        object(sphere(0.9), at(xs[5], 0.0, 0.0)).named("e"),
    ];
    let mut s = strip(objects);
    s.solids = vec![
        solid(Csg::Difference(Box::new(leaf("a")), Box::new(leaf("b")))),
        solid(Csg::Union(vec![leaf("c"), Csg::Intersection(vec![leaf("d"), leaf("e")])])),
    ];
    let setup = CsgSetup::new(&s);
    assert_eq!(setup.trees.len(), 2);
    assert_eq!(setup.leaf[1], None, "plain is in no solid");
    let (diced, _) = dice(&s);
    assert_eq!(diced.csg_trees, setup.trees, "the trees the hider resolves are the setup's");

    let un = Unproject::new(&s);
    let mut counts = [0usize; 6];
    for mp in &diced.mpolys {
        let i = nearest(&xs, un.centroid(mp).x);
        counts[i] += 1;
        let want = setup.leaf[i].unwrap_or((0, 0));
        assert_eq!((mp.csg_tree, mp.csg_node), want, "object {i}");
    }
    assert!(counts.iter().all(|&c| c > 50), "every object diced: {counts:?}");
    // Operand labels: two trees, slots non-zero and distinct within a tree.
    let labels: Vec<(u16, u16)> = setup.leaf.iter().flatten().copied().collect();
    assert_eq!(labels.len(), 5);
    for (k, &(tree, slot)) in labels.iter().enumerate() {
        assert!(slot != 0 && (tree as usize) < setup.trees.len());
        assert!(labels[..k].iter().all(|&l| l != (tree, slot)), "{labels:?}");
    }
    assert_eq!(setup.leaf[0].map(|l| l.0), Some(0));
    assert_eq!(setup.leaf[5].map(|l| l.0), Some(1));
}

/// One piece of a closed solid's boundary, in object space.
struct Piece {
    name: &'static str,
    /// Distance-like measure of a point from the piece (0 on it).
    off: Box<dyn Fn(Vec3) -> f32>,
    /// Outward normal at a point of the piece (any length).
    outward: Box<dyn Fn(Vec3) -> Vec3>,
    /// +1 if the micropolygons wind outward, -1 if inward.
    winding: f32,
}

fn plane(name: &'static str, z: f32, up: bool) -> Piece {
    let n = if up { Vec3::Z } else { Vec3::NEG_Z };
    Piece {
        name,
        off: Box::new(move |p| (p.z - z).abs()),
        outward: Box::new(move |_| n),
        winding: 1.0,
    }
}

/// What [`check_closed`] found.
#[derive(Debug)]
struct Found {
    /// Per piece: micropolygons and their total object-space area.
    pieces: Vec<(usize, f64)>,
    /// Sum of signed raster areas, each times its piece's winding sign: a closed,
    /// consistently oriented surface projects to zero net area.
    net: f64,
    /// Sum of absolute raster areas.
    total: f64,
}

/// Every micropolygon labelled `label` lies on one of `pieces` (all four vertices within
/// [`on_surface_eps`] of it) with its vector area pointing out of the solid (into it for a
/// piece of winding -1).
fn check_closed(
    scene: &Scene,
    diced: &Diced,
    object_index: usize,
    label: (u16, u16),
    pieces: &[Piece],
) -> Found {
    let un = Unproject::new(scene);
    let eps = on_surface_eps(scene, &un);
    let to_object = object_to_world(&scene.objects[object_index].transform).inverse();
    let mut out = Found { pieces: vec![(0, 0.0); pieces.len()], net: 0.0, total: 0.0 };
    for mp in diced.mpolys.iter().filter(|m| (m.csg_tree, m.csg_node) == label) {
        let p = mp.v.map(|v| to_object.transform_point3(un.world(v)));
        let on = |piece: &Piece| p.iter().zip(&mp.v).all(|(&q, v)| (piece.off)(q) < eps(v[2]));
        let Some(k) = pieces.iter().position(on) else {
            panic!("a micropolygon on no piece of the solid: {p:?}");
        };
        let area = 0.5 * (p[2] - p[0]).cross(p[3] - p[1]);
        let centre = p.iter().sum::<Vec3>() / 4.0;
        let outward = (pieces[k].outward)(centre).normalize() * pieces[k].winding;
        let name = pieces[k].name;
        // Degenerate (apex, centre) cells may have no area; any area must face out.
        assert!(area.dot(outward) > -1e-6, "{name}: area {area} vs outward {outward} at {p:?}");
        if area.length() > 1e-4 {
            assert!(area.dot(outward) > 0.5 * area.length(), "{name}: {area} vs {outward}");
        }
        out.pieces[k].0 += 1;
        out.pieces[k].1 += f64::from(area.length());
        let raster = signed_area(mp);
        out.net += raster * f64::from(pieces[k].winding);
        out.total += raster.abs();
    }
    assert!(out.net.abs() < 0.01 * out.total, "closed: net {} of {}", out.net, out.total);
    out
}

/// How far from its surface a diced vertex may lie, in object units, at camera depth `z`.
///
/// Interior vertices are on the surface. Boundary vertices are on their side's shared
/// polyline (crack-free dicing, crates/dice/src/split/edge.rs): between polyline vertices,
/// on a chord that strays from the surface by at most the edge tolerance `tol` raster
/// pixels, which the dicer checks both across the screen and in camera-space depth (as
/// pixels at the point's depth, `k / z` pixels per unit). The pieces here are arcs of
/// circles and parabolas, whose chord strays most at its middle, one of the points tested,
/// so a vertex is within `tol * z / k` camera units of the surface, the same in object
/// units (the operands are only rotated and moved). `tol` is at most the flatness bound
/// (`hider.flatness`, 0.05 pixel here; the relative bound only lowers it). Plus rounding:
/// unprojecting a raster point at depth ~13 in `f32` costs a few ulps of 13 (1e-6 each);
/// 1e-4 is about a hundred of them.
fn on_surface_eps(scene: &Scene, un: &Unproject) -> impl Fn(f32) -> f32 {
    let tol = scene.hider.flatness;
    let k = un.setup.pixels_per_unit();
    move |z: f32| tol * z / k + 1e-4
}

/// An oblique view of `operand` (object 0) in a difference with a small sphere, placed by
/// a rotation and a translation so that every face is seen.
fn operand_scene(shape: Shape) -> Scene {
    let xf = vec![
        Transform::Rotate { angle: 50.0, axis: [1.0, 0.4, 0.0] },
        Transform::Translate([0.3, -0.2, 1.0]),
    ];
    let mut s = scene(
        96,
        96,
        camera([0.0, 0.0, -10.0], [0.0, 0.0, 1.0], 40.0, None),
        vec![object(shape, xf).named("x"), object(sphere(0.3), at(0.3, -0.2, 1.0)).named("s")],
    );
    s.solids = vec![solid(Csg::Difference(Box::new(leaf("x")), Box::new(leaf("s"))))];
    s
}

/// [`operand_scene`] of `shape`, diced, and the operand's `(tree, slot)` label.
fn diced_operand(shape: Shape) -> (Scene, Diced, (u16, u16)) {
    let s = operand_scene(shape);
    let (diced, _) = dice(&s);
    let label = CsgSetup::new(&s).leaf[0].expect("an operand");
    (s, diced, label)
}

#[test]
fn cylinder_operand_is_closed_by_caps_facing_out() {
    let (r, z0, z1) = (1.0_f32, -1.0_f32, 2.0_f32);
    let (s, diced, label) =
        diced_operand(Shape::Cylinder { radius: r, zmin: z0, zmax: z1, thetamax: 360.0 });
    let pieces = [
        plane("bottom", z0, false),
        plane("top", z1, true),
        Piece {
            name: "side",
            off: Box::new(move |p| (p.truncate().length() - r).abs()),
            outward: Box::new(|p| Vec3::new(p.x, p.y, 0.0)),
            winding: 1.0,
        },
    ];
    let found = check_closed(&s, &diced, 0, label, &pieces).pieces;
    let disk = f64::from(std::f32::consts::PI * r * r);
    for (k, name) in ["bottom", "top"].into_iter().enumerate() {
        let (count, area) = found[k];
        assert!(count > 20, "{name} cap: {count} micropolygons");
        assert!((area - disk).abs() < 0.03 * disk, "{name} cap covers the disk: {area}");
    }
    let side = f64::from(std::f32::consts::TAU * r * (z1 - z0));
    assert!((found[2].1 - side).abs() < 0.03 * side, "side: {}", found[2].1);
}

#[test]
fn cone_and_paraboloid_operands_are_closed_by_caps_facing_out() {
    for height in [1.5_f32, -1.5] {
        let radius = 1.0_f32;
        let (s, diced, label) = diced_operand(Shape::Cone { height, radius, thetamax: 360.0 });
        let pieces = [
            plane("base", 0.0, height < 0.0),
            Piece {
                name: "cone",
                off: Box::new(move |p| {
                    (p.truncate().length() - radius * (1.0 - p.z / height)).abs()
                }),
                outward: Box::new(move |p| {
                    let c = p.truncate().normalize_or_zero();
                    Vec3::new(height.abs() * c.x, height.abs() * c.y, radius.copysign(height))
                }),
                // See the module docs: inward-wound below the base.
                winding: height.signum(),
            },
        ];
        let found = check_closed(&s, &diced, 0, label, &pieces).pieces;
        assert!(found[0].0 > 20, "h {height}: base cap {found:?}");
        let disk = f64::from(std::f32::consts::PI * radius * radius);
        assert!((found[0].1 - disk).abs() < 0.03 * disk, "h {height}: {found:?}");
    }
    for zmin in [0.0_f32, 0.5] {
        let (rmax, zmax) = (1.2_f32, 2.0_f32);
        let k = rmax * rmax / zmax;
        let (s, diced, label) =
            diced_operand(Shape::Paraboloid { rmax, zmin, zmax, thetamax: 360.0 });
        let mut pieces = vec![
            plane("bottom", zmin, false),
            plane("top", zmax, true),
            Piece {
                name: "paraboloid",
                // |f| / |grad f| of f = x^2 + y^2 - k z: the distance to first order.
                off: Box::new(move |p| {
                    let f = p.x * p.x + p.y * p.y - k * p.z;
                    f.abs() / Vec3::new(2.0 * p.x, 2.0 * p.y, -k).length()
                }),
                outward: Box::new(move |p| Vec3::new(2.0 * p.x, 2.0 * p.y, -k)),
                winding: 1.0,
            },
        ];
        if zmin == 0.0 {
            // A cell within `on_surface_eps` of both the plane z = 0 and the surface (the
            // apex's, a few hundred of them under a CSG operand's finer dicing) is the
            // surface's: only a cell on the plane alone would be a cap.
            pieces.rotate_right(1);
        }
        let found = check_closed(&s, &diced, 0, label, &pieces).pieces;
        let found = if zmin == 0.0 { vec![found[1], found[2], found[0]] } else { found };
        let top = f64::from(std::f32::consts::PI * rmax * rmax);
        assert!(found[1].0 > 20 && (found[1].1 - top).abs() < 0.03 * top, "{found:?}");
        if zmin > 0.0 {
            let bottom = top * f64::from(zmin / zmax);
            assert!(found[0].0 > 10, "bottom cap at zmin: {found:?}");
            assert!((found[0].1 - bottom).abs() < 0.05 * bottom, "{found:?}");
        } else {
            // At the apex the surface itself closes the solid: no bottom cap. (The
            // apex's own cells lie near the plane z = 0 only as degenerate slivers.)
            assert!(found[0].1 < 1e-3, "no cap at the apex: {found:?}");
        }
    }
}

#[test]
fn objects_in_no_solid_dice_exactly_as_without_csg() {
    let plain = vec![
        object(
            Shape::Cylinder { radius: 0.6, zmin: -0.8, zmax: 0.8, thetamax: 360.0 },
            at(-6.0, 0.0, 0.0),
        )
        .named("cyl"),
        object(
            Shape::Paraboloid { rmax: 0.8, zmin: 0.2, zmax: 1.2, thetamax: 360.0 },
            at(-3.0, 0.0, 0.0),
        )
        .named("para"),
        object(Shape::Cone { height: 1.2, radius: 0.8, thetamax: 360.0 }, at(0.0, 0.0, 0.0))
            .named("cone"),
    ];
    let alone = strip(plain.clone());
    let (before, _) = dice(&alone);
    let mut objects = plain;
    objects.push(object(sphere(0.9), at(4.0, 0.0, 0.0)).named("p"));
    objects.push(object(sphere(0.9), at(4.5, 0.0, 0.0)).named("q"));
    let mut with = strip(objects);
    with.solids = vec![solid(Csg::Union(vec![leaf("p"), leaf("q")]))];
    let (after, _) = dice(&with);
    let n = before.mpolys.len();
    assert!(n > 200);
    assert!(before.csg_trees.is_empty() && after.csg_trees.len() == 1);
    assert_eq!(&after.mpolys[..n], &before.mpolys[..], "same micropolygons, no caps");
    assert!(after.mpolys[n..].iter().all(|m| m.csg_node != 0), "the solid's own");
    assert!(before.mpolys.iter().all(|m| (m.csg_tree, m.csg_node) == (0, 0)));
    assert!(before.mpolys.iter().all(|m| !m.has(flags::GOURAUD) && !m.has(flags::GLASS)));
    assert!(before.mpolys.iter().all(|m| m.glass_opacity == 0.0));
    // No cap: no micropolygon of the plain cylinder lies in the plane of an end.
    let un = Unproject::new(&alone);
    let in_end_plane = |m: &Micropolygon| {
        let z: Vec<f32> = m.v.iter().map(|v| un.world(*v).z).collect();
        [-0.8_f32, 0.8].iter().any(|e| z.iter().all(|q| (q - e).abs() < 1e-3))
    };
    let cyl: Vec<&Micropolygon> =
        before.mpolys.iter().filter(|m| un.centroid(m).x < -4.5).collect();
    assert!(cyl.len() > 50 && !cyl.iter().any(|m| in_end_plane(m)));
}

#[test]
fn gouraud_and_glass_set_their_flags() {
    let xs = [-6.0_f32, -2.0, 2.0, 6.0];
    let mut objects: Vec<Object> =
        xs.iter().map(|&x| object(sphere(1.0), at(x, 0.0, 0.0))).collect();
    objects[1].interpolation = Interpolation::Gouraud;
    objects[2].glass = Some(0.25);
    objects[3].interpolation = Interpolation::Gouraud;
    objects[3].glass = Some(0.75);
    objects[3].name = "both".into();
    objects.push(object(sphere(1.0), at(6.5, 0.0, 0.0)).named("other"));
    let mut s = strip(objects);
    s.solids = vec![solid(Csg::Intersection(vec![leaf("both"), leaf("other")]))];
    let centres = [xs[0], xs[1], xs[2], xs[3], 6.5];
    let (diced, _) = dice(&s);
    let un = Unproject::new(&s);
    let setup = CsgSetup::new(&s);
    let mut seen = [0usize; 5];
    for mp in &diced.mpolys {
        let i = nearest(&centres, un.centroid(mp).x);
        // Objects 3 and 4 overlap: tell them apart by their labels instead.
        let i = if i >= 3 {
            if Some((mp.csg_tree, mp.csg_node)) == setup.leaf[3] { 3 } else { 4 }
        } else {
            i
        };
        seen[i] += 1;
        let gouraud = i == 1 || i == 3;
        let glass = match i {
            2 => Some(0.25),
            3 => Some(0.75),
            _ => None,
        };
        assert_eq!(mp.has(flags::GOURAUD), gouraud, "object {i}");
        assert_eq!(mp.has(flags::GLASS), glass.is_some(), "object {i}");
        assert_eq!(mp.glass_opacity, glass.unwrap_or(0.0), "object {i}");
        assert!(mp.has(flags::OPAQUE), "the other flags stay");
        if i >= 3 {
            assert_eq!(Some((mp.csg_tree, mp.csg_node)), setup.leaf[i]);
        }
    }
    assert!(seen.iter().all(|&c| c > 50), "{seen:?}");
}
