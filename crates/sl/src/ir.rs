//! The checked, typed IR: what the checker hands the grid machine.
//!
//! Every expression carries its type and its detail (uniform or varying), known at compile time;
//! every implicit conversion is an explicit [`ExprKind::Convert`] node; every call is resolved to
//! one overload of the standard library or to one user function; every variable is one entry of
//! [`CheckedShader::vars`] with its final detail; and each `if`/loop records whether its
//! control flow is varying (so the grid machine knows where it needs a mask).

use crate::error::{Pos, SourceMap};
use crate::types::{BaseType, Detail, ShaderKind, Type};

pub use crate::ast::{AssignOp, BinOp, UnOp};

/// Index into [`CheckedShader::vars`].
pub type VarId = usize;
/// Index into [`CheckedShader::functions`].
pub type FuncId = usize;

/// A checked shader.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckedShader {
    /// Its type.
    pub kind: ShaderKind,
    /// Its name.
    pub name: String,
    /// Where its name is.
    pub pos: Pos,
    /// Its parameters (instance variables), in order.
    pub params: Vec<VarId>,
    /// Every variable: parameters, locals and function formals.
    pub vars: Vec<Var>,
    /// User functions (nested ones included), in definition order.
    pub functions: Vec<Function>,
    /// The body.
    pub body: Vec<Stmt>,
    /// Predefined variables the shader (or its functions) reads.
    pub globals_read: Vec<&'static str>,
    /// Predefined variables it writes.
    pub globals_written: Vec<&'static str>,
    /// The files read (positions index them).
    pub sources: SourceMap,
}

impl CheckedShader {
    /// The parameter called `name`.
    pub fn param(&self, name: &str) -> Option<&Var> {
        self.params.iter().map(|&i| &self.vars[i]).find(|v| v.name == name)
    }
}

/// What a variable is.
#[derive(Debug, Clone, PartialEq)]
pub enum VarKind {
    /// A shader parameter: its default (checked, converted to the parameter's type) and
    /// whether it is an `output` parameter.
    Param {
        /// The default value.
        default: Option<Expr>,
        /// `output`.
        output: bool,
    },
    /// A local variable of the shader body or a function body.
    Local,
    /// A formal parameter of a user function.
    Formal {
        /// The function.
        func: FuncId,
        /// `output`.
        output: bool,
    },
}

/// A variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Var {
    /// Name as written.
    pub name: String,
    /// Type.
    pub ty: Type,
    /// Final detail: as declared, or as inferred (varying if it ever holds a varying value or is
    /// assigned under varying control flow).
    pub detail: Detail,
    /// The detail written in the source, if any.
    pub declared: Option<Detail>,
    /// What it is.
    pub kind: VarKind,
    /// Where it is declared.
    pub pos: Pos,
}

/// A user function.
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    /// Name.
    pub name: String,
    /// Result type.
    pub ret: Type,
    /// Result detail (varying if any return value is, or a return is under varying control).
    pub ret_detail: Detail,
    /// Formals, in order.
    pub params: Vec<VarId>,
    /// Body.
    pub body: Vec<Stmt>,
    /// Where its name is.
    pub pos: Pos,
}

/// A statement.
#[derive(Debug, Clone, PartialEq)]
pub enum Stmt {
    /// Evaluate for effect (assignments, calls).
    Expr(Expr),
    /// Declare a local; `init` is its initial value, converted to its type.
    Local {
        /// The variable.
        var: VarId,
        /// The initialiser.
        init: Option<Expr>,
    },
    /// A block.
    Block(Vec<Stmt>),
    /// `if`.
    If {
        /// Condition, of type boolean.
        cond: Expr,
        /// Then branch.
        then: Vec<Stmt>,
        /// Else branch.
        els: Vec<Stmt>,
    },
    /// `while` and `for` (a `for` is its `init` statement, then this loop with `step`).
    Loop {
        /// Condition (boolean), checked before each iteration.
        cond: Expr,
        /// Body.
        body: Vec<Stmt>,
        /// Run after the body and after `continue` (the `for` step).
        step: Option<Expr>,
        /// The loop's control flow is varying: its condition is varying, or a `break` or
        /// `continue` under varying control leaves some points behind.
        varying: bool,
    },
    /// `break n` (n >= 1 loops).
    Break(u32),
    /// `continue n`.
    Continue(u32),
    /// `return` from a user function.
    Return(Option<Expr>),
    /// `illuminance`: runs `body` once per light source, with `L`, `Cl`, `Ol` set.
    Illuminance {
        /// Light category (`""`: all lights).
        category: Option<Expr>,
        /// The point being lit.
        position: Expr,
        /// Cone axis and angle (absent: the whole sphere).
        cone: Option<(Expr, Expr)>,
        /// Renderer-specific options.
        options: Vec<(String, Expr)>,
        /// Body.
        body: Vec<Stmt>,
    },
    /// `illuminate` (light shaders): light from `position`, optionally in a cone.
    Illuminate {
        /// Where the light comes from.
        position: Expr,
        /// Cone axis and angle.
        cone: Option<(Expr, Expr)>,
        /// Body.
        body: Vec<Stmt>,
    },
    /// `solar` (light shaders): light from a direction, or from all directions.
    Solar {
        /// Axis and angle.
        cone: Option<(Expr, Expr)>,
        /// Body.
        body: Vec<Stmt>,
    },
}

/// An expression with its static type and detail.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What it computes.
    pub kind: ExprKind,
    /// Its type.
    pub ty: Type,
    /// Uniform or varying.
    pub detail: Detail,
    /// Where it is written.
    pub pos: Pos,
}

/// What can be assigned.
#[derive(Debug, Clone, PartialEq)]
pub enum Place {
    /// A variable (parameter, local, formal).
    Var(VarId),
    /// A predefined variable.
    Global(&'static str),
}

/// Which function a call calls.
#[derive(Debug, Clone, PartialEq)]
pub enum Callee {
    /// The standard library: name and the index of the overload in its table.
    Builtin {
        /// Name.
        name: &'static str,
        /// Overload index in [`crate::library::Library::get`].
        overload: usize,
    },
    /// A user function.
    User(FuncId),
}

/// The kinds of expression.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A float constant.
    Float(f64),
    /// A string constant.
    Str(String),
    /// A variable.
    Var(VarId),
    /// A predefined variable.
    Global(&'static str),
    /// An array element.
    Index(Box<Expr>, Box<Expr>),
    /// A conversion to this expression's type: float to triple (all three components) or to
    /// matrix (the float times the identity), between point, vector and normal (the same three
    /// numbers), float to boolean (`!= 0`).
    Convert(Box<Expr>),
    /// A unary operator.
    Unary(UnOp, Box<Expr>),
    /// A binary operator; operands already converted (float operands of triple arithmetic are
    /// promoted, so both sides have the same type except for `*`/`/` with a matrix and a float).
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// Assignment: the value is already of the place's type (for compound assignment, the
    /// operator's right operand).
    Assign {
        /// What is assigned.
        place: Place,
        /// Array index, if an element is assigned.
        index: Option<Box<Expr>>,
        /// `=`, `+=`, ...
        op: AssignOp,
        /// The value.
        value: Box<Expr>,
    },
    /// `c ? a : b`.
    Cond(Box<Expr>, Box<Expr>, Box<Expr>),
    /// A triple from 3 floats or a matrix from 16 (row by row), in `space` when given (then
    /// transformed to "current"; for colours, from that colour space to RGB).
    Construct {
        /// Components, each float.
        parts: Vec<Expr>,
        /// The space they are in.
        space: Option<String>,
    },
    /// A value of the cast type read as being in `space`, transformed to "current".
    SpaceCast {
        /// The space name.
        space: String,
        /// The value.
        value: Box<Expr>,
    },
    /// A call.
    Call {
        /// The function.
        callee: Callee,
        /// Positional arguments, converted to the parameter types (output arguments are places:
        /// `Var`, `Global` or `Index` expressions).
        args: Vec<Expr>,
        /// Texture channel (`texture("map"[1], ...)`).
        channel: Option<Box<Expr>>,
        /// Optional name/value parameters.
        options: Vec<(String, Expr)>,
    },
    /// An array initialiser.
    Array(Vec<Expr>),
}

impl Expr {
    /// Whether this is a float constant (after conversions).
    pub fn as_const(&self) -> Option<f64> {
        match &self.kind {
            ExprKind::Float(v) => Some(*v),
            ExprKind::Unary(UnOp::Neg, e) => e.as_const().map(|v| -v),
            _ => None,
        }
    }

    /// The base type.
    pub fn base(&self) -> BaseType {
        self.ty.base
    }
}

impl CheckedShader {
    /// A readable listing of the IR: every variable with its final detail and type, every call
    /// with the type of the overload it resolved to, every implicit conversion as `(type)`, and
    /// every `if` and loop marked uniform or varying. For tests and for reading.
    pub fn dump(&self) -> String {
        let mut out = String::new();
        let p = Printer { s: self };
        out.push_str(&format!("{} {}\n", self.kind, self.name));
        for &id in &self.params {
            let v = &self.vars[id];
            let output = matches!(v.kind, VarKind::Param { output: true, .. });
            let default = match &v.kind {
                VarKind::Param { default: Some(d), .. } => format!(" = {}", p.expr(d)),
                _ => String::new(),
            };
            out.push_str(&format!(
                "  param {}{} {} {}{default}\n",
                if output { "output " } else { "" },
                v.detail.name(),
                v.ty,
                v.name
            ));
        }
        for f in &self.functions {
            let params: Vec<String> = f
                .params
                .iter()
                .map(|&i| {
                    let v = &self.vars[i];
                    let output = matches!(v.kind, VarKind::Formal { output: true, .. });
                    format!(
                        "{}{} {} {}",
                        if output { "output " } else { "" },
                        v.detail.name(),
                        v.ty,
                        v.name
                    )
                })
                .collect();
            out.push_str(&format!(
                "  function {} {} {}({})\n",
                f.ret_detail.name(),
                f.ret,
                f.name,
                params.join(", ")
            ));
            p.block(&f.body, 2, &mut out);
        }
        out.push_str("  body\n");
        p.block(&self.body, 2, &mut out);
        let list = |v: &[&str]| if v.is_empty() { "-".to_string() } else { v.join(" ") };
        out.push_str(&format!(
            "  reads {}; writes {}\n",
            list(&self.globals_read),
            list(&self.globals_written)
        ));
        out
    }
}

struct Printer<'a> {
    s: &'a CheckedShader,
}

impl Printer<'_> {
    fn block(&self, stmts: &[Stmt], depth: usize, out: &mut String) {
        for st in stmts {
            self.stmt(st, depth, out);
        }
    }

    fn line(&self, depth: usize, text: &str, out: &mut String) {
        out.push_str(&"  ".repeat(depth));
        out.push_str(text);
        out.push('\n');
    }

    fn cone(&self, cone: &Option<(Expr, Expr)>) -> String {
        match cone {
            Some((a, b)) => format!(", {}, {}", self.expr(a), self.expr(b)),
            None => String::new(),
        }
    }

    fn stmt(&self, st: &Stmt, d: usize, out: &mut String) {
        match st {
            Stmt::Expr(e) => self.line(d, &self.expr(e), out),
            Stmt::Local { var, init } => {
                let v = &self.s.vars[*var];
                let init = init.as_ref().map_or(String::new(), |e| format!(" = {}", self.expr(e)));
                self.line(d, &format!("{} {} {}{init}", v.detail.name(), v.ty, v.name), out);
            }
            Stmt::Block(b) => {
                self.line(d, "{", out);
                self.block(b, d + 1, out);
                self.line(d, "}", out);
            }
            Stmt::If { cond, then, els } => {
                self.line(d, &format!("if {} {}", cond.detail.name(), self.expr(cond)), out);
                self.block(then, d + 1, out);
                if !els.is_empty() {
                    self.line(d, "else", out);
                    self.block(els, d + 1, out);
                }
            }
            Stmt::Loop { cond, body, step, varying } => {
                let kind = if *varying { "varying" } else { "uniform" };
                let step =
                    step.as_ref().map_or(String::new(), |e| format!(" step {}", self.expr(e)));
                self.line(d, &format!("loop {kind} {}{step}", self.expr(cond)), out);
                self.block(body, d + 1, out);
            }
            Stmt::Break(n) => self.line(d, &format!("break {n}"), out),
            Stmt::Continue(n) => self.line(d, &format!("continue {n}"), out),
            Stmt::Return(e) => {
                let v = e.as_ref().map_or(String::new(), |e| format!(" {}", self.expr(e)));
                self.line(d, &format!("return{v}"), out);
            }
            Stmt::Illuminance { category, position, cone, options, body } => {
                let cat =
                    category.as_ref().map_or(String::new(), |c| format!("{}, ", self.expr(c)));
                let opts: String =
                    options.iter().map(|(n, v)| format!(", \"{n}\", {}", self.expr(v))).collect();
                self.line(
                    d,
                    &format!("illuminance({cat}{}{}{opts})", self.expr(position), self.cone(cone)),
                    out,
                );
                self.block(body, d + 1, out);
            }
            Stmt::Illuminate { position, cone, body } => {
                self.line(
                    d,
                    &format!("illuminate({}{})", self.expr(position), self.cone(cone)),
                    out,
                );
                self.block(body, d + 1, out);
            }
            Stmt::Solar { cone, body } => {
                let c = self.cone(cone);
                self.line(d, &format!("solar({})", c.trim_start_matches(", ")), out);
                self.block(body, d + 1, out);
            }
        }
    }

    fn expr(&self, e: &Expr) -> String {
        let list = |v: &[Expr]| v.iter().map(|x| self.expr(x)).collect::<Vec<_>>().join(", ");
        match &e.kind {
            ExprKind::Float(v) => format!("{v}"),
            ExprKind::Str(s) => crate::lexer::quote(s),
            ExprKind::Var(id) => self.s.vars[*id].name.clone(),
            ExprKind::Global(g) => (*g).to_string(),
            ExprKind::Index(a, i) => format!("{}[{}]", self.expr(a), self.expr(i)),
            ExprKind::Convert(x) => format!("({}){}", e.ty, self.expr(x)),
            ExprKind::Unary(UnOp::Neg, x) => format!("-{}", self.expr(x)),
            ExprKind::Unary(UnOp::Not, x) => format!("!{}", self.expr(x)),
            ExprKind::Binary(op, a, b) => {
                format!("({} {} {})", self.expr(a), op.as_str(), self.expr(b))
            }
            ExprKind::Assign { place, index, op, value } => {
                let name = match place {
                    Place::Var(id) => self.s.vars[*id].name.clone(),
                    Place::Global(g) => (*g).to_string(),
                };
                let idx = index.as_ref().map_or(String::new(), |i| format!("[{}]", self.expr(i)));
                format!("{name}{idx} {} {}", op.as_str(), self.expr(value))
            }
            ExprKind::Cond(c, a, b) => {
                format!("({} ? {} : {})", self.expr(c), self.expr(a), self.expr(b))
            }
            ExprKind::Construct { parts, space } => {
                let sp = space
                    .as_ref()
                    .map_or(String::new(), |s| format!(" {}", crate::lexer::quote(s)));
                format!("{}{sp}({})", e.ty, list(parts))
            }
            ExprKind::SpaceCast { space, value } => {
                format!("{} {} {}", e.ty, crate::lexer::quote(space), self.expr(value))
            }
            ExprKind::Call { callee, args, channel, options } => {
                let name = match callee {
                    Callee::Builtin { name, .. } => (*name).to_string(),
                    Callee::User(f) => self.s.functions[*f].name.clone(),
                };
                let mut a: Vec<String> = args.iter().map(|x| self.expr(x)).collect();
                if let (Some(c), Some(first)) = (channel, a.first_mut()) {
                    first.push_str(&format!("[{}]", self.expr(c)));
                }
                for (n, v) in options {
                    a.push(format!("\"{n}\", {}", self.expr(v)));
                }
                format!("{name}:{}({})", e.ty, a.join(", "))
            }
            ExprKind::Array(v) => format!("{{{}}}", list(v)),
        }
    }
}
