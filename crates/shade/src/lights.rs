//! The scene's direct lights set up for shading: distant, point and spot lights (with
//! optional hard shadows) and area lights, whose shape is sampled at one point per shading
//! call.
//!
//! Invariants: light directions are unit; an area light's motion keys have normalised,
//! strictly increasing times (normalised over the camera shutter exactly as the tracer and
//! the dicer normalise object keys: 0 at open, 1 at close, clamped, NaN as 0; only the first
//! key when the shutter is closed) and are held before the first and after the last.

use glam::Vec3;
use reyes_dice::SpotLight;
use reyes_scene::{AreaShape, Light, Scene};

use crate::sample::concentric_disk;

/// `d^2` below which a light sample is taken to sit on the shaded point and is ignored (the
/// dicer's rule for point lights).
pub(crate) const MIN_DIST2: f32 = 1e-20;

/// A non-ambient light after setup (ambient lights are summed by the dicer's `Shader`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum DirectLight {
    /// Parallel light: unit direction toward the light, `intensity * color`.
    Distant { l: Vec3, cl: Vec3, shadows: bool },
    /// Point light: position, `intensity * color` (divided by `d^2` at the surface).
    Point { from: Vec3, cl: Vec3, shadows: bool },
    /// RenderMan's spotlight (the dicer's, so both shading paths light alike).
    Spot { spot: SpotLight, shadows: bool },
    /// Area light (always shadows).
    Area(AreaLight),
}

/// An area light: its shape, colour and motion.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct AreaLight {
    shape: Emitter,
    color: Vec3,
    /// Keys `(normalised time, offset, intensity)`; empty: still at `intensity`.
    keys: Vec<(f32, Vec3, f32)>,
    intensity: f32,
    /// Flat shapes emit toward their normal's side only.
    one_sided: bool,
}

/// The emitting shape, in world space at zero offset.
#[derive(Debug, Clone, PartialEq)]
enum Emitter {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// A disk with unit normal `n` and the orthonormal pair `(e1, e2)` spanning its plane.
    Disk {
        center: Vec3,
        radius: f32,
        n: Vec3,
        e1: Vec3,
        e2: Vec3,
    },
    /// A parallelogram with unit normal `n` (zero when the edges are parallel: it emits
    /// nothing).
    Rectangle {
        corner: Vec3,
        edge_u: Vec3,
        edge_v: Vec3,
        n: Vec3,
    },
    /// A convex polygon as the fan of triangles `(a, b, c)` from its first corner, with the
    /// running sum of their areas (the last is the polygon's area) and its unit normal.
    Polygon {
        fan: Vec<[Vec3; 3]>,
        cumulative: Vec<f32>,
        n: Vec3,
    },
}

/// One point drawn on an area light, as seen from a shaded point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LightSample {
    /// The point on the light, world space.
    pub point: Vec3,
    /// Unit vector from the shaded point to `point`.
    pub l: Vec3,
    /// Colour arriving if nothing is in the way: `intensity(t) * color * |cos at the
    /// light| / d^2` (the cosine is 1 for spheres).
    pub cl: Vec3,
}

/// Normalisation of scene times over the shutter, as the tracer does it.
pub(crate) struct ShutterNorm {
    open: f32,
    span: f32,
    /// `close <= open` (or not finite): everything happens at `open`.
    pub closed: bool,
}

impl ShutterNorm {
    pub fn new(scene: &Scene) -> ShutterNorm {
        let shutter = scene.camera.shutter;
        let span = shutter.close - shutter.open;
        ShutterNorm { open: shutter.open, span, closed: !span.is_finite() || span <= 0.0 }
    }

    /// Scene time to normalised time in `[0, 1]` (0 when closed, NaN as 0).
    pub fn norm(&self, t: f32) -> f32 {
        let t = if self.closed { 0.0 } else { (t - self.open) / self.span };
        if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) }
    }
}

impl DirectLight {
    /// The direct light of `light`, or `None` for ambient lights and distant and spot lights
    /// without a direction (`from == to`: they light nothing, as in the dicer).
    pub fn new(light: &Light, shutter: &ShutterNorm) -> Option<DirectLight> {
        match light {
            Light::Ambient { .. } => None,
            Light::Distant { from, to, color, intensity, shadows } => {
                let l = (Vec3::from(*from) - Vec3::from(*to)).try_normalize()?;
                Some(DirectLight::Distant {
                    l,
                    cl: *intensity * Vec3::from(*color),
                    shadows: *shadows,
                })
            }
            Light::Point { from, color, intensity, shadows } => Some(DirectLight::Point {
                from: Vec3::from(*from),
                cl: *intensity * Vec3::from(*color),
                shadows: *shadows,
            }),
            Light::Spot { shadows, .. } => {
                Some(DirectLight::Spot { spot: SpotLight::of(light)?, shadows: *shadows })
            }
            Light::Area { shape, color, intensity, motion, one_sided } => {
                let shape = match shape {
                    AreaShape::Sphere { center, radius } => {
                        Emitter::Sphere { center: Vec3::from(*center), radius: *radius }
                    }
                    AreaShape::Disk { center, normal, radius } => {
                        let n = Vec3::from(*normal).try_normalize().unwrap_or(Vec3::Y);
                        let (e1, e2) = n.any_orthonormal_pair();
                        Emitter::Disk { center: Vec3::from(*center), radius: *radius, n, e1, e2 }
                    }
                    AreaShape::Rectangle { corner, edge_u, edge_v } => {
                        let (edge_u, edge_v) = (Vec3::from(*edge_u), Vec3::from(*edge_v));
                        Emitter::Rectangle {
                            corner: Vec3::from(*corner),
                            edge_u,
                            edge_v,
                            n: edge_u.cross(edge_v).normalize_or_zero(),
                        }
                    }
                    AreaShape::Polygon { points } => polygon(points),
                };
                let mut keys: Vec<(f32, Vec3, f32)> = Vec::with_capacity(motion.len());
                for key in motion {
                    let t = shutter.norm(key.time);
                    // Keys at or before an earlier key's time are dropped, as the tracer does.
                    if keys.last().is_some_and(|(before, _, _)| t <= *before) {
                        continue;
                    }
                    keys.push((t, Vec3::from(key.offset), key.intensity));
                    if shutter.closed {
                        break;
                    }
                }
                Some(DirectLight::Area(AreaLight {
                    shape,
                    color: Vec3::from(*color),
                    keys,
                    intensity: *intensity,
                    one_sided: *one_sided,
                }))
            }
        }
    }
}

impl AreaLight {
    /// Offset and intensity at normalised `time`: linear between keys, held outside them.
    pub fn at(&self, time: f32) -> (Vec3, f32) {
        let time = if time.is_finite() { time } else { 0.0 };
        let Some(&(t0, o0, i0)) = self.keys.first() else {
            return (Vec3::ZERO, self.intensity);
        };
        if time <= t0 {
            return (o0, i0);
        }
        for pair in self.keys.windows(2) {
            let ((ta, oa, ia), (tb, ob, ib)) = (pair[0], pair[1]);
            if time <= tb {
                let w = ((time - ta) / (tb - ta)).clamp(0.0, 1.0);
                return (oa.lerp(ob, w), ia + (ib - ia) * w);
            }
        }
        self.keys.last().map_or((Vec3::ZERO, self.intensity), |&(_, o, i)| (o, i))
    }

    /// The point of the light chosen by `u` (in `[0, 1)^2`) for the shaded point `p` at
    /// normalised `time`, or `None` when it sits on `p` or sends nothing.
    ///
    /// * Disk: the concentric map of `u` onto the disk (uniform in area, strata compact).
    /// * Rectangle: `corner + u1 edge_u + u2 edge_v` (uniform in area).
    /// * Polygon: a triangle of its fan chosen by area, a point uniform in it.
    /// * Sphere: the concentric map onto the disk of radius `r` through the centre,
    ///   perpendicular to the direction from the centre to `p`. Seen from `p` at distance
    ///   `d`, that disk's outline subtends the half-angle `atan(r / d)` and the ball's
    ///   silhouette `asin(r / d)`, equal to first order in `r / d` (and the disk lies
    ///   inside the ball), so points uniform on the disk are, up to that order, uniform
    ///   over the silhouette the ball shows `p`, which is what a ball of uniform radiance
    ///   emits toward `p`; a ball looks the same from every side, so no cosine at the
    ///   light. (Appendix B draws uniformly inside the ball instead, by rejection, which
    ///   projects to a denser centre and is not stratified.)
    pub fn sample(&self, p: Vec3, time: f32, u: (f32, f32)) -> Option<LightSample> {
        let (offset, intensity) = self.at(time);
        let (point, normal) = match &self.shape {
            &Emitter::Sphere { center, radius } => {
                let c = center + offset;
                let w = (p - c).try_normalize().unwrap_or(Vec3::Z);
                let (e1, e2) = w.any_orthonormal_pair();
                let q = concentric_disk(u) * radius;
                (c + q.x * e1 + q.y * e2, None)
            }
            &Emitter::Disk { center, radius, n, e1, e2 } => {
                let q = concentric_disk(u) * radius;
                (center + offset + q.x * e1 + q.y * e2, Some(n))
            }
            &Emitter::Rectangle { corner, edge_u, edge_v, n } => {
                (corner + offset + u.0 * edge_u + u.1 * edge_v, Some(n))
            }
            Emitter::Polygon { fan, cumulative, n } => {
                (offset + in_polygon(fan, cumulative, u)?, Some(*n))
            }
        };
        let d = point - p;
        let d2 = d.length_squared();
        if !d2.is_finite() || d2 <= MIN_DIST2 {
            return None;
        }
        let l = d / d2.sqrt();
        // Both faces of flat shapes emit (the cosine's absolute value), unless one-sided: then
        // only where the light leaves the point toward the normal's side.
        if self.one_sided && normal.is_some_and(|n| n.dot(l) >= 0.0) {
            return None;
        }
        let cos_light = normal.map_or(1.0, |n| n.dot(l).abs());
        let cl = self.color * (intensity * cos_light / d2);
        (cl != Vec3::ZERO).then_some(LightSample { point, l, cl })
    }
}

/// The fan of a convex polygon (see [`Emitter::Polygon`]).
fn polygon(points: &[[f32; 3]]) -> Emitter {
    let p: Vec<Vec3> = points.iter().map(|&q| Vec3::from(q)).collect();
    let mut fan = Vec::new();
    let mut cumulative = Vec::new();
    let mut total = 0.0;
    let mut normal = Vec3::ZERO;
    for k in 1..p.len().saturating_sub(1) {
        let (a, b, c) = (p[0], p[k], p[k + 1]);
        let cross = (b - a).cross(c - a);
        normal += cross;
        total += 0.5 * cross.length();
        fan.push([a, b, c]);
        cumulative.push(total);
    }
    Emitter::Polygon { fan, cumulative, n: normal.normalize_or_zero() }
}

/// The point of the fan chosen by `u`, uniform in area: `u.0` picks the triangle by area
/// and is rescaled within it (so strata stay strata), then the square-root map fills the
/// triangle uniformly.
fn in_polygon(fan: &[[Vec3; 3]], cumulative: &[f32], u: (f32, f32)) -> Option<Vec3> {
    let total = *cumulative.last()?;
    let x = u.0 * total;
    let k = cumulative.iter().position(|&c| x < c).unwrap_or(fan.len() - 1);
    let below = if k == 0 { 0.0 } else { cumulative[k - 1] };
    let span = cumulative[k] - below;
    let w = if span > 0.0 { ((x - below) / span).clamp(0.0, 1.0) } else { 0.5 };
    let s = w.sqrt();
    let [a, b, c] = fan[k];
    Some(a * (1.0 - s) + b * (s * (1.0 - u.1)) + c * (s * u.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use reyes_scene::LightKey;

    fn moving(open: f32, close: f32, keys: &[(f32, f32, f32)]) -> AreaLight {
        let mut scene = reyes_scene::parse(
            "Scene(image: (width: 8, height: 8), \
             camera: (eye: (0.0, 0.0, -10.0), look_at: (0.0, 0.0, 0.0)))",
            std::path::Path::new("t.ron"),
        )
        .expect("parses");
        scene.camera.shutter.open = open;
        scene.camera.shutter.close = close;
        let light = Light::Area {
            shape: AreaShape::Sphere { center: [0.0; 3], radius: 1.0 },
            color: [1.0; 3],
            intensity: 7.0,
            motion: keys
                .iter()
                .map(|&(time, x, intensity)| LightKey { time, offset: [x, 0.0, 0.0], intensity })
                .collect(),
            one_sided: false,
        };
        match DirectLight::new(&light, &ShutterNorm::new(&scene)) {
            Some(DirectLight::Area(a)) => a,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn motion_keys_are_normalised_by_the_shutter_and_held() {
        // Shutter [10, 14]; keys at scene times 11 and 13 (normalised 0.25 and 0.75).
        let a = moving(10.0, 14.0, &[(11.0, 2.0, 1.0), (13.0, 4.0, 3.0)]);
        assert_eq!(a.at(0.0), (Vec3::new(2.0, 0.0, 0.0), 1.0));
        assert_eq!(a.at(0.5), (Vec3::new(3.0, 0.0, 0.0), 2.0));
        assert_eq!(a.at(1.0), (Vec3::new(4.0, 0.0, 0.0), 3.0));
        // Closed shutter: the first key only.
        let a = moving(10.0, 10.0, &[(11.0, 2.0, 1.0), (13.0, 4.0, 3.0)]);
        assert_eq!(a.at(0.7), (Vec3::new(2.0, 0.0, 0.0), 1.0));
        // No keys: still at the light's own intensity.
        assert_eq!(moving(0.0, 1.0, &[]).at(0.3), (Vec3::ZERO, 7.0));
    }

    #[test]
    fn disk_light_cosine_and_inverse_square() {
        let light = Light::Area {
            shape: AreaShape::Disk {
                center: [0.0, 2.0, 0.0],
                normal: [0.0, -1.0, 0.0],
                radius: 1e-3,
            },
            color: [1.0, 0.5, 0.25],
            intensity: 8.0,
            motion: vec![],
            one_sided: false,
        };
        let Some(DirectLight::Area(a)) =
            DirectLight::new(&light, &ShutterNorm { open: 0.0, span: 1.0, closed: false })
        else {
            panic!("area light");
        };
        // From (2, 0, 0): d^2 = 8, cos at the light = 2 / sqrt(8).
        let s = a.sample(Vec3::new(2.0, 0.0, 0.0), 0.0, (0.5, 0.5)).expect("lit");
        let want = 8.0 * (2.0 / 8f32.sqrt()) / 8.0;
        assert!((s.cl.x - want).abs() < 1e-4 && (s.cl.z - want / 4.0).abs() < 1e-4, "{:?}", s.cl);
        // The back face emits too.
        let s = a.sample(Vec3::new(2.0, 4.0, 0.0), 0.0, (0.5, 0.5)).expect("lit");
        assert!((s.cl.x - want).abs() < 1e-4);
    }

    #[test]
    fn one_sided_lights_emit_toward_their_normal_only() {
        let light = Light::Area {
            shape: AreaShape::Polygon {
                points: vec![[0.0, 2.0, 0.0], [1.0, 2.0, 0.0], [0.0, 2.0, 1.0]],
            },
            color: [1.0; 3],
            intensity: 1.0,
            motion: vec![],
            one_sided: true,
        };
        let Some(DirectLight::Area(a)) =
            DirectLight::new(&light, &ShutterNorm { open: 0.0, span: 1.0, closed: false })
        else {
            panic!("area light");
        };
        // (1, 0, 0) x (0, 0, 1) = (0, -1, 0): the triangle faces down.
        assert!(a.sample(Vec3::new(0.2, 0.0, 0.2), 0.0, (0.3, 0.6)).is_some());
        assert!(a.sample(Vec3::new(0.2, 4.0, 0.2), 0.0, (0.3, 0.6)).is_none());
        // Uniform in area: the point lies in the triangle for every draw.
        for u in [(0.0, 0.0), (0.99, 0.99), (0.5, 0.1), (0.1, 0.9)] {
            let q = a.sample(Vec3::new(0.2, 0.0, 0.2), 0.0, u).expect("lit").point;
            assert!(q.x >= -1e-6 && q.z >= -1e-6 && q.x + q.z <= 1.0 + 1e-6, "{q}");
        }
    }
}
