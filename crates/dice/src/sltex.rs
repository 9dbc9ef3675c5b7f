//! The shading language's texture calls over reyes-texture (issue #32): the machine's
//! [`Textures`] callback for `texture`, `environment` and `shadow`, and the answers of
//! `textureinfo`.
//!
//! The maps are the scene's `shaders.maps` (the files its shader parameters name), loaded with
//! the scene's other textures before rendering ([`crate::Lookdev::load`]); a call finds its map
//! by the name the shader passes. A name that is no loaded map follows the Specification's
//! fallback: the lookup returns 0 (`shadow`: 0, unshadowed), and the render warns once per
//! name; so does `shadow()` of a map that is not a shadow map. `environment()` of a plain
//! texture reads it as a latitude-longitude map.
//!
//! Channels: `texture("map"[c], ...)` reads the map's channels `c, c + 1, ...`; a grey map read
//! as a colour gives its grey in all three; a channel the map lacks reads `"fill"`.
//! Options are taken per point (a varying `"blur"` blurs each point by its own).

use std::collections::{BTreeSet, HashMap};
use std::sync::{Arc, Mutex, PoisonError};

use reyes_scene::sl::exec::space::{Mat, xform_point};
use reyes_scene::sl::exec::{
    ExecError, GridContext, LookupKind, Num, TextureQuery, Textures, Value,
};
use reyes_texture::lookup::Options;
use reyes_texture::prepared::MapKind;
use reyes_texture::{TextureId, TextureSystem};

/// The maps of a scene's shaders, shared by every grid.
#[derive(Debug)]
pub struct ShaderMaps {
    /// None: the scene's shaders name no map (every lookup takes the fallback).
    system: Option<Arc<TextureSystem>>,
    ids: HashMap<String, TextureId>,
    /// Names looked up that are no map, and shadow lookups of other maps, for the warnings.
    misses: Mutex<BTreeSet<String>>,
}

impl ShaderMaps {
    /// The maps `ids` (name to texture) of `system`.
    pub(crate) fn new(system: Arc<TextureSystem>, ids: HashMap<String, TextureId>) -> ShaderMaps {
        ShaderMaps { system: Some(system), ids, misses: Mutex::new(BTreeSet::new()) }
    }

    /// No maps: every lookup reads 0 (the RIB front end warned of names that look like
    /// texture files and are not found).
    pub(crate) fn none() -> ShaderMaps {
        ShaderMaps { system: None, ids: HashMap::new(), misses: Mutex::new(BTreeSet::new()) }
    }

    fn miss(&self, what: String) {
        self.misses.lock().unwrap_or_else(PoisonError::into_inner).insert(what);
    }

    /// What the render should warn about: one line per name.
    pub fn warnings(&self) -> Vec<String> {
        self.misses.lock().unwrap_or_else(PoisonError::into_inner).iter().cloned().collect()
    }

    /// Gives `g` the answers of `textureinfo` for every map: `"resolution"` (float[2]),
    /// `"type"` ("texture", "environment" or "shadow"), `"channels"`, and for shadow maps
    /// `"viewingmatrix"` (world to the light's camera) and `"projectionmatrix"` (world to
    /// its screen).
    pub(crate) fn set_messages(&self, g: &mut GridContext<'_>) {
        let Some(system) = &self.system else { return };
        for (name, &id) in &self.ids {
            let t = system.texture(id);
            let (w, h) = (t.levels[0].width as f32, t.levels[0].height as f32);
            let res = Value::Array(vec![Value::Num(Num::scalar(w)), Value::Num(Num::scalar(h))]);
            g.set_message("textureinfo", &format!("{name}:resolution"), res);
            let kind = match t.kind {
                MapKind::Plain => "texture",
                MapKind::LatLong | MapKind::CubeFace => "environment",
                MapKind::Shadow => "shadow",
            };
            g.set_message("textureinfo", &format!("{name}:type"), Value::Str(kind.into()));
            let channels = Value::Num(Num::scalar(t.channels as f32));
            g.set_message("textureinfo", &format!("{name}:channels"), channels);
            if let Some(hd) = &t.header {
                for (field, m) in [
                    ("viewingmatrix", hd.world_to_camera),
                    ("projectionmatrix", hd.world_to_screen),
                ] {
                    if let Some(m) = m {
                        g.set_message(
                            "textureinfo",
                            &format!("{name}:{field}"),
                            Value::Num(Num::uniform(&m)),
                        );
                    }
                }
            }
        }
    }
}

/// The callback for one shader run: the maps and the run's "current" to RenderMan's world.
pub(crate) struct SlTextures {
    pub maps: Arc<ShaderMaps>,
    pub current_to_world: Mat,
}

/// The lookup options at point `i`.
fn options(q: &TextureQuery<'_>, i: usize) -> Options {
    let mut o = Options::default();
    let mut bias = None;
    let (mut bias0, mut bias1) = (None, None);
    for (k, v) in &q.options {
        let f = || match v {
            Value::Num(n) => n.f(i),
            _ => 0.0,
        };
        match k.as_str() {
            "blur" => o.blur = [f(); 2],
            "sblur" => o.blur[0] = f(),
            "tblur" => o.blur[1] = f(),
            "width" => o.width = [f(); 2],
            "swidth" => o.width[0] = f(),
            "twidth" => o.width[1] = f(),
            "fill" => o.fill = f(),
            "samples" => o.samples = f().max(1.0) as u32,
            "bias" => bias = Some(f()),
            "bias0" => bias0 = Some(f()),
            "bias1" => bias1 = Some(f()),
            "filter" => {
                if let Value::Str(s) = v {
                    o.filter = s.clone();
                }
            }
            _ => {}
        }
    }
    o.bias = match (bias, bias0, bias1) {
        (_, Some(a), Some(b)) => [a, b],
        (Some(b), ..) => [b, b],
        (None, Some(a), None) | (None, None, Some(a)) => [a, a],
        _ => [0.0, 0.0],
    };
    o
}

/// Channel `c` of an RGBA texel of a map of `channels` channels (see the module).
fn channel(rgba: [f32; 4], channels: u32, c: usize, colour_of_grey: bool, fill: f32) -> f32 {
    match (channels, c) {
        (1, 0) => rgba[0],
        (1, 1 | 2) if colour_of_grey => rgba[0],
        (2, 0) => rgba[0],
        (2, 1) => rgba[3],
        (3 | 4, 0..=2) => rgba[c],
        (4, 3) => rgba[3],
        _ => fill,
    }
}

impl Textures for SlTextures {
    fn lookup(&mut self, q: &TextureQuery<'_>) -> Result<Num, ExecError> {
        let n = q.mask.on.len();
        let (Some(&id), Some(system)) = (self.maps.ids.get(q.name), self.maps.system.as_ref())
        else {
            self.maps.miss(format!(
                "texture \"{}\" is not a texture file along the texture search path: its lookups read 0",
                q.name
            ));
            return Ok(Num::zeros(q.channels, false, n));
        };
        let tex = system.texture(id);
        if q.kind == LookupKind::Shadow && tex.kind != MapKind::Shadow {
            self.maps.miss(format!(
                "shadow(\"{}\"): not a shadow map (its texture format is {:?}): it reads 0, unshadowed",
                q.name,
                tex.header.as_ref().map_or("", |h| h.format.as_str())
            ));
            return Ok(Num::zeros(q.channels, false, n));
        }
        let mut out = Num::zeros(q.channels, true, n);
        let corners =
            if q.kind == LookupKind::Texture { q.coords.len() / 2 } else { q.coords.len() };
        for &i in &q.mask.idx {
            let i = i as usize;
            let o = options(q, i);
            let rgba = match q.kind {
                LookupKind::Texture => {
                    let at = |k: usize| [q.coords[2 * k].f(i), q.coords[2 * k + 1].f(i)];
                    let c = if corners >= 4 { [at(0), at(1), at(2), at(3)] } else { [at(0); 4] };
                    system.texture_corners(id, c, &o)
                }
                LookupKind::Environment => {
                    let dirs: Vec<[f32; 3]> = q.coords.iter().map(|d| d.v3(i)).collect();
                    system.environment(id, &dirs, &o)
                }
                LookupKind::Shadow => {
                    let points: Vec<[f32; 3]> = q
                        .coords
                        .iter()
                        .map(|p| xform_point(&self.current_to_world, p.v3(i)))
                        .collect();
                    let v = system.shadow(id, &points, &o);
                    [v, v, v, v]
                }
            };
            let lane = out.lane_mut(i);
            for (k, v) in lane.iter_mut().enumerate() {
                *v = if q.kind == LookupKind::Shadow {
                    rgba[0]
                } else {
                    channel(rgba, tex.channels, q.channel + k, q.channels == 3, o.fill)
                };
            }
        }
        Ok(out)
    }
}
