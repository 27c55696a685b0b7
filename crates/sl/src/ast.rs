//! The Shading Language syntax tree, before and after checking.
//!
//! This file (with `types.rs`) is the ABI between the front end (`illume-sl`, which produces a
//! *checked* [`Program`]) and the grid executor (`illume-slvm`, which runs it). Change it only
//! additively and log every change in `crates/sl/AST_CHANGES.md`.
//!
//! One tree serves both stages. The parser fills the syntax and leaves every annotation at its
//! placeholder (`ty: Type::UNKNOWN`, `detail: Detail::Uniform`, `var: None`, `callee: None`);
//! the checker fills the annotations in place and makes implicit conversions explicit
//! ([`ExprKind::Promote`], [`ExprKind::Cast`] without a space). A program the checker accepted
//! without errors has, everywhere:
//! - every [`Expr::ty`] concrete (no [`BaseType::Unknown`]) and [`Expr::detail`] inferred
//!   (varying iff anything it reads is varying);
//! - every [`VarUse::var`], [`LValue::var`] and [`Declarator::var`] resolved;
//! - every [`Call::callee`] resolved, with `args[i]` already of type `params[i].ty` of the chosen
//!   [`Signature`] (promotions inserted);
//! - no [`ExprKind::Error`] or [`StmtKind::Error`].
//!
//! Names follow the RI Specification 3.2, chapters 11–15 (Shading Language).

use crate::span::Span;
use crate::types::{ArrayLen, BaseType, Detail, ShaderKind, Type};

/// Index of a shader in [`Program::shaders`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ShaderId(pub u32);

/// Index of a user function in [`Program::functions`] (nested functions included).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FuncId(pub u32);

/// Index of a variable slot in the `vars` table of the shader or function that owns it
/// ([`ShaderDef::vars`], [`FunctionDef::vars`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VarId(pub u32);

/// Which shader or function owns a variable table (or encloses a nested function).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Owner {
    /// A shader's parameters and locals.
    Shader(ShaderId),
    /// A function's parameters and locals.
    Function(FuncId),
}

/// A whole compiled file: every shader and every function it defines.
///
/// Functions are numbered in the order their definitions *start* in the source, so a function
/// has a smaller id than the functions nested in it; [`FunctionDef::parent`] records the
/// nesting.
#[derive(Debug, Clone, Default)]
pub struct Program {
    /// Shaders, in source order (a file normally defines one).
    pub shaders: Vec<ShaderDef>,
    /// All user functions, top-level and nested.
    pub functions: Vec<FunctionDef>,
    /// The top-level definitions in source order (functions must be defined before use).
    pub items: Vec<Item>,
}

impl Program {
    /// The shader with the given id.
    pub fn shader(&self, id: ShaderId) -> &ShaderDef {
        &self.shaders[id.0 as usize]
    }

    /// The function with the given id.
    pub fn function(&self, id: FuncId) -> &FunctionDef {
        &self.functions[id.0 as usize]
    }

    /// The variable table of a shader or function.
    pub fn vars(&self, owner: Owner) -> &[VarInfo] {
        match owner {
            Owner::Shader(id) => &self.shader(id).vars,
            Owner::Function(id) => &self.function(id).vars,
        }
    }
}

/// A top-level definition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Item {
    /// `surface name (params) { … }` and the other shader kinds.
    Shader(ShaderId),
    /// `type name (params) { … }` at file scope.
    Function(FuncId),
}

/// `surface plastic (float Ka = 1; …) { … }`: one shader.
#[derive(Debug, Clone)]
pub struct ShaderDef {
    /// Surface, light, displacement, volume, imager or transformation.
    pub kind: ShaderKind,
    /// The shader's name (what `Surface "name"` in RIB selects).
    pub name: String,
    /// Location of the name.
    pub span: Span,
    /// Instance parameters, each with its default (required for shader parameters).
    pub params: Vec<Param>,
    /// The body.
    pub body: Block,
    /// Slot table (checker): parameters first, in order (slot `i` is `params[i]`), then every
    /// local declared anywhere in the body, each block-scoped declaration getting its own slot.
    pub vars: Vec<VarInfo>,
}

/// `color MaterialPlastic (normal Nf; color basecolor; …) { … }`: a user function.
#[derive(Debug, Clone)]
pub struct FunctionDef {
    /// Function name; several functions may share one (overloading by parameter types).
    pub name: String,
    /// Location of the name.
    pub span: Span,
    /// Return type (`void` when nothing is returned). RI 3.2 functions return scalars.
    pub ret: Type,
    /// Formal parameters; `output` ones are passed by reference.
    pub params: Vec<Param>,
    /// The body.
    pub body: Block,
    /// Slot table (checker): parameters first, in order, then locals (as in [`ShaderDef::vars`]).
    pub vars: Vec<VarInfo>,
    /// The function or shader this one is nested in (`None` at file scope). A nested function
    /// reaches its encloser's variables through `extern` declarations ([`VarRef::Outer`]).
    pub parent: Option<Owner>,
    /// Checker: true when the body reads something varying that is not a parameter (a
    /// varying global such as `P`, an `extern` variable, an `illuminance` loop), so a call is
    /// varying even with all-uniform arguments.
    pub reads_varying: bool,
}

/// A shader or function parameter.
#[derive(Debug, Clone)]
pub struct Param {
    /// Parameter name.
    pub name: String,
    /// Location of the name.
    pub span: Span,
    /// `output` was written: a shader output parameter (readable by message passing) or a
    /// function parameter passed by reference.
    pub output: bool,
    /// `uniform` / `varying` as written, if written.
    pub detail: Option<Detail>,
    /// Declared type (arrays allowed; `[]` only on function parameters).
    pub ty: Type,
    /// Default value expression (shader parameters must have one; RI 3.2 functions have none,
    /// parsed for leniency).
    pub default: Option<Expr>,
    /// Checker: this parameter's slot in the owner's `vars`.
    pub var: Option<VarId>,
}

/// What a variable slot holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VarKind {
    /// A shader instance parameter (bound from RIB parameter lists).
    ShaderParam {
        /// Declared `output`.
        output: bool,
    },
    /// A function's formal parameter.
    FunctionParam {
        /// Declared `output` (passed by reference).
        output: bool,
    },
    /// A local variable declared in a body.
    Local,
}

/// One slot of a variable table, filled by the checker.
#[derive(Debug, Clone)]
pub struct VarInfo {
    /// Source name (several slots may share a name in different scopes).
    pub name: String,
    /// Location of the declaration.
    pub span: Span,
    /// Declared type.
    pub ty: Type,
    /// Parameter or local.
    pub kind: VarKind,
    /// `uniform` / `varying` as written, if written.
    pub declared: Option<Detail>,
    /// The detail the spec gives it: `declared` if written, otherwise uniform for shader
    /// parameters and string locals, varying for other locals and function parameters (a function parameter without
    /// a qualifier takes its argument's detail at each call; `Varying` is the safe bound).
    pub detail: Detail,
    /// Inferred detail: equals `detail`, except that an unqualified local is refined to
    /// `Uniform` when every value assigned to it is uniform and no assignment sits under varying
    /// control flow (a varying `if`, loop condition or `illuminance`). The executor may store a
    /// variable with `inferred == Uniform` once per grid.
    pub inferred: Detail,
}

/// `{ stmt… }`.
#[derive(Debug, Clone, Default)]
pub struct Block {
    /// Statements in order.
    pub stmts: Vec<Stmt>,
    /// Location of the `{` (or of the single statement a control construct wraps).
    pub span: Span,
}

/// A statement.
#[derive(Debug, Clone)]
pub struct Stmt {
    /// What the statement is.
    pub kind: StmtKind,
    /// Location of its first token.
    pub span: Span,
}

/// The statement forms of RI 3.2 §12.
#[derive(Debug, Clone)]
pub enum StmtKind {
    /// `[extern] [uniform|varying] type a [= e], b[3] [= {…}];`
    Decl(Decl),
    /// An expression evaluated for effect (assignments, calls).
    Expr(Expr),
    /// `{ … }`: a new scope.
    Block(Block),
    /// `if (cond) then [else otherwise]`. The condition's detail says whether the executor
    /// needs to split the running state.
    If {
        /// Condition (float or relation; nonzero is true).
        cond: Expr,
        /// Taken branch.
        then: Box<Stmt>,
        /// `else` branch.
        otherwise: Option<Box<Stmt>>,
    },
    /// `while (cond) body`.
    While {
        /// Loop condition.
        cond: Expr,
        /// Loop body.
        body: Box<Stmt>,
    },
    /// `for (init; cond; step) body`. RI 3.2 allows expressions (not declarations) in `init`.
    For {
        /// Initialiser expression.
        init: Option<Expr>,
        /// Condition; absent means forever (until `break`).
        cond: Option<Expr>,
        /// Step expression.
        step: Option<Expr>,
        /// Loop body.
        body: Box<Stmt>,
    },
    /// `break [n];`: leave `n` (default 1) enclosing loops (`illuminance` counts as a loop).
    Break(u32),
    /// `continue [n];`: next iteration of the `n`th enclosing loop (default 1).
    Continue(u32),
    /// `return [e];`
    Return(Option<Expr>),
    /// `illuminance ([category,] position [, axis, angle]) body` (surface, volume shaders).
    Illuminance(Illuminance),
    /// `illuminate (position [, axis, angle]) body` (light shaders).
    Illuminate(Illuminate),
    /// `solar ([axis, angle]) body` (light shaders).
    Solar(Solar),
    /// A function defined inside a body (nested functions are legal Shading Language; see
    /// ERRATA.md on Listing 9.12). The definition itself lives in [`Program::functions`].
    Function(FuncId),
    /// `;` alone.
    Empty,
    /// Parser recovery placeholder for a statement that failed to parse (an error was reported).
    Error,
}

/// A declaration statement: one type and detail for a list of names.
#[derive(Debug, Clone)]
pub struct Decl {
    /// `extern`: the names refer to existing variables — a global (`extern point P;`) or a
    /// variable of an enclosing function or shader — rather than new ones.
    pub is_extern: bool,
    /// `uniform` / `varying` as written.
    pub detail: Option<Detail>,
    /// Element type shared by every declarator.
    pub base: BaseType,
    /// The declared names.
    pub vars: Vec<Declarator>,
}

/// One name in a declaration: `a`, `a = 1`, `a[3]`, `a[3] = {1, 2, 3}`.
#[derive(Debug, Clone)]
pub struct Declarator {
    /// The name.
    pub name: String,
    /// Location of the name.
    pub span: Span,
    /// `[n]` if written (only `Fixed` for locals).
    pub array: Option<ArrayLen>,
    /// Initial value, if any.
    pub init: Option<Expr>,
    /// Checker: the slot declared ([`VarRef::Slot`]) or, for `extern`, the variable referred to.
    pub var: Option<VarRef>,
}

/// A light cone: `axis, angle` in `illuminance`, `illuminate` and `solar`.
#[derive(Debug, Clone)]
pub struct Cone {
    /// Cone axis (a vector; in `illuminance` usually `N`).
    pub axis: Expr,
    /// Half-angle in radians.
    pub angle: Expr,
}

/// `illuminance ([category,] position [, axis, angle]) body`: loop over the lights.
///
/// The form is identified by which optional parts are present: without `cone` every light
/// contributes (spec: "all directions"); with a cone only lights whose `L` lies within `angle`
/// of `axis`. Inside the body `L` (pointing from the surface to the light, unnormalised) and
/// `Cl` are defined.
#[derive(Debug, Clone)]
pub struct Illuminance {
    /// Category string selecting lights by their `__category` parameter (`"-name"` excludes).
    pub category: Option<Expr>,
    /// The point being illuminated (usually `P`).
    pub position: Expr,
    /// Optional gathering cone.
    pub cone: Option<Cone>,
    /// Loop body, run once per light (as a loop: `break`/`continue` apply).
    pub body: Box<Stmt>,
}

/// `illuminate (position [, axis, angle]) body`: a light emitting from a point.
///
/// Without `cone` the light radiates in all directions (pointlight); with it, only into the
/// cone (spotlight). The body sees `L = Ps - position` and sets `Cl`.
#[derive(Debug, Clone)]
pub struct Illuminate {
    /// Emitting position.
    pub position: Expr,
    /// Optional emission cone.
    pub cone: Option<Cone>,
    /// Body run for the surface points the light reaches.
    pub body: Box<Stmt>,
}

/// `solar ([axis, angle]) body`: a light at infinity.
///
/// Without `cone` light arrives from all directions (an environment-like light); with it, from
/// directions within `angle` of `axis` (`solar (axis, 0)` is a distant light: `L = axis`).
#[derive(Debug, Clone)]
pub struct Solar {
    /// Optional direction cone.
    pub cone: Option<Cone>,
    /// Body.
    pub body: Box<Stmt>,
}

/// An expression with the checker's annotations.
#[derive(Debug, Clone)]
pub struct Expr {
    /// What the expression is.
    pub kind: ExprKind,
    /// Location of its first token (of the operator for binary expressions).
    pub span: Span,
    /// Checker: concrete type. For a call whose return type depends on context (`noise`,
    /// `texture`, `random`, …) this is the type the checker chose from the assignment or
    /// argument context, per RI 3.2 §15.
    pub ty: Type,
    /// Checker: uniform if everything the expression reads is uniform, else varying.
    pub detail: Detail,
}

impl Expr {
    /// A new unannotated expression (the parser's constructor).
    pub fn new(kind: ExprKind, span: Span) -> Expr {
        Expr {
            kind,
            span,
            ty: Type::UNKNOWN,
            detail: Detail::Uniform,
        }
    }
}

/// Expression forms of RI 3.2 §12.
#[derive(Debug, Clone)]
pub enum ExprKind {
    /// Numeric literal (kept as f64 so the text's value is exact; the executor narrows to f32).
    Float(f64),
    /// String literal, escapes already decoded.
    Str(String),
    /// A variable read.
    Var(VarUse),
    /// `(a, b, c)` or `(m00, …, m33)`: a triple or matrix constructor. Its type comes from a cast
    /// in front of it or from context (`Cs = (1, 0, 0)`); after checking every element is float.
    Tuple(Vec<Expr>),
    /// `{a, b, c}`: an array initialiser (declarations and parameter defaults only).
    ArrayInit(Vec<Expr>),
    /// `type ["space"] expr`: `color "hsv" (h, s, v)`, `point "world" (0, 0, 0)`,
    /// `vector "object" v`, `matrix "shader" 1`. The value of `expr` (a tuple, a float promoted
    /// component-wise, or a triple) is taken as a `to` in the named space and converted into
    /// the current space ("current" for geometry, "rgb" for colour). Without `space` it is a
    /// reinterpretation; the checker also inserts space-less casts for implicit conversions
    /// between point, vector and normal.
    Cast {
        /// Target type.
        to: BaseType,
        /// Space or colour-space name (a string expression, usually a literal).
        space: Option<Box<Expr>>,
        /// Converted value.
        expr: Box<Expr>,
    },
    /// Checker-inserted: a float promoted to the expression's type (a triple gets the value in
    /// every component; a matrix gets it on the diagonal, RI 3.2 §11.2.4).
    Promote(Box<Expr>),
    /// `-e`, `!e`.
    Unary {
        /// The operator.
        op: UnaryOp,
        /// Operand.
        expr: Box<Expr>,
    },
    /// `a op b` (arithmetic, `.` dot, `^` cross, relations, logic).
    Binary {
        /// The operator.
        op: BinaryOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// `cond ? a : b`.
    Ternary {
        /// Condition.
        cond: Box<Expr>,
        /// Value when true.
        then: Box<Expr>,
        /// Value when false.
        otherwise: Box<Expr>,
    },
    /// `target op= value`. An expression in SL (`a = b = 0` is legal); its value is the
    /// assigned value.
    Assign {
        /// `=`, `+=`, `-=`, `*=`, `/=`.
        op: AssignOp,
        /// Variable or array element assigned.
        target: LValue,
        /// Right-hand side, converted by the checker to the target's element type.
        value: Box<Expr>,
    },
    /// `array[index]`: element read (also `"map"[channel]` inside [`TextureCall::channel`]).
    Index {
        /// The array (a variable).
        array: Box<Expr>,
        /// Element index (float, truncated).
        index: Box<Expr>,
    },
    /// A call to a built-in or user function.
    Call(Call),
    /// `texture`, `environment`, `shadow`, `bump`: the calls with a channel selector and
    /// optional `"name", value` parameters.
    Texture(TextureCall),
    /// Parser recovery placeholder (an error was reported).
    Error,
}

/// A variable read.
#[derive(Debug, Clone)]
pub struct VarUse {
    /// The name as written.
    pub name: String,
    /// Checker: what it refers to.
    pub var: Option<VarRef>,
}

/// What an identifier resolves to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VarRef {
    /// A predeclared global (`P`, `N`, `Ci`, …).
    Global(Global),
    /// A slot in the `vars` table of the shader or function the expression is in
    /// ([`VarInfo::kind`] says shader parameter, function parameter or local).
    Slot(VarId),
    /// A slot of an enclosing shader or function, reached from a nested function through
    /// `extern`.
    Outer {
        /// The encloser owning the slot.
        owner: Owner,
        /// Slot in `owner`'s table.
        var: VarId,
    },
}

/// The target of an assignment or an `output` argument: a variable or one array element.
#[derive(Debug, Clone)]
pub struct LValue {
    /// Variable name.
    pub name: String,
    /// Location of the name.
    pub span: Span,
    /// `[index]`, for an array element.
    pub index: Option<Box<Expr>>,
    /// Checker: the variable.
    pub var: Option<VarRef>,
}

/// Unary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UnaryOp {
    /// `-e` (component-wise; a matrix negates every element).
    Neg,
    /// `!e` (logical not of a condition).
    Not,
}

/// Binary operators (RI 3.2 §12.2 precedence, lowest first: `||`, `&&`, relations `== != < <= >
/// >=`, `+ -`, `^`, `* /`, `.`; `^` and `.` bind tighter than `+`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BinaryOp {
    /// `+` component-wise.
    Add,
    /// `-` component-wise.
    Sub,
    /// `*` component-wise (matrix × matrix is the matrix product; a float times a matrix
    /// scales every element, and that float operand is *not* wrapped in a `Promote`).
    Mul,
    /// `/` component-wise (matrix / matrix multiplies by the inverse; matrix / float divides
    /// every element, the float unpromoted).
    Div,
    /// `.`: dot product of two triples (float result).
    Dot,
    /// `^`: cross product of two vectors/points/normals.
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
    /// `&&` (both sides are evaluated; SL has no side-effect-visible short circuit requirement).
    And,
    /// `||`.
    Or,
}

impl BinaryOp {
    /// The operator as written.
    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Dot => ".",
            BinaryOp::Cross => "^",
            BinaryOp::Eq => "==",
            BinaryOp::Ne => "!=",
            BinaryOp::Lt => "<",
            BinaryOp::Le => "<=",
            BinaryOp::Gt => ">",
            BinaryOp::Ge => ">=",
            BinaryOp::And => "&&",
            BinaryOp::Or => "||",
        }
    }

    /// True for the relations and logical operators, whose result is a condition (typed float:
    /// 1 for true, 0 for false).
    pub fn is_condition(self) -> bool {
        !matches!(
            self,
            BinaryOp::Add
                | BinaryOp::Sub
                | BinaryOp::Mul
                | BinaryOp::Div
                | BinaryOp::Dot
                | BinaryOp::Cross
        )
    }
}

/// Assignment operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AssignOp {
    /// `=`.
    Assign,
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
    /// The arithmetic operator a compound assignment applies (`None` for plain `=`).
    pub fn binary(self) -> Option<BinaryOp> {
        match self {
            AssignOp::Assign => None,
            AssignOp::Add => Some(BinaryOp::Add),
            AssignOp::Sub => Some(BinaryOp::Sub),
            AssignOp::Mul => Some(BinaryOp::Mul),
            AssignOp::Div => Some(BinaryOp::Div),
        }
    }
}

/// `name (args…)`.
#[derive(Debug, Clone)]
pub struct Call {
    /// Function name as written.
    pub name: String,
    /// Arguments as written (an `output` parameter's argument is a [`ExprKind::Var`] or an
    /// [`ExprKind::Index`] of a variable).
    pub args: Vec<Expr>,
    /// Checker: the function called.
    pub callee: Option<Callee>,
}

/// A resolved call target.
#[derive(Debug, Clone, PartialEq)]
pub enum Callee {
    /// A built-in function of RI 3.2 chapter 15 (plus the message-passing and renderer-info
    /// calls), with the overload chosen.
    Builtin(BuiltinCall),
    /// A user function (the overload chosen by argument types).
    User(FuncId),
}

/// A resolved built-in call.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltinCall {
    /// The built-in's name (`"noise"`, `"diffuse"`, `"lightsource"`, …).
    pub name: String,
    /// The concrete overload: exactly one [`SigParam`] per argument of this call (variadic
    /// tails such as `spline` knots and `printf` arguments expanded), return type chosen from
    /// context for the polymorphic ones (`noise`, `random`, `cellnoise`, `pnoise`, `spline`,
    /// message passing's value argument).
    pub sig: Signature,
    /// Index of the first `"name", value` optional-parameter pair, for built-ins that take
    /// them (`filterstep (edge, s, "width", 2)`); `None` when the call passes none. The
    /// signature types the pairs as `string`, then the value's own type.
    pub optional_from: Option<usize>,
}

/// A concrete function signature.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Signature {
    /// Return type (`void` for none).
    pub ret: Type,
    /// Parameters in order.
    pub params: Vec<SigParam>,
}

/// One parameter of a [`Signature`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SigParam {
    /// Parameter type.
    pub ty: Type,
    /// Written through (`output`): the argument must be assignable.
    pub output: bool,
}

/// Which texture-access built-in a [`TextureCall`] is (RI 3.2 §15.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TextureKind {
    /// `texture (name[chan] [, s, t | , s1, t1, s2, t2, s3, t3, s4, t4] [, params])`.
    Texture,
    /// `environment (name[chan], R | R1, R2, R3, R4 [, params])`.
    Environment,
    /// `shadow (name[chan], P | P1, P2, P3, P4 [, params])`.
    Shadow,
    /// `bump (name[chan], N, dPds, dPdt [, s, t …] [, params])` (RI 3.2; parsed, rarely
    /// implemented).
    Bump,
}

impl TextureKind {
    /// The built-in's name.
    pub fn name(self) -> &'static str {
        match self {
            TextureKind::Texture => "texture",
            TextureKind::Environment => "environment",
            TextureKind::Shadow => "shadow",
            TextureKind::Bump => "bump",
        }
    }
}

/// A texture-family call. The result type (float or color; `bump` returns a point/vector) is
/// [`Expr::ty`], chosen from context like `noise`.
#[derive(Debug, Clone)]
pub struct TextureCall {
    /// Which call.
    pub kind: TextureKind,
    /// Texture file name (string expression).
    pub map: Box<Expr>,
    /// `[channel]` after the name: first channel to read (float); absent means 0.
    pub channel: Option<Box<Expr>>,
    /// Coordinate arguments between the name and the first optional parameter (`s, t`, `R`,
    /// `P`, or their four-corner forms). Which form was used is given by `coords.len()`;
    /// the checker verifies it and converts each to its expected type.
    pub coords: Vec<Expr>,
    /// Optional `"blur", 0.1, "width", 2, …` pairs, in order.
    pub params: Vec<NamedArg>,
}

/// One `"name", value` optional parameter.
#[derive(Debug, Clone)]
pub struct NamedArg {
    /// Parameter name (uniform string; usually a literal such as `"blur"`, `"samples"`,
    /// `"bias"`, `"swidth"`, `"fill"`).
    pub name: Expr,
    /// Its value.
    pub value: Expr,
}

/// The predeclared global variables (RI 3.2 §11.3, tables 11.1–11.6). Which are readable and
/// writable depends on the [`ShaderKind`]; the checker enforces that.
#[allow(non_camel_case_types)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Global {
    /// `point P`: surface position (light shaders: point on the light's area geometry).
    P,
    /// `vector dPdu`: derivative of P along u.
    dPdu,
    /// `vector dPdv`: derivative of P along v.
    dPdv,
    /// `normal N`: shading normal.
    N,
    /// `normal Ng`: geometric normal.
    Ng,
    /// `float u`: surface parameter.
    u,
    /// `float v`: surface parameter.
    v,
    /// `float du`: change in u between adjacent grid points.
    du,
    /// `float dv`: change in v between adjacent grid points.
    dv,
    /// `float s`: texture coordinate.
    s,
    /// `float t`: texture coordinate.
    t,
    /// `vector L`: direction to (surface shaders) or from (light shaders) the light.
    L,
    /// `color Cl`: light colour.
    Cl,
    /// `color Ol`: light opacity.
    Ol,
    /// `color Cs`: surface colour attribute.
    Cs,
    /// `color Os`: surface opacity attribute.
    Os,
    /// `color Ci`: resulting colour.
    Ci,
    /// `color Oi`: resulting opacity.
    Oi,
    /// `vector I`: incident ray direction, from the eye to P.
    I,
    /// `point E`: eye position (uniform).
    E,
    /// `point Ps`: the surface point being illuminated (light shaders).
    Ps,
    /// `uniform float ncomps`: number of colour components (3).
    ncomps,
    /// `uniform float time`: current shutter time.
    time,
    /// `uniform float dtime`: shutter interval (PRMan extension, widely used).
    dtime,
    /// `vector dPdtime`: motion of P over the shutter (PRMan extension).
    dPdtime,
    /// `float alpha`: pixel coverage (imager shaders).
    alpha,
}

impl Global {
    /// Every global, in declaration order.
    pub const ALL: [Global; 26] = [
        Global::P,
        Global::dPdu,
        Global::dPdv,
        Global::N,
        Global::Ng,
        Global::u,
        Global::v,
        Global::du,
        Global::dv,
        Global::s,
        Global::t,
        Global::L,
        Global::Cl,
        Global::Ol,
        Global::Cs,
        Global::Os,
        Global::Ci,
        Global::Oi,
        Global::I,
        Global::E,
        Global::Ps,
        Global::ncomps,
        Global::time,
        Global::dtime,
        Global::dPdtime,
        Global::alpha,
    ];

    /// The name as written in source.
    pub fn name(self) -> &'static str {
        match self {
            Global::P => "P",
            Global::dPdu => "dPdu",
            Global::dPdv => "dPdv",
            Global::N => "N",
            Global::Ng => "Ng",
            Global::u => "u",
            Global::v => "v",
            Global::du => "du",
            Global::dv => "dv",
            Global::s => "s",
            Global::t => "t",
            Global::L => "L",
            Global::Cl => "Cl",
            Global::Ol => "Ol",
            Global::Cs => "Cs",
            Global::Os => "Os",
            Global::Ci => "Ci",
            Global::Oi => "Oi",
            Global::I => "I",
            Global::E => "E",
            Global::Ps => "Ps",
            Global::ncomps => "ncomps",
            Global::time => "time",
            Global::dtime => "dtime",
            Global::dPdtime => "dPdtime",
            Global::alpha => "alpha",
        }
    }

    /// The global with this name, if any.
    pub fn from_name(name: &str) -> Option<Global> {
        Global::ALL.into_iter().find(|g| g.name() == name)
    }

    /// Its type.
    pub fn ty(self) -> Type {
        match self {
            Global::P | Global::E | Global::Ps => Type::POINT,
            Global::dPdu | Global::dPdv | Global::L | Global::I | Global::dPdtime => Type::VECTOR,
            Global::N | Global::Ng => Type::NORMAL,
            Global::Cl | Global::Ol | Global::Cs | Global::Os | Global::Ci | Global::Oi => {
                Type::COLOR
            }
            Global::u
            | Global::v
            | Global::du
            | Global::dv
            | Global::s
            | Global::t
            | Global::ncomps
            | Global::time
            | Global::dtime
            | Global::alpha => Type::FLOAT,
        }
    }

    /// Its detail: `E`, `ncomps`, `time` and `dtime` are uniform, everything else varying.
    pub fn detail(self) -> Detail {
        match self {
            Global::E | Global::ncomps | Global::time | Global::dtime => Detail::Uniform,
            _ => Detail::Varying,
        }
    }
}

/// How a shader kind may use a global (RI 3.2 tables 11.1–11.6, with the common renderer
/// leniencies: surface shaders may write `P` and `N`, light shaders may write `L`, as
/// Listing 9.14's `L = 0` does).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Access {
    /// Not defined in this kind of shader.
    None,
    /// Readable only.
    Read,
    /// Readable and writable.
    ReadWrite,
}

impl Global {
    /// How a shader of `kind` may use this global. In surface and volume shaders `L`, `Cl` and
    /// `Ol` are additionally only meaningful inside `illuminance` (the checker enforces that).
    pub fn access(self, kind: ShaderKind) -> Access {
        use Access::{None as No, Read as R, ReadWrite as RW};
        use Global as G;
        match kind {
            ShaderKind::Surface => match self {
                G::P | G::N | G::Ci | G::Oi => RW,
                G::Ps | G::alpha => No,
                _ => R,
            },
            ShaderKind::Light => match self {
                G::L | G::Cl | G::Ol => RW,
                G::Cs | G::Os | G::Ci | G::Oi | G::I | G::alpha => No,
                _ => R,
            },
            ShaderKind::Displacement => match self {
                G::P | G::N => RW,
                G::L | G::Cl | G::Ol | G::Ci | G::Oi | G::Ps | G::alpha => No,
                _ => R,
            },
            ShaderKind::Volume => match self {
                G::Ci | G::Oi => RW,
                G::P | G::I | G::E | G::L | G::Cl | G::Ol | G::ncomps | G::time | G::dtime => R,
                _ => No,
            },
            ShaderKind::Imager => match self {
                G::Ci | G::Oi | G::alpha => RW,
                G::P | G::ncomps | G::time | G::dtime => R,
                _ => No,
            },
            ShaderKind::Transformation => match self {
                G::P => RW,
                G::time | G::dtime => R,
                _ => No,
            },
        }
    }
}
