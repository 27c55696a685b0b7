//! Shading Language types (RI Specification 3.2, chapter 11 "Types") and storage detail.
//!
//! This file is half of the ABI between the front end (`illume-sl`) and the grid executor
//! (`illume-slvm`); change it only additively and log changes in `AST_CHANGES.md`.

use std::fmt;

/// The base type of a value. `point`, `vector` and `normal` are all three-float "triples" that
/// differ only in how `transform`-family functions and space casts treat them; `color` has
/// `ncomps` components, which Illume fixes at 3 (RGB), as PRMan, BMRT and Aqsis do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BaseType {
    /// 32-bit float at run time; the only numeric scalar type in the language.
    Float,
    /// RGB colour (3 floats).
    Color,
    /// Position: transformed with the full matrix (translation applies).
    Point,
    /// Direction: transformed with the upper 3×3 (no translation).
    Vector,
    /// Surface normal: transformed with the inverse transpose.
    Normal,
    /// 4×4 transformation matrix (16 floats, row-major like RenderMan's `ConcatTransform`).
    Matrix,
    /// Character string (always uniform: RI 3.2 has no varying strings).
    String,
    /// No value: the return type of a function that returns nothing, and of statements.
    Void,
    /// Not yet known (the parser's placeholder before checking) or the type of an expression
    /// that had an error. Never present in a program the checker accepted without errors.
    Unknown,
}

impl BaseType {
    /// True for the three-float geometric types and colour, which promote from float and
    /// convert among each other component-wise.
    pub fn is_triple(self) -> bool {
        matches!(
            self,
            BaseType::Color | BaseType::Point | BaseType::Vector | BaseType::Normal
        )
    }

    /// True for `point`, `vector` and `normal` (the triples a space name can transform).
    pub fn is_geometric(self) -> bool {
        matches!(self, BaseType::Point | BaseType::Vector | BaseType::Normal)
    }

    /// Number of floats one value occupies (0 for string, void and unknown).
    pub fn components(self) -> usize {
        match self {
            BaseType::Float => 1,
            BaseType::Color | BaseType::Point | BaseType::Vector | BaseType::Normal => 3,
            BaseType::Matrix => 16,
            BaseType::String | BaseType::Void | BaseType::Unknown => 0,
        }
    }

    /// The keyword that spells this type in source.
    pub fn keyword(self) -> &'static str {
        match self {
            BaseType::Float => "float",
            BaseType::Color => "color",
            BaseType::Point => "point",
            BaseType::Vector => "vector",
            BaseType::Normal => "normal",
            BaseType::Matrix => "matrix",
            BaseType::String => "string",
            BaseType::Void => "void",
            BaseType::Unknown => "<unknown>",
        }
    }

    /// The type named by a keyword, if the word is a type keyword.
    pub fn from_keyword(word: &str) -> Option<BaseType> {
        Some(match word {
            "float" => BaseType::Float,
            "color" => BaseType::Color,
            "point" => BaseType::Point,
            "vector" => BaseType::Vector,
            "normal" => BaseType::Normal,
            "matrix" => BaseType::Matrix,
            "string" => BaseType::String,
            "void" => BaseType::Void,
            _ => return None,
        })
    }
}

impl fmt::Display for BaseType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.keyword())
    }
}

/// Array-ness of a type. RI 3.2 arrays are one-dimensional with a length fixed at compile time;
/// a function parameter may be declared `float a[]` to accept an array of any length (PRMan and
/// Aqsis accept this; the length is then the argument's).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ArrayLen {
    /// `name[n]`: exactly `n` elements.
    Fixed(u32),
    /// `name[]` as a function parameter: the length of whatever array is passed.
    Open,
}

/// A complete value type: base type plus optional array length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Type {
    /// Element type.
    pub base: BaseType,
    /// `None` for a scalar (non-array) value.
    pub array: Option<ArrayLen>,
}

impl Type {
    /// Scalar float.
    pub const FLOAT: Type = Type::scalar(BaseType::Float);
    /// Scalar color.
    pub const COLOR: Type = Type::scalar(BaseType::Color);
    /// Scalar point.
    pub const POINT: Type = Type::scalar(BaseType::Point);
    /// Scalar vector.
    pub const VECTOR: Type = Type::scalar(BaseType::Vector);
    /// Scalar normal.
    pub const NORMAL: Type = Type::scalar(BaseType::Normal);
    /// Scalar matrix.
    pub const MATRIX: Type = Type::scalar(BaseType::Matrix);
    /// Scalar string.
    pub const STRING: Type = Type::scalar(BaseType::String);
    /// No value.
    pub const VOID: Type = Type::scalar(BaseType::Void);
    /// Placeholder before checking (see [`BaseType::Unknown`]).
    pub const UNKNOWN: Type = Type::scalar(BaseType::Unknown);

    /// A non-array value of `base`.
    pub const fn scalar(base: BaseType) -> Type {
        Type { base, array: None }
    }

    /// A fixed-length array of `base`.
    pub const fn array(base: BaseType, len: u32) -> Type {
        Type {
            base,
            array: Some(ArrayLen::Fixed(len)),
        }
    }

    /// True when this is an array type (fixed or open).
    pub fn is_array(self) -> bool {
        self.array.is_some()
    }

    /// The element type of an array (or the type itself for a scalar).
    pub fn element(self) -> Type {
        Type::scalar(self.base)
    }

    /// The fixed length of an array type (`None` for scalars and open arrays).
    pub fn array_len(self) -> Option<u32> {
        match self.array {
            Some(ArrayLen::Fixed(n)) => Some(n),
            _ => None,
        }
    }
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.array {
            None => write!(f, "{}", self.base),
            Some(ArrayLen::Fixed(n)) => write!(f, "{}[{}]", self.base, n),
            Some(ArrayLen::Open) => write!(f, "{}[]", self.base),
        }
    }
}

/// Storage class of a value over a grid (RI 3.2 §11.4 "Uniform and varying variables").
///
/// A *uniform* value is the same at every point of the grid and is computed once per grid; a
/// *varying* value has one value per grid point and is computed under the running-state mask.
/// Ordered so that `max` combines details: anything that reads a varying value is varying.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub enum Detail {
    /// One value per grid.
    #[default]
    Uniform,
    /// One value per grid point.
    Varying,
}

impl Detail {
    /// The detail of a value computed from both inputs: varying if either is.
    pub fn join(self, other: Detail) -> Detail {
        self.max(other)
    }

    /// The keyword that spells this detail in source.
    pub fn keyword(self) -> &'static str {
        match self {
            Detail::Uniform => "uniform",
            Detail::Varying => "varying",
        }
    }
}

impl fmt::Display for Detail {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.keyword())
    }
}

/// The kinds of shader a file can define (RI 3.2 §11.1). `atmosphere`, `interior` and
/// `exterior` shaders are all written as `volume` shaders.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShaderKind {
    /// `surface`: computes `Ci`, `Oi` at surface points.
    Surface,
    /// `light`: computes `Cl` (and `Ol`) towards the surface point `Ps`.
    Light,
    /// `displacement`: moves `P` and recomputes `N`.
    Displacement,
    /// `volume`: attenuates `Ci`/`Oi` along `I` (atmosphere, interior, exterior).
    Volume,
    /// `imager`: operates on final pixel colours.
    Imager,
    /// `transformation`: maps `P` (RI 3.2 lists it; rarely implemented, parsed for completeness).
    Transformation,
}

impl ShaderKind {
    /// The keyword that introduces this kind of shader.
    pub fn keyword(self) -> &'static str {
        match self {
            ShaderKind::Surface => "surface",
            ShaderKind::Light => "light",
            ShaderKind::Displacement => "displacement",
            ShaderKind::Volume => "volume",
            ShaderKind::Imager => "imager",
            ShaderKind::Transformation => "transformation",
        }
    }

    /// The shader kind introduced by a keyword, if the word is one.
    pub fn from_keyword(word: &str) -> Option<ShaderKind> {
        Some(match word {
            "surface" => ShaderKind::Surface,
            "light" => ShaderKind::Light,
            "displacement" => ShaderKind::Displacement,
            "volume" => ShaderKind::Volume,
            "imager" => ShaderKind::Imager,
            "transformation" => ShaderKind::Transformation,
            _ => return None,
        })
    }
}

impl fmt::Display for ShaderKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.keyword())
    }
}
