//! Parameter declarations: `Declare "Kd" "uniform float"` and inline forms such as
//! `"varying point[5] MyP"` or `"constant string texturename"` (RI Spec 3.2 §3.x, `RiDeclare`).
//!
//! The parser only knows the *syntax*; which names are predeclared (P, N, Cs, st, …) and the
//! per-scene `Declare` table live in `illume-ri`.
use std::fmt;
use thiserror::Error;

/// Storage class of a primitive variable: how many values a primitive carries and how they are
/// interpolated (RI Spec 3.2 §5, "Primitive variables").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    Constant,
    Uniform,
    Varying,
    Vertex,
    FaceVarying,
    FaceVertex,
}

/// Data type of a declared variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Type {
    Float,
    Integer,
    String,
    Point,
    Vector,
    Normal,
    Color,
    /// Homogeneous point, 4 floats (`Pw`).
    HPoint,
    Matrix,
}

impl Type {
    /// Number of scalar components of one element (color = 3: Illume uses RGB `ColorSamples`).
    pub fn components(self) -> usize {
        match self {
            Type::Float | Type::Integer | Type::String => 1,
            Type::Point | Type::Vector | Type::Normal | Type::Color => 3,
            Type::HPoint => 4,
            Type::Matrix => 16,
        }
    }
}

/// A parsed declaration: `[class] type ['[' n ']'] [name]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Declaration {
    pub class: Class,
    pub ty: Type,
    /// Array length; 1 for scalars.
    pub array_len: usize,
    /// The variable name of an inline declaration (`"uniform float Ks"` → `Ks`); `None` for the
    /// type string of a `Declare` request.
    pub name: Option<String>,
}

impl Declaration {
    /// Scalars per element, counting the array length.
    pub fn element_size(&self) -> usize {
        self.ty.components() * self.array_len
    }
}

#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum DeclarationError {
    #[error("empty declaration")]
    Empty,
    #[error("unknown type `{0}` in declaration")]
    UnknownType(String),
    #[error("bad array length in declaration `{0}`")]
    BadArray(String),
    #[error("unexpected `{0}` after declaration")]
    Trailing(String),
}

fn class_of(word: &str) -> Option<Class> {
    Some(match word {
        "constant" => Class::Constant,
        "uniform" => Class::Uniform,
        "varying" => Class::Varying,
        "vertex" => Class::Vertex,
        "facevarying" => Class::FaceVarying,
        "facevertex" => Class::FaceVertex,
        _ => return None,
    })
}

fn type_of(word: &str) -> Option<Type> {
    Some(match word {
        "float" => Type::Float,
        "integer" | "int" => Type::Integer,
        "string" => Type::String,
        "point" => Type::Point,
        "vector" => Type::Vector,
        "normal" => Type::Normal,
        "color" => Type::Color,
        "hpoint" => Type::HPoint,
        "matrix" => Type::Matrix,
        _ => return None,
    })
}

impl Declaration {
    /// Parses a declaration; the class defaults to `uniform` as `RiDeclare` says.
    ///
    /// Accepts the spacing real exporters write: `" varying point[5]"`, `"point [5]"`,
    /// `"uniform float Ks"`.
    pub fn parse(text: &str) -> Result<Declaration, DeclarationError> {
        // Split "[" and "]" into their own words so `point[5]` and `point [ 5 ]` read alike.
        let spaced = text.replace('[', " [ ").replace(']', " ] ");
        let mut words = spaced.split_whitespace().peekable();
        let first = words.next().ok_or(DeclarationError::Empty)?;
        let (class, type_word) = match class_of(first) {
            Some(c) => (c, words.next().ok_or(DeclarationError::Empty)?),
            None => (Class::Uniform, first),
        };
        let ty = type_of(type_word)
            .ok_or_else(|| DeclarationError::UnknownType(type_word.to_string()))?;
        let mut array_len = 1;
        if words.peek() == Some(&"[") {
            words.next();
            let n = words
                .next()
                .ok_or_else(|| DeclarationError::BadArray(text.to_string()))?;
            array_len = n
                .parse::<usize>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| DeclarationError::BadArray(text.to_string()))?;
            if words.next() != Some("]") {
                return Err(DeclarationError::BadArray(text.to_string()));
            }
        }
        let name = words.next().map(str::to_string);
        if let Some(extra) = words.next() {
            return Err(DeclarationError::Trailing(extra.to_string()));
        }
        Ok(Declaration {
            class,
            ty,
            array_len,
            name,
        })
    }

    /// Splits a parameter token into an inline declaration and the bare name:
    /// `"uniform float Ks"` → `(Some(decl), "Ks")`, `"Ks"` → `(None, "Ks")`.
    pub fn split_inline(token: &str) -> Result<(Option<Declaration>, &str), DeclarationError> {
        let trimmed = token.trim();
        if !trimmed.contains(char::is_whitespace) && !trimmed.contains('[') {
            return Ok((None, trimmed));
        }
        let decl = Declaration::parse(trimmed)?;
        match decl.name.as_deref() {
            Some(_) => {
                let name = trimmed
                    .rsplit(char::is_whitespace)
                    .next()
                    .unwrap_or(trimmed);
                // `point[5]MyP` has no space before the name; fall back to the text after `]`.
                let name = name.rsplit(']').next().unwrap_or(name);
                Ok((Some(decl), name))
            }
            None => Err(DeclarationError::Empty),
        }
    }
}

impl fmt::Display for Class {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Class::Constant => "constant",
            Class::Uniform => "uniform",
            Class::Varying => "varying",
            Class::Vertex => "vertex",
            Class::FaceVarying => "facevarying",
            Class::FaceVertex => "facevertex",
        })
    }
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Type::Float => "float",
            Type::Integer => "integer",
            Type::String => "string",
            Type::Point => "point",
            Type::Vector => "vector",
            Type::Normal => "normal",
            Type::Color => "color",
            Type::HPoint => "hpoint",
            Type::Matrix => "matrix",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn class_defaults_to_uniform() {
        let d = Declaration::parse("float").unwrap();
        assert_eq!(
            (d.class, d.ty, d.array_len, d.name),
            (Class::Uniform, Type::Float, 1, None)
        );
    }

    #[test]
    fn inline_array_declaration_with_odd_spacing() {
        let d = Declaration::parse(" varying point[5] MyP").unwrap();
        assert_eq!(
            (d.class, d.ty, d.array_len),
            (Class::Varying, Type::Point, 5)
        );
        assert_eq!(d.name.as_deref(), Some("MyP"));
        assert_eq!(d.element_size(), 15);
    }

    #[test]
    fn split_inline_returns_bare_name() {
        let (d, name) = Declaration::split_inline("constant string texturename").unwrap();
        assert_eq!(name, "texturename");
        assert_eq!(d.unwrap().ty, Type::String);
        assert_eq!(Declaration::split_inline("Kd").unwrap(), (None, "Kd"));
    }

    #[test]
    fn unknown_type_is_an_error() {
        assert_eq!(
            Declaration::parse("uniform flot"),
            Err(DeclarationError::UnknownType("flot".into()))
        );
        assert!(matches!(
            Declaration::parse("float[0]"),
            Err(DeclarationError::BadArray(_))
        ));
    }
}
