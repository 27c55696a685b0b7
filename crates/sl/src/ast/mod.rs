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
//! - every [`Expr::ty`] concrete (no [`crate::types::BaseType::Unknown`]) and [`Expr::detail`] inferred
//!   (varying iff anything it reads is varying);
//! - every [`VarUse::var`], [`LValue::var`] and [`Declarator::var`] resolved;
//! - every [`Call::callee`] resolved (except calls to unknown functions, which were warned
//!   about and are an error only if executed), with `args[i]` already of type `params[i].ty` of the chosen
//!   [`Signature`] (promotions inserted);
//! - no [`ExprKind::Error`] or [`StmtKind::Error`].
//!
//! Names follow the RI Specification 3.2, chapters 11–15 (Shading Language).

mod call;
mod expr;
mod global;
mod stmt;

pub use crate::builtins::{BuiltinId, Family};
pub use call::{
    BuiltinCall, Call, Callee, NamedArg, SigParam, Signature, TextureCall, TextureKind,
};
pub use expr::{AssignOp, BinaryOp, Expr, ExprKind, LValue, UnaryOp, VarRef, VarUse};
pub use global::{Access, Global};
pub use stmt::{Block, Cone, Decl, Declarator, Illuminance, Illuminate, Solar, Stmt, StmtKind};

use crate::span::Span;
use crate::types::{Detail, ShaderKind, Type};

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
    /// The path of each file read, indexed by [`crate::span::FileId`] (the compiler's
    /// `SourceMap`, without the text), so run-time problems can name `file:line:col`.
    pub files: Vec<std::path::PathBuf>,
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
