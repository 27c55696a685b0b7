//! Binding RIB parameter lists to a shader's declared parameters (names, types, listing
//! defaults), and reading them per point with user primitive variables overriding them.
use crate::shadinggrid::ShadingGrid;
use glam::Vec3;
use illume_rib::{Declaration, Param, Type, Value};

/// A shader parameter's value as bound.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    Float(f32),
    Color(Vec3),
    /// `point`, `vector` or `normal` (3 floats).
    Point(Vec3),
    String(String),
}

impl ParamValue {
    fn type_name(&self) -> &'static str {
        match self {
            ParamValue::Float(_) => "float",
            ParamValue::Color(_) => "color",
            ParamValue::Point(_) => "point",
            ParamValue::String(_) => "string",
        }
    }

    fn accepts(&self, ty: Type) -> bool {
        matches!(
            (self, ty),
            (ParamValue::Float(_), Type::Float | Type::Integer)
                | (ParamValue::Color(_), Type::Color)
                | (
                    ParamValue::Point(_),
                    Type::Point | Type::Vector | Type::Normal
                )
                | (ParamValue::String(_), Type::String)
        )
    }

    /// Reads `value` in the shape of `self`; `None` if type or count does not match.
    fn read(&self, value: &Value) -> Option<ParamValue> {
        match self {
            ParamValue::String(_) => match value {
                Value::Strings(s) if s.len() == 1 => Some(ParamValue::String(s[0].clone())),
                _ => None,
            },
            ParamValue::Float(_) => match value.as_floats() {
                Some(f) if f.len() == 1 => Some(ParamValue::Float(f[0])),
                _ => None,
            },
            ParamValue::Color(_) => match value.as_floats() {
                Some(f) if f.len() == 3 => Some(ParamValue::Color(Vec3::from_slice(&f))),
                // A single number for a color is a grey, as SL's float→color promotion.
                Some(f) if f.len() == 1 => Some(ParamValue::Color(Vec3::splat(f[0]))),
                _ => None,
            },
            ParamValue::Point(_) => match value.as_floats() {
                Some(f) if f.len() == 3 => Some(ParamValue::Point(Vec3::from_slice(&f))),
                _ => None,
            },
        }
    }

    /// A value of an undeclared parameter, shaped by what was written (for `lightsource()`).
    fn guess(value: &Value) -> Option<ParamValue> {
        match value {
            Value::Strings(s) if s.len() == 1 => Some(ParamValue::String(s[0].clone())),
            _ => match value.as_floats()?.as_slice() {
                [f] => Some(ParamValue::Float(*f)),
                [r, g, b] => Some(ParamValue::Color(Vec3::new(*r, *g, *b))),
                _ => None,
            },
        }
    }
}

/// The bound parameters of one shader instance, in declaration order, defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ShaderParams {
    pub values: Vec<(String, ParamValue)>,
}

impl ShaderParams {
    /// Binds `params` against `specs` (name, default). A parameter of the wrong type or count is
    /// reported in the returned warnings and ignored. Undeclared names are kept (so
    /// `lightsource()` can read them) when `keep_unknown`, otherwise warned about.
    pub fn bind(
        shader: &str,
        specs: &[(&str, ParamValue)],
        params: &[Param],
        keep_unknown: bool,
    ) -> (ShaderParams, Vec<String>) {
        let mut values: Vec<(String, ParamValue)> = specs
            .iter()
            .map(|(n, v)| (n.to_string(), v.clone()))
            .collect();
        let mut warnings = Vec::new();
        for param in params {
            let (decl, name) = match Declaration::split_inline(&param.name) {
                Ok(x) => x,
                Err(e) => {
                    warnings.push(format!(
                        "shader `{shader}`: parameter \"{}\": bad declaration ({e}); ignored",
                        param.name
                    ));
                    continue;
                }
            };
            match values.iter().position(|(n, _)| n == name) {
                Some(k) => {
                    let default = &values[k].1;
                    if let Some(d) = &decl {
                        if !default.accepts(d.ty) || d.array_len != 1 {
                            warnings.push(format!(
                                "shader `{shader}`: parameter `{name}` is declared `{}{}` but the \
                                 shader expects `{}`; ignored",
                                d.ty,
                                if d.array_len != 1 {
                                    format!("[{}]", d.array_len)
                                } else {
                                    String::new()
                                },
                                default.type_name()
                            ));
                            continue;
                        }
                    }
                    match default.read(&param.value) {
                        Some(v) => values[k].1 = v,
                        None => warnings.push(format!(
                            "shader `{shader}`: parameter `{name}` expects one {}, found {} {}; ignored",
                            default.type_name(),
                            param.value.len(),
                            match param.value {
                                Value::Strings(_) => "string(s)",
                                _ => "number(s)",
                            }
                        )),
                    }
                }
                None if keep_unknown => match ParamValue::guess(&param.value) {
                    Some(v) => values.push((name.to_string(), v)),
                    None => warnings.push(format!(
                        "shader `{shader}`: extra parameter `{name}` has {} values; ignored",
                        param.value.len()
                    )),
                },
                None => warnings.push(format!(
                    "shader `{shader}` has no parameter `{name}`; ignored"
                )),
            }
        }
        (ShaderParams { values }, warnings)
    }

    pub fn get(&self, name: &str) -> Option<&ParamValue> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, v)| v)
    }

    pub fn float(&self, name: &str) -> f32 {
        match self.get(name) {
            Some(ParamValue::Float(f)) => *f,
            _ => 0.0,
        }
    }

    pub fn vec3(&self, name: &str) -> Vec3 {
        match self.get(name) {
            Some(ParamValue::Color(c)) | Some(ParamValue::Point(c)) => *c,
            Some(ParamValue::Float(f)) => Vec3::splat(*f),
            _ => Vec3::ZERO,
        }
    }

    pub fn string(&self, name: &str) -> &str {
        match self.get(name) {
            Some(ParamValue::String(s)) => s,
            _ => "",
        }
    }

    /// A float parameter read per point: a user primitive variable of the same name overrides
    /// the bound value.
    pub fn float_on<'g>(&self, grid: &'g ShadingGrid, name: &str) -> FloatParam<'g> {
        FloatParam {
            uniform: self.float(name),
            varying: grid.var(name, 1),
        }
    }

    /// A color/point parameter read per point, overridable like [`ShaderParams::float_on`].
    pub fn vec3_on<'g>(&self, grid: &'g ShadingGrid, name: &str) -> Vec3Param<'g> {
        Vec3Param {
            uniform: self.vec3(name),
            varying: grid.var(name, 3),
        }
    }
}

/// A float parameter: one value, or one per point (or one per grid) from a primitive variable.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FloatParam<'g> {
    uniform: f32,
    varying: Option<&'g [f32]>,
}

impl FloatParam<'_> {
    pub fn at(&self, i: usize) -> f32 {
        match self.varying {
            Some(v) if v.len() == 1 => v[0],
            Some(v) => v[i],
            None => self.uniform,
        }
    }
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Vec3Param<'g> {
    uniform: Vec3,
    varying: Option<&'g [f32]>,
}

impl Vec3Param<'_> {
    pub fn at(&self, i: usize) -> Vec3 {
        match self.varying {
            Some(v) if v.len() == 3 => Vec3::from_slice(v),
            Some(v) => Vec3::from_slice(&v[3 * i..3 * i + 3]),
            None => self.uniform,
        }
    }
}
