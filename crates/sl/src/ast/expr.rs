//! Expressions of the checked tree (RI 3.2 §12): literals, variables, operators, casts,
//! assignments; every node carries the type and detail the checker inferred.

use super::{Call, Global, Owner, TextureCall, VarId};
use crate::span::Span;
use crate::types::{BaseType, Detail, Type};

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
