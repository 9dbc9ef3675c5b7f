//! What the dicer stores per grid vertex for the scene's AOVs (docs/outputs.md): the values
//! the hider interpolates or composites at each sample.
//!
//! Invariant: the layout depends only on the scene's `outputs` section; a scene without AOVs
//! stores nothing, and its micropolygons, bucket lists and colours are exactly as before.

use reyes_scene::{AovSource, Scene};

/// The per-vertex AOV values of a scene, `stride()` floats per vertex:
/// `[N camera x y z, P camera x y z, s, t, object id, material id]`, then for each light set
/// of `groups` its premultiplied `[ambient rgb, diffuse rgb, specular rgb]`, then each of
/// `outputs`' shader output variables.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VertexAovs {
    /// The light sets whose shading components are stored (`None`: every light and the unlit
    /// terms), in the order the scene's AOVs first name them.
    pub groups: Vec<Option<Vec<u32>>>,
    /// The shader output variables stored, each once, with their floats (1 or 3), in the
    /// order the scene's AOVs first name them.
    pub outputs: Vec<(String, usize)>,
}

impl VertexAovs {
    /// Offset of the camera-space normal.
    pub const N: usize = 0;
    /// Offset of the camera-space position.
    pub const P: usize = 3;
    /// Offset of s (t follows).
    pub const S: usize = 6;
    /// Offset of t.
    pub const T: usize = 7;
    /// Offset of the object id.
    pub const OBJECT_ID: usize = 8;
    /// Offset of the material id.
    pub const MATERIAL_ID: usize = 9;
    /// Floats before the shading components.
    pub const BASE: usize = 10;

    /// The layout for `scene`, or `None` if it writes no AOVs.
    pub fn for_scene(scene: &Scene) -> Option<VertexAovs> {
        let o = &scene.outputs;
        if o.aovs.is_empty() {
            return None;
        }
        let mut groups: Vec<Option<Vec<u32>>> = Vec::new();
        for aov in o.aovs.iter().filter(|a| a.source.is_component()) {
            let set = aov.light_group.as_ref().map(|name| {
                o.light_groups
                    .iter()
                    .find(|g| &g.name == name)
                    .map_or(Vec::new(), |g| g.lights.clone())
            });
            if !groups.contains(&set) {
                groups.push(set);
            }
        }
        let mut outputs: Vec<(String, usize)> = Vec::new();
        for aov in o.aovs.iter().filter(|a| a.source == AovSource::Output) {
            let name = aov.variable.clone().unwrap_or_default();
            if !outputs.iter().any(|(n, _)| *n == name) {
                outputs.push((name, aov.channels().len()));
            }
        }
        Some(VertexAovs { groups, outputs })
    }

    /// Floats per vertex.
    pub fn stride(&self) -> usize {
        Self::BASE + 9 * self.groups.len() + self.outputs.iter().map(|(_, w)| w).sum::<usize>()
    }

    /// Offset and floats of the shader output variable `name`, if it is stored.
    pub fn output(&self, name: &str) -> Option<(usize, usize)> {
        let mut at = Self::BASE + 9 * self.groups.len();
        for (n, w) in &self.outputs {
            if n == name {
                return Some((at, *w));
            }
            at += w;
        }
        None
    }

    /// Offset of the component `source` (`Ambient`, `Diffuse` or `Specular`) of light set
    /// `group` (as an AOV names it), if it is stored.
    pub fn component(&self, source: AovSource, group: Option<&[u32]>) -> Option<usize> {
        let g = self.groups.iter().position(|s| s.as_deref() == group)?;
        let k = match source {
            AovSource::Ambient => 0,
            AovSource::Diffuse => 1,
            AovSource::Specular => 2,
            _ => return None,
        };
        Some(Self::BASE + 9 * g + 3 * k)
    }
}

/// The ids of every object of `scene`: `[1 + object index, 1 + index of the first object
/// with an equal material]`, as floats (exact below 2^24, which validation's limits keep).
pub fn object_ids(scene: &Scene) -> Vec<[f32; 2]> {
    let objects = &scene.objects;
    (0..objects.len())
        .map(|i| {
            let first = objects.iter().position(|o| o.material == objects[i].material).unwrap_or(i);
            [(i + 1) as f32, (first + 1) as f32]
        })
        .collect()
}
