//! Attribute requests of the RI state machine (Spec 3.2, 4.2) that need more than a field
//! set: `Attribute`, the light sources and `Illuminate`, and `Basis`.
//!
//! Invariant: each changes only the current attribute block (and, for a light, adds it to
//! the frame's lights), so `AttributeEnd` undoes it.

use reyes_scene::{Basis, Light};

use super::frame::{Machine, handle};
use crate::{Request, RibError, Value, Warning};

impl Machine {
    pub(super) fn attribute(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).unwrap_or_default();
        for p in &r.params {
            match (name, p.name.as_str()) {
                ("identifier", "name") => {
                    self.attributes.name = p.strings().and_then(|s| s.first()).cloned();
                }
                ("displacementbound", "sphere") => match p.floats() {
                    Some([r]) if r.is_finite() && *r >= 0.0 => {
                        self.attributes.displacement_bound = Some(*r);
                    }
                    _ => {
                        return Err(r.param_error(p, "\"sphere\" must be one number >= 0"));
                    }
                },
                ("trimcurve", "sense") => {
                    match p.strings().and_then(|s| s.first()).map(String::as_str) {
                        Some("inside") => self.attributes.trim_outside = false,
                        Some("outside") => self.attributes.trim_outside = true,
                        other => {
                            return Err(r.param_error(
                                p,
                                format!(
                                    "\"sense\" must be \"inside\" or \"outside\", got {}",
                                    other.map_or("no string".into(), |s| format!("\"{s}\""))
                                ),
                            ));
                        }
                    }
                }
                ("displacementbound", "coordinatesystem") => {
                    let space = p.strings().and_then(|s| s.first()).map_or("", String::as_str);
                    if space != "object" {
                        let w = Warning {
                            at: r.param_location(p),
                            message: format!(
                                "Attribute: displacementbound in \"{space}\" space is taken in object space, where displacement happens here"
                            ),
                        };
                        self.warn_once(format!("displacementbound space {space}"), w);
                    }
                }
                _ => {
                    let w = Warning {
                        at: r.param_location(p),
                        message: format!(
                            "Attribute: \"{name}\" \"{}\" is not supported: ignored",
                            p.name
                        ),
                    };
                    self.warn_once(format!("attribute {name} {}", p.name), w);
                }
            }
        }
        Ok(())
    }

    pub(super) fn light_source(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).unwrap_or_default().to_string();
        let h = handle(r, 1).ok_or_else(|| r.error("expected a light handle"))?;
        if self.sl_light(r, &name, &h)? {
            return Ok(());
        }
        let to_world = self.to_world();
        let mut tolerated = Vec::new();
        let made = super::shaders::light(
            &name,
            &r.params,
            &to_world,
            &r.at,
            &mut self.warnings,
            &mut tolerated,
        );
        let light = match made {
            super::shaders::LightResult::Light(l) => l,
            super::shaders::LightResult::Unknown(n) => {
                if self.options.strict {
                    return Err(r.error(format!("unknown light shader \"{n}\" (--strict)")));
                }
                let w = r.warning(format!(
                    "unknown light shader \"{n}\": stands in as a pointlight of its \"intensity\" and \"lightcolor\" at its \"from\""
                ));
                self.warn_once(format!("light {n}"), w);
                match super::shaders::light(
                    "pointlight",
                    &r.params,
                    &to_world,
                    &r.at,
                    &mut Vec::new(),
                    &mut Vec::new(),
                ) {
                    super::shaders::LightResult::Light(l) => l,
                    super::shaders::LightResult::Unknown(_) => {
                        Light::Ambient { color: [0.0; 3], intensity: 0.0 }
                    }
                }
            }
        };
        for t in tolerated {
            self.tolerate(&t.at, r.name(), t.what, &t.done)?;
        }
        match &mut self.build {
            Some(b) => {
                let index = b.add_light(h, light, r.at.clone());
                if !self.attributes.lights_on.contains(&index) {
                    self.attributes.lights_on.push(index);
                }
            }
            // A light before WorldBegin is placed in camera space and shines in every world
            // block that follows: to the end of its frame if declared in one, else in every
            // frame (FrameBegin saves the lights declared so far, FrameEnd restores them).
            None => self.pending_lights.push((h, light, r.at.clone())),
        }
        Ok(())
    }

    /// `AreaLightSource name handle params`: the primitives that follow in the attribute
    /// block are its emitters (see `area.rs`); the light is on for the block, and its handle
    /// names it for `Illuminate`.
    pub(super) fn area_light_source(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).unwrap_or_default().to_string();
        let h = handle(r, 1).ok_or_else(|| r.error("expected a light handle"))?;
        if name != "arealight" {
            self.tolerate(
                &r.at,
                "AreaLightSource",
                format!("unknown area light shader \"{name}\""),
                "stands in as arealight with its \"intensity\" and \"lightcolor\"",
            )?;
        }
        let (intensity, color) = super::area::shader(&name, &r.params, &r.at, &mut self.warnings);
        let Some(b) = &mut self.build else {
            let w = r.warning("an area light before WorldBegin has no geometry: ignored");
            self.warnings.push(w);
            return Ok(());
        };
        let slot = b.add_area_light(h);
        if !self.attributes.lights_on.contains(&slot) {
            self.attributes.lights_on.push(slot);
        }
        self.attributes.area_light = Some(super::area::AreaSource { slot, color, intensity });
        Ok(())
    }

    pub(super) fn illuminate(&mut self, r: &Request) -> Result<(), RibError> {
        let h = handle(r, 0).ok_or_else(|| r.error("expected a light handle"))?;
        let on = r.int(1).unwrap_or(1) != 0;
        let b =
            self.build.as_ref().ok_or_else(|| r.error("Illuminate must be inside the world"))?;
        let Some(index) = b.light_index(&h) else {
            return Err(r.error(format!("no light with handle {h}")));
        };
        let lights = &mut self.attributes.lights_on;
        if on && !lights.contains(&index) {
            lights.push(index);
        } else if !on {
            lights.retain(|&k| k != index);
        }
        Ok(())
    }

    pub(super) fn basis(&mut self, r: &Request) -> Result<(), RibError> {
        let basis = |i: usize| -> Result<Basis, RibError> {
            match r.args.get(i) {
                Some(Value::String(s)) => match s.as_str() {
                    "bezier" => Ok(Basis::Bezier),
                    "b-spline" => Ok(Basis::BSpline),
                    "catmull-rom" => Ok(Basis::CatmullRom),
                    "hermite" => Ok(Basis::Hermite),
                    "power" => Ok(Basis::Power),
                    other => Err(r.error(format!(
                        "unknown basis \"{other}\" (bezier, b-spline, catmull-rom, hermite, power, or 16 numbers)"
                    ))),
                },
                // RtBasis as written: M[row][col], row by row.
                Some(Value::Floats(v)) if v.len() == 16 => {
                    Ok(Basis::Matrix(std::array::from_fn(|row| std::array::from_fn(|col| v[4 * row + col]))))
                }
                _ => Err(r.error("each basis must be a name or 16 numbers")),
            }
        };
        let (u, v) = (basis(0)?, basis(2)?);
        let step = |i: usize| -> Result<u32, RibError> {
            let s = r.int(i).unwrap_or(3);
            u32::try_from(s)
                .ok()
                .filter(|&s| s >= 1)
                .ok_or_else(|| r.error(format!("steps must be at least 1, got {s}")))
        };
        self.attributes.basis = (u, step(1)?, v, step(3)?);
        Ok(())
    }
}
