//! Typed look-ups in a request's parameter list by bare name (`"uniform float Ks"` matches `Ks`).
use illume_rib::{Declaration, Param, ParamList, Value};

fn bare(name: &str) -> &str {
    match Declaration::split_inline(name) {
        Ok((_, bare)) => bare,
        Err(_) => name.trim(),
    }
}

pub fn find<'a>(params: &'a ParamList, name: &str) -> Option<&'a Param> {
    params.iter().find(|p| bare(&p.name) == name)
}

pub fn floats(params: &ParamList, name: &str) -> Option<Vec<f32>> {
    find(params, name).and_then(|p| p.value.as_floats())
}

pub fn float(params: &ParamList, name: &str) -> Option<f32> {
    floats(params, name).and_then(|v| v.first().copied())
}

pub fn string(params: &ParamList, name: &str) -> Option<String> {
    match &find(params, name)?.value {
        Value::Strings(s) => s.first().cloned(),
        _ => None,
    }
}

/// Bare names of every parameter, for "unknown parameter" reports.
pub fn names(params: &ParamList) -> impl Iterator<Item = &str> {
    params.iter().map(|p| bare(&p.name))
}
