//! Statements of the checked tree (RI 3.2 §12): blocks, declarations, control flow and the
//! lighting constructs `illuminance`, `illuminate`, `solar`.

use super::{Expr, FuncId, VarRef};
use crate::span::Span;
use crate::types::{ArrayLen, BaseType, Detail};

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
