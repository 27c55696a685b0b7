//! Calls: to user functions and built-ins (resolved by the checker to a [`FuncId`] or a
//! [`BuiltinId`] with a concrete [`Signature`]), and the texture-access family.

use super::{Expr, FuncId};
use crate::builtins::BuiltinId;
use crate::types::Type;

/// `name (args…)`.
#[derive(Debug, Clone)]
pub struct Call {
    /// Function name as written.
    pub name: String,
    /// Arguments as written (an `output` parameter's argument is a [`ExprKind::Var`] or an
    /// [`ExprKind::Index`] of a variable).
    pub args: Vec<Expr>,
    /// Checker: the function called; stays `None` after checking only for a name that is
    /// neither a built-in nor a user function (another renderer's extension such as
    /// `bake`), which the checker warned about and the executor reports if reached.
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
    /// The built-in, resolved once by the checker: executors dispatch on it, never on `name`.
    pub id: BuiltinId,
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
