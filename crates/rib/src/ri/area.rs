//! `AreaLightSource`: the geometry that follows it in its attribute block becomes the shape
//! of true area lights of the model, one per primitive, and each primitive is linked to its
//! light (`Object::area_light`) so that it glows and does not shadow the light it emits.
//!
//! Invariants: `arealight`'s `intensity * lightcolor` is the emitted radiance; the model's
//! intensity is that radiance times the emitter's area as seen face on (a sphere's and a
//! disk's `pi r^2`, a polygon's area), so that a point under the light receives
//! `pi * radiance * form factor` whatever the emitter's size. Emitters are placed at shutter
//! open.

use glam::{DMat4, DVec3};
use reyes_scene::{AreaShape, Light, Object, Shape};

use super::frame::Machine;
use super::shaders::{color, float, unused};
use super::xform::{Xform, point};
use crate::{Location, Param, Request, Warning};

/// An `AreaLightSource` in force for the primitives of its attribute block.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct AreaSource {
    /// The light slot its handle names (see `FrameBuild::add_area_light`).
    pub slot: usize,
    /// `lightcolor`.
    pub color: [f32; 3],
    /// `intensity`: the radiance scale.
    pub intensity: f32,
}

/// `intensity` and `lightcolor` of the area light shader `name` (the standard `arealight`;
/// another name reads the same two parameters, its caller warns), with warnings for
/// parameters `arealight` does not take.
pub(crate) fn shader(
    name: &str,
    params: &[Param],
    at: &Location,
    warnings: &mut Vec<Warning>,
) -> (f32, [f32; 3]) {
    if name == "arealight" {
        unused(name, params, &[("intensity", 1), ("lightcolor", 3)], at, warnings);
    }
    (float(params, "intensity").unwrap_or(1.0), color(params, "lightcolor").unwrap_or([1.0; 3]))
}

impl Machine {
    /// Makes `object` (made by `r`, placed by `to_world`) an emitter of the area light
    /// `area`: a light of the model over its surface, linked to it, glowing with the light's
    /// radiance. Geometry the model cannot emit from is drawn but emits nothing (a warning).
    pub(super) fn emitter(
        &mut self,
        r: &Request,
        area: &AreaSource,
        object: &mut Object,
        to_world: &Xform,
    ) {
        if to_world.keys.len() > 1 {
            let w = r.warning("an area light stays where its moving geometry is at shutter open");
            self.warn_once(format!("area motion {}", r.at), w);
        }
        let m = to_world.at(f32::NEG_INFINITY);
        // RenderMan's normal, the side `arealight` shines to: the surface's own (dPdu x dPdv,
        // a polygon's by the right-hand rule around its vertices, a disk's +z) carried by `m`
        // as a normal, flipped by ReverseOrientation or Orientation "inside".
        let flip = (m.determinant() < 0.0) != self.attributes.reverse_orientation;
        let (shape, size) = match emitter(&object.shape, &m, flip) {
            Ok(found) => found,
            Err(why) => {
                let w = r.warning(format!("{why}: drawn, but emits no light (AreaLightSource)"));
                self.warn_once(format!("area {why}"), w);
                return;
            }
        };
        let Some(b) = &mut self.build else { return };
        let light = Light::Area {
            shape,
            color: area.color,
            intensity: area.intensity * size,
            motion: vec![],
            one_sided: true,
        };
        let index = b.add_emitter(area.slot, light, r.at.clone(), "AreaLightSource");
        object.area_light = Some(index as u32);
        object.emission = Some(area.color.map(|c| c * area.intensity));
    }
}

/// The emitting shape of `shape` placed by `m`, with the area that scales its radiance into
/// the model's intensity; or why the model cannot emit from it. The shape's normal is the
/// surface's numerical one in world space (turned over with `flip`): the side it emits to.
pub(crate) fn emitter(shape: &Shape, m: &DMat4, flip: bool) -> Result<(AreaShape, f32), String> {
    let full = |thetamax: f32| thetamax >= 360.0;
    match shape {
        Shape::Sphere { radius, zmin, zmax, thetamax } => {
            let whole = zmin.is_none_or(|z| z <= -radius)
                && zmax.is_none_or(|z| z >= *radius)
                && full(*thetamax);
            if !whole {
                return Err("a partial sphere cannot emit (only a whole one)".into());
            }
            let s = similarity(m).ok_or("a sphere under a non-uniform scale cannot emit")?;
            let r = radius.abs() * s;
            let center = point(m, [0.0; 3]);
            Ok((AreaShape::Sphere { center, radius: r }, std::f32::consts::PI * r * r))
        }
        Shape::Disk { height, radius, thetamax } => {
            if !full(*thetamax) {
                return Err("a partial disk cannot emit (only a whole one)".into());
            }
            let s = similarity(m).ok_or("a disk under a non-uniform scale cannot emit")?;
            let n = m.transform_vector3(DVec3::Z) * if flip { -1.0 } else { 1.0 };
            let normal = [n.x as f32, n.y as f32, n.z as f32];
            let center = point(m, [0.0, 0.0, *height]);
            let r = radius.abs() * s;
            Ok((AreaShape::Disk { center, normal, radius: r }, std::f32::consts::PI * r * r))
        }
        // The patch's corners (0,0) (1,0) (0,1) (1,1), in order around it.
        Shape::BilinearPatch { points } => {
            let p = [points[0], points[1], points[3], points[2]];
            flat(&p.map(|q| point(m, q)), flip)
        }
        Shape::Mesh { points, faces, .. } if faces.len() == 1 => {
            let face = faces.get(0).unwrap_or_default();
            let p: Option<Vec<[f32; 3]>> =
                face.iter().map(|&i| points.get(i as usize).map(|&q| point(m, q))).collect();
            flat(&p.ok_or("a polygon vertex is out of range")?, flip)
        }
        Shape::Mesh { .. } => {
            Err("a mesh of several faces cannot emit (give each emitting polygon its own request)"
                .into())
        }
        other => Err(format!("the model cannot emit from a {}", other.name())),
    }
}

/// A planar convex polygon in world space: a parallelogram as a `Rectangle`, anything else
/// as a `Polygon`, with its area; its normal by the right-hand rule around `p`, or the
/// other way with `flip`.
fn flat(p: &[[f32; 3]], flip: bool) -> Result<(AreaShape, f32), String> {
    let mut p = p.to_vec();
    if flip {
        p.reverse();
    }
    if let Some(flaw) = AreaShape::polygon_flaw(&p) {
        return Err(format!("an emitting polygon must be planar and convex: {flaw}"));
    }
    let d: Vec<DVec3> = p.iter().map(|q| DVec3::from(q.map(f64::from))).collect();
    let n: DVec3 = (0..d.len()).map(|i| d[i].cross(d[(i + 1) % d.len()])).sum();
    let area = (0.5 * n.length()) as f32;
    let size = d.iter().map(|q| (*q - d[0]).length()).fold(0.0, f64::max);
    let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    if d.len() == 4 && (d[0] + d[2] - d[1] - d[3]).length() <= 1e-6 * size {
        let (edge_u, edge_v) = (sub(p[1], p[0]), sub(p[3], p[0]));
        return Ok((AreaShape::Rectangle { corner: p[0], edge_u, edge_v }, area));
    }
    Ok((AreaShape::Polygon { points: p }, area))
}

/// The scale of `m` if it is a similarity (its linear part a rotation times a uniform scale,
/// no perspective), to 1e-4 relative.
fn similarity(m: &DMat4) -> Option<f32> {
    if m.row(3).truncate() != DVec3::ZERO {
        return None;
    }
    let c = [m.x_axis.truncate(), m.y_axis.truncate(), m.z_axis.truncate()];
    let s = c[0].length();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-4 * s * s;
    let ok = s > 0.0
        && c.iter().all(|v| close(v.length_squared(), s * s))
        && close(c[0].dot(c[1]), 0.0)
        && close(c[1].dot(c[2]), 0.0)
        && close(c[0].dot(c[2]), 0.0);
    ok.then_some(s as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallelograms_are_rectangles_and_other_quads_polygons() {
        let m = DMat4::from_translation(DVec3::new(0.0, 2.0, 0.0));
        let square = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 3.0], [0.0, 0.0, 3.0]];
        let (s, area) = flat(&square.map(|q| point(&m, q)), false).expect("flat");
        assert!(matches!(s, AreaShape::Rectangle { .. }) && (area - 6.0).abs() < 1e-5, "{s:?}");
        let kite = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 3.0], [0.0, 0.0, 1.0]];
        let (s, area) = flat(&kite, false).expect("flat");
        // Shoelace: (0*0-2*0) + (2*3-3*0) + (3*1-0*3) + 0 = 9, halved.
        assert!(matches!(s, AreaShape::Polygon { .. }) && (area - 4.5).abs() < 1e-5, "{s:?}");
        let bent = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 3.0], [0.0, 0.0, 3.0]];
        assert!(flat(&bent, false).unwrap_err().contains("not planar"));
        // Turned over: the same square, its normal the other way.
        let (s, _) = flat(&square, true).expect("flat");
        let AreaShape::Rectangle { edge_u, edge_v, .. } = s else { panic!("{s:?}") };
        let n = glam::Vec3::from(edge_u).cross(glam::Vec3::from(edge_v));
        assert!(n.y > 0.0, "{n}");
    }

    #[test]
    fn spheres_and_disks_need_a_similarity() {
        let sphere = Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 };
        let m = DMat4::from_scale(DVec3::splat(2.0));
        let (s, area) = emitter(&sphere, &m, false).expect("emits");
        assert_eq!(s, AreaShape::Sphere { center: [0.0; 3], radius: 2.0 });
        assert!((area - 4.0 * std::f32::consts::PI).abs() < 1e-5);
        let squashed = DMat4::from_scale(DVec3::new(1.0, 2.0, 1.0));
        assert!(emitter(&sphere, &squashed, false).is_err());
        let half = Shape::Sphere { radius: 1.0, zmin: Some(0.0), zmax: None, thetamax: 360.0 };
        assert!(emitter(&half, &m, false).is_err());
    }
}
