//! Assembling one frame's scene: the lights, objects and solids of a world block with the
//! frame's options, validated by the scene crate, with every validation failure reported at
//! the RIB request that produced the offending value.
//!
//! Invariants: object names are unique where CSG needs them (leaves get generated names);
//! motion keys are fitted to the shutter (interpolated at its ends, dropped outside), so a
//! RIB motion block longer than the shutter renders what the shutter sees.

use std::collections::HashMap;

use glam::{DMat4, DVec3};
use reyes_scene::{
    Camera, CameraKey, Csg, Faces, Hider, Image, Lens, Light, Material, Object, PointsKey, Scene,
    Shape, Shutter, Solid, TransformKey,
};

use super::state::{Display, FrameOptions, Projection};
use super::xform::{self, Xform};
use crate::{Location, Request, RibError, Warning};

/// An open `SolidBegin` block.
struct SolidNode {
    op: String,
    name: Option<String>,
    at: Location,
    children: Vec<Csg>,
}

/// Where a value of the scene came from.
#[derive(Debug, Clone)]
pub(super) struct Origin {
    pub at: Location,
    pub request: &'static str,
}

/// The attributes of an object that the model keeps per scene or not yet at all.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ObjectAttributes {
    /// `ShadingRate`.
    pub shading_rate: f32,
    /// The lights on for it (light slots, see [`FrameBuild::add_light`]).
    pub lights: Vec<usize>,
}

/// Points of a deforming shape at the times of its motion block.
type PointKeys = Vec<(f32, Vec<[f32; 3]>)>;

/// One frame's world block being built.
pub(super) struct FrameBuild {
    pub options: FrameOptions,
    /// `WorldBegin`.
    at: Location,
    /// The frame is one of those asked for (else it is read and dropped).
    pub wanted: bool,
    lights: Vec<Light>,
    /// Where each light of the model was made, and by which request.
    light_origins: Vec<(Location, &'static str)>,
    /// Per RIB light (a light slot): its lights of the model, one for `LightSource`, one per
    /// emitting primitive for `AreaLightSource`.
    slots: Vec<Vec<usize>>,
    /// Handle -> light slot.
    light_handles: HashMap<String, usize>,
    objects: Vec<Object>,
    object_origins: Vec<Origin>,
    /// Per object: its transformation keys (before fitting to the shutter) and point keys.
    object_motion: Vec<(Xform, PointKeys)>,
    object_attributes: Vec<ObjectAttributes>,
    /// Object names, kept for messages after the objects move into the scene.
    object_names: Vec<String>,
    /// Objects merged into another (a solid's welded polygons, a quadric's caps).
    dropped: Vec<bool>,
    solids: Vec<Solid>,
    solid_origins: Vec<Location>,
    solid_stack: Vec<SolidNode>,
    leaves: usize,
    /// Shading-language lights (the imager comes from the options).
    pub shaders: reyes_scene::SceneShaders,
    /// The light slots of shading-language light shaders.
    pub shader_light_slots: Vec<usize>,
}

impl FrameBuild {
    pub fn new(options: FrameOptions, at: Location, wanted: bool) -> FrameBuild {
        FrameBuild {
            options,
            at,
            wanted,
            lights: Vec::new(),
            light_origins: Vec::new(),
            slots: Vec::new(),
            light_handles: HashMap::new(),
            objects: Vec::new(),
            object_origins: Vec::new(),
            object_motion: Vec::new(),
            object_attributes: Vec::new(),
            object_names: Vec::new(),
            dropped: Vec::new(),
            solids: Vec::new(),
            solid_origins: Vec::new(),
            solid_stack: Vec::new(),
            leaves: 0,
            shaders: Default::default(),
            shader_light_slots: Vec::new(),
        }
    }

    /// Adds a light under `handle` (a handle used again names the new light) and returns its
    /// light slot: what light sets (`Attributes::lights_on`) hold, resolved into lights of the
    /// model when the frame is finished.
    pub fn add_light(&mut self, handle: String, light: Light, at: Location) -> usize {
        let slot = self.add_area_light(handle);
        self.add_emitter(slot, light, at, "LightSource");
        slot
    }

    /// A light slot under `handle` without lights yet: an `AreaLightSource`, whose lights
    /// come with its geometry ([`FrameBuild::add_emitter`]).
    pub fn add_area_light(&mut self, handle: String) -> usize {
        self.slots.push(Vec::new());
        let slot = self.slots.len() - 1;
        self.light_handles.insert(handle, slot);
        slot
    }

    /// Adds `light` to the light slot `slot` and returns its index among the model's lights.
    pub fn add_emitter(
        &mut self,
        slot: usize,
        light: Light,
        at: Location,
        request: &'static str,
    ) -> usize {
        self.lights.push(light);
        self.light_origins.push((at, request));
        let index = self.lights.len() - 1;
        self.slots[slot].push(index);
        index
    }

    /// The number of lights of the model so far.
    pub fn light_count(&self) -> usize {
        self.lights.len()
    }

    /// The light slot with `handle`.
    pub fn light_index(&self, handle: &str) -> Option<usize> {
        self.light_handles.get(handle).copied()
    }

    /// Adds an object placed by `to_world` (with its motion) and, for a deforming shape, its
    /// points at the motion block's times.
    pub fn add_object(
        &mut self,
        mut object: Object,
        to_world: &Xform,
        deform: PointKeys,
        attributes: ObjectAttributes,
        origin: Origin,
    ) {
        if let Some(node) = self.solid_stack.last_mut() {
            // A CSG leaf: a name of its own.
            self.leaves += 1;
            let base = if object.name.is_empty() { "solid" } else { object.name.as_str() };
            object.name = format!("{base}#{}", self.leaves);
            node.children.push(Csg::Object(object.name.clone()));
        }
        object.transform = xform::to_model(&to_world.keys[0].1);
        self.object_names.push(object.name.clone());
        self.dropped.push(false);
        self.objects.push(object);
        self.object_origins.push(origin);
        self.object_motion.push((to_world.clone(), deform));
        self.object_attributes.push(attributes);
    }

    /// How many `SolidBegin` blocks are open.
    pub fn solid_depth(&self) -> usize {
        self.solid_stack.len()
    }

    pub fn solid_begin(&mut self, op: String, name: Option<String>, at: Location) {
        self.solid_stack.push(SolidNode { op, name, at, children: Vec::new() });
    }

    pub fn solid_end(&mut self, r: &Request) -> Result<(), RibError> {
        let node = self.solid_stack.pop().ok_or_else(|| r.error("no SolidBegin is open"))?;
        let mut children = node.children;
        if node.op == "primitive" && children.len() > 1 {
            children = self.one_surface(children);
        }
        let tree = match node.op.as_str() {
            "primitive" | "union" if children.len() == 1 => children.pop(),
            "primitive" | "union" if children.is_empty() => None,
            "primitive" | "union" => Some(Csg::Union(children)),
            "intersection" if children.len() == 1 => children.pop(),
            "intersection" if children.is_empty() => None,
            "intersection" => Some(Csg::Intersection(children)),
            _ => {
                // Difference: the first minus the rest.
                if children.is_empty() {
                    None
                } else {
                    let first = children.remove(0);
                    match children.len() {
                        0 => Some(first),
                        1 => Some(Csg::Difference(Box::new(first), Box::new(children.remove(0)))),
                        _ => Some(Csg::Difference(Box::new(first), Box::new(Csg::Union(children)))),
                    }
                }
            }
        };
        let Some(tree) = tree else {
            return Err(RibError::Request {
                at: node.at,
                request: "SolidBegin",
                message: "the solid has no geometry".into(),
            });
        };
        match self.solid_stack.last_mut() {
            Some(parent) => parent.children.push(tree),
            None => {
                // A lone primitive at the top is just its objects.
                if let Csg::Object(_) = tree {
                    return Ok(());
                }
                let name = node.name.unwrap_or_else(|| format!("solid{}", self.solids.len()));
                self.solids.push(Solid { name, tree });
                self.solid_origins.push(node.at);
            }
        }
        Ok(())
    }

    /// The leaves of one `SolidBegin "primitive"` block as the one closed surface RenderMan
    /// takes them to be: polygons under one transformation are welded into one mesh (shared
    /// positions become shared vertices, so the mesh is closed when the faces close it), and
    /// disks that exactly cap a cylinder, cone or paraboloid are dropped (the model closes
    /// those by their caps). Anything else is left as it is, and validation names the open
    /// operand.
    fn one_surface(&mut self, children: Vec<Csg>) -> Vec<Csg> {
        let index: Vec<Option<usize>> = children
            .iter()
            .map(|c| match c {
                Csg::Object(n) => self.objects_named(n),
                _ => None,
            })
            .collect();
        let Some(ix) = index.iter().copied().collect::<Option<Vec<usize>>>() else {
            return children;
        };
        let first = &self.objects[ix[0]];
        let same_place = ix.iter().all(|&i| {
            let o = &self.objects[i];
            o.transform == first.transform
                && self.object_motion[i].0 == self.object_motion[ix[0]].0
                && self.object_motion[i].1.is_empty()
        });
        if !same_place {
            return children;
        }
        if ix.iter().all(|&i| matches!(self.objects[i].shape, Shape::Mesh { .. })) {
            let merged = weld(ix.iter().map(|&i| &self.objects[i]));
            let keep = ix[0];
            self.objects[keep].shape = merged.0;
            self.objects[keep].material = merged.1;
            for &i in &ix[1..] {
                self.dropped[i] = true;
            }
            return vec![children[0].clone()];
        }
        // One capped quadric and the disks on its ends.
        let quadric: Vec<usize> = ix
            .iter()
            .copied()
            .filter(|&i| !matches!(self.objects[i].shape, Shape::Disk { .. }))
            .collect();
        if let [q] = quadric[..] {
            let caps = caps_of(&self.objects[q].shape);
            let all_caps = ix.iter().filter(|&&i| i != q).all(|&i| match self.objects[i].shape {
                Shape::Disk { height, radius, thetamax } => {
                    thetamax >= 360.0
                        && caps
                            .iter()
                            .any(|&(h, r)| h == height && (r - radius).abs() <= 1e-6 * r.max(1.0))
                }
                _ => false,
            });
            if all_caps && !caps.is_empty() {
                for &i in &ix {
                    self.dropped[i] = i != q;
                }
                let name = Csg::Object(self.object_names[q].clone());
                return vec![name];
            }
        }
        children
    }

    /// The frame's scene, validated, and its displays.
    pub fn finish(
        mut self,
        warnings: &mut Vec<Warning>,
    ) -> Result<(Scene, Vec<Display>), RibError> {
        let (open, close) = self.options.shutter;
        let camera = self.camera(warnings)?;
        // Objects: motion fitted to the shutter.
        for (object, (to_world, deform)) in self.objects.iter_mut().zip(&self.object_motion) {
            let keys = fit_keys(&to_world.keys, open, close);
            if keys.len() > 1 {
                object.motion = keys
                    .iter()
                    .map(|(t, m)| TransformKey { time: *t, transform: xform::to_model(m) })
                    .collect();
            } else {
                object.transform = xform::to_model(&keys[0].1);
            }
            if !deform.is_empty() {
                object.deform = fit_points(deform, open, close)
                    .into_iter()
                    .map(|(time, points)| PointsKey { time, points })
                    .collect();
                if object.deform.len() == 1 {
                    // A closed shutter: the points at shutter open are the shape's.
                    let points = object.deform.remove(0).points;
                    set_points(&mut object.shape, points);
                }
            }
        }
        if self.dropped.iter().any(|&d| d) {
            let dropped = std::mem::take(&mut self.dropped);
            retain_kept(&mut self.objects, &dropped);
            retain_kept(&mut self.object_origins, &dropped);
            retain_kept(&mut self.object_attributes, &dropped);
            retain_kept(&mut self.object_names, &dropped);
        }
        let shading_rate = self.shared_attributes();
        let o = &self.options;
        let hider = Hider {
            shading_rate,
            pixel_samples: o.pixel_samples,
            filter: o.filter,
            jitter: o.jitter,
            depth_filter: o.depth_filter,
            method: o.method,
            bucket_size: o.bucket_size.unwrap_or(Hider::default().bucket_size),
            max_grid_size: o.max_grid_size.unwrap_or(Hider::default().max_grid_size),
            ..Hider::default()
        };
        let mut scene = Scene {
            image: Image { width: o.width, height: o.height, crop: o.crop },
            camera,
            hider,
            lights: std::mem::take(&mut self.lights),
            objects: std::mem::take(&mut self.objects),
            solids: std::mem::take(&mut self.solids),
            raytrace: Default::default(),
            outputs: reyes_scene::Outputs { aovs: o.aovs.clone(), ..Default::default() },
            texture_cache: Default::default(),
            shader_path: Vec::new(),
            shaders: reyes_scene::SceneShaders {
                imager: o.imager.clone(),
                world_to_model: super::rsl::sl_matrix(&o.camera.at(f32::NEG_INFINITY)),
                ..std::mem::take(&mut self.shaders)
            },
        };
        for name in scene.resolve_output_types() {
            warnings.push(Warning {
                at: self.at.clone(),
                message: format!(
                    "Display: no surface or atmosphere shader of the frame has an output \
                     variable \"{name}\" of a type an image holds: its layer is 0"
                ),
            });
        }
        let displays = self.options.displays.clone();
        match reyes_scene::validate(scene) {
            Ok(scene) => Ok((scene, displays)),
            Err(issue) => Err(self.locate(&issue.path, &issue.message)),
        }
    }

    /// The model camera: RenderMan's camera space at shutter open is the world, so the camera
    /// sits at the origin looking down +z; a moving camera gets keys relative to that pose.
    fn camera(&self, warnings: &mut Vec<Warning>) -> Result<Camera, RibError> {
        let o = &self.options;
        let (projection, fov) = match o.projection {
            Projection::Perspective { fov } => (reyes_scene::Projection::Perspective, fov),
            Projection::Orthographic => (reyes_scene::Projection::Orthographic, 90.0),
        };
        // The screen window: as given, else the default for the frame aspect ratio (which
        // defaults to the image's).
        let screen_window = match (o.screen_window, o.frame_aspect) {
            (Some(w), _) => Some(w),
            (None, Some(a)) if a > 0.0 && a.is_finite() => {
                Some(if a >= 1.0 { [-a, a, -1.0, 1.0] } else { [-1.0, 1.0, -1.0 / a, 1.0 / a] })
            }
            (None, Some(a)) => {
                return Err(self.option_error(
                    "camera.screen_window",
                    &format!("the frame aspect ratio must be > 0, got {a}"),
                ));
            }
            (None, None) => None,
        };
        if o.depth_of_field.is_some() && projection == reyes_scene::Projection::Orthographic {
            warnings.push(Warning {
                at: self.at.clone(),
                message: "WorldBegin: depth of field is ignored by the orthographic projection"
                    .into(),
            });
        }
        let (open, close) = o.shutter;
        let lens = o.depth_of_field.map(|(f_stop, focal_length, focal_distance)| Lens {
            focal_length,
            f_stop,
            focal_distance,
        });
        let mut camera = Camera {
            eye: [0.0; 3],
            look_at: [0.0, 0.0, 1.0],
            up: [0.0, 1.0, 0.0],
            projection,
            screen_window,
            fov,
            hither: o.hither,
            yon: o.yon,
            shutter: Shutter { open, close, ..Shutter::default() },
            lens,
            motion: Vec::new(),
        };
        let keys = fit_keys(&o.camera.keys, open, close);
        if keys.len() > 1 {
            let c0 = keys[0].1;
            camera.motion = keys
                .iter()
                .map(|(t, c)| {
                    // The camera's pose at time t in the world of shutter open.
                    let pose: DMat4 = c0 * c.inverse();
                    let eye = pose.transform_point3(DVec3::ZERO);
                    let look = pose.transform_point3(DVec3::Z);
                    let up = pose.transform_vector3(DVec3::Y);
                    let f = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32];
                    CameraKey { time: *t, eye: f(eye), look_at: f(look), up: f(up) }
                })
                .collect();
        }
        Ok(camera)
    }

    /// The scene's shading rate (the first object's) and, per object, its own rate where it
    /// differs and its light set where it is not every light (RenderMan's ShadingRate and
    /// light sources are attributes; the model keeps them per object).
    fn shared_attributes(&mut self) -> f32 {
        let first = self.object_attributes.first().map_or(1.0, |a| a.shading_rate);
        let all: Vec<usize> = (0..self.lights.len()).collect();
        for (o, a) in self.objects.iter_mut().zip(&self.object_attributes) {
            if a.shading_rate != first {
                o.shading_rate = Some(a.shading_rate);
            }
            let mut lights: Vec<usize> =
                a.lights.iter().flat_map(|&slot| self.slots[slot].iter().copied()).collect();
            lights.sort_unstable();
            lights.dedup();
            if lights != all {
                o.lights = Some(lights.iter().map(|&l| l as u32).collect());
            }
        }
        first
    }

    fn option_error(&self, field: &str, message: &str) -> RibError {
        let origin = self.options.origins.iter().find(|(f, _, _)| field.starts_with(f));
        match origin {
            Some((_, at, request)) => {
                RibError::Request { at: at.clone(), request, message: message.to_string() }
            }
            None => RibError::Request {
                at: self.at.clone(),
                request: "WorldBegin",
                message: message.to_string(),
            },
        }
    }

    /// The index of the object named `name` (CSG leaves have unique names).
    fn objects_named(&self, name: &str) -> Option<usize> {
        self.object_names.iter().position(|n| n == name)
    }

    /// A validation failure at `path`, reported at the request that made the value.
    fn locate(&self, path: &str, message: &str) -> RibError {
        let index = |prefix: &str| -> Option<usize> {
            let rest = path.strip_prefix(prefix)?;
            rest[..rest.find(']')?].parse().ok()
        };
        let what = format!("{path}: {message}");
        if let Some(i) = index("objects[")
            && let Some(o) = self.object_origins.get(i)
        {
            return RibError::Request { at: o.at.clone(), request: o.request, message: what };
        }
        if let Some(i) = index("lights[")
            && let Some((at, request)) = self.light_origins.get(i)
        {
            return RibError::Request { at: at.clone(), request, message: what };
        }
        // A CSG operand at fault: its own primitive.
        if path.starts_with("solids[")
            && let Some(name) = message.split('"').nth(1)
            && let Some(i) = self.objects_named(name)
        {
            let o = &self.object_origins[i];
            return RibError::Request { at: o.at.clone(), request: o.request, message: what };
        }
        if let Some(i) = index("solids[")
            && let Some(at) = self.solid_origins.get(i)
        {
            return RibError::Request { at: at.clone(), request: "SolidBegin", message: what };
        }
        self.option_error(path, &what)
    }
}

/// The keys of a transformation seen through the shutter `[open, close]`: interpolated at the
/// shutter's ends where the keys reach past them, keys outside dropped; one key when the
/// shutter is closed or the transformation still.
pub(super) fn fit_keys(keys: &[(f32, DMat4)], open: f32, close: f32) -> Vec<(f32, DMat4)> {
    let x = Xform { keys: keys.to_vec() };
    if keys.len() == 1 {
        return keys.to_vec();
    }
    if close <= open {
        return vec![(open, x.at(open))];
    }
    let mut out = vec![(open, x.at(open))];
    out.extend(keys.iter().filter(|(t, _)| *t > open && *t < close).copied());
    out.push((close, x.at(close)));
    out
}

/// Point keys seen through the shutter, as [`fit_keys`] does for transformations.
fn fit_points(keys: &[(f32, Vec<[f32; 3]>)], open: f32, close: f32) -> PointKeys {
    let at = |time: f32| -> Vec<[f32; 3]> {
        if time <= keys[0].0 {
            return keys[0].1.clone();
        }
        for w in keys.windows(2) {
            let ((t0, p0), (t1, p1)) = (&w[0], &w[1]);
            if time <= *t1 {
                let f = if t1 > t0 { (time - t0) / (t1 - t0) } else { 1.0 };
                return p0
                    .iter()
                    .zip(p1)
                    .map(|(a, b)| std::array::from_fn(|k| a[k] + (b[k] - a[k]) * f))
                    .collect();
            }
        }
        keys[keys.len() - 1].1.clone()
    };
    if close <= open {
        return vec![(open, at(open))];
    }
    let mut out = vec![(open, at(open))];
    out.extend(keys.iter().filter(|(t, _)| *t > open && *t < close).cloned());
    out.push((close, at(close)));
    out
}

/// Replaces the control points of a shape that has them.
fn set_points(shape: &mut Shape, new: Vec<[f32; 3]>) {
    match shape {
        Shape::Mesh { points, .. }
        | Shape::PatchMesh { points, .. }
        | Shape::SubdivisionMesh { points, .. } => *points = new,
        Shape::BilinearPatch { points } if new.len() == 4 => {
            *points = [new[0], new[1], new[2], new[3]];
        }
        Shape::NuPatch { points, .. } => {
            for (p, q) in points.iter_mut().zip(new) {
                *p = [q[0] * p[3], q[1] * p[3], q[2] * p[3], p[3]];
            }
        }
        _ => {}
    }
}

/// The `(height, radius)` of the end caps that close a full quadric, in its own space.
fn caps_of(shape: &Shape) -> Vec<(f32, f32)> {
    match *shape {
        Shape::Cylinder { radius, zmin, zmax, thetamax } if thetamax >= 360.0 => {
            vec![(zmin, radius), (zmax, radius)]
        }
        Shape::Cone { radius, thetamax, .. } if thetamax >= 360.0 => vec![(0.0, radius)],
        Shape::Paraboloid { rmax, zmin, zmax, thetamax } if thetamax >= 360.0 => {
            let mut caps = vec![(zmax, rmax)];
            if zmin > 0.0 {
                caps.push((zmin, rmax * (zmin / zmax).sqrt()));
            }
            caps
        }
        _ => Vec::new(),
    }
}

/// The meshes of `objects` (under one transformation) as one, their vertices welded where
/// their positions are equal. A material colour that differs between the parts becomes a
/// per-vertex colour on a white material of the first part's kind.
fn weld<'a>(objects: impl Iterator<Item = &'a Object>) -> (Shape, Material) {
    let objects: Vec<&Object> = objects.collect();
    let color_of = |m: &Material| match *m {
        Material::Constant { color, .. }
        | Material::Matte { color, .. }
        | Material::Plastic { color, .. }
        | Material::Metal { color, .. }
        | Material::DefaultSurface { color, .. }
        | Material::Shader { color, .. } => color,
    };
    let base = objects[0].material.clone();
    let one_color = objects.iter().all(|o| color_of(&o.material) == color_of(&base));
    let mut points: Vec<[f32; 3]> = Vec::new();
    let mut colors: Vec<[f32; 3]> = Vec::new();
    let mut faces = Faces::new();
    let mut at: HashMap<[u32; 3], u32> = HashMap::new();
    let mut any_colors = !one_color;
    for o in &objects {
        let Shape::Mesh { points: p, faces: f, colors: c, .. } = &o.shape else { continue };
        any_colors |= c.is_some();
        let cs = color_of(&o.material);
        let remap: Vec<u32> = p
            .iter()
            .enumerate()
            .map(|(k, q)| {
                let key = q.map(f32::to_bits);
                *at.entry(key).or_insert_with(|| {
                    points.push(*q);
                    let tint = c.as_ref().map_or([1.0; 3], |c| c[k]);
                    let base = if one_color { [1.0; 3] } else { cs };
                    colors.push(std::array::from_fn(|i| base[i] * tint[i]));
                    (points.len() - 1) as u32
                })
            })
            .collect();
        for face in f {
            faces.push_iter(face.iter().map(|&k| remap[k as usize]));
        }
    }
    let material = if one_color { base } else { with_color(base, [1.0; 3]) };
    (
        Shape::Mesh {
            points,
            faces,
            colors: any_colors.then_some(colors),
            normals: None,
            st: None,
        },
        material,
    )
}

/// `m` with its surface colour replaced.
fn with_color(m: Material, color: [f32; 3]) -> Material {
    match m {
        Material::Constant { opacity, .. } => Material::Constant { color, opacity },
        Material::Matte { opacity, ka, kd, .. } => Material::Matte { color, opacity, ka, kd },
        Material::Plastic { opacity, ka, kd, ks, roughness, specular_color, .. } => {
            Material::Plastic { color, opacity, ka, kd, ks, roughness, specular_color }
        }
        Material::Metal { opacity, ka, ks, roughness, .. } => {
            Material::Metal { color, opacity, ka, ks, roughness }
        }
        Material::DefaultSurface { opacity, ka, kd, .. } => {
            Material::DefaultSurface { color, opacity, ka, kd }
        }
        Material::Shader { name, params, opacity, .. } => {
            Material::Shader { name, params, color, opacity }
        }
    }
}

/// Keeps the entries of `v` whose `dropped` flag is false.
fn retain_kept<T>(v: &mut Vec<T>, dropped: &[bool]) {
    let mut k = dropped.iter();
    v.retain(|_| !k.next().copied().unwrap_or(false));
}
