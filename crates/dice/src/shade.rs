//! Shading stage: colour and transmittance at grid vertices, in world space, at shutter open.
//!
//! Invariants: lighting is two-sided (the normal is face-forwarded toward the eye), the
//! output colour is premultiplied by opacity (`Os * Ci`) and `trans = 1 - Os`; every output
//! is finite for finite input (a point light at the shaded point contributes nothing).
//!
//! The illumination models themselves ([`Shader::illuminate`]) are public so that the
//! ray-traced shading (reyes-shade) evaluates the same Constant, Matte, Plastic and Metal
//! models under its own lights (shadowed, area-sampled) without a second copy of them.
//!
//! An object lit by a light set (`Object::lights`) is shaded by [`Shader::for_object`] under
//! those lights only, ambient ones included; the viewing vector comes from a [`Viewer`] (the
//! eye, or an orthographic camera's view direction).

use glam::Vec3;
use reyes_scene::{Light, Material, Object};

use crate::camera::Viewer;
pub use crate::lookdev::Looked;
use crate::spot::SpotLight;

/// A light after setup: the ambient ones are summed into [`Shader`]'s ambient term.
#[derive(Debug, Clone, Copy, PartialEq)]
enum DirectLight {
    /// Parallel light: unit direction towards the light and colour.
    Distant { l: Vec3, cl: Vec3 },
    /// Point light: position and `intensity * color` (divided by d^2 at the surface).
    Point { from: Vec3, cl: Vec3 },
    /// RenderMan's spotlight.
    Spot(SpotLight),
}

/// The illumination model of a material.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Model {
    Constant,
    Matte { ka: f32, kd: f32 },
    Plastic { ka: f32, kd: f32, ks: f32, exponent: f32, specular: Vec3 },
    Metal { ka: f32, ks: f32, exponent: f32 },
    Headlight { ka: f32, kd: f32 },
}

/// Shades points of one object: its material's illumination model, colour and opacity,
/// and the scene's (or the object's light set's) ambient, distant, point and spot lights.
#[derive(Debug, Clone, PartialEq)]
pub struct Shader {
    model: Model,
    /// Surface colour `Cs` (before mesh tints).
    cs: Vec3,
    /// Opacity `Os`.
    os: Vec3,
    /// Sum of the ambient lights.
    ambient: Vec3,
    lights: Vec<DirectLight>,
    viewer: Viewer,
    /// Each ambient light's scene index and `intensity * color`, in the order `ambient`
    /// sums them (for the shading components of a light group).
    ambient_each: Vec<(usize, Vec3)>,
    /// The scene index of each of `lights`.
    light_index: Vec<usize>,
}

/// The premultiplied ambient, diffuse and specular terms of one shaded point
/// ([`Shader::components`]).
pub type Components = [Vec3; 3];

/// The smallest factor a roughness map may scale a material's roughness by (the exponent
/// `8 / roughness` stays finite).
pub const MIN_ROUGHNESS: f32 = 1e-3;

/// `d^2` below which a point light is taken to sit on the surface and is ignored.
const MIN_DIST2: f32 = 1e-20;

impl Shader {
    /// Set up the shading of `material` under `lights`, seen from `eye_world`.
    pub fn new(material: &Material, lights: &[Light], eye_world: Vec3) -> Shader {
        Shader::with_lights(material, lights.iter().enumerate(), Viewer::Eye(eye_world))
    }

    /// Set up the shading of `object`'s material under the lights of the scene's `lights`
    /// that illuminate it ([`Object::lit_by`]: all of them without a light set), seen by
    /// `viewer`.
    pub fn for_object(object: &Object, lights: &[Light], viewer: Viewer) -> Shader {
        let lit = lights.iter().enumerate().filter(|(i, _)| object.lit_by(*i));
        Shader::with_lights(&object.material, lit, viewer)
    }

    /// Set up the shading of `material` under `lights` (with their scene indices), in order,
    /// seen by `viewer`.
    fn with_lights<'l>(
        material: &Material,
        lights: impl Iterator<Item = (usize, &'l Light)>,
        viewer: Viewer,
    ) -> Shader {
        let (model, cs, os) = match *material {
            Material::Constant { color, opacity } => (Model::Constant, color, opacity),
            Material::Matte { color, opacity, ka, kd } => (Model::Matte { ka, kd }, color, opacity),
            Material::Plastic { color, opacity, ka, kd, ks, roughness, specular_color } => (
                Model::Plastic {
                    ka,
                    kd,
                    ks,
                    // RenderMan's specular(): PRMan, BMRT, Aqsis and Pixie all raise N.H to
                    // 1 / (roughness / 8); the Specification's listing leaves it open.
                    exponent: 8.0 / roughness,
                    specular: Vec3::from(specular_color),
                },
                color,
                opacity,
            ),
            Material::Metal { color, opacity, ka, ks, roughness } => {
                (Model::Metal { ka, ks, exponent: 8.0 / roughness }, color, opacity)
            }
            Material::DefaultSurface { color, opacity, ka, kd } => {
                (Model::Headlight { ka, kd }, color, opacity)
            }
            // Shaded on the grid machine (object.shaders): the native model only gives its
            // Cs and Os.
            Material::Shader { color, opacity, .. } => (Model::Constant, color, opacity),
        };
        let mut ambient = Vec3::ZERO;
        let mut direct = Vec::new();
        let (mut ambient_each, mut light_index) = (Vec::new(), Vec::new());
        for (index, light) in lights {
            let before = direct.len();
            match *light {
                Light::Ambient { color, intensity } => {
                    ambient += intensity * Vec3::from(color);
                    ambient_each.push((index, intensity * Vec3::from(color)));
                }
                Light::Distant { from, to, color, intensity, .. } => {
                    // A light with from == to has no direction and lights nothing.
                    if let Some(l) = (Vec3::from(from) - Vec3::from(to)).try_normalize() {
                        direct.push(DirectLight::Distant { l, cl: intensity * Vec3::from(color) });
                    }
                }
                Light::Point { from, color, intensity, .. } => direct.push(DirectLight::Point {
                    from: Vec3::from(from),
                    cl: intensity * Vec3::from(color),
                }),
                Light::Spot { .. } => {
                    // A spot light with from == to has no axis and lights nothing.
                    if let Some(spot) = SpotLight::of(light) {
                        direct.push(DirectLight::Spot(spot));
                    }
                }
                // Area lights are sampled by the ray-traced shading (reyes-shade).
                Light::Area { .. } => {}
            }
            light_index.extend(std::iter::repeat_n(index, direct.len() - before));
        }
        Shader {
            model,
            cs: Vec3::from(cs),
            os: Vec3::from(os),
            ambient,
            lights: direct,
            viewer,
            ambient_each,
            light_index,
        }
    }

    /// True if the material is fully opaque in every channel.
    pub fn opaque(&self) -> bool {
        self.os == Vec3::ONE
    }

    /// The material's surface colour `Cs` (before tints and patterns).
    pub fn color(&self) -> Vec3 {
        self.cs
    }

    /// The material's opacity `Os`.
    pub fn opacity(&self) -> Vec3 {
        self.os
    }

    /// The sum of the scene's ambient lights (`intensity * color` each).
    pub fn ambient(&self) -> Vec3 {
        self.ambient
    }

    /// True if the material ignores lights (`Constant`): [`Shader::illuminate`] then never
    /// reads its light list.
    pub fn unlit(&self) -> bool {
        self.model == Model::Constant
    }

    /// The colour `Ci` (not premultiplied) of a point of surface colour `cs`, with unit
    /// normal `n` already face-forwarded toward the viewer and unit vector `v` toward the
    /// viewer, under the ambient lights and the direct lights `lights`: pairs of the unit
    /// vector `L` toward the light and the colour `Cl` arriving (already divided by any
    /// distance fall-off and multiplied by any shadowing). Per model:
    ///
    /// * Constant: `cs` (the lights are not read);
    /// * Matte: `cs * (ka * ambient + kd * sum Cl max(0, N.L))`;
    /// * Plastic: the Matte terms with its `ka`, `kd`, plus
    ///   `specular_color * ks * sum Cl max(0, N.H)^(8/roughness)`, `H = normalize(L + V)`,
    ///   over the lights with `N.L > 0`;
    /// * Metal: `cs * (ka * ambient + ks * sum Cl max(0, N.H)^(8/roughness))`, the same
    ///   specular sum coloured by the surface (RenderMan's `metal`);
    /// * DefaultSurface: `cs * (ka + kd * (N.V)^2)`, a headlight at the eye (RenderMan's
    ///   `defaultsurface`; the lights are not read).
    pub fn illuminate(
        &self,
        cs: Vec3,
        n: Vec3,
        v: Vec3,
        lights: impl IntoIterator<Item = (Vec3, Vec3)>,
    ) -> Vec3 {
        self.illuminate_with(self.model, cs, n, v, lights)
    }

    /// [`Shader::illuminate`] with the model's roughness and specular coefficient scaled by
    /// texture maps (`looked`; the colour and opacity maps are the caller's).
    pub fn illuminate_looked(
        &self,
        looked: &Looked,
        cs: Vec3,
        n: Vec3,
        v: Vec3,
        lights: impl IntoIterator<Item = (Vec3, Vec3)>,
    ) -> Vec3 {
        self.illuminate_with(self.model_looked(looked), cs, n, v, lights)
    }

    /// The model with its roughness multiplied by `looked.roughness` (kept at or above
    /// [`MIN_ROUGHNESS`] times the material's) and its `ks` by `looked.specular`.
    fn model_looked(&self, looked: &Looked) -> Model {
        let exponent = |e: f32| e / looked.roughness.max(MIN_ROUGHNESS);
        match self.model {
            Model::Plastic { ka, kd, ks, exponent: e, specular } => {
                Model::Plastic { ka, kd, ks: ks * looked.specular, exponent: exponent(e), specular }
            }
            Model::Metal { ka, ks, exponent: e } => {
                Model::Metal { ka, ks: ks * looked.specular, exponent: exponent(e) }
            }
            other => other,
        }
    }

    fn illuminate_with(
        &self,
        model: Model,
        cs: Vec3,
        n: Vec3,
        v: Vec3,
        lights: impl IntoIterator<Item = (Vec3, Vec3)>,
    ) -> Vec3 {
        match model {
            Model::Constant => cs,
            Model::Matte { ka, kd } => {
                let (diffuse, _) = direct(n, None, lights);
                cs * (ka * self.ambient + kd * diffuse)
            }
            Model::Plastic { ka, kd, ks, exponent, specular } => {
                let (diffuse, spec) = direct(n, Some((v, exponent)), lights);
                cs * (ka * self.ambient + kd * diffuse) + specular * ks * spec
            }
            Model::Metal { ka, ks, exponent } => {
                let (_, spec) = direct(n, Some((v, exponent)), lights);
                cs * (ka * self.ambient + ks * spec)
            }
            Model::Headlight { ka, kd } => {
                let d = n.dot(v);
                cs * (ka + kd * d * d)
            }
        }
    }

    /// Premultiplied colour `Os * Ci` and transmittance `1 - Os` at a world-space point with
    /// (not necessarily face-forwarded) normal `n_world`; `tint` multiplies `Cs`.
    pub fn shade(&self, p_world: Vec3, n_world: Vec3, tint: Vec3) -> ([f32; 3], [f32; 3]) {
        self.shade_looked(p_world, n_world, tint, &Looked::NONE)
    }

    /// [`Shader::shade`] under texture maps: `looked.color` multiplies `Cs`, `looked.opacity`
    /// multiplies `Os`, and the roughness and `ks` are scaled ([`Shader::illuminate_looked`]).
    pub fn shade_looked(
        &self,
        p_world: Vec3,
        n_world: Vec3,
        tint: Vec3,
        looked: &Looked,
    ) -> ([f32; 3], [f32; 3]) {
        let cs = self.cs * tint * looked.color;
        let os = self.os * looked.opacity;
        let ci = if self.unlit() {
            cs
        } else {
            let (n, v) = facing(p_world, n_world, self.viewer.seen_from(p_world));
            let lights = self.arriving(p_world).map(|(_, l, cl)| (l, cl));
            self.illuminate_with(self.model_looked(looked), cs, n, v, lights)
        };
        ((os * ci).to_array(), (Vec3::ONE - os).to_array())
    }

    /// The number of direct (non-ambient) lights.
    pub fn direct_lights(&self) -> usize {
        self.lights.len()
    }

    /// For the shading-language machine: per direct light, in order, the vector from the
    /// light to `p_world` (a distant light's unit direction) and the colour arriving there
    /// (as [`Shader::shade`] computes it), or `None` where nothing arrives.
    pub fn light_vectors(&self, p_world: Vec3) -> impl Iterator<Item = Option<(Vec3, Vec3)>> + '_ {
        self.lights.iter().map(move |light| match *light {
            DirectLight::Distant { l, cl } => Some((-l, cl)),
            DirectLight::Point { from, cl } => {
                let d = p_world - from;
                let d2 = d.length_squared();
                (d2.is_finite() && d2 > MIN_DIST2).then(|| (d, cl / d2))
            }
            DirectLight::Spot(spot) => {
                spot.arriving(p_world).map(|(_, cl)| (p_world - spot.from(), cl))
            }
        })
    }

    /// The direct lights arriving at `p_world`: each one's position in `lights`, unit vector
    /// toward it and colour arriving (a point light at the point contributes nothing).
    fn arriving(&self, p_world: Vec3) -> impl Iterator<Item = (usize, Vec3, Vec3)> + '_ {
        self.lights.iter().enumerate().filter_map(move |(k, light)| match *light {
            DirectLight::Distant { l, cl } => Some((k, l, cl)),
            DirectLight::Point { from, cl } => {
                let d = from - p_world;
                let d2 = d.length_squared();
                if !d2.is_finite() || d2 <= MIN_DIST2 {
                    return None;
                }
                Some((k, d / d2.sqrt(), cl / d2))
            }
            DirectLight::Spot(spot) => spot.arriving(p_world).map(|(l, cl)| (k, l, cl)),
        })
    }

    /// The shading components at a point, as [`Shader::shade`] sees it, premultiplied by
    /// opacity: `[ambient, diffuse, specular]` (RenderMan's `__ambient`, `__diffuse`,
    /// `__specular`). With `group`, only the lights whose scene indices it lists; without,
    /// every light and the terms no light causes (a Constant material's colour and the
    /// DefaultSurface headlight's `ka`, counted as ambient, and its `kd (N.V)^2`, counted as
    /// diffuse). Without a group the three add up to [`Shader::shade`]'s colour to within
    /// float rounding: they are the same products, summed in a different order.
    pub fn components(
        &self,
        p_world: Vec3,
        n_world: Vec3,
        tint: Vec3,
        group: Option<&[u32]>,
    ) -> Components {
        self.components_looked(p_world, n_world, tint, group, &Looked::NONE)
    }

    /// [`Shader::components`] under texture maps, as [`Shader::shade_looked`] shades.
    pub fn components_looked(
        &self,
        p_world: Vec3,
        n_world: Vec3,
        tint: Vec3,
        group: Option<&[u32]>,
        looked: &Looked,
    ) -> Components {
        let cs = self.cs * tint * looked.color;
        let os = self.os * looked.opacity;
        let in_group = |index: usize| group.is_none_or(|g| g.iter().any(|&i| i as usize == index));
        let ungrouped = group.is_none();
        let mut ambient = Vec3::ZERO;
        for &(index, cl) in &self.ambient_each {
            if in_group(index) {
                ambient += cl;
            }
        }
        let (n, v) = facing(p_world, n_world, self.viewer.seen_from(p_world));
        let lights = || {
            self.arriving(p_world)
                .filter(|&(k, _, _)| in_group(self.light_index[k]))
                .map(|(_, l, cl)| (l, cl))
        };
        let c = match self.model_looked(looked) {
            Model::Constant => [if ungrouped { cs } else { Vec3::ZERO }, Vec3::ZERO, Vec3::ZERO],
            Model::Matte { ka, kd } => {
                let (diffuse, _) = direct(n, None, lights());
                [cs * (ka * ambient), cs * (kd * diffuse), Vec3::ZERO]
            }
            Model::Plastic { ka, kd, ks, exponent, specular } => {
                let (diffuse, spec) = direct(n, Some((v, exponent)), lights());
                [cs * (ka * ambient), cs * (kd * diffuse), specular * ks * spec]
            }
            Model::Metal { ka, ks, exponent } => {
                let (_, spec) = direct(n, Some((v, exponent)), lights());
                [cs * (ka * ambient), Vec3::ZERO, cs * (ks * spec)]
            }
            Model::Headlight { ka, kd } if ungrouped => {
                let d = n.dot(v);
                [cs * ka, cs * (kd * d * d), Vec3::ZERO]
            }
            Model::Headlight { .. } => [Vec3::ZERO; 3],
        };
        c.map(|term| os * term)
    }
}

/// The unit normal `n_world` face-forwarded toward `from` (two-sided lighting: flipped when
/// it faces away), and the unit vector from `p_world` to `from` (zero if they coincide).
pub fn facing(p_world: Vec3, n_world: Vec3, from: Vec3) -> (Vec3, Vec3) {
    let v = (from - p_world).normalize_or_zero();
    let n = n_world.normalize_or_zero();
    (if n.dot(v) < 0.0 { -n } else { n }, v)
}

/// Sums over `lights` of `Cl * max(0, N.L)` and, when `specular` gives `(V, exponent)`, of
/// `Cl * max(0, N.H)^exponent` where `N.L > 0`.
fn direct(
    n: Vec3,
    specular: Option<(Vec3, f32)>,
    lights: impl IntoIterator<Item = (Vec3, Vec3)>,
) -> (Vec3, Vec3) {
    let mut diffuse = Vec3::ZERO;
    let mut spec = Vec3::ZERO;
    for (l, cl) in lights {
        let n_dot_l = n.dot(l);
        if n_dot_l <= 0.0 {
            continue;
        }
        diffuse += cl * n_dot_l;
        if let Some((v, exponent)) = specular {
            let h = (l + v).normalize_or_zero();
            spec += cl * n.dot(h).max(0.0).powf(exponent);
        }
    }
    (diffuse, spec)
}

#[cfg(test)]
mod tests {
    use super::*;
    use reyes_testkit::fixtures;

    fn close3(a: [f32; 3], b: Vec3) -> bool {
        (Vec3::from(a) - b).abs().max_element() < 1e-5
    }

    const EYE: Vec3 = Vec3::new(0.0, 0.0, -10.0);

    /// An opaque Plastic with no ambient term and white highlights.
    fn plastic(color: [f32; 3], kd: f32, ks: f32, roughness: f32) -> Material {
        let (opacity, specular_color) = ([1.0; 3], [1.0; 3]);
        Material::Plastic { color, opacity, ka: 0.0, kd, ks, roughness, specular_color }
    }

    /// A white distant light of intensity 1 shining from `from` towards the origin.
    fn distant(from: [f32; 3]) -> Light {
        Light::Distant { from, to: [0.0; 3], color: [1.0; 3], intensity: 1.0, shadows: false }
    }

    #[test]
    fn constant_is_premultiplied_colour() {
        let m = Material::Constant { color: [0.5, 1.0, 0.2], opacity: [0.5, 1.0, 0.0] };
        let s = Shader::new(&m, &[], EYE);
        let (c, t) = s.shade(Vec3::ZERO, Vec3::Z, Vec3::new(1.0, 0.5, 1.0));
        assert!(close3(c, Vec3::new(0.25, 0.5, 0.0)), "{c:?}");
        assert!(close3(t, Vec3::new(0.5, 0.0, 1.0)), "{t:?}");
        assert!(!s.opaque());
        assert!(
            Shader::new(&Material::Constant { color: [1.0; 3], opacity: [1.0; 3] }, &[], EYE)
                .opaque()
        );
    }

    #[test]
    fn matte_ambient_plus_lambert_two_sided() {
        let m = Material::Matte { color: [1.0, 0.5, 0.25], opacity: [1.0; 3], ka: 0.5, kd: 2.0 };
        let lights = [
            Light::Ambient { color: [0.2, 0.2, 0.2], intensity: 1.0 },
            // From the eye's side at 60 degrees off the normal: cos = 0.5.
            Light::Distant {
                from: [0.0, 3.0_f32.sqrt(), -1.0],
                to: [0.0, 0.0, 0.0],
                color: [1.0, 1.0, 1.0],
                intensity: 0.8,
                shadows: false,
            },
        ];
        let s = Shader::new(&m, &lights, EYE);
        let expect = Vec3::new(1.0, 0.5, 0.25) * (0.5 * 0.2 + 2.0 * 0.8 * 0.5);
        // The normal facing away from the eye is flipped: both sides shade the same.
        for n in [Vec3::NEG_Z, Vec3::Z] {
            let (c, _) = s.shade(Vec3::ZERO, n, Vec3::ONE);
            assert!(close3(c, expect), "n {n}: {c:?} vs {expect}");
        }
    }

    #[test]
    fn point_light_falls_off_with_distance_squared() {
        let m = Material::Matte { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, kd: 1.0 };
        let lights = [Light::Point {
            from: [0.0, 0.0, -4.0],
            color: [1.0, 0.5, 1.0],
            intensity: 8.0,
            shadows: false,
        }];
        let s = Shader::new(&m, &lights, EYE);
        let (c, _) = s.shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
        assert!(close3(c, Vec3::new(0.5, 0.25, 0.5)), "{c:?}");
        // A light at the surface point contributes nothing instead of NaN.
        let (c, _) = s.shade(Vec3::new(0.0, 0.0, -4.0), Vec3::NEG_Z, Vec3::ONE);
        assert!(close3(c, Vec3::ZERO), "{c:?}");
        // A light behind the surface (after face-forwarding) contributes nothing.
        // (The point at z = -5 faces the eye at z = -10; the light is on its far side.)
        let (c, _) = s.shade(Vec3::new(0.0, 0.0, -5.0), Vec3::Z, Vec3::ONE);
        assert!(close3(c, Vec3::ZERO), "{c:?}");
    }

    #[test]
    fn plastic_specular_peak_and_cut_off() {
        let m = plastic([1.0, 0.0, 0.0], 0.5, 0.5, 0.1);
        // Light straight along the view: N.L = N.H = 1.
        let lights = [distant([0.0, 0.0, -1.0])];
        let s = Shader::new(&m, &lights, EYE);
        let (c, _) = s.shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
        assert!(close3(c, Vec3::new(1.0, 0.5, 0.5)), "{c:?}");
        // Off the mirror direction the highlight falls as cos^(8/roughness).
        let tilted = [distant([0.0, 1.0, -1.0])];
        let s = Shader::new(&m, &tilted, EYE);
        let (c, _) = s.shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
        let n_dot_l = 0.5_f32.sqrt();
        let n_dot_h = (22.5_f32).to_radians().cos();
        let spec = 0.5 * n_dot_h.powf(80.0);
        assert!(close3(c, Vec3::new(0.5 * n_dot_l + spec, spec, spec)), "{c:?}");
        // Light behind the surface: no diffuse and no specular.
        let behind = [distant([0.0, 0.0, 1.0])];
        let s = Shader::new(&m, &behind, EYE);
        let (c, _) = s.shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
        assert!(close3(c, Vec3::ZERO), "{c:?}");
    }

    #[test]
    fn metal_is_specular_in_the_surface_colour() {
        let m = Material::Metal {
            color: [0.9, 0.6, 0.3],
            opacity: [0.5, 1.0, 1.0],
            ka: 0.5,
            ks: 0.8,
            roughness: 0.2,
        };
        let lights =
            [Light::Ambient { color: [0.4; 3], intensity: 0.5 }, distant([0.0, 1.0, -1.0])];
        let s = Shader::new(&m, &lights, EYE);
        // Ci = Os * Cs * (Ka ambient + Ks specular); no diffuse term.
        let n_dot_h = 22.5_f32.to_radians().cos();
        let spec = n_dot_h.powf(8.0 / 0.2);
        let ci = Vec3::new(0.9, 0.6, 0.3) * (0.5 * 0.2 + 0.8 * spec);
        let (c, t) = s.shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
        assert!(close3(c, Vec3::new(0.5, 1.0, 1.0) * ci), "{c:?} vs {ci}");
        assert!(close3(t, Vec3::new(0.5, 0.0, 0.0)), "{t:?}");
        // The specular term is Plastic's: with ka = kd = 0 and a white surface, the same.
        let plastic = plastic([1.0; 3], 0.0, 0.8, 0.2);
        let metal = Material::Metal {
            color: [1.0; 3],
            opacity: [1.0; 3],
            ka: 0.0,
            ks: 0.8,
            roughness: 0.2,
        };
        for from in [[0.0, 1.0, -1.0], [0.3, 0.2, -1.0], [-1.0, 0.5, -0.2]] {
            let lights = [distant(from)];
            let a = Shader::new(&plastic, &lights, EYE).shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
            let b = Shader::new(&metal, &lights, EYE).shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE);
            assert_eq!(a, b, "light from {from:?}");
        }
    }

    #[test]
    fn spot_light_shades_by_the_specifications_falloff() {
        let m = Material::Matte { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, kd: 1.0 };
        // Aimed straight down at the origin from 4 units above; the surface faces up.
        let spot = |to: [f32; 3], cone: f32, delta: f32| Light::Spot {
            from: [0.0, 4.0, 0.0],
            to,
            color: [1.0; 3],
            intensity: 16.0,
            cone_angle: cone,
            cone_delta: delta,
            beam_distribution: 2.0,
            shadows: false,
        };
        let s = Shader::new(&m, &[spot([0.0; 3], 30.0, 5.0)], Vec3::new(0.0, 10.0, -1.0));
        for x in [0.0f32, 1.0, 1.8, 2.0, 2.2, 2.5, 3.0] {
            let p = Vec3::new(x, 0.0, 0.0);
            let d2 = 16.0 + x * x;
            let cos = 4.0 / d2.sqrt();
            let step = smoothstep_f64(30.0, 25.0, f64::from(cos));
            // Lambert: N.L = cos as well.
            let want = 16.0 * cos * cos / d2 * step as f32 * cos;
            let (c, _) = s.shade(p, Vec3::Y, Vec3::ONE);
            assert!((c[0] - want).abs() < 1e-5, "x {x}: {} vs {want}", c[0]);
        }
        // From the light with from == to nothing arrives.
        let aimless = spot([0.0, 4.0, 0.0], 30.0, 5.0);
        let (c, _) = Shader::new(&m, &[aimless], EYE).shade(Vec3::ZERO, Vec3::Y, Vec3::ONE);
        assert_eq!(c, [0.0; 3]);
    }

    /// The Shading Language's smoothstep between the cosines of two angles in degrees.
    fn smoothstep_f64(outer: f64, inner: f64, x: f64) -> f64 {
        reyes_testkit::shading::smoothstep(outer.to_radians().cos(), inner.to_radians().cos(), x)
    }

    #[test]
    fn an_objects_light_set_selects_its_lights_ambient_included() {
        let lights = [
            Light::Ambient { color: [1.0; 3], intensity: 0.25 },
            distant([0.0, 0.0, -1.0]),
            Light::Ambient { color: [1.0; 3], intensity: 0.5 },
        ];
        let shape = fixtures::sphere(1.0);
        let m = Material::Matte { color: [1.0; 3], opacity: [1.0; 3], ka: 1.0, kd: 1.0 };
        let object =
            |set: Option<Vec<u32>>| Object { lights: set, ..Object::new(shape.clone(), m.clone()) };
        let shade = |set: Option<Vec<u32>>| {
            Shader::for_object(&object(set), &lights, Viewer::Eye(EYE))
                .shade(Vec3::ZERO, Vec3::NEG_Z, Vec3::ONE)
                .0[0]
        };
        assert!((shade(None) - 1.75).abs() < 1e-6, "every light: {}", shade(None));
        assert_eq!(
            Shader::for_object(&object(None), &lights, Viewer::Eye(EYE)),
            Shader::new(&m, &lights, EYE),
            "no light set is every light"
        );
        assert!((shade(Some(vec![1])) - 1.0).abs() < 1e-6, "the distant light only");
        assert!((shade(Some(vec![2, 0])) - 0.75).abs() < 1e-6, "the ambient lights only");
        assert_eq!(shade(Some(vec![])), 0.0, "an empty set lights nothing");
    }

    #[test]
    fn an_orthographic_viewer_sees_along_its_view_direction() {
        let m = plastic([0.0; 3], 0.0, 1.0, 0.1);
        // Light and view both along -z: the highlight peaks wherever the surface faces -z,
        // however far off the axis (a perspective eye would see those points obliquely).
        let lights = [distant([0.0, 0.0, -1.0])];
        let viewer = Viewer::Along { eye: EYE, forward: Vec3::Z };
        let object = Object::new(fixtures::sphere(1.0), m.clone());
        let ortho = Shader::for_object(&object, &lights, viewer);
        let persp = Shader::new(&m, &lights, EYE);
        for x in [0.0f32, 3.0, -8.0] {
            let p = Vec3::new(x, 2.0, 1.0);
            let (c, _) = ortho.shade(p, Vec3::NEG_Z, Vec3::ONE);
            assert!((c[0] - 1.0).abs() < 1e-5, "x {x}: {c:?}");
        }
        let (c, _) = persp.shade(Vec3::new(-8.0, 2.0, 1.0), Vec3::NEG_Z, Vec3::ONE);
        assert!(c[0] < 0.5, "the perspective eye sees it obliquely: {c:?}");
    }
}
