//! The syntax tree the parser builds: every node with the position of the token that names it.
//! The checker turns it into the typed IR ([`crate::ir`]).

use crate::error::Pos;
use crate::types::{BaseType, Detail};

/// A parsed file: its shader and function definitions, in order.
#[derive(Debug, Clone, PartialEq)]
pub struct File {
    /// Definitions in source order.
    pub items: Vec<Item>,
    /// Position of the end of the input (for "no shader").
    pub end: Pos,
}

/// A top-level definition.
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    /// A shader.
    Shader(Shader),
    /// A function.
    Function(Function),
    /// `transformation` shaders are parsed, then refused by the checker.
    Transformation(Pos),
}

/// A declared type: detail, base type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TypeSpec {
    /// `uniform`/`varying` if written.
    pub detail: Option<Detail>,
    /// The base type.
    pub base: BaseType,
    /// Where the type is written.
    pub pos: Pos,
}

/// An array size: `[n]` or (function formals only) `[]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArraySpec {
    /// `[n]`.
    Fixed(u32),
    /// `[]`.
    Open,
}

/// One name in a declaration, with its array size and initialiser.
#[derive(Debug, Clone, PartialEq)]
pub struct VarDef {
    /// The name.
    pub name: String,
    /// Where the name is.
    pub pos: Pos,
    /// Array size if any.
    pub array: Option<ArraySpec>,
    /// `= expr` (or `= {…}` for arrays).
    pub init: Option<Expr>,
}

/// A declaration: `[extern] [output] [uniform|varying] type name [= init], ...`.
#[derive(Debug, Clone, PartialEq)]
pub struct Decl {
    /// `output` (formals only).
    pub output: bool,
    /// `extern`.
    pub is_extern: bool,
    /// The type.
    pub ty: TypeSpec,
    /// The names.
    pub vars: Vec<VarDef>,
}

/// A function definition.
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    /// Result type (`void` when written so or omitted).
    pub ret: TypeSpec,
    /// Name.
    pub name: String,
    /// Where the name is.
    pub pos: Pos,
    /// Formal parameters.
    pub params: Vec<Decl>,
    /// Body.
    pub body: Vec<Stmt>,
}

/// A shader definition.
#[derive(Debug, Clone, PartialEq)]
pub struct Shader {
    /// Its type.
    pub kind: crate::types::ShaderKind,
    /// Name.
    pub name: String,
    /// Where the name is.
    pub pos: Pos,
    /// Instance variables (parameters), each with a default.
    pub params: Vec<Decl>,
    /// Body.
    pub body: Vec<Stmt>,
}

/// A statement.
#[derive(Debug, Clone, PartialEq)]
pub enum Stmt {
    /// A variable declaration.
    Decl(Decl),
    /// An expression (assignment, call).
    Expr(Expr),
    /// `{ ... }`.
    Block(Vec<Stmt>),
    /// `if (c) a [else b]`.
    If {
        /// Condition.
        cond: Expr,
        /// Then branch.
        then: Box<Stmt>,
        /// Else branch.
        els: Option<Box<Stmt>>,
    },
    /// `while (c) body`.
    While {
        /// Condition.
        cond: Expr,
        /// Body.
        body: Box<Stmt>,
    },
    /// `for (init; cond; step) body`.
    For {
        /// Initialiser.
        init: Option<Expr>,
        /// Condition (always true when absent).
        cond: Option<Expr>,
        /// Step.
        step: Option<Expr>,
        /// Body.
        body: Box<Stmt>,
        /// Where `for` is.
        pos: Pos,
    },
    /// `break [n];`.
    Break(u32, Pos),
    /// `continue [n];`.
    Continue(u32, Pos),
    /// `return [e];`.
    Return(Option<Expr>, Pos),
    /// A nested function definition.
    Function(Function),
    /// `illuminance ([category,] P [, axis, angle] [, ...]) body`.
    Illuminance {
        /// The arguments as written (the checker finds the category by its type).
        args: Vec<Expr>,
        /// Body.
        body: Box<Stmt>,
        /// Where `illuminance` is.
        pos: Pos,
    },
    /// `illuminate (from [, axis, angle]) body`.
    Illuminate {
        /// Arguments.
        args: Vec<Expr>,
        /// Body.
        body: Box<Stmt>,
        /// Where `illuminate` is.
        pos: Pos,
    },
    /// `solar ([axis, angle]) body`.
    Solar {
        /// Arguments.
        args: Vec<Expr>,
        /// Body.
        body: Box<Stmt>,
        /// Where `solar` is.
        pos: Pos,
    },
    /// `;`.
    Empty,
}

/// Unary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnOp {
    /// `-x`.
    Neg,
    /// `!x`.
    Not,
}

/// Binary operators (assignment is [`ExprKind::Assign`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `.` (dot product).
    Dot,
    /// `^` (cross product).
    Cross,
    /// `==`.
    Eq,
    /// `!=`.
    Ne,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
    /// `&&`.
    And,
    /// `||`.
    Or,
}

impl BinOp {
    /// The operator as written.
    pub fn as_str(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Dot => ".",
            BinOp::Cross => "^",
            BinOp::Eq => "==",
            BinOp::Ne => "!=",
            BinOp::Lt => "<",
            BinOp::Le => "<=",
            BinOp::Gt => ">",
            BinOp::Ge => ">=",
            BinOp::And => "&&",
            BinOp::Or => "||",
        }
    }
}

/// Assignment operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AssignOp {
    /// `=`.
    Set,
    /// `+=`.
    Add,
    /// `-=`.
    Sub,
    /// `*=`.
    Mul,
    /// `/=`.
    Div,
}

impl AssignOp {
    /// The operator as written.
    pub fn as_str(self) -> &'static str {
        match self {
            AssignOp::Set => "=",
            AssignOp::Add => "+=",
            AssignOp::Sub => "-=",
            AssignOp::Mul => "*=",
            AssignOp::Div => "/=",
        }
    }

    /// The arithmetic of a compound assignment.
    pub fn binop(self) -> Option<BinOp> {
        match self {
            AssignOp::Set => None,
            AssignOp::Add => Some(BinOp::Add),
            AssignOp::Sub => Some(BinOp::Sub),
            AssignOp::Mul => Some(BinOp::Mul),
            AssignOp::Div => Some(BinOp::Div),
        }
    }
}

/// An expression and its position (for operators: the operator's).
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where.
    pub pos: Pos,
}

/// The kinds of expression.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A number.
    Num(f64),
    /// A string literal.
    Str(String),
    /// A name (variable).
    Name(String),
    /// `a[i]`: array element, or the channel of a texture name.
    Index(Box<Expr>, Box<Expr>),
    /// `f(args)`.
    Call(String, Vec<Expr>),
    /// `-x`, `!x`.
    Unary(UnOp, Box<Expr>),
    /// `a op b`.
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// `a = b`, `a += b`, ...
    Assign(AssignOp, Box<Expr>, Box<Expr>),
    /// `c ? a : b`.
    Cond(Box<Expr>, Box<Expr>, Box<Expr>),
    /// `type ["space"] expr`: a typecast, or a space-typed constructor.
    Cast(BaseType, Option<(String, Pos)>, Box<Expr>),
    /// `(a, b, c)` or the 16 numbers of a matrix.
    Tuple(Vec<Expr>),
    /// `{a, b, ...}`: an array initialiser.
    ArrayLit(Vec<Expr>),
}
