//! What the reader hands on: a [`Request`] (kind, location, normalised positional arguments,
//! typed parameters).
//!
//! Invariant: a request returned by the reader fits its [`crate::Signature`]: `args` holds one
//! [`Value`] per present argument, of the variant its [`crate::ArgKind`] documents, so the
//! typed accessors below return `Some` for every required argument. Every declared parameter
//! holds a whole number of elements of its declaration, and exactly one when `constant`.

use crate::decl::Decl;
use crate::error::{Location, Pos, RibError, Warning, quote};
use crate::signature::RequestKind;

/// A positional argument's value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An integer.
    Int(i32),
    /// A number.
    Float(f32),
    /// A string.
    String(String),
    /// An integer array.
    Ints(Vec<i32>),
    /// A number array (also bare numbers gathered: a colour, a matrix, motion times).
    Floats(Vec<f32>),
    /// A string array.
    Strings(Vec<String>),
}

/// A parameter's values, stored by type: floats for `float`, `color`, `point`, `vector`,
/// `normal`, `hpoint` and `matrix` (components flattened), integers, or strings.
#[derive(Debug, Clone, PartialEq)]
pub enum Data {
    /// Float-based types.
    Floats(Vec<f32>),
    /// `integer`.
    Ints(Vec<i32>),
    /// `string`.
    Strings(Vec<String>),
}

impl Data {
    /// Number of scalars.
    pub fn len(&self) -> usize {
        match self {
            Data::Floats(v) => v.len(),
            Data::Ints(v) => v.len(),
            Data::Strings(v) => v.len(),
        }
    }

    /// True if there are no values.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One `"token" value` pair of a parameter list.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    /// The name, without any inline declaration (`"uniform float Kd"` gives `Kd`).
    pub name: String,
    /// The declaration used: the inline one, else the table's; `None` if the name is not
    /// declared, in which case `data` is as written (integers if every number was an integer
    /// literal, else floats; or strings) and a warning was recorded.
    pub decl: Option<Decl>,
    /// The values.
    pub data: Data,
    /// Where the token string starts (in the request's file).
    pub at: Pos,
}

impl Param {
    /// The float values, if stored as floats.
    pub fn floats(&self) -> Option<&[f32]> {
        match &self.data {
            Data::Floats(v) => Some(v),
            _ => None,
        }
    }

    /// The integer values, if stored as integers.
    pub fn ints(&self) -> Option<&[i32]> {
        match &self.data {
            Data::Ints(v) => Some(v),
            _ => None,
        }
    }

    /// The strings, if stored as strings.
    pub fn strings(&self) -> Option<&[String]> {
        match &self.data {
            Data::Strings(v) => Some(v),
            _ => None,
        }
    }

    /// Number of elements (scalars divided by the declaration's size), if declared.
    pub fn elements(&self, color_samples: usize) -> Option<usize> {
        self.decl.map(|d| self.data.len() / d.scalars(color_samples))
    }
}

/// One RIB request, checked against its signature and declarations.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// Which request.
    pub kind: RequestKind,
    /// Where its name starts.
    pub at: Location,
    /// The positional arguments present, normalised (see [`crate::ArgKind`]); optional ones
    /// absent are simply missing (`DepthOfField` may have none).
    pub args: Vec<Value>,
    /// The parameter list, in input order.
    pub params: Vec<Param>,
}

impl Request {
    /// The RIB name.
    pub fn name(&self) -> &'static str {
        self.kind.name()
    }

    /// Argument `i` as a float (an [`Value::Int`] converts).
    pub fn float(&self, i: usize) -> Option<f32> {
        match self.args.get(i)? {
            Value::Float(f) => Some(*f),
            Value::Int(n) => Some(*n as f32),
            _ => None,
        }
    }

    /// Argument `i` as an integer.
    pub fn int(&self, i: usize) -> Option<i32> {
        match self.args.get(i)? {
            Value::Int(n) => Some(*n),
            _ => None,
        }
    }

    /// Argument `i` as a string.
    pub fn string(&self, i: usize) -> Option<&str> {
        match self.args.get(i)? {
            Value::String(s) => Some(s),
            _ => None,
        }
    }

    /// Argument `i` as floats (an array, or gathered bare numbers).
    pub fn floats(&self, i: usize) -> Option<&[f32]> {
        match self.args.get(i)? {
            Value::Floats(v) => Some(v),
            _ => None,
        }
    }

    /// Argument `i` as integers.
    pub fn ints(&self, i: usize) -> Option<&[i32]> {
        match self.args.get(i)? {
            Value::Ints(v) => Some(v),
            _ => None,
        }
    }

    /// Argument `i` as strings.
    pub fn strings(&self, i: usize) -> Option<&[String]> {
        match self.args.get(i)? {
            Value::Strings(v) => Some(v),
            _ => None,
        }
    }

    /// The first parameter named `name` (the name without inline declaration).
    pub fn param(&self, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.name == name)
    }

    /// Location of parameter `p` of this request.
    pub fn param_location(&self, p: &Param) -> Location {
        self.at.at(p.at)
    }

    /// An error about this request in the house form, `file:line:col: Request: message`: for
    /// the state machine's own checks (scope, counts per primitive, handles).
    pub fn error(&self, message: impl Into<String>) -> RibError {
        RibError::Request { at: self.at.clone(), request: self.name(), message: message.into() }
    }

    /// An error about parameter `p` of this request, at the parameter's position:
    /// `file:line:col: Request: parameter "name": message`.
    pub fn param_error(&self, p: &Param, message: impl AsRef<str>) -> RibError {
        RibError::Request {
            at: self.param_location(p),
            request: self.name(),
            message: format!("parameter {}: {}", quote(&p.name), message.as_ref()),
        }
    }

    /// A warning about this request: `file:line:col: warning: Request: message`.
    pub fn warning(&self, message: impl AsRef<str>) -> Warning {
        Warning { at: self.at.clone(), message: format!("{}: {}", self.name(), message.as_ref()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decl::{Class, Type};
    use std::sync::Arc;

    #[test]
    fn accessors() {
        let r = Request {
            kind: RequestKind::Sphere,
            at: Location { file: Arc::from("a.rib"), pos: Pos { line: 1, col: 1 } },
            args: vec![Value::Float(1.0), Value::Int(2), Value::String("x".into())],
            params: vec![Param {
                name: "Kd".into(),
                decl: Some(Decl::new(Class::Uniform, Type::Float)),
                data: Data::Floats(vec![0.5]),
                at: Pos { line: 1, col: 20 },
            }],
        };
        assert_eq!(r.float(0), Some(1.0));
        assert_eq!(r.float(1), Some(2.0));
        assert_eq!(r.int(0), None);
        assert_eq!(r.string(2), Some("x"));
        assert_eq!(r.float(9), None);
        assert_eq!(r.param("Kd").and_then(Param::floats), Some(&[0.5][..]));
        assert_eq!(r.param("Kd").and_then(|p| p.elements(3)), Some(1));
        assert_eq!(r.param_location(&r.params[0]).to_string(), "a.rib:1:20");
        assert_eq!(r.name(), "Sphere");
        assert_eq!(
            r.error("outside WorldBegin").to_string(),
            "a.rib:1:1: Sphere: outside WorldBegin"
        );
        assert_eq!(
            r.param_error(&r.params[0], "expected 4 values (one per vertex), got 1").to_string(),
            "a.rib:1:20: Sphere: parameter \"Kd\": expected 4 values (one per vertex), got 1"
        );
        assert_eq!(r.warning("ignored").to_string(), "a.rib:1:1: warning: Sphere: ignored");
    }
}
