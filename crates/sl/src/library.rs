//! The standard library of chapter 15 (and the few later functions real shaders call, marked
//! extensions): every function's overloads, which the checker resolves calls against.
//!
//! The table is written in a small signature language, parsed once:
//! `[ext] [varying] RET NAME(ARG, ...)` where an ARG is `[output] TYPE` (TYPE a base type,
//! `TYPE[]` for an array of any length, or `any`), and the last may be `...TYPE` (more of that
//! type), `...` (any values: printf) or `...params` (name/value pairs: texture options). A line
//! starting `<T=a,b,c>` stands for one line per type, with `T` replaced. `varying` marks
//! functions whose result is varying whatever their arguments (lighting, texture, random).

use std::collections::HashMap;
use std::sync::OnceLock;

use crate::types::{BaseType, Type};

/// One parameter of a built-in signature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BParam {
    /// `None`: a value of any type (message passing, `textureinfo`).
    pub ty: Option<Type>,
    /// The function writes it.
    pub output: bool,
}

/// What may follow the fixed parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rest {
    /// Nothing.
    None,
    /// More values of this type (`min`, `max`, `concat`, `spline`).
    Same(Type),
    /// Any values (`printf`, `format`).
    Any,
    /// Optional name/value pairs (texture and lighting options).
    Params,
}

/// One overload.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Signature {
    /// Result type.
    pub ret: Type,
    /// Fixed parameters.
    pub params: Vec<BParam>,
    /// What may follow them.
    pub rest: Rest,
    /// Result varying whatever the arguments.
    pub varying: bool,
    /// Not in the 3.2 Specification (a later PRMan function real shaders call).
    pub extension: bool,
}

impl Signature {
    /// `float noise(point)`-style text, for messages.
    pub fn show(&self, name: &str) -> String {
        let mut args: Vec<String> = self
            .params
            .iter()
            .map(|p| {
                let t = p.ty.map_or("any".to_string(), |t| t.to_string());
                if p.output { format!("output {t}") } else { t }
            })
            .collect();
        match self.rest {
            Rest::None => {}
            Rest::Same(t) => args.push(format!("{t}...")),
            Rest::Any => args.push("...".into()),
            Rest::Params => args.push("[\"name\", value]...".into()),
        }
        format!("{} {name}({})", self.ret, args.join(", "))
    }
}

/// Where the checker resolves the standard library.
pub struct Library {
    funcs: HashMap<&'static str, Vec<Signature>>,
    order: Vec<&'static str>,
}

impl Library {
    /// The overloads of `name`.
    pub fn get(&self, name: &str) -> Option<&[Signature]> {
        self.funcs.get(name).map(Vec::as_slice)
    }

    /// Every function name, in table order.
    pub fn names(&self) -> &[&'static str] {
        &self.order
    }
}

/// The standard library.
pub fn library() -> &'static Library {
    static LIB: OnceLock<Library> = OnceLock::new();
    LIB.get_or_init(|| parse_table(TABLE))
}

/// The signature table. `transform` of a vector or normal transforms it as one (as `vtransform`
/// and `ntransform` do), so a vector argument resolves to its own overload, not to the point one.
const TABLE: &str = r#"
# 15.1 Mathematical functions
float radians(float)
float degrees(float)
float sin(float)
float asin(float)
float cos(float)
float acos(float)
float tan(float)
float atan(float)
float atan(float, float)
float pow(float, float)
ext color pow(color, color)
float exp(float)
float sqrt(float)
float inversesqrt(float)
float log(float)
float log(float, float)
float mod(float, float)
float abs(float)
float sign(float)
<T=float,color,point,vector,normal> T min(T, T, ...T)
<T=float,color,point,vector,normal> T max(T, T, ...T)
<T=float,color,point,vector,normal> T clamp(T, T, T)
<T=float,color,point,vector,normal> T mix(T, T, float)
<T=color,point,vector,normal> T mix(T, T, T)
float floor(float)
float ceil(float)
float round(float)
float step(float, float)
float smoothstep(float, float, float)
float filterstep(float, float, ...params)
float filterstep(float, float, float, ...params)
<T=float,color,point,vector> T spline(float, T, T, T, T, ...T)
<T=float,color,point,vector> T spline(string, float, T, T, T, T, ...T)
<T=float,color,point,vector> T spline(float, T[])
<T=float,color,point,vector> T spline(string, float, T[])
<T=float,color,vector,normal> T Du(T)
<T=float,color,vector,normal> T Dv(T)
<T=float,color,vector,normal> T Deriv(T, float)
vector Du(point)
vector Dv(point)
vector Deriv(point, float)
<T=float,color,vector,normal> T Dtime(T)
vector Dtime(point)
<T=float,color,point,vector> varying T random()
<T=float,color,point,vector> T noise(float)
<T=float,color,point,vector> T noise(float, float)
<T=float,color,point,vector> T noise(point)
<T=float,color,point,vector> T noise(point, float)
<T=float,color,point,vector> T pnoise(float, float)
<T=float,color,point,vector> T pnoise(float, float, float, float)
<T=float,color,point,vector> T pnoise(point, point)
<T=float,color,point,vector> T pnoise(point, float, point, float)
<T=float,color,point,vector> T cellnoise(float)
<T=float,color,point,vector> T cellnoise(float, float)
<T=float,color,point,vector> T cellnoise(point)
<T=float,color,point,vector> T cellnoise(point, float)

# 15.2 Geometric functions
float xcomp(point)
float ycomp(point)
float zcomp(point)
<T=point,vector,normal> void setxcomp(output T, float)
<T=point,vector,normal> void setycomp(output T, float)
<T=point,vector,normal> void setzcomp(output T, float)
float length(vector)
<T=vector,normal> T normalize(T)
float distance(point, point)
float ptlined(point, point, point)
point rotate(point, float, point, point)
float area(point)
<T=vector,normal> T faceforward(T, vector)
<T=vector,normal> T faceforward(T, vector, vector)
vector reflect(vector, vector)
vector refract(vector, vector, float)
void fresnel(vector, normal, float, output float, output float)
void fresnel(vector, normal, float, output float, output float, output vector, output vector)
point transform(string, point)
point transform(string, string, point)
point transform(matrix, point)
point transform(string, matrix, point)
<T=vector,normal> T transform(string, T)
<T=vector,normal> T transform(string, string, T)
<T=vector,normal> T transform(matrix, T)
<T=vector,normal> T transform(string, matrix, T)
vector vtransform(string, vector)
vector vtransform(string, string, vector)
vector vtransform(matrix, vector)
vector vtransform(string, matrix, vector)
normal ntransform(string, normal)
normal ntransform(string, string, normal)
normal ntransform(matrix, normal)
normal ntransform(string, matrix, normal)
float depth(point)
normal calculatenormal(point)

# 15.3 Color functions
float comp(color, float)
void setcomp(output color, float, float)
color ctransform(string, color)
color ctransform(string, string, color)

# 15.4 Matrix functions
float comp(matrix, float, float)
void setcomp(output matrix, float, float, float)
float determinant(matrix)
ext matrix inverse(matrix)
matrix translate(matrix, vector)
matrix rotate(matrix, float, vector)
matrix scale(matrix, point)

# 15.5 String functions
string concat(string, ...string)
void printf(string, ...)
string format(string, ...)
float match(string, string)

# 15.6 Shading and lighting functions
varying color ambient()
varying color diffuse(normal)
varying color specular(normal, vector, float)
varying color specularbrdf(vector, normal, vector, float)
varying color phong(normal, vector, float)
varying color trace(point, vector)

# 15.7 Texture mapping functions
<T=float,color> varying T texture(string, ...params)
<T=float,color> varying T texture(string, float, float, ...params)
<T=float,color> varying T texture(string, float, float, float, float, float, float, float, float, ...params)
<T=float,color> varying T environment(string, vector, ...params)
<T=float,color> varying T environment(string, vector, vector, vector, vector, ...params)
varying float shadow(string, point, ...params)
varying float shadow(string, point, point, point, point, ...params)
float textureinfo(string, string, output any)

# 15.8 Message passing and information functions
float atmosphere(string, output any)
float displacement(string, output any)
float lightsource(string, output any)
float surface(string, output any)
float incident(string, output any)
float opposite(string, output any)
float attribute(string, output any)
float option(string, output any)
float rendererinfo(string, output any)
ext string shadername()
ext string shadername(string)

# Extensions: later PRMan ray-tracing and point-cloud functions the public shaders call.
ext varying float occlusion(point, normal, float, ...params)
ext varying float occlusion(string, point, normal, float, ...params)
ext varying color indirectdiffuse(point, normal, float, ...params)
ext varying color transmission(point, point, ...params)
ext varying float visibility(point, point)
ext varying float bake3d(string, string, point, normal, ...params)
ext varying float texture3d(string, point, normal, ...params)
ext varying float bake(string, float, float, float)
ext varying float bake(string, float, float, color)
ext float filterwidth(float)
ext vector filterwidth(point)
ext float isshadowray()
ext varying float raylevel()
"#;

fn parse_type(s: &str) -> Option<Type> {
    if let Some(b) = s.strip_suffix("[]") {
        return Some(Type { base: BaseType::from_keyword(b)?, array: Some(0) });
    }
    BaseType::from_keyword(s).map(Type::scalar)
}

fn parse_table(text: &str) -> Library {
    let mut funcs: HashMap<&'static str, Vec<Signature>> = HashMap::new();
    let mut order = Vec::new();
    for raw in text.lines() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let (subs, rest): (Vec<&str>, &str) = match line.strip_prefix("<T=") {
            Some(r) => {
                let (list, rest) = r.split_once('>').expect("table: <T=...>");
                (list.split(',').collect(), rest.trim())
            }
            None => (vec![""], line),
        };
        for sub in subs {
            let l = if sub.is_empty() { rest.to_string() } else { replace_t(rest, sub) };
            let (name, sig) = parse_line(&l);
            let name: &'static str = Box::leak(name.into_boxed_str());
            if !funcs.contains_key(name) {
                order.push(name);
            }
            funcs.entry(name).or_default().push(sig);
        }
    }
    Library { funcs, order }
}

/// Replaces the type variable T (a whole word) by `ty`.
fn replace_t(s: &str, ty: &str) -> String {
    let mut out = String::new();
    let chars: Vec<char> = s.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        let word = |k: usize| chars.get(k).is_some_and(|c| c.is_alphanumeric() || *c == '_');
        if c == 'T' && (i == 0 || !word(i - 1)) && !word(i + 1) {
            out.push_str(ty);
        } else {
            out.push(c);
        }
    }
    out
}

fn parse_line(l: &str) -> (String, Signature) {
    let mut words = l;
    let mut extension = false;
    let mut varying = false;
    loop {
        if let Some(r) = words.strip_prefix("ext ") {
            extension = true;
            words = r;
        } else if let Some(r) = words.strip_prefix("varying ") {
            varying = true;
            words = r;
        } else {
            break;
        }
    }
    let (head, args) = words.split_once('(').expect("table: '('");
    let args = args.strip_suffix(')').expect("table: ')'");
    let (ret, name) = head.trim().split_once(' ').expect("table: RET NAME");
    let ret = parse_type(ret).expect("table: return type");
    let mut params = Vec::new();
    let mut rest = Rest::None;
    for a in args.split(',').map(str::trim).filter(|a| !a.is_empty()) {
        if a == "..." {
            rest = Rest::Any;
        } else if a == "...params" {
            rest = Rest::Params;
        } else if let Some(t) = a.strip_prefix("...") {
            rest = Rest::Same(parse_type(t).expect("table: ...TYPE"));
        } else {
            let (output, t) = match a.strip_prefix("output ") {
                Some(t) => (true, t),
                None => (false, a),
            };
            let ty = if t == "any" { None } else { Some(parse_type(t).expect("table: arg type")) };
            params.push(BParam { ty, output });
        }
    }
    (name.trim().to_string(), Signature { ret, params, rest, varying, extension })
}

/// The options texture, environment and shadow calls take, with their value types (names not
/// listed here are renderer-specific and pass through).
pub fn texture_option(name: &str) -> Option<BaseType> {
    Some(match name {
        "blur" | "sblur" | "tblur" | "width" | "swidth" | "twidth" | "fill" | "samples"
        | "bias" | "bias0" | "bias1" | "lerp" | "maxdist" | "coneangle" | "falloff" => {
            BaseType::Float
        }
        "filter" | "label" | "subset" | "hitmode" | "coordsystem" | "envspace" | "hitsides" => {
            BaseType::String
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_parses_and_holds_the_chapter() {
        let lib = library();
        for name in [
            "radians",
            "noise",
            "cellnoise",
            "spline",
            "transform",
            "fresnel",
            "ctransform",
            "determinant",
            "concat",
            "printf",
            "format",
            "match",
            "ambient",
            "diffuse",
            "specular",
            "specularbrdf",
            "phong",
            "trace",
            "texture",
            "environment",
            "shadow",
            "textureinfo",
            "atmosphere",
            "lightsource",
            "attribute",
            "option",
            "rendererinfo",
            "setxcomp",
            "comp",
            "setcomp",
            "translate",
            "scale",
            "rotate",
            "filterstep",
        ] {
            assert!(lib.get(name).is_some(), "{name}");
        }
        assert_eq!(lib.get("noise").unwrap().len(), 16);
        let s = &lib.get("fresnel").unwrap()[0];
        assert_eq!(
            s.show("fresnel"),
            "void fresnel(vector, normal, float, output float, output float)"
        );
        assert_eq!(lib.get("min").unwrap()[1].show("min"), "color min(color, color, color...)");
    }
}
