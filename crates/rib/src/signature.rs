//! The request table: every RIB request of Spec 3.2 (and a few later ones in common use), with
//! the count and types of its positional arguments and whether a parameter list follows.
//!
//! Invariant: [`RequestKind::ALL`] lists each request once, names are unique, and for every
//! signature `required <= args.len()`; the reader checks arguments against this table only.

use std::fmt;

/// How one positional argument is written and what [`crate::Value`] it becomes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArgKind {
    /// An integer → [`crate::Value::Int`].
    Int,
    /// A number → [`crate::Value::Float`] (integers convert).
    Float,
    /// A string → [`crate::Value::String`].
    Str,
    /// A light or object handle: an integer (Spec 3.2) or a string (later specs) →
    /// [`crate::Value::Int`] or [`crate::Value::String`].
    Handle,
    /// `[ integers ]` → [`crate::Value::Ints`].
    Ints,
    /// `[ numbers ]` → [`crate::Value::Floats`].
    Floats,
    /// `[ strings ]` → [`crate::Value::Strings`].
    Strings,
    /// Motion times: `[ numbers ]` or the numbers bare → [`crate::Value::Floats`].
    Times,
    /// Exactly `n` numbers, bare or as one array (a point, a bound, a matrix) →
    /// [`crate::Value::Floats`] of length `n`.
    Fixed(usize),
    /// A colour of `ColorSamples` numbers, bare or as one array → [`crate::Value::Floats`].
    Color,
    /// A basis: a name (`"bezier"`, ...) → [`crate::Value::String`], or 16 numbers, bare or as
    /// one array → [`crate::Value::Floats`].
    Basis,
}

impl ArgKind {
    /// A few words for messages, e.g. `an integer`, `an array of 16 numbers`.
    pub fn describe(self) -> String {
        match self {
            ArgKind::Int => "an integer".into(),
            ArgKind::Float => "a number".into(),
            ArgKind::Str => "a string".into(),
            ArgKind::Handle => "an integer or string handle".into(),
            ArgKind::Ints => "an array of integers".into(),
            ArgKind::Floats => "an array of numbers".into(),
            ArgKind::Strings => "an array of strings".into(),
            ArgKind::Times => "an array of times".into(),
            ArgKind::Fixed(n) => format!("{n} numbers"),
            ArgKind::Color => "a colour".into(),
            ArgKind::Basis => "a basis name or 16 numbers".into(),
        }
    }
}

/// One positional argument: its name in the spec's synopsis, and its kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Arg {
    /// The spec's name, e.g. `thetamax`.
    pub name: &'static str,
    /// How it is written.
    pub kind: ArgKind,
}

/// A request's positional arguments and whether a parameter list may follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Signature {
    /// The positional arguments, in order.
    pub args: &'static [Arg],
    /// How many of them must be present; the rest are optional and come all together or not
    /// at all (`DepthOfField` with none, `SubdivisionMesh` without tags).
    pub required: usize,
    /// True if `"token" value` pairs may follow.
    pub params: bool,
    /// True if the [`ArgKind::Float`] arguments may instead be given as one array of as many
    /// numbers (Spec: `ScreenWindow [l r b t]`).
    pub array_form: bool,
}

macro_rules! kind {
    (i) => {
        ArgKind::Int
    };
    (f) => {
        ArgKind::Float
    };
    (s) => {
        ArgKind::Str
    };
    (h) => {
        ArgKind::Handle
    };
    (ia) => {
        ArgKind::Ints
    };
    (fa) => {
        ArgKind::Floats
    };
    (sa) => {
        ArgKind::Strings
    };
    (times) => {
        ArgKind::Times
    };
    (point) => {
        ArgKind::Fixed(3)
    };
    (bound) => {
        ArgKind::Fixed(6)
    };
    (matrix) => {
        ArgKind::Fixed(16)
    };
    (color) => {
        ArgKind::Color
    };
    (basis) => {
        ArgKind::Basis
    };
}

macro_rules! requests {
    (@name $variant:ident $name:literal) => {
        $name
    };
    (@name $variant:ident) => {
        stringify!($variant)
    };
    ($( $variant:ident $(= $name:literal)? ( $( $k:ident $a:ident ),* ) $(opt $req:literal)? $([$($flag:ident)*])? ; )*) => {
        /// A request of the table, by its RIB name (each variant's synopsis is the spec's; a
        /// trailing `...` means a parameter list may follow).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum RequestKind {
            $(
                #[doc = concat!("`", requests!(@name $variant $($name)?), $(" ", stringify!($a),)* "`")]
                $variant,
            )*
        }

        impl RequestKind {
            /// Every request, in the spec's order.
            pub const ALL: &'static [RequestKind] = &[$(RequestKind::$variant),*];

            /// The request named `name` (case-sensitive, as RIB is).
            pub fn from_name(name: &[u8]) -> Option<RequestKind> {
                // A `match` on strings compiles to a switch on length, then comparisons.
                match std::str::from_utf8(name).ok()? {
                    $(requests!(@name $variant $($name)?) => Some(RequestKind::$variant),)*
                    _ => None,
                }
            }

            /// The request's RIB name, e.g. `Sphere` (and `version`).
            pub fn name(self) -> &'static str {
                match self {
                    $(RequestKind::$variant => requests!(@name $variant $($name)?),)*
                }
            }

            /// The request's positional arguments and whether parameters follow.
            pub fn signature(self) -> Signature {
                match self {
                    $(RequestKind::$variant => {
                        const ARGS: &[Arg] = &[$(Arg { name: stringify!($a), kind: kind!($k) }),*];
                        #[allow(unused_mut, unused_assignments)]
                        let mut required = ARGS.len();
                        $(required = $req;)?
                        let flags: &[&str] = &[$($(stringify!($flag)),*)?];
                        Signature {
                            args: ARGS,
                            required,
                            params: flags.contains(&"params"),
                            array_form: flags.contains(&"array_form"),
                        }
                    })*
                }
            }
        }
    };
}

requests! {
    // RIB only.
    Version = "version" (f version);
    // Relationship to the Shading Language.
    Declare (s name, s declaration);
    // Graphics state.
    FrameBegin (i frame);
    FrameEnd ();
    WorldBegin ();
    WorldEnd ();
    // Camera options.
    Format (i xresolution, i yresolution, f pixelaspectratio);
    FrameAspectRatio (f frameratio);
    ScreenWindow (f left, f right, f bottom, f top) [array_form];
    CropWindow (f xmin, f xmax, f ymin, f ymax) [array_form];
    Projection (s name) [params];
    Clipping (f near, f far);
    ClippingPlane (f x, f y, f z, f nx, f ny, f nz);
    DepthOfField (f fstop, f focallength, f focaldistance) opt 0;
    Shutter (f opentime, f closetime);
    // Display options.
    PixelVariance (f variation);
    PixelSamples (f xsamples, f ysamples);
    PixelFilter (s filter, f xwidth, f ywidth);
    Exposure (f gain, f gamma);
    Imager (s name) [params];
    Quantize (s type, i one, i min, i max, f ditheramplitude);
    Display (s name, s type, s mode) [params];
    // Additional options.
    Hider (s type) [params];
    ColorSamples (fa nRGB, fa RGBn);
    RelativeDetail (f relativedetail);
    Option (s name) [params];
    // Attributes.
    AttributeBegin ();
    AttributeEnd ();
    Color (color color);
    Opacity (color color);
    TextureCoordinates (f s1, f t1, f s2, f t2, f s3, f t3, f s4, f t4) [array_form];
    LightSource (s shadername, h handle) [params];
    AreaLightSource (s shadername, h handle) [params];
    Illuminate (h handle, i onoff);
    Surface (s name) [params];
    Displacement (s name) [params];
    Atmosphere (s name) [params];
    Interior (s name) [params];
    Exterior (s name) [params];
    Deformation (s name) [params];
    ShadingRate (f size);
    ShadingInterpolation (s type);
    Matte (i onoff);
    Bound (bound bound);
    Detail (bound bound);
    DetailRange (f offlow, f onlow, f onhigh, f offhigh) [array_form];
    GeometricApproximation (s type, f value);
    Orientation (s orientation);
    ReverseOrientation ();
    Sides (i nsides);
    Attribute (s name) [params];
    // Transformations.
    Identity ();
    Transform (matrix transform);
    ConcatTransform (matrix transform);
    Perspective (f fov);
    Translate (f dx, f dy, f dz);
    Rotate (f angle, f dx, f dy, f dz);
    Scale (f sx, f sy, f sz);
    Skew (f angle, f dx1, f dy1, f dz1, f dx2, f dy2, f dz2) [array_form];
    CoordinateSystem (s space);
    CoordSysTransform (s space);
    TransformBegin ();
    TransformEnd ();
    // Geometric primitives.
    Polygon () [params];
    GeneralPolygon (ia nvertices) [params];
    PointsPolygons (ia nvertices, ia vertices) [params];
    PointsGeneralPolygons (ia nloops, ia nvertices, ia vertices) [params];
    Basis (basis ubasis, i ustep, basis vbasis, i vstep);
    Patch (s type) [params];
    PatchMesh (s type, i nu, s uwrap, i nv, s vwrap) [params];
    NuPatch (i nu, i uorder, fa uknot, f umin, f umax, i nv, i vorder, fa vknot, f vmin, f vmax) [params];
    TrimCurve (ia ncurves, ia order, fa knot, fa min, fa max, ia n, fa u, fa v, fa w);
    SubdivisionMesh (s scheme, ia nvertices, ia vertices, sa tags, ia nargs, ia intargs, fa floatargs) opt 3 [params];
    Sphere (f radius, f zmin, f zmax, f thetamax) [params];
    Cone (f height, f radius, f thetamax) [params];
    Cylinder (f radius, f zmin, f zmax, f thetamax) [params];
    Hyperboloid (point point1, point point2, f thetamax) [params];
    Paraboloid (f rmax, f zmin, f zmax, f thetamax) [params];
    Disk (f height, f radius, f thetamax) [params];
    Torus (f majorradius, f minorradius, f phimin, f phimax, f thetamax) [params];
    Points () [params];
    Curves (s type, ia nvertices, s wrap) [params];
    Blobby (i nleaf, ia code, fa floats, sa strings) [params];
    Procedural (s name, sa args, bound bound);
    Geometry (s type) [params];
    SolidBegin (s operation);
    SolidEnd ();
    ObjectBegin (h handle);
    ObjectEnd ();
    ObjectInstance (h handle);
    // Motion.
    MotionBegin (times times);
    MotionEnd ();
    // Texture map utilities.
    MakeTexture (s picturename, s texturename, s swrap, s twrap, s filter, f swidth, f twidth) [params];
    MakeBump (s picturename, s texturename, s swrap, s twrap, s filter, f swidth, f twidth) [params];
    MakeLatLongEnvironment (s picturename, s texturename, s filter, f swidth, f twidth) [params];
    MakeCubeFaceEnvironment (s px, s nx, s py, s ny, s pz, s nz, s texturename, f fov, s filter, f swidth, f twidth) [params];
    MakeShadow (s picturename, s texturename) [params];
    // Errors and archives.
    ErrorHandler (s name);
    ReadArchive (s name) [params];
    // Later than 3.2, common in RIB files: inline archives, conditionals, cameras, resources.
    ArchiveBegin (s name) [params];
    ArchiveEnd ();
    IfBegin (s condition);
    ElseIf (s condition);
    Else ();
    IfEnd ();
    Camera (s name) [params];
    ScopedCoordinateSystem (s space);
    Resource (s handle, s type) [params];
    ResourceBegin ();
    ResourceEnd ();
    // RenderMan's RIS (PRMan 19 on): read so each is told once, not run.
    Bxdf (s name, h handle) [params];
    Pattern (s name, h handle) [params];
    Integrator (s name, h handle) [params];
    Light (s name, h handle) [params];
    LightFilter (s name, h handle) [params];
    DisplayFilter (s name, h handle) [params];
    SampleFilter (s name, h handle) [params];
}

impl RequestKind {
    /// True for the requests of later specifications than 3.2 ([`RequestKind::ArchiveBegin`]
    /// onwards, RIS's included).
    pub fn is_extension(self) -> bool {
        self >= RequestKind::ArchiveBegin
    }

    /// True for RenderMan's RIS requests (`Bxdf`, `Pattern`, `Integrator`, `Light`,
    /// `LightFilter`, `DisplayFilter`, `SampleFilter`): a shading model other than the
    /// Specification's, which this renderer does not run.
    pub fn is_ris(self) -> bool {
        self >= RequestKind::Bxdf
    }

    /// The synopsis, e.g. `Sphere radius zmin zmax thetamax ...` (`[...]` around optional
    /// arguments, `...` for a parameter list).
    pub fn synopsis(self) -> String {
        self.to_string()
    }
}

impl fmt::Display for RequestKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sig = self.signature();
        f.write_str(self.name())?;
        for (i, a) in sig.args.iter().enumerate() {
            let open = if i == sig.required && i < sig.args.len() { " [" } else { " " };
            write!(f, "{open}{}", a.name)?;
        }
        if sig.required < sig.args.len() {
            f.write_str("]")?;
        }
        if sig.params {
            f.write_str(" ...")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_found() {
        for (i, k) in RequestKind::ALL.iter().enumerate() {
            assert_eq!(RequestKind::from_name(k.name().as_bytes()), Some(*k));
            for other in &RequestKind::ALL[i + 1..] {
                assert_ne!(k.name(), other.name());
            }
            let s = k.signature();
            assert!(s.required <= s.args.len(), "{k:?}");
        }
        assert_eq!(RequestKind::from_name(b"sphere"), None);
        assert_eq!(RequestKind::Version.name(), "version");
    }

    #[test]
    fn synopses() {
        assert_eq!(RequestKind::Sphere.synopsis(), "Sphere radius zmin zmax thetamax ...");
        assert_eq!(
            RequestKind::DepthOfField.synopsis(),
            "DepthOfField [fstop focallength focaldistance]"
        );
        assert_eq!(
            RequestKind::SubdivisionMesh.synopsis(),
            "SubdivisionMesh scheme nvertices vertices [tags nargs intargs floatargs] ..."
        );
        assert_eq!(RequestKind::WorldBegin.synopsis(), "WorldBegin");
        assert!(RequestKind::Camera.is_extension());
        assert!(!RequestKind::ReadArchive.is_extension());
    }

    #[test]
    fn spec_table_size() {
        // Spec 3.2's 98 RIB requests plus `version`, then the 11 later ones and RIS's 7.
        assert_eq!(RequestKind::ALL.len(), 117);
        assert_eq!(RequestKind::ALL.iter().filter(|k| k.is_extension()).count(), 18);
        assert_eq!(RequestKind::ALL.iter().filter(|k| k.is_ris()).count(), 7);
        assert!(!RequestKind::ResourceEnd.is_ris());
    }
}
