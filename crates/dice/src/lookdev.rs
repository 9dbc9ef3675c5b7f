//! Look development set up for the dicer: every texture of the scene loaded once into one
//! [`TextureSystem`], and per object its maps, displacement and bump sources and emission,
//! evaluated at grid vertices over the micropolygon footprint.
//!
//! Invariants: a vertex's values are pure functions of the scene, the vertex's surface
//! parameters, its grid's parameter spacing (the footprint) and its object-space point at
//! shutter open, so they do not depend on threads or dicing order; the displacement bound
//! of an object ([`ObjectLook::bound`]) is at least the largest `|amount * (source -
//! center)|` its source can give (texture lookups are convex combinations of texels, noise
//! is bounded by `noise::fbm_bound`, a wave by 1), so bounds grown by it are conservative
//! whatever the declared `displacementbound`.

use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec3;
use reyes_scene::{ColorSpace, Maps, Scalar, Scene, TextureMap, TextureWrap};
use reyes_texture::{TextureError, TextureId, TextureStats, TextureSystem, Wrap, noise};

/// A texture map after setup.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MapRef {
    id: TextureId,
    wrap: Wrap,
    repeat: [f32; 2],
    width: f32,
}

/// A scalar source after setup.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Source {
    Constant(f32),
    Noise { frequency: f32, octaves: u32 },
    Wave { frequency: [f32; 2], phase: f32 },
    Texture(MapRef),
}

/// `amount * (source - center)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Field {
    pub source: Source,
    pub amount: f32,
    pub center: f32,
}

/// One object's look development.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ObjectLook {
    pub color: Option<MapRef>,
    pub opacity: Option<MapRef>,
    pub roughness: Option<MapRef>,
    pub specular: Option<MapRef>,
    pub displace: Option<Field>,
    pub bump: Option<Field>,
    pub emission: Option<Vec3>,
    /// The bound used for splitting and culling, in object-space units: the larger of the
    /// declared bound and the source's own (0 without displacement).
    pub bound: f32,
    /// The declared `displacementbound`, if any.
    pub declared: Option<f32>,
}

/// Where a vertex is, for the lookups: surface parameters, the grid's parameter spacing
/// (the micropolygon's footprint) and the object-space point at shutter open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct At {
    pub uv: [f32; 2],
    pub duv: [f32; 2],
    pub p_object: Vec3,
}

/// What the maps make of a vertex's material (1 where there is no map).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Looked {
    /// Multiplies the surface colour.
    pub color: Vec3,
    /// Multiplies the opacity.
    pub opacity: Vec3,
    /// Multiplies the roughness.
    pub roughness: f32,
    /// Multiplies the specular coefficient.
    pub specular: f32,
}

impl Looked {
    /// No maps.
    pub const NONE: Looked =
        Looked { color: Vec3::ONE, opacity: Vec3::ONE, roughness: 1.0, specular: 1.0 };
}

/// Every object's look development and the textures they share.
#[derive(Debug, Clone)]
pub struct Lookdev {
    system: Arc<TextureSystem>,
    /// The maps the shading-language shaders read (issue #32).
    shader_maps: Option<Arc<crate::sltex::ShaderMaps>>,
    objects: Vec<Option<Arc<ObjectLook>>>,
    /// What setup has to say: objects displaced without a declared bound.
    warnings: Vec<String>,
}

/// One object's look with the textures it reads.
#[derive(Debug, Clone)]
pub(crate) struct Look {
    pub system: Arc<TextureSystem>,
    pub object: Arc<ObjectLook>,
}

impl Lookdev {
    /// Load every texture of `scene` (each file and colour space once) into a cache of the
    /// scene's `texture_cache.max_bytes`, and set up every object.
    pub fn load(scene: &Scene) -> Result<Lookdev, TextureError> {
        let mut system = TextureSystem::new(scene.texture_cache.max_bytes)
            .map_err(|source| TextureError::Backing { file: "(temporary)".into(), source })?;
        let mut loaded: HashMap<(String, ColorSpace), TextureId> = HashMap::new();
        let mut objects = Vec::with_capacity(scene.objects.len());
        let mut warnings = Vec::new();
        for (i, o) in scene.objects.iter().enumerate() {
            let Maps { color, opacity, roughness, specular } = &o.maps;
            let mut map = |m: &TextureMap| load_map(&mut system, &mut loaded, m);
            let mut opt = |m: &Option<TextureMap>| m.as_ref().map(&mut map).transpose();
            let (color, opacity, roughness, specular) =
                (opt(color)?, opt(opacity)?, opt(roughness)?, opt(specular)?);
            let mut field = |s: &Scalar, amount: f32, center: f32| -> Result<Field, TextureError> {
                let mut map = |m: &TextureMap| load_map(&mut system, &mut loaded, m);
                let source = match s {
                    Scalar::Constant(v) => Source::Constant(*v),
                    Scalar::Noise { frequency, octaves } => {
                        Source::Noise { frequency: *frequency, octaves: *octaves }
                    }
                    Scalar::Wave { frequency, phase } => Source::Wave {
                        frequency: [frequency.0, frequency.1],
                        phase: phase.to_radians(),
                    },
                    Scalar::Texture(m) => Source::Texture(map(m)?),
                };
                Ok(Field { source, amount, center })
            };
            let displace = match &o.displacement {
                Some(d) => Some(field(&d.source, d.amount, d.center)?),
                None => None,
            };
            let bump = match &o.bump {
                Some(b) => Some(field(&b.source, b.amount, b.center)?),
                None => None,
            };
            if !(o.maps.is_empty() && displace.is_none() && bump.is_none() && o.emission.is_none())
            {
                let own = displace.map_or(0.0, |f| f.reach(&system));
                let declared = o.displacement.as_ref().and_then(|d| d.bound);
                let name = if o.name.is_empty() { format!("objects[{i}]") } else { o.name.clone() };
                if displace.is_some() {
                    match declared {
                        None => warnings.push(format!(
                            "objects[{i}] ({name}): displacement without a displacement bound \
                             (displacementbound); using the displacement's own, {own}"
                        )),
                        // Noise's own bound is a proven but loose one (reached nowhere
                        // near): a declared bound below it is judged by the escapes alone.
                        Some(b) if b < own && !displace.is_some_and(|f| f.is_noise()) => warnings
                            .push(format!(
                                "objects[{i}] ({name}): the displacement can reach {own}, beyond \
                             its declared bound {b}; bounds use {own}"
                            )),
                        Some(_) => {}
                    }
                }
                objects.push(Some(Arc::new(ObjectLook {
                    color,
                    opacity,
                    roughness,
                    specular,
                    displace,
                    bump,
                    emission: o.emission.map(Vec3::from),
                    bound: declared.unwrap_or(0.0).max(own),
                    declared,
                })));
            } else {
                objects.push(None);
            }
        }
        // The shaders' maps, read as stored (linear), each file once.
        let mut ids = HashMap::new();
        for (name, file) in &scene.shaders.maps {
            // A map the scene's file was to write itself (a multipass file's depth pass or
            // `Make*` request) that is not there: its lookups read 0, with the warning of a
            // name that is no map.
            if !file.exists() {
                continue;
            }
            let key = (file.to_string_lossy().into_owned(), ColorSpace::Linear);
            let id = match loaded.get(&key) {
                Some(&id) => id,
                None => {
                    let id = system.load(file, reyes_texture::ColorSpace::Linear)?;
                    loaded.insert(key, id);
                    id
                }
            };
            ids.insert(name.clone(), id);
        }
        let system = Arc::new(system);
        let shader_maps = (!scene.shaders.maps.is_empty())
            .then(|| Arc::new(crate::sltex::ShaderMaps::new(system.clone(), ids)));
        Ok(Lookdev { system, shader_maps, objects, warnings })
    }

    /// The maps of the shading-language shaders, if the scene's shaders name any.
    pub(crate) fn shader_maps(&self) -> Option<Arc<crate::sltex::ShaderMaps>> {
        self.shader_maps.clone()
    }

    /// Warnings of the render so far: shader lookups of names that are no map.
    pub fn lookup_warnings(&self) -> Vec<String> {
        self.shader_maps.as_ref().map(|m| m.warnings()).unwrap_or_default()
    }

    /// Object `i`'s look, if it has one.
    pub(crate) fn object(&self, i: usize) -> Option<Look> {
        let object = self.objects.get(i)?.as_ref()?.clone();
        Some(Look { system: self.system.clone(), object })
    }

    /// The warnings of setup (displacement without, or beyond, a declared bound).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The texture system's totals.
    pub fn texture_stats(&self) -> TextureStats {
        self.system.stats()
    }

    /// True if some tile could not be read back (see [`TextureSystem::read_failed`]).
    pub fn read_failed(&self) -> bool {
        self.system.read_failed()
    }
}

/// The reference of map `m`, loading its file into `system` unless `loaded` has it.
fn load_map(
    system: &mut TextureSystem,
    loaded: &mut HashMap<(String, ColorSpace), TextureId>,
    m: &TextureMap,
) -> Result<MapRef, TextureError> {
    let key = (m.file.clone(), m.color_space);
    let id = match loaded.get(&key) {
        Some(id) => *id,
        None => {
            let space = match m.color_space {
                ColorSpace::Srgb => reyes_texture::ColorSpace::Srgb,
                ColorSpace::Linear => reyes_texture::ColorSpace::Linear,
            };
            let id = system.load(std::path::Path::new(&m.file), space)?;
            loaded.insert(key, id);
            id
        }
    };
    let wrap = match m.wrap {
        TextureWrap::Periodic => Wrap::Periodic,
        TextureWrap::Clamp => Wrap::Clamp,
        TextureWrap::Black => Wrap::Black,
    };
    Ok(MapRef { id, wrap, repeat: [m.repeat.0, m.repeat.1], width: m.width })
}

impl MapRef {
    /// The filtered RGBA value at `at`.
    fn lookup(&self, system: &TextureSystem, at: &At) -> [f32; 4] {
        let st = [self.repeat[0] * at.uv[0], self.repeat[1] * at.uv[1]];
        let dst = [
            (self.repeat[0] * at.duv[0]).abs() * self.width,
            (self.repeat[1] * at.duv[1]).abs() * self.width,
        ];
        system.lookup(self.id, st, dst, self.wrap)
    }
}

impl Field {
    /// `amount * (source - center)` at `at`.
    pub fn eval(&self, system: &TextureSystem, at: &At) -> f32 {
        let s = match self.source {
            Source::Constant(v) => v,
            Source::Noise { frequency, octaves } => {
                noise::fbm((at.p_object * frequency).to_array(), octaves)
            }
            Source::Wave { frequency, phase } => {
                let x = std::f32::consts::TAU * (frequency[0] * at.uv[0] + frequency[1] * at.uv[1]);
                (x + phase).sin()
            }
            Source::Texture(m) => m.lookup(system, at)[0],
        };
        self.amount * (s - self.center)
    }

    /// True for gradient noise, whose own bound is loose.
    fn is_noise(&self) -> bool {
        matches!(self.source, Source::Noise { .. })
    }

    /// The largest `|amount * (source - center)|` the source can give.
    fn reach(&self, system: &TextureSystem) -> f32 {
        let (lo, hi) = match self.source {
            Source::Constant(v) => (v, v),
            Source::Noise { octaves, .. } => {
                let b = noise::fbm_bound(octaves);
                (-b, b)
            }
            Source::Wave { .. } => (-1.0, 1.0),
            Source::Texture(m) => {
                let (min, max) = system.range(m.id);
                let (lo, hi) = (min[0], max[0]);
                // Black wrap reads zeros outside the image.
                if m.wrap == Wrap::Black { (lo.min(0.0), hi.max(0.0)) } else { (lo, hi) }
            }
        };
        (self.amount * (lo - self.center)).abs().max((self.amount * (hi - self.center)).abs())
    }
}

impl ObjectLook {
    /// True if the opacity may be below 1 somewhere (an opacity map).
    pub fn may_be_transparent(&self) -> bool {
        self.opacity.is_some()
    }

    /// What the maps make of the material at `at`.
    pub fn looked(&self, system: &TextureSystem, at: &At) -> Looked {
        let mut l = Looked::NONE;
        if let Some(m) = &self.color {
            let v = m.lookup(system, at);
            l.color = Vec3::new(v[0], v[1], v[2]);
        }
        if let Some(m) = &self.opacity {
            let v = m.lookup(system, at);
            l.opacity = Vec3::new(v[0], v[1], v[2]).clamp(Vec3::ZERO, Vec3::ONE);
        }
        if let Some(m) = &self.roughness {
            l.roughness = m.lookup(system, at)[0].max(0.0);
        }
        if let Some(m) = &self.specular {
            l.specular = m.lookup(system, at)[0].max(0.0);
        }
        l
    }
}
