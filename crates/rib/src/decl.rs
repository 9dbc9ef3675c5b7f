//! Parameter declarations (Spec 3.2 §3 `RiDeclare`, and inline declarations): the storage class,
//! type and array size that give a parameter's values their meaning, and the table of declared
//! names with the spec's standard variables predeclared.
//!
//! Invariant: a [`Decl`] is always well formed (array sizes are at least 1), so the number of
//! scalars per element, [`Decl::scalars`], is positive.

use std::collections::HashMap;
use std::fmt;

use crate::error::quote;

/// Storage class: how many values a primitive takes (Spec 3.2 §5 "Primitive variables").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Class {
    /// One value for the whole primitive.
    Constant,
    /// One value per face or patch (the default class).
    Uniform,
    /// One value per corner of the parametric grid, interpolated bilinearly.
    Varying,
    /// One value per control vertex, interpolated like `P`.
    Vertex,
    /// One value per face corner, interpolated like `varying` but per face.
    FaceVarying,
    /// One value per face corner, interpolated like `vertex` but per face.
    FaceVertex,
}

impl Class {
    /// The keyword, as written in RIB.
    pub fn name(self) -> &'static str {
        match self {
            Class::Constant => "constant",
            Class::Uniform => "uniform",
            Class::Varying => "varying",
            Class::Vertex => "vertex",
            Class::FaceVarying => "facevarying",
            Class::FaceVertex => "facevertex",
        }
    }

    fn from_word(w: &str) -> Option<Class> {
        Some(match w {
            "constant" => Class::Constant,
            "uniform" => Class::Uniform,
            "varying" => Class::Varying,
            "vertex" => Class::Vertex,
            "facevarying" => Class::FaceVarying,
            "facevertex" => Class::FaceVertex,
            _ => return None,
        })
    }
}

/// Value type of a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Type {
    /// One float.
    Float,
    /// One 32-bit integer (`int` is accepted as a synonym).
    Integer,
    /// One string.
    String,
    /// `ColorSamples` floats (3 unless changed).
    Color,
    /// Three floats, transformed as a point.
    Point,
    /// Three floats, transformed as a direction.
    Vector,
    /// Three floats, transformed as a surface normal.
    Normal,
    /// Four floats, a homogeneous point.
    HPoint,
    /// Sixteen floats, a 4x4 matrix in row order.
    Matrix,
}

impl Type {
    /// The keyword, as written in RIB.
    pub fn name(self) -> &'static str {
        match self {
            Type::Float => "float",
            Type::Integer => "integer",
            Type::String => "string",
            Type::Color => "color",
            Type::Point => "point",
            Type::Vector => "vector",
            Type::Normal => "normal",
            Type::HPoint => "hpoint",
            Type::Matrix => "matrix",
        }
    }

    fn from_word(w: &str) -> Option<Type> {
        Some(match w {
            "float" => Type::Float,
            "integer" | "int" => Type::Integer,
            "string" => Type::String,
            "color" => Type::Color,
            "point" => Type::Point,
            "vector" => Type::Vector,
            "normal" => Type::Normal,
            "hpoint" => Type::HPoint,
            "matrix" => Type::Matrix,
            _ => return None,
        })
    }

    /// Scalars in one value of this type; `color_samples` is the current `ColorSamples` count.
    pub fn scalars(self, color_samples: usize) -> usize {
        match self {
            Type::Float | Type::Integer | Type::String => 1,
            Type::Color => color_samples,
            Type::Point | Type::Vector | Type::Normal => 3,
            Type::HPoint => 4,
            Type::Matrix => 16,
        }
    }

    /// How the values are stored: floats, integers or strings.
    pub fn storage(self) -> Storage {
        match self {
            Type::Integer => Storage::Ints,
            Type::String => Storage::Strings,
            _ => Storage::Floats,
        }
    }
}

/// The Rust type a parameter's values are stored as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Storage {
    /// `Vec<f32>`.
    Floats,
    /// `Vec<i32>`.
    Ints,
    /// `Vec<String>`.
    Strings,
}

/// A declaration: class, type and array size, e.g. `uniform float[2]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Decl {
    /// Storage class (`uniform` when not written).
    pub class: Class,
    /// Value type.
    pub ty: Type,
    /// Array size `n` of `type[n]`, at least 1; `None` when not an array.
    pub array: Option<u32>,
}

impl Decl {
    /// A declaration without an array size.
    pub const fn new(class: Class, ty: Type) -> Decl {
        Decl { class, ty, array: None }
    }

    /// Scalars (floats, integers or strings) per element: the type's size times the array size.
    pub fn scalars(&self, color_samples: usize) -> usize {
        self.ty.scalars(color_samples) * self.array.map_or(1, |n| n as usize)
    }

    /// Parses a declaration as `Declare` takes it: `[class] type [ '[' n ']' ]`, e.g.
    /// `"varying color"`, `"uniform float[2]"`, `"float [3]"`.
    pub fn parse(text: &str) -> Result<Decl, String> {
        let words = words(text);
        if words.is_empty() {
            return Err("empty declaration".into());
        }
        let (decl, used) = parse_words(&words)?;
        match words.get(used) {
            None => Ok(decl),
            Some(w) => Err(format!("unexpected {} after the type", quote(w))),
        }
    }
}

impl fmt::Display for Decl {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.class.name(), self.ty.name())?;
        if let Some(n) = self.array {
            write!(f, "[{n}]")?;
        }
        Ok(())
    }
}

/// Splits a declaration into words, `[`, `n` and `]` standing alone.
fn words(text: &str) -> Vec<String> {
    let spaced = text.replace('[', " [ ").replace(']', " ] ");
    spaced.split_ascii_whitespace().map(str::to_owned).collect()
}

/// Parses `[class] type ['[' n ']']` from the front of `words`; returns the declaration and the
/// number of words used.
fn parse_words(words: &[String]) -> Result<(Decl, usize), String> {
    let mut i = 0;
    let class = match Class::from_word(&words[0]) {
        Some(c) => {
            i = 1;
            c
        }
        None => Class::Uniform,
    };
    let Some(word) = words.get(i) else {
        return Err(format!("class {} without a type", words[0]));
    };
    let Some(ty) = Type::from_word(word) else {
        return Err(format!("unknown type {}", quote(word)));
    };
    i += 1;
    let mut array = None;
    if words.get(i).map(String::as_str) == Some("[") {
        let size = words.get(i + 1).ok_or("unterminated array size")?;
        let n =
            size.parse::<u32>().ok().filter(|&n| n >= 1).ok_or_else(|| {
                format!("array size must be a positive integer, got {}", quote(size))
            })?;
        if words.get(i + 2).map(String::as_str) != Some("]") {
            return Err("unterminated array size".into());
        }
        array = Some(n);
        i += 3;
    }
    Ok((Decl { class, ty, array }, i))
}

/// Splits a parameter token into an inline declaration and the name, e.g.
/// `"facevarying float[2] st"` gives `(Some(facevarying float[2]), Some("st"))`. A token of one
/// word gives `(None, None)` when it is the name as it stands (look it up), or `(None,
/// Some(word))` when blanks around it were trimmed. A token of several words that is no
/// declaration followed by one name is an error.
pub(crate) fn parse_token(token: &str) -> Result<(Option<Decl>, Option<String>), String> {
    let trimmed = token.trim_ascii();
    if !trimmed.contains(|c: char| c.is_ascii_whitespace() || c == '[' || c == ']') {
        return Ok((None, (trimmed.len() != token.len()).then(|| trimmed.to_owned())));
    }
    let words = words(trimmed);
    if words.len() < 2 {
        return Err("no name after the declaration".into());
    }
    let (decl, used) = parse_words(&words)?;
    match &words[used..] {
        [name] if !matches!(name.as_str(), "[" | "]") => Ok((Some(decl), Some(name.clone()))),
        [] => Err("no name after the declaration".into()),
        [_, extra, ..] => Err(format!("unexpected {} after the name", quote(extra))),
        [bad] => Err(format!("unexpected {}", quote(bad))),
    }
}

/// The declaration table: names declared by `Declare` or predeclared by the spec.
#[derive(Debug, Clone)]
pub struct Declarations {
    map: HashMap<String, Decl>,
}

impl Default for Declarations {
    fn default() -> Self {
        Declarations::standard()
    }
}

/// The predeclared variables: Spec 3.2's standard primitive variables (§5) and the parameters of
/// its standard shaders and requests (Appendix A, `Projection "perspective" "fov"`), then a few
/// implementation tokens common in RIB files (`Option "statistics" "endofframe"`,
/// `Option "searchpath"`, `Option "limits"`, `Attribute "identifier" "name"`,
/// `Attribute "displacementbound"`, `Display "origin"`, `Hider "jitter"` and `"depthfilter"`).
pub const STANDARD: &[(&str, Class, Type, Option<u32>)] = {
    use Class::*;
    use Type::*;
    &[
        // Standard geometric primitive variables.
        ("P", Vertex, Point, None),
        ("Pz", Vertex, Float, None),
        ("Pw", Vertex, HPoint, None),
        ("N", Varying, Normal, None),
        ("Np", Uniform, Normal, None),
        ("Cs", Varying, Color, None),
        ("Os", Varying, Color, None),
        ("s", Varying, Float, None),
        ("t", Varying, Float, None),
        ("st", Varying, Float, Some(2)),
        ("width", Varying, Float, None),
        ("constantwidth", Constant, Float, None),
        // Parameters of the standard shaders.
        ("Ka", Uniform, Float, None),
        ("Kd", Uniform, Float, None),
        ("Ks", Uniform, Float, None),
        ("Kr", Uniform, Float, None),
        ("Km", Uniform, Float, None),
        ("roughness", Uniform, Float, None),
        ("specularcolor", Uniform, Color, None),
        ("texturename", Uniform, String, None),
        ("intensity", Uniform, Float, None),
        ("lightcolor", Uniform, Color, None),
        ("from", Uniform, Point, None),
        ("to", Uniform, Point, None),
        ("coneangle", Uniform, Float, None),
        ("conedeltaangle", Uniform, Float, None),
        ("beamdistribution", Uniform, Float, None),
        ("mindistance", Uniform, Float, None),
        ("maxdistance", Uniform, Float, None),
        ("distance", Uniform, Float, None),
        ("background", Uniform, Color, None),
        ("amplitude", Uniform, Float, None),
        // Parameters of standard requests.
        ("fov", Uniform, Float, None),
        // Common implementation tokens.
        ("endofframe", Uniform, Integer, None),
        ("shader", Uniform, String, None),
        ("texture", Uniform, String, None),
        ("archive", Uniform, String, None),
        ("procedural", Uniform, String, None),
        ("display", Uniform, String, None),
        ("bucketsize", Uniform, Integer, Some(2)),
        ("gridsize", Uniform, Integer, None),
        ("texturememory", Uniform, Integer, None),
        ("name", Uniform, String, None),
        ("sphere", Uniform, Float, None),
        ("coordinatesystem", Uniform, String, None),
        ("sense", Uniform, String, None),
        ("origin", Uniform, Integer, Some(2)),
        ("jitter", Uniform, Integer, None),
        ("depthfilter", Uniform, String, None),
    ]
};

impl Declarations {
    /// The table with only the predeclared names of [`STANDARD`].
    pub fn standard() -> Declarations {
        let map = STANDARD
            .iter()
            .map(|&(name, class, ty, array)| (name.to_owned(), Decl { class, ty, array }))
            .collect();
        Declarations { map }
    }

    /// The declaration of `name`, if any.
    pub fn get(&self, name: &str) -> Option<&Decl> {
        self.map.get(name)
    }

    /// Declares (or redeclares) `name`.
    pub fn declare(&mut self, name: &str, decl: Decl) {
        self.map.insert(name.to_owned(), decl);
    }

    /// Number of declared names.
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// True if nothing is declared.
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d(class: Class, ty: Type, array: Option<u32>) -> Decl {
        Decl { class, ty, array }
    }

    #[test]
    fn declare_forms() {
        use Class::*;
        use Type::*;
        assert_eq!(Decl::parse("float"), Ok(d(Uniform, Float, None)));
        assert_eq!(Decl::parse("uniform float"), Ok(d(Uniform, Float, None)));
        assert_eq!(Decl::parse("varying color"), Ok(d(Varying, Color, None)));
        assert_eq!(Decl::parse("constant string"), Ok(d(Constant, String, None)));
        assert_eq!(Decl::parse("vertex point"), Ok(d(Vertex, Point, None)));
        assert_eq!(Decl::parse("facevarying float[2]"), Ok(d(FaceVarying, Float, Some(2))));
        assert_eq!(Decl::parse("facevertex normal"), Ok(d(FaceVertex, Normal, None)));
        assert_eq!(Decl::parse("float [3]"), Ok(d(Uniform, Float, Some(3))));
        assert_eq!(Decl::parse(" uniform  float[ 4 ] "), Ok(d(Uniform, Float, Some(4))));
        assert_eq!(Decl::parse("int"), Ok(d(Uniform, Integer, None)));
        assert_eq!(Decl::parse("integer[2]"), Ok(d(Uniform, Integer, Some(2))));
        assert_eq!(Decl::parse("vector"), Ok(d(Uniform, Vector, None)));
        assert_eq!(Decl::parse("hpoint"), Ok(d(Uniform, HPoint, None)));
        assert_eq!(Decl::parse("matrix"), Ok(d(Uniform, Matrix, None)));
    }

    #[test]
    fn declare_errors() {
        assert_eq!(Decl::parse(""), Err("empty declaration".into()));
        assert_eq!(Decl::parse("flaot"), Err("unknown type \"flaot\"".into()));
        assert_eq!(Decl::parse("varying"), Err("class varying without a type".into()));
        assert_eq!(
            Decl::parse("float[0]"),
            Err("array size must be a positive integer, got \"0\"".into())
        );
        assert_eq!(
            Decl::parse("float[x]"),
            Err("array size must be a positive integer, got \"x\"".into())
        );
        assert_eq!(Decl::parse("float[2"), Err("unterminated array size".into()));
        assert_eq!(Decl::parse("float Kd"), Err("unexpected \"Kd\" after the type".into()));
    }

    #[test]
    fn inline_tokens() {
        use Class::*;
        use Type::*;
        assert_eq!(parse_token("Kd"), Ok((None, None)));
        assert_eq!(parse_token(" Kd "), Ok((None, Some("Kd".into()))));
        assert_eq!(
            parse_token("uniform float Kd"),
            Ok((Some(d(Uniform, Float, None)), Some("Kd".into())))
        );
        assert_eq!(
            parse_token("varying color Cs"),
            Ok((Some(d(Varying, Color, None)), Some("Cs".into())))
        );
        assert_eq!(
            parse_token("constant string texturename"),
            Ok((Some(d(Constant, String, None)), Some("texturename".into())))
        );
        assert_eq!(
            parse_token("vertex point P"),
            Ok((Some(d(Vertex, Point, None)), Some("P".into())))
        );
        assert_eq!(
            parse_token("facevarying float[2] st"),
            Ok((Some(d(FaceVarying, Float, Some(2))), Some("st".into())))
        );
        assert_eq!(
            parse_token("float[3] v"),
            Ok((Some(d(Uniform, Float, Some(3))), Some("v".into())))
        );
        assert_eq!(parse_token("float Kd"), Ok((Some(d(Uniform, Float, None)), Some("Kd".into()))));
        assert_eq!(parse_token("user:foo"), Ok((None, None)));
    }

    #[test]
    fn inline_errors() {
        assert_eq!(parse_token("unifrom float Kd"), Err("unknown type \"unifrom\"".into()));
        assert_eq!(parse_token("uniform float"), Err("no name after the declaration".into()));
        assert_eq!(
            parse_token("float Kd extra"),
            Err("unexpected \"extra\" after the name".into())
        );
        assert_eq!(parse_token("float[2 st"), Err("unterminated array size".into()));
    }

    #[test]
    fn sizes() {
        let st = Decl { class: Class::Varying, ty: Type::Float, array: Some(2) };
        assert_eq!(st.scalars(3), 2);
        assert_eq!(Decl::new(Class::Varying, Type::Color).scalars(3), 3);
        assert_eq!(Decl::new(Class::Varying, Type::Color).scalars(5), 5);
        assert_eq!(Decl::new(Class::Vertex, Type::HPoint).scalars(3), 4);
        assert_eq!(Decl::new(Class::Uniform, Type::Matrix).scalars(3), 16);
        assert_eq!(st.to_string(), "varying float[2]");
    }

    #[test]
    fn predeclared() {
        let t = Declarations::standard();
        assert_eq!(t.get("P"), Some(&Decl::new(Class::Vertex, Type::Point)));
        assert_eq!(t.get("st").and_then(|d| d.array), Some(2));
        for name in [
            "Pw",
            "Pz",
            "N",
            "Np",
            "Cs",
            "Os",
            "s",
            "t",
            "Ka",
            "Kd",
            "Ks",
            "roughness",
            "specularcolor",
            "intensity",
            "lightcolor",
            "from",
            "to",
            "coneangle",
            "conedeltaangle",
            "beamdistribution",
            "fov",
            "texturename",
        ] {
            assert!(t.get(name).is_some(), "{name}");
        }
        assert!(t.get("Kq").is_none());
    }
}
