//! The types of RSL: a base type, an array shape, and uniform/varying-ness (the detail).

use std::fmt;

/// The base types. `Bool` is the type of relations (`a < b`, `&&`); it cannot be declared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BaseType {
    /// `float`.
    Float,
    /// `color` (three components in this implementation: `ncomps` is 3).
    Color,
    /// `point`.
    Point,
    /// `vector`.
    Vector,
    /// `normal`.
    Normal,
    /// `matrix` (4x4).
    Matrix,
    /// `string`.
    String,
    /// `void` (function results only).
    Void,
    /// The result of a relation; conditions take it.
    Bool,
}

impl BaseType {
    /// The keyword.
    pub fn name(self) -> &'static str {
        match self {
            BaseType::Float => "float",
            BaseType::Color => "color",
            BaseType::Point => "point",
            BaseType::Vector => "vector",
            BaseType::Normal => "normal",
            BaseType::Matrix => "matrix",
            BaseType::String => "string",
            BaseType::Void => "void",
            BaseType::Bool => "boolean",
        }
    }

    /// The type keyword `s` names.
    pub fn from_keyword(s: &str) -> Option<BaseType> {
        Some(match s {
            "float" => BaseType::Float,
            "color" => BaseType::Color,
            "point" => BaseType::Point,
            "vector" => BaseType::Vector,
            "normal" => BaseType::Normal,
            "matrix" => BaseType::Matrix,
            "string" => BaseType::String,
            "void" => BaseType::Void,
            _ => return None,
        })
    }

    /// `point`, `vector` or `normal`.
    pub fn is_spatial(self) -> bool {
        matches!(self, BaseType::Point | BaseType::Vector | BaseType::Normal)
    }

    /// A three-component type: spatial or `color`.
    pub fn is_triple(self) -> bool {
        self.is_spatial() || self == BaseType::Color
    }

    /// Float, triples and matrices: what arithmetic takes.
    pub fn is_numeric(self) -> bool {
        matches!(self, BaseType::Float | BaseType::Matrix) || self.is_triple()
    }
}

impl fmt::Display for BaseType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Uniform (one value for the whole grid) or varying (one value per grid point).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Detail {
    /// One value for the grid.
    Uniform,
    /// One value per point.
    Varying,
}

impl Detail {
    /// The keyword.
    pub fn name(self) -> &'static str {
        match self {
            Detail::Uniform => "uniform",
            Detail::Varying => "varying",
        }
    }

    /// Varying if either is.
    pub fn join(self, other: Detail) -> Detail {
        self.max(other)
    }
}

/// A type: base and array shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Type {
    /// The base type (of the elements, for arrays).
    pub base: BaseType,
    /// `Some(n)` for an array of n; `Some(0)` for an open array formal `float a[]` of a
    /// function, which takes arrays of any length.
    pub array: Option<u32>,
}

impl Type {
    /// A scalar (non-array) type.
    pub const fn scalar(base: BaseType) -> Type {
        Type { base, array: None }
    }

    /// `float`.
    pub const FLOAT: Type = Type::scalar(BaseType::Float);
    /// `color`.
    pub const COLOR: Type = Type::scalar(BaseType::Color);
    /// `point`.
    pub const POINT: Type = Type::scalar(BaseType::Point);
    /// `vector`.
    pub const VECTOR: Type = Type::scalar(BaseType::Vector);
    /// `normal`.
    pub const NORMAL: Type = Type::scalar(BaseType::Normal);
    /// `matrix`.
    pub const MATRIX: Type = Type::scalar(BaseType::Matrix);
    /// `string`.
    pub const STRING: Type = Type::scalar(BaseType::String);
    /// `void`.
    pub const VOID: Type = Type::scalar(BaseType::Void);
    /// The relation type.
    pub const BOOL: Type = Type::scalar(BaseType::Bool);

    /// Is an array.
    pub fn is_array(self) -> bool {
        self.array.is_some()
    }

    /// The element type of an array (or the type itself).
    pub fn element(self) -> Type {
        Type::scalar(self.base)
    }
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.array {
            None => write!(f, "{}", self.base),
            Some(0) => write!(f, "{}[]", self.base),
            Some(n) => write!(f, "{}[{n}]", self.base),
        }
    }
}

/// A type with its detail: the full static description of a value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Typed {
    /// The type.
    pub ty: Type,
    /// Uniform or varying.
    pub detail: Detail,
}

impl fmt::Display for Typed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.detail.name(), self.ty)
    }
}

/// The five shader types (and `transformation`, parsed and refused).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShaderKind {
    /// `surface`.
    Surface,
    /// `displacement`.
    Displacement,
    /// `light`.
    Light,
    /// `volume` (atmosphere, interior, exterior).
    Volume,
    /// `imager`.
    Imager,
}

impl ShaderKind {
    /// The keyword.
    pub fn name(self) -> &'static str {
        match self {
            ShaderKind::Surface => "surface",
            ShaderKind::Displacement => "displacement",
            ShaderKind::Light => "light",
            ShaderKind::Volume => "volume",
            ShaderKind::Imager => "imager",
        }
    }

    /// All five.
    pub const ALL: [ShaderKind; 5] = [
        ShaderKind::Surface,
        ShaderKind::Displacement,
        ShaderKind::Light,
        ShaderKind::Volume,
        ShaderKind::Imager,
    ];
}

impl fmt::Display for ShaderKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
