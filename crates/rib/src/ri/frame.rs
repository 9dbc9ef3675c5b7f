//! The request loop of the RI state machine: blocks, options, attributes and transformations
//! (the involved transformation requests in [`super::spaces`]);
//! geometry is handed to [`super::primitives`], solids and object instances to
//! [`super::solids`], and each `WorldEnd` to [`super::build`].
//!
//! Invariants: every request is handled in the block structure the Specification allows
//! (options before `WorldBegin`, geometry inside it); the block stack is checked at every
//! `...End` and at the end of input; the machine never holds more than the current frame.

use std::collections::HashMap;

use reyes_scene::Light;

use super::build::FrameBuild;
use super::make::is_depth_driver;
use super::state::{Attributes, FrameOptions, SurfaceShader};
use super::xform::Xform;
use super::{Frame, Loaded, RiOptions};
use crate::{Location, Reader, Request, RequestKind as K, RibError, Value, Warning};

/// An open block.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Block {
    Frame,
    World,
    Attribute,
    Transform,
    Solid,
}

impl Block {
    fn begin(&self) -> &'static str {
        match self {
            Block::Frame => "FrameBegin",
            Block::World => "WorldBegin",
            Block::Attribute => "AttributeBegin",
            Block::Transform => "TransformBegin",
            Block::Solid => "SolidBegin",
        }
    }
}

/// Most `SolidBegin` blocks open at once: each makes at most two levels of the model's CSG
/// tree, which validation limits to [`reyes_scene::MAX_CSG_DEPTH`].
pub(super) const MAX_SOLID_NESTING: usize = reyes_scene::MAX_CSG_DEPTH / 2;
/// Most `ObjectInstance`s replaying inside each other (an object whose definition instances
/// itself would replay forever).
pub(super) const MAX_INSTANCE_NESTING: usize = 64;
/// Most requests the object instances of one world block may replay in all. The model has no
/// instancing, so every replayed primitive becomes an object of its own; definitions that
/// instance the one before twice double with every level, and 40 levels would make 2^40.
pub(super) const MAX_INSTANCED_REQUESTS: usize = 1 << 20;

/// An open `MotionBegin` block: its times and the requests gathered so far.
pub(super) struct Motion {
    pub times: Vec<f32>,
    pub at: Location,
    pub requests: Vec<Request>,
}

/// The RI state machine over one reader.
pub(crate) struct Machine {
    pub(super) reader: Reader,
    pub(super) options: RiOptions,
    pub(super) permissions: super::Permissions,
    /// The options in force (restored at `FrameEnd`).
    pub(super) frame_options: FrameOptions,
    saved_options: Vec<FrameOptions>,
    pub(super) attributes: Attributes,
    attribute_stack: Vec<Attributes>,
    /// Current transformation: current space to camera space before `WorldBegin`, to world
    /// space inside it.
    pub(super) ctm: Xform,
    ctm_stack: Vec<Xform>,
    /// Open blocks, with where each began.
    pub(super) blocks: Vec<(Block, Location)>,
    pub(super) motion: Option<Motion>,
    /// Named coordinate systems (`CoordinateSystem`), as current-to-camera (before the world)
    /// or current-to-world transformations, with whether they were named inside the world.
    pub(super) coordinate_systems: HashMap<String, (Xform, bool)>,
    /// Lights declared before `WorldBegin`, added to each world block.
    pub(super) pending_lights: Vec<(String, Light, Location)>,
    /// The shading-language shaders compiled so far (`rsl.rs`).
    pub(super) sl: super::rsl::ShaderTable,
    /// The lights declared outside the frame, saved at `FrameBegin` and restored at
    /// `FrameEnd`: like every option and attribute declared outside a frame, they hold for
    /// every frame, while those declared inside one end with it.
    saved_lights: Vec<Vec<(String, Light, Location)>>,
    /// The frame being built (from `WorldBegin` to `WorldEnd`).
    pub(super) build: Option<FrameBuild>,
    frame_number: Option<i32>,
    /// Object definitions: handle -> requests to replay.
    pub(super) objects: HashMap<String, Vec<Request>>,
    /// The object definition being recorded.
    pub(super) recording: Option<(String, Vec<Request>, usize)>,
    /// Inline archives (`ArchiveBegin`/`ArchiveEnd`): name -> requests to replay.
    pub(super) archives: HashMap<String, Vec<Request>>,
    /// The inline archive being recorded: its name, requests, `ArchiveBegin`s open inside it,
    /// and where it began.
    pub(super) archive_recording: Option<(String, Vec<Request>, usize, Location)>,
    /// Inline archives replaying now, one inside the other.
    pub(super) archive_replaying: Vec<String>,
    /// `ObjectInstance`s replaying now, one inside the other.
    pub(super) instancing: usize,
    /// Requests replayed by object instances in this world block.
    pub(super) instanced: usize,
    pub(super) warnings: Vec<Warning>,
    /// Warnings given once per key (unknown shaders, unsupported features).
    pub(super) warned: std::collections::HashSet<String>,
    frames: Vec<Frame>,
    pub(super) multipass: super::make::Multipass,
    /// World blocks read, built or not (`--frames` may skip some): how many frames the file
    /// has, which decides whether output names are numbered.
    worlds: usize,
    /// The main `Display` name of every world block read, built or not.
    display_names: Vec<String>,
}

/// A handle argument as a key (RIB handles are integers or strings; `1` and `"1"` differ).
pub(super) fn handle(r: &Request, i: usize) -> Option<String> {
    match r.args.get(i)? {
        Value::Int(n) => Some(format!("{n}")),
        Value::Float(f) => Some(format!("{f}")),
        Value::String(s) => Some(format!("\"{s}\"")),
        _ => None,
    }
}

fn f3(v: &[f32]) -> [f32; 3] {
    [v[0], v[1], v[2]]
}

impl Machine {
    pub(super) fn new(
        reader: Reader,
        options: RiOptions,
        permissions: super::Permissions,
    ) -> Machine {
        Machine {
            reader,
            options,
            permissions,
            frame_options: FrameOptions::default(),
            saved_options: Vec::new(),
            attributes: Attributes::default(),
            attribute_stack: Vec::new(),
            ctm: Xform::default(),
            ctm_stack: Vec::new(),
            blocks: Vec::new(),
            motion: None,
            coordinate_systems: HashMap::new(),
            pending_lights: Vec::new(),
            sl: Default::default(),
            saved_lights: Vec::new(),
            build: None,
            frame_number: None,
            objects: HashMap::new(),
            recording: None,
            archives: HashMap::new(),
            archive_recording: None,
            archive_replaying: Vec::new(),
            instancing: 0,
            instanced: 0,
            warnings: Vec::new(),
            warned: Default::default(),
            frames: Vec::new(),
            multipass: Default::default(),
            worlds: 0,
            display_names: Vec::new(),
        }
    }

    /// A warning, once per `key`.
    pub(super) fn warn_once(&mut self, key: impl Into<String>, w: Warning) {
        if self.warned.insert(key.into()) {
            self.warnings.push(w);
        }
    }

    /// Input RenderMan renderers tolerate: a warning `Request: what: done` at `at`, or under
    /// `--strict` the error `Request: what (--strict)`.
    pub(super) fn tolerate(
        &mut self,
        at: &Location,
        request: &'static str,
        what: impl std::fmt::Display,
        done: &str,
    ) -> Result<(), RibError> {
        if self.options.strict {
            return Err(RibError::Request {
                at: at.clone(),
                request,
                message: format!("{what} (--strict)"),
            });
        }
        self.warnings
            .push(Warning { at: at.clone(), message: format!("{request}: {what}: {done}") });
        Ok(())
    }

    /// Reads every request and returns the frames; on the first error, that error with the
    /// warnings gathered before it, so that a refused scene still says what it tolerated.
    /// Either way the warnings are in file order ([`in_file_order`]).
    pub(super) fn run(mut self) -> Result<Loaded, (RibError, Vec<Warning>)> {
        let result = self.read_all();
        self.warnings.extend(self.reader.take_warnings());
        in_file_order(&mut self.warnings);
        match result {
            Ok(()) => Ok(Loaded {
                frames: self.frames,
                makes_after: self.multipass.pending,
                warnings: self.warnings,
                several_frames: self.worlds > 1,
                display_repeats: repeats(&self.display_names),
            }),
            Err(e) => Err((e, self.warnings)),
        }
    }

    fn read_all(&mut self) -> Result<(), RibError> {
        while let Some(r) = self.reader.next_request()? {
            self.warnings.extend(self.reader.take_warnings());
            self.request(r)?;
        }
        self.warnings.extend(self.reader.take_warnings());
        if let Some(m) = &self.motion {
            return Err(RibError::Request {
                at: m.at.clone(),
                request: "MotionBegin",
                message: "no MotionEnd before the end of the input".into(),
            });
        }
        if let Some((_, _, _, at)) = &self.archive_recording {
            return Err(RibError::Request {
                at: at.clone(),
                request: "ArchiveBegin",
                message: "no ArchiveEnd before the end of the input".into(),
            });
        }
        if let Some((b, at)) = self.blocks.last() {
            return Err(RibError::Request {
                at: at.clone(),
                request: b.begin(),
                message: "block not closed at the end of the input".into(),
            });
        }
        Ok(())
    }

    pub(super) fn in_world(&self) -> bool {
        self.build.is_some()
    }

    /// One request, in or out of a motion block, an object definition or an inline archive.
    pub(super) fn request(&mut self, r: Request) -> Result<(), RibError> {
        // An inline archive's body is recorded as written, ReadArchive included.
        if let Some((_, recorded, depth, _)) = &mut self.archive_recording {
            match r.kind {
                K::ArchiveBegin => *depth += 1,
                K::ArchiveEnd if *depth == 0 => return self.archive_end(),
                K::ArchiveEnd => *depth -= 1,
                _ => {}
            }
            recorded.push(r);
            return Ok(());
        }
        // Elsewhere an archive is read where it stands, even in an object definition or a
        // motion block, so that its requests are recorded or gathered in their place.
        if r.kind == K::ReadArchive {
            return self.read_archive(&r);
        }
        if let Some((_, recorded, depth)) = &mut self.recording {
            match r.kind {
                K::ObjectBegin => *depth += 1,
                K::ObjectEnd if *depth == 0 => return self.object_end(&r),
                K::ObjectEnd => *depth -= 1,
                _ => {}
            }
            recorded.push(r);
            return Ok(());
        }
        if self.motion.is_some() && r.kind != K::MotionEnd {
            if r.kind == K::MotionBegin {
                return Err(r.error("motion blocks do not nest"));
            }
            if let Some(m) = &mut self.motion {
                m.requests.push(r);
            }
            return Ok(());
        }
        self.dispatch(r)
    }

    pub(super) fn dispatch(&mut self, r: Request) -> Result<(), RibError> {
        match r.kind {
            // Blocks.
            K::FrameBegin => self.frame_begin(&r),
            K::FrameEnd => self.frame_end(&r),
            K::WorldBegin => self.world_begin(&r),
            K::WorldEnd => self.world_end(&r),
            K::AttributeBegin => {
                self.push(Block::Attribute, &r.at);
                Ok(())
            }
            K::AttributeEnd => self.pop(&r, Block::Attribute),
            K::TransformBegin => {
                self.blocks.push((Block::Transform, r.at.clone()));
                self.ctm_stack.push(self.ctm.clone());
                Ok(())
            }
            K::TransformEnd => self.pop(&r, Block::Transform),
            K::MotionBegin => {
                let times = r.floats(0).unwrap_or(&[]).to_vec();
                if times.is_empty() || times.windows(2).any(|w| w[0] >= w[1] || w[1].is_nan()) {
                    return Err(r.error("times must be one or more increasing numbers"));
                }
                self.motion = Some(Motion { times, at: r.at.clone(), requests: Vec::new() });
                Ok(())
            }
            K::MotionEnd => self.motion_end(&r),
            K::SolidBegin => self.solid_begin(&r),
            K::SolidEnd => self.solid_end(&r),
            K::ObjectBegin => {
                let h = handle(&r, 0).ok_or_else(|| r.error("expected a handle"))?;
                self.recording = Some((h, Vec::new(), 0));
                Ok(())
            }
            K::ObjectEnd => Err(r.error("no ObjectBegin is open")),
            K::ObjectInstance => self.object_instance(&r),

            // Transformations.
            K::Identity => {
                self.ctm = Xform::default();
                Ok(())
            }
            K::Transform => {
                self.ctm = Xform::still(self.matrix_of(&r)?);
                Ok(())
            }
            K::ConcatTransform | K::Translate | K::Rotate | K::Scale | K::Skew | K::Perspective => {
                let m = self.matrix_of(&r)?;
                self.ctm = self.ctm.then_apply(&m);
                Ok(())
            }
            K::CoordinateSystem | K::ScopedCoordinateSystem => {
                let name = r.string(0).unwrap_or_default().to_string();
                self.coordinate_systems.insert(name, (self.ctm.clone(), self.in_world()));
                Ok(())
            }
            K::CoordSysTransform => self.coord_sys_transform(&r),

            // Attributes.
            K::Color => {
                self.attributes.color = f3(r.floats(0).unwrap_or(&[1.0; 3]));
                Ok(())
            }
            K::Opacity => {
                self.attributes.opacity = f3(r.floats(0).unwrap_or(&[1.0; 3]));
                Ok(())
            }
            K::Surface => {
                self.attributes.surface = SurfaceShader::of(&r);
                Ok(())
            }
            K::TextureCoordinates => {
                // The corners' (s, t) at (u, v) = (0, 0), (1, 0), (0, 1), (1, 1). A scale
                // of the parameters (s = a u, t = b v) is texture maps' `repeat`; other
                // maps are not supported.
                let st: Vec<f32> = r
                    .floats(0)
                    .map(<[f32]>::to_vec)
                    .unwrap_or_else(|| (0..8).map(|i| r.float(i).unwrap_or(f32::NAN)).collect());
                match st.as_slice() {
                    [0.0, 0.0, a, 0.0, 0.0, b, a2, b2]
                        if a == a2
                            && b == b2
                            && *a != 0.0
                            && *b != 0.0
                            && a.is_finite()
                            && b.is_finite() =>
                    {
                        self.attributes.repeat = (*a, *b);
                    }
                    _ => {
                        let w = r.warning(
                            "only a scale of the surface parameters (0 0 a 0 0 b a b) is supported: ignored",
                        );
                        self.warn_once("texture coordinates", w);
                    }
                }
                Ok(())
            }
            K::Displacement => {
                self.attributes.displacement = SurfaceShader::of(&r);
                Ok(())
            }
            K::Atmosphere => {
                self.attributes.atmosphere = SurfaceShader::of(&r);
                Ok(())
            }
            K::ShadingRate => {
                let rate = r.float(0).unwrap_or(1.0);
                if !(rate > 0.0 && rate.is_finite()) {
                    return Err(r.error(format!("size must be > 0, got {rate}")));
                }
                self.attributes.shading_rate = rate;
                Ok(())
            }
            K::GeometricApproximation => {
                let kind = r.string(0).unwrap_or("");
                let value = r.float(1).unwrap_or(0.0);
                if !value.is_finite() {
                    return Err(r.error(format!("value must be finite, got {value}")));
                }
                if kind.eq_ignore_ascii_case("flatness") {
                    if value < 0.0 {
                        return Err(r.error(format!("flatness must be >= 0, got {value}")));
                    }
                    self.attributes.flatness = Some(value);
                } else if kind.eq_ignore_ascii_case("motionfactor") {
                    if value < 0.0 {
                        return Err(r.error(format!("motionfactor must be >= 0, got {value}")));
                    }
                    self.attributes.motion_factor = Some(value);
                } else if kind.eq_ignore_ascii_case("focusfactor") {
                    if value < 0.0 {
                        return Err(r.error(format!("focusfactor must be >= 0, got {value}")));
                    }
                    self.attributes.focus_factor = Some(value);
                } else {
                    let w = r.warning(format!("\"{kind}\" is not supported: ignored"));
                    self.warn_once(format!("geometric approximation {kind}"), w);
                }
                Ok(())
            }
            K::Sides => {
                let n = r.int(0).unwrap_or(2);
                if n != 1 && n != 2 {
                    return Err(r.error(format!("nsides must be 1 or 2, got {n}")));
                }
                self.attributes.sides = n;
                Ok(())
            }
            K::Orientation => {
                let o = r.string(0).unwrap_or_default();
                match o {
                    "outside" | "lh" => {}
                    "inside" | "rh" => {}
                    other => {
                        return Err(r.error(format!(
                            "orientation must be \"outside\", \"inside\", \"lh\" or \"rh\", got \"{other}\""
                        )));
                    }
                }
                self.attributes.reverse_orientation = matches!(o, "inside" | "rh");
                Ok(())
            }
            K::ReverseOrientation => {
                self.attributes.reverse_orientation = !self.attributes.reverse_orientation;
                Ok(())
            }
            K::Matte => {
                self.attributes.matte = r.int(0).unwrap_or(0) != 0;
                Ok(())
            }
            K::ShadingInterpolation => {
                self.attributes.smooth = match r.string(0).unwrap_or_default() {
                    "constant" => false,
                    "smooth" => true,
                    other => {
                        let why = format!("type must be \"constant\" or \"smooth\", got {other:?}");
                        return Err(r.error(why));
                    }
                };
                Ok(())
            }
            K::Attribute => self.attribute(&r),
            K::TrimCurve => self.trim_curve(&r),
            K::LightSource => self.light_source(&r),
            K::AreaLightSource => self.area_light_source(&r),
            K::RelativeDetail => self.relative_detail(&r),
            K::Detail => self.detail(&r),
            K::DetailRange => self.detail_range(&r),
            K::Illuminate => self.illuminate(&r),
            K::Basis => self.basis(&r),
            K::Declare | K::Version | K::ColorSamples => Ok(()),

            // Options.
            K::Format
            | K::FrameAspectRatio
            | K::ScreenWindow
            | K::CropWindow
            | K::Projection
            | K::Clipping
            | K::DepthOfField
            | K::Shutter
            | K::PixelSamples
            | K::PixelFilter
            | K::Exposure
            | K::Quantize
            | K::Display
            | K::Hider
            | K::Option
            | K::PixelVariance
            | K::ClippingPlane
            | K::Imager => self.option(&r),

            // Geometry.
            K::Sphere
            | K::Cone
            | K::Cylinder
            | K::Disk
            | K::Paraboloid
            | K::Torus
            | K::Hyperboloid
            | K::Polygon
            | K::GeneralPolygon
            | K::PointsPolygons
            | K::PointsGeneralPolygons
            | K::Patch
            | K::PatchMesh
            | K::NuPatch
            | K::SubdivisionMesh
            | K::Points
            | K::Curves
            | K::Blobby
            | K::Geometry => {
                if !self.in_world() {
                    return Err(r.error("geometry must be inside WorldBegin/WorldEnd"));
                }
                self.primitive(&r, None)
            }
            K::Procedural => self.procedural(&r),
            K::ReadArchive => self.read_archive(&r),
            K::ArchiveBegin => self.archive_begin(&r),
            K::ArchiveEnd => Err(r.error("no ArchiveBegin is open")),
            K::MakeTexture
            | K::MakeBump
            | K::MakeLatLongEnvironment
            | K::MakeCubeFaceEnvironment
            | K::MakeShadow => self.make(&r),

            // RIS: once per request name.
            k if k.is_ris() => {
                let name = r.name();
                let what = format!(
                    "RenderMan's RIS requests are not supported (this renderer runs the shading of the \
                     RenderMan Interface 3.2); every {name} request is ignored"
                );
                if self.options.strict {
                    return Err(r.error(format!("{what} (--strict)")));
                }
                let w = r.warning(what);
                self.warn_once(format!("ris {name}"), w);
                Ok(())
            }
            // Accepted and ignored, with a warning.
            _ => {
                let w = r.warning("not supported: ignored");
                self.warn_once(format!("request {}", r.name()), w);
                Ok(())
            }
        }
    }

    pub(super) fn push(&mut self, b: Block, at: &Location) {
        self.blocks.push((b, at.clone()));
        self.attribute_stack.push(self.attributes.clone());
        self.ctm_stack.push(self.ctm.clone());
    }

    /// Closes the innermost block, which must be `b`.
    pub(super) fn pop(&mut self, r: &Request, b: Block) -> Result<(), RibError> {
        match self.blocks.last().map(|(top, _)| top) {
            Some(top) if *top == b => {}
            Some(top) => {
                return Err(r.error(format!(
                    "closes {} but the open block is {}",
                    b.begin(),
                    top.begin()
                )));
            }
            None => return Err(r.error(format!("no {} is open", b.begin()))),
        }
        self.blocks.pop();
        if let Some(c) = self.ctm_stack.pop() {
            self.ctm = c;
        }
        if b != Block::Transform
            && let Some(a) = self.attribute_stack.pop()
        {
            self.attributes = a;
        }
        Ok(())
    }

    fn frame_begin(&mut self, r: &Request) -> Result<(), RibError> {
        if !self.blocks.is_empty() {
            return Err(r.error("frames must be outside every other block"));
        }
        self.frame_number = r.int(0);
        self.saved_options.push(self.frame_options.clone());
        self.saved_lights.push(self.pending_lights.clone());
        self.push(Block::Frame, &r.at);
        Ok(())
    }

    fn frame_end(&mut self, r: &Request) -> Result<(), RibError> {
        self.pop(r, Block::Frame)?;
        self.pending_lights = self.saved_lights.pop().unwrap_or_default();
        if let Some(o) = self.saved_options.pop() {
            self.frame_options = o;
        }
        self.frame_number = None;
        Ok(())
    }

    fn world_begin(&mut self, r: &Request) -> Result<(), RibError> {
        if self.in_world()
            || self.blocks.iter().any(|(b, _)| matches!(b, Block::World | Block::Solid))
        {
            return Err(r.error("WorldBegin must be outside every block but a frame"));
        }
        // Houdini writes the world inside an attribute or transformation block; RenderMan
        // renderers take it, the transformation at WorldBegin being the camera's.
        if let Some((b, at)) =
            self.blocks.iter().find(|(b, _)| matches!(b, Block::Attribute | Block::Transform))
        {
            let what = format!("opened inside the {} block of {}", b.begin(), at.pos);
            self.tolerate(
                &r.at,
                r.name(),
                what,
                "allowed, as RenderMan renderers allow it: the transformation at WorldBegin is the camera's",
            )?;
        }
        // The transformation so far is the camera's: world to camera.
        self.frame_options.camera = self.ctm.clone();
        let number = self.frame_number.unwrap_or(1);
        let mut build =
            FrameBuild::new(self.frame_options.clone(), r.at.clone(), self.options.wants(number));
        self.push(Block::World, &r.at);
        self.instanced = 0;
        self.ctm = Xform::default();
        // Lights of the world block are new for every frame; those declared before it are on.
        self.attributes.lights_on.clear();
        for (h, light, at) in self.pending_lights.clone() {
            let index = build.add_light(h, light, at);
            self.attributes.lights_on.push(index);
        }
        self.build = Some(build);
        Ok(())
    }

    fn world_end(&mut self, r: &Request) -> Result<(), RibError> {
        self.pop(r, Block::World)?;
        let build = self.build.take().ok_or_else(|| r.error("no WorldBegin is open"))?;
        let frame_number = self.frame_number;
        self.worlds += 1;
        if let Some(d) = self.frame_options.displays.iter().find(|d| !d.extra) {
            self.display_names.push(d.name.clone());
        }
        let depth = self.frame_options.displays.iter().filter(|d| is_depth_driver(&d.driver));
        let written: Vec<_> = depth.map(|d| self.reader.resolve_archive(&d.name, &r.at)).collect();
        self.multipass.made.extend(written);
        if build.wanted {
            let (scene, displays) = build.finish(&mut self.warnings)?;
            let makes = std::mem::take(&mut self.multipass.pending);
            self.frames.push(Frame { number: frame_number, scene, displays, makes });
        }
        // Outside the world block the transformation is the camera's again.
        self.ctm = self.frame_options.camera.clone();
        Ok(())
    }
}

/// Whether some name occurs more than once.
fn repeats(names: &[String]) -> bool {
    let mut sorted: Vec<&String> = names.iter().collect();
    sorted.sort_unstable();
    sorted.windows(2).any(|w| w[0] == w[1])
}

/// Sorts warnings into file order: by line and column within each source, and the sources in
/// the order their first warning was raised (the main file first; an archive's warnings
/// together, where the first of them was raised). Most warnings are raised as their request
/// is read; a few only when a frame is built (the camera's, at `WorldBegin`'s place), which this
/// puts back in place. The sort is stable, so warnings at one position keep their order.
pub(super) fn in_file_order(warnings: &mut [Warning]) {
    let mut files: Vec<std::sync::Arc<str>> = Vec::new();
    for w in warnings.iter() {
        if !files.contains(&w.at.file) {
            files.push(w.at.file.clone());
        }
    }
    warnings.sort_by_key(|w| (files.iter().position(|f| *f == w.at.file), w.at.pos));
}
