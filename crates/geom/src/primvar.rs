//! Primitive variables resolved from a parameter list (RI Spec 3.2 §5, "Primitive variables").
//!
//! Resolution turns `"varying color Cs" [..]` into a [`PrimVar`] whose declaration is known and
//! whose value count has been checked against the primitive's topology ([`ClassCounts`]): only
//! geom knows how many uniform, varying, vertex and facevarying values a primitive carries.
use crate::parametric::{Interp, SurfaceVar};
use crate::GeomError;
use illume_rib::{Class, Declaration, Param, Type, Value};
use std::cell::RefCell;

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

impl PrimVar {
    /// Scalars per value (`ty.components() × array_len`).
    pub fn element_size(&self) -> usize {
        self.ty.components() * self.array_len
    }

    /// The numbers, or an empty slice for strings.
    pub fn floats(&self) -> &[f32] {
        match &self.data {
            PrimVarData::Floats(v) => v,
            PrimVarData::Strings(_) => &[],
        }
    }

    /// Value `i` of this variable (`element_size` scalars).
    pub fn element(&self, i: usize) -> &[f32] {
        let n = self.element_size();
        &self.floats()[i * n..(i + 1) * n]
    }
}

/// How many values each storage class holds on one primitive (RI Spec 3.2 §5.1):
/// constant 1, uniform one per face/patch, varying one per parametric corner, vertex one per
/// control point, facevarying one per face corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClassCounts {
    pub uniform: usize,
    pub varying: usize,
    pub vertex: usize,
    pub facevarying: usize,
}

impl ClassCounts {
    /// Counts of a single parametric surface (quadric, single patch): one face, four corners,
    /// `vertex` control points.
    pub fn surface(vertex: usize) -> ClassCounts {
        ClassCounts {
            uniform: 1,
            varying: 4,
            vertex,
            facevarying: 4,
        }
    }

    pub fn count(&self, class: Class) -> usize {
        match class {
            Class::Constant => 1,
            Class::Uniform => self.uniform,
            Class::Varying => self.varying,
            Class::Vertex => self.vertex,
            Class::FaceVarying | Class::FaceVertex => self.facevarying,
        }
    }

    fn unit(class: Class) -> &'static str {
        match class {
            Class::Constant => "constant value",
            Class::Uniform => "faces",
            Class::Varying => "varying points",
            Class::Vertex => "vertices",
            Class::FaceVarying | Class::FaceVertex => "face corners",
        }
    }
}

/// Names whose declaration the spec fixes, used when `ctx.declarations` does not know them
/// (RI Spec 3.2 §5.1, Table 5.1 "Standard geometric primitive variables").
fn predeclared(name: &str) -> Option<Declaration> {
    let (class, ty, array_len) = match name {
        "P" => (Class::Vertex, Type::Point, 1),
        "Pz" => (Class::Vertex, Type::Float, 1),
        "Pw" => (Class::Vertex, Type::HPoint, 1),
        "N" => (Class::Varying, Type::Normal, 1),
        "Np" => (Class::Uniform, Type::Normal, 1),
        "Cs" | "Os" => (Class::Varying, Type::Color, 1),
        "s" | "t" => (Class::Varying, Type::Float, 1),
        "st" => (Class::Varying, Type::Float, 2),
        "width" => (Class::Varying, Type::Float, 1),
        "constantwidth" => (Class::Constant, Type::Float, 1),
        _ => return None,
    };
    Some(Declaration {
        class,
        ty,
        array_len,
        name: None,
    })
}

/// Resolves a geometry request's parameter list into primitive variables and checks each
/// variable's value count against `counts`.
///
/// Inline declarations win over `declarations`, which win over the spec's predeclared names.
/// A parameter nobody declared cannot be interpreted and is skipped (`ri` reports unknown
/// parameters); a malformed inline declaration is an error.
///
/// A variable with the wrong number of values is repaired, as Aqsis and PRMan do, instead of
/// losing the primitive (real files have them: the regression suite's `Bug1412162` gives
/// `"st"` 9 values where 8 are needed): too many are cut to the count expected, too few drop
/// that variable only. Either way a warning naming the variable, the count found and the
/// count expected goes to `warnings`. A position (`P`, `Pw`, `Pz`) with the wrong count stays
/// an error: it decides the primitive's shape.
pub fn resolve(
    request: &str,
    params: &[Param],
    declarations: &dyn Fn(&str) -> Option<Declaration>,
    counts: &ClassCounts,
    warnings: Option<&RefCell<Vec<String>>>,
) -> Result<Vec<PrimVar>, GeomError> {
    let mut vars = Vec::with_capacity(params.len());
    for param in params {
        let (inline, name) =
            Declaration::split_inline(&param.name).map_err(|e| GeomError::Invalid {
                request: request.to_string(),
                message: format!("parameter \"{}\": {e}", param.name),
            })?;
        let Some(decl) = inline
            .or_else(|| declarations(name))
            .or_else(|| predeclared(name))
        else {
            continue;
        };
        let mismatch = count_mismatch(name, &decl, &param.value, counts);
        let data = match mismatch {
            None => resolve_data(request, name, &decl, &param.value)?,
            Some((message, _)) if matches!(name, "P" | "Pw" | "Pz") => {
                return Err(GeomError::Invalid {
                    request: request.to_string(),
                    message,
                })
            }
            Some((message, expected)) if param.value.len() > expected => {
                warn(warnings, format!("{message}; using the first {expected}"));
                truncate(resolve_data(request, name, &decl, &param.value)?, expected)
            }
            Some((message, _)) => {
                warn(warnings, format!("{message}; the variable is ignored"));
                continue;
            }
        };
        vars.push(PrimVar {
            name: name.to_string(),
            class: decl.class,
            ty: decl.ty,
            array_len: decl.array_len,
            data,
        });
    }
    Ok(vars)
}

fn warn(warnings: Option<&RefCell<Vec<String>>>, message: String) {
    if let Some(w) = warnings {
        w.borrow_mut().push(message);
    }
}

/// `None` when `value` has the number of values `decl` needs on a primitive of `counts`,
/// else the message that says so and the count expected.
fn count_mismatch(
    name: &str,
    decl: &Declaration,
    value: &Value,
    counts: &ClassCounts,
) -> Option<(String, usize)> {
    let n = counts.count(decl.class);
    // Saturating: hostile counts or array lengths must not overflow (they only fail the check).
    let expected = n.saturating_mul(decl.ty.components().saturating_mul(decl.array_len));
    let found = value.len();
    let array = if decl.array_len > 1 {
        format!("[{}]", decl.array_len)
    } else {
        String::new()
    };
    (found != expected).then(|| {
        let message = format!(
            "\"{name}\" has {found} values, expected {expected} ({} {}{array}, {n} {})",
            decl.class,
            decl.ty,
            ClassCounts::unit(decl.class)
        );
        (message, expected)
    })
}

/// The first `n` values.
fn truncate(data: PrimVarData, n: usize) -> PrimVarData {
    match data {
        PrimVarData::Floats(mut v) => {
            v.truncate(n);
            PrimVarData::Floats(v)
        }
        PrimVarData::Strings(mut v) => {
            v.truncate(n);
            PrimVarData::Strings(v)
        }
    }
}

/// The values of `value` as `decl`'s type says; numbers for a string (or the reverse) are an
/// error.
fn resolve_data(
    request: &str,
    name: &str,
    decl: &Declaration,
    value: &Value,
) -> Result<PrimVarData, GeomError> {
    Ok(match (decl.ty, value) {
        (Type::String, Value::Strings(s)) => PrimVarData::Strings(s.clone()),
        (Type::String, _) | (_, Value::Strings(_)) => {
            return Err(GeomError::Invalid {
                request: request.to_string(),
                message: format!(
                    "\"{name}\" is declared {} but was given {}",
                    decl.ty,
                    if matches!(value, Value::Strings(_)) {
                        "strings"
                    } else {
                        "numbers"
                    }
                ),
            })
        }
        (_, v) => PrimVarData::Floats(v.as_floats().unwrap_or_default()),
    })
}

/// Whether a variable is a position (`P`, `Pw`, `Pz`), which the surface itself carries.
pub fn is_position(var: &PrimVar) -> bool {
    matches!(var.name.as_str(), "P" | "Pw" | "Pz")
}

/// The non-position numeric variables of one surface, each interpolated as `interp` says for
/// its class, moved to camera space.
pub(crate) fn surface_vars(
    vars: &[PrimVar],
    camera_from_object: &glam::DMat4,
    mut interp: impl FnMut(&PrimVar) -> Interp,
) -> Vec<SurfaceVar> {
    vars.iter()
        .filter(|v| !is_position(v) && matches!(v.data, PrimVarData::Floats(_)))
        .map(|v| {
            let mut sv = SurfaceVar {
                name: v.name.clone(),
                ty: v.ty,
                components: v.element_size(),
                interp: interp(v),
            };
            sv.to_camera(camera_from_object);
            sv
        })
        .collect()
}

/// All values of `var` widened to f64 and moved to camera space (points, vectors and normals
/// by their type), for primitives that interpolate them themselves.
pub(crate) fn camera_values(var: &PrimVar, m: &glam::DMat4) -> Vec<f64> {
    let mut sv = SurfaceVar {
        name: String::new(),
        ty: var.ty,
        components: var.element_size(),
        interp: Interp::Constant(var.floats().iter().map(|&x| f64::from(x)).collect()),
    };
    sv.to_camera(m);
    // `to_camera` keeps the interpolation kind.
    match sv.interp {
        Interp::Constant(v) => v,
        _ => Vec::new(),
    }
}

/// Value `i` of `var` widened to f64.
pub(crate) fn element64(var: &PrimVar, i: usize) -> Vec<f64> {
    var.element(i).iter().map(|&x| x as f64).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_decls(_: &str) -> Option<Declaration> {
        None
    }

    fn param(name: &str, value: Value) -> Param {
        Param {
            name: name.to_string(),
            value,
        }
    }

    #[test]
    fn too_few_values_drop_the_variable_with_a_warning_that_names_the_counts() {
        let counts = ClassCounts {
            uniform: 1,
            varying: 4,
            vertex: 4,
            facevarying: 4,
        };
        let warnings = RefCell::new(Vec::new());
        let vars = resolve(
            "PointsPolygons",
            &[
                param("Cs", Value::Floats(vec![0.5; 5])),
                param("s", Value::Floats(vec![0.25; 4])),
            ],
            &no_decls,
            &counts,
            Some(&warnings),
        )
        .unwrap();
        assert_eq!(vars.len(), 1);
        assert_eq!(vars[0].name, "s");
        assert_eq!(
            warnings.into_inner(),
            vec!["\"Cs\" has 5 values, expected 12 (varying color, 4 varying points); the variable is ignored"]
        );
    }

    #[test]
    fn too_many_values_are_cut_to_the_count_expected() {
        // Aqsis's Bug1412162: "st" with 9 values on a 4-point polygon.
        let st = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0];
        let warnings = RefCell::new(Vec::new());
        let vars = resolve(
            "Polygon",
            &[param("st", Value::Floats(st.to_vec()))],
            &no_decls,
            &ClassCounts::surface(4),
            Some(&warnings),
        )
        .unwrap();
        assert_eq!(vars[0].floats(), &st[..8]);
        let w = warnings.into_inner();
        assert_eq!(w.len(), 1);
        assert!(w[0].contains("\"st\" has 9 values, expected 8"), "{w:?}");
        assert!(w[0].ends_with("using the first 8"), "{w:?}");
    }

    #[test]
    fn a_position_with_the_wrong_count_is_still_an_error() {
        let err = resolve(
            "Patch",
            &[param("P", Value::Floats(vec![0.0; 13]))],
            &no_decls,
            &ClassCounts::surface(4),
            None,
        )
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "Patch: \"P\" has 13 values, expected 12 (vertex point, 4 vertices)"
        );
    }

    #[test]
    fn inline_declaration_overrides_table_and_ints_widen() {
        let decls = |n: &str| (n == "Kd").then(|| Declaration::parse("uniform float").unwrap());
        let counts = ClassCounts::surface(16);
        let vars = resolve(
            "Patch",
            &[
                param("vertex float Kd", Value::Ints((0..16).collect())),
                param("P", Value::Floats(vec![0.0; 48])),
            ],
            &decls,
            &counts,
            None,
        )
        .unwrap();
        assert_eq!(vars[0].class, Class::Vertex);
        assert_eq!(vars[0].floats()[15], 15.0);
        assert_eq!(vars[1].ty, Type::Point);
    }

    #[test]
    fn undeclared_parameter_is_skipped_and_strings_type_checked() {
        let counts = ClassCounts::surface(4);
        let vars = resolve(
            "Sphere",
            &[param("mystery", Value::Floats(vec![1.0]))],
            &no_decls,
            &counts,
            None,
        )
        .unwrap();
        assert!(vars.is_empty());
        let err = resolve(
            "Sphere",
            &[param("constant string tex", Value::Floats(vec![1.0]))],
            &no_decls,
            &counts,
            None,
        );
        assert!(err.is_err());
    }
}
