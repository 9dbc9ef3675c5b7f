//! The predefined (global) variables of each shader type, as the Specification's tables list
//! them (section 12), with their types, detail and access.
//!
//! The Specification's rule: every predefined variable is read-only, except the results of
//! each shader type, and `Cs`, `Os`, `N`, `s` and `t`, which may be written wherever they can
//! be read. Two extensions: surface shaders may write `P` (old-style bump mapping; both peers
//! accept it, and public shaders do it), and imager shaders may use `s` and `t` (as Aqsis).

use crate::types::{BaseType, Detail, ShaderKind, Type};

/// What a shader type may do with a global.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Not available in this shader type.
    None,
    /// Read only.
    Read,
    /// Read and write.
    ReadWrite,
}

/// A predefined variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Global {
    /// Its name.
    pub name: &'static str,
    /// Its type.
    pub ty: Type,
    /// Uniform or varying.
    pub detail: Detail,
    /// Access per shader type, in [`ShaderKind::ALL`] order: surface, displacement, light,
    /// volume, imager.
    pub access: [Access; 5],
    /// In surface shaders, readable only inside `illuminance` (`L`, `Cl`, `Ol`).
    pub in_illuminance: bool,
    /// What it is.
    pub doc: &'static str,
}

impl Global {
    /// Access in a shader of type `kind`.
    pub fn access(&self, kind: ShaderKind) -> Access {
        self.access[ShaderKind::ALL.iter().position(|k| *k == kind).expect("five kinds")]
    }
}

use Access::{None as No, Read as R, ReadWrite as RW};
use BaseType as B;
use Detail::{Uniform as U, Varying as V};

const fn g(
    name: &'static str,
    base: BaseType,
    detail: Detail,
    access: [Access; 5],
    doc: &'static str,
) -> Global {
    Global { name, ty: Type::scalar(base), detail, access, in_illuminance: false, doc }
}

const fn lit(name: &'static str, base: BaseType, access: [Access; 5], doc: &'static str) -> Global {
    Global { name, ty: Type::scalar(base), detail: V, access, in_illuminance: true, doc }
}

/// Every predefined variable. Columns of `access`: surface, displacement, light, volume, imager.
pub const GLOBALS: &[Global] = &[
    g(
        "P",
        B::Point,
        V,
        [RW, RW, R, R, R],
        "surface position (light: point on the light; volume: ray end; imager: raster position)",
    ),
    g("dPdu", B::Vector, V, [R, R, R, No, No], "derivative of P along u"),
    g("dPdv", B::Vector, V, [R, R, R, No, No], "derivative of P along v"),
    g("N", B::Normal, V, [RW, RW, RW, No, No], "shading normal"),
    g("Ng", B::Normal, V, [R, R, R, No, No], "geometric normal"),
    g("u", B::Float, V, [R, R, R, No, No], "surface parameter u"),
    g("v", B::Float, V, [R, R, R, No, No], "surface parameter v"),
    g("du", B::Float, V, [R, R, R, No, No], "change in u"),
    g("dv", B::Float, V, [R, R, R, No, No], "change in v"),
    g("s", B::Float, V, [RW, RW, RW, No, RW], "texture coordinate s (imager: extension, as Aqsis)"),
    g("t", B::Float, V, [RW, RW, RW, No, RW], "texture coordinate t (imager: extension, as Aqsis)"),
    g("Cs", B::Color, V, [RW, No, No, No, No], "surface colour"),
    g("Os", B::Color, V, [RW, No, No, No, No], "surface opacity"),
    lit(
        "L",
        B::Vector,
        [R, No, RW, No, No],
        "direction of incoming light (surface: from the point to the light; light: from the light to Ps)",
    ),
    lit("Cl", B::Color, [R, No, RW, No, No], "light colour"),
    lit("Ol", B::Color, [R, No, RW, No, No], "light opacity"),
    g("Ps", B::Point, V, [No, No, R, No, No], "the point being illuminated"),
    g("Ns", B::Normal, V, [No, No, R, No, No], "the normal at Ps (extension: later PRMan, Aqsis)"),
    g("I", B::Vector, V, [R, R, No, R, No], "incident ray direction"),
    g("E", B::Point, U, [R, R, R, R, No], "position of the eye"),
    g("Ci", B::Color, V, [RW, No, No, RW, RW], "result colour"),
    g("Oi", B::Color, V, [RW, No, No, RW, RW], "result opacity"),
    g("alpha", B::Float, V, [No, No, No, No, RW], "coverage of the pixel"),
    g("ncomps", B::Float, U, [R, R, R, R, R], "number of colour components"),
    g("time", B::Float, U, [R, R, R, R, R], "current shutter time"),
    g("dtime", B::Float, U, [R, R, R, R, R], "shutter time this shading sample covers"),
    g("dPdtime", B::Vector, V, [R, R, R, No, No], "change of P per unit time"),
    g("PI", B::Float, U, [R, R, R, R, R], "the constant 3.14159..."),
];

/// The global called `name`, if any.
pub fn global(name: &str) -> Option<&'static Global> {
    GLOBALS.iter().find(|g| g.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_specification_rules() {
        let a = |n: &str, k| global(n).unwrap().access(k);
        assert_eq!(a("Ci", ShaderKind::Surface), Access::ReadWrite);
        assert_eq!(a("Ci", ShaderKind::Displacement), Access::None);
        assert_eq!(a("P", ShaderKind::Displacement), Access::ReadWrite);
        assert_eq!(a("Cl", ShaderKind::Light), Access::ReadWrite);
        assert_eq!(a("Ps", ShaderKind::Surface), Access::None);
        assert_eq!(a("alpha", ShaderKind::Imager), Access::ReadWrite);
        assert_eq!(global("E").unwrap().detail, Detail::Uniform);
        // Cs, Os, N, s, t: writable wherever readable.
        for n in ["Cs", "Os", "N", "s", "t"] {
            for k in ShaderKind::ALL {
                assert_ne!(a(n, k), Access::Read, "{n} in {k}");
            }
        }
    }
}
