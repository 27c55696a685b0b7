//! Primitive variables resolved from a parameter list (RI Spec 3.2 §5, "Primitive variables").
use illume_rib::{Class, Type};

#[derive(Clone, Debug, PartialEq)]
pub enum PrimVarData {
    Floats(Vec<f32>),
    Strings(Vec<String>),
}

/// One primitive variable with its resolved declaration. `data` holds
/// `count(class) × ty.components() × array_len` scalars, in the space the file gave them
/// (transforming P/N/vectors to camera space happens when the primitive is built).
#[derive(Clone, Debug, PartialEq)]
pub struct PrimVar {
    pub name: String,
    pub class: Class,
    pub ty: Type,
    pub array_len: usize,
    pub data: PrimVarData,
}
