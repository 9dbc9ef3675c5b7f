//! The transformation requests of the RI state machine that need more than a matrix
//! product: snapping exporters' rounding noise (`Transform`, `ConcatTransform`),
//! `CoordSysTransform`, the requests gathered by a motion block, and the current space to
//! the model's world.

use glam::DMat4;

use super::frame::Machine;
use super::xform::{self, Xform};
use crate::{Request, RequestKind as K, RibError};

impl Machine {
    /// The matrix of a transformation request. A `Transform` or `ConcatTransform` whose
    /// projective terms are (0, 0, 0, 1) but for exporters' rounding noise is snapped to it,
    /// with a warning (an error under `--strict`).
    pub(super) fn matrix_of(&mut self, r: &Request) -> Result<DMat4, RibError> {
        let v = |i| r.float(i).unwrap_or(0.0);
        Ok(match r.kind {
            K::ConcatTransform | K::Transform => {
                let m = r.floats(0).unwrap_or(&[0.0; 16]);
                match xform::projective(m) {
                    xform::Projective::Near(terms) => {
                        let [a, b, c, d] = terms.map(xform::show);
                        self.tolerate(
                            &r.at,
                            r.name(),
                            format!(
                                "the matrix's projective terms (its numbers 4, 8, 12 and 16) are \
                                 ({a}, {b}, {c}, {d}), not (0, 0, 0, 1)"
                            ),
                            &format!(
                                "snapped to (0, 0, 0, 1), being within {} of it relative to the \
                                 matrix's scale",
                                xform::show(xform::SNAP)
                            ),
                        )?;
                        xform::from_rib(&xform::snapped(m))
                    }
                    _ => xform::from_rib(m),
                }
            }
            K::Translate => xform::translate([v(0), v(1), v(2)]),
            K::Rotate => xform::rotate(v(0), [v(1), v(2), v(3)]),
            K::Scale => xform::scale([v(0), v(1), v(2)]),
            K::Skew => {
                let a = r.floats(0).map(<[f32]>::to_vec).unwrap_or_else(|| (0..7).map(v).collect());
                if a.len() != 7 {
                    return Err(r.error("expected 7 numbers"));
                }
                xform::skew(a[0], [a[1], a[2], a[3]], [a[4], a[5], a[6]]).ok_or_else(|| {
                    r.error("the vectors are parallel or the angle turns one past the other")
                })?
            }
            K::Perspective => xform::perspective(v(0))
                .ok_or_else(|| r.error(format!("fov must be in (0, 180) degrees, got {}", v(0))))?,
            _ => DMat4::IDENTITY,
        })
    }

    pub(super) fn coord_sys_transform(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).unwrap_or_default();
        let in_world = self.in_world();
        match (name, self.coordinate_systems.get(name)) {
            ("world", _) if in_world => self.ctm = Xform::default(),
            ("camera" | "screen" | "raster" | "NDC", _) if in_world => {
                // Camera space inside the world: the inverse of the camera transformation.
                let c = &self.frame_options.camera;
                self.ctm = Xform { keys: c.keys.iter().map(|(t, m)| (*t, m.inverse())).collect() };
            }
            (_, Some((x, named_in_world))) if *named_in_world == in_world => self.ctm = x.clone(),
            (_, Some(_)) => {
                return Err(r.error(format!(
                    "coordinate system \"{name}\" was named on the other side of WorldBegin"
                )));
            }
            (_, None) => {
                return Err(r.error(format!("no coordinate system named \"{name}\"")));
            }
        }
        Ok(())
    }

    pub(super) fn motion_end(&mut self, r: &Request) -> Result<(), RibError> {
        let m = self.motion.take().ok_or_else(|| r.error("no MotionBegin is open"))?;
        let Some(first) = m.requests.first() else { return Ok(()) };
        let n = m.times.len();
        let transform_kinds = [
            K::ConcatTransform,
            K::Translate,
            K::Rotate,
            K::Scale,
            K::Skew,
            K::Transform,
            K::Perspective,
        ];
        if transform_kinds.contains(&first.kind) {
            if m.requests.len() != n || m.requests.iter().any(|q| q.kind != first.kind) {
                let mut kinds: Vec<&str> = m.requests.iter().map(Request::name).collect();
                kinds.dedup();
                return Err(RibError::Request {
                    at: m.at.clone(),
                    request: "MotionBegin",
                    message: format!(
                        "{n} times need {n} transformations of one kind, got {} ({})",
                        m.requests.len(),
                        kinds.join(", ")
                    ),
                });
            }
            let mut ms: Vec<DMat4> = Vec::with_capacity(n);
            for q in &m.requests {
                ms.push(self.matrix_of(q)?);
            }
            self.ctm = if first.kind == K::Transform {
                Xform { keys: m.times.iter().copied().zip(ms).collect() }
            } else {
                self.ctm.then_apply_keys(&m.times, &ms)
            };
            return Ok(());
        }
        if m.requests.len() != n || m.requests.iter().any(|q| q.kind != first.kind) {
            return Err(RibError::Request {
                at: m.at.clone(),
                request: "MotionBegin",
                message: format!(
                    "{n} times need {n} requests of one kind, got {}",
                    m.requests.len()
                ),
            });
        }
        match first.kind {
            K::Color | K::Opacity | K::Surface | K::LightSource | K::ShadingRate => {
                // Moving attributes: the value at shutter open, as the peers do.
                let w = first
                    .warning("motion of this attribute is not supported: the first value is used");
                self.warn_once(format!("motion {}", first.name()), w);
                let first = first.clone();
                self.dispatch(first)
            }
            _ if self.in_world() => {
                let keys = m.requests;
                let q = keys[0].clone();
                self.primitive(&q, Some((&m.times, &keys)))
            }
            _ => Err(first.error("geometry must be inside WorldBegin/WorldEnd")),
        }
    }

    /// Current space to the model's world at every time of the transformation.
    pub(super) fn to_world(&self) -> Xform {
        if self.in_world() {
            let c0 = self.frame_options.camera.at(f32::NEG_INFINITY);
            Xform::still(c0).compose(&self.ctm)
        } else {
            self.ctm.clone()
        }
    }
}
