//! Python values to RI arguments: numbers, strings, sequences and numpy arrays (via `tolist`).
use illume_session::{Arg, ParamData, Type};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

/// Flattens nested sequences (lists of points, numpy arrays) into scalars.
fn flatten<'py>(v: &Bound<'py, PyAny>, out: &mut Vec<Bound<'py, PyAny>>) -> PyResult<()> {
    if v.hasattr("tolist")? && !v.is_instance_of::<pyo3::types::PyString>() {
        let list = v.call_method0("tolist")?;
        if list.is_instance_of::<pyo3::types::PyList>() {
            return flatten(&list, out);
        }
        out.push(list);
        return Ok(());
    }
    if v.is_instance_of::<pyo3::types::PyList>() || v.is_instance_of::<pyo3::types::PyTuple>() {
        for item in v.try_iter()? {
            flatten(&item?, out)?;
        }
        return Ok(());
    }
    out.push(v.clone());
    Ok(())
}

fn is_sequence(v: &Bound<'_, PyAny>) -> PyResult<bool> {
    Ok(v.is_instance_of::<pyo3::types::PyList>()
        || v.is_instance_of::<pyo3::types::PyTuple>()
        || (v.hasattr("tolist")? && !v.is_instance_of::<pyo3::types::PyString>()))
}

/// A positional argument: int, float, string, or a sequence of one kind.
pub fn arg(v: &Bound<'_, PyAny>) -> PyResult<Arg> {
    if v.is_instance_of::<pyo3::types::PyBool>() {
        return Ok(Arg::Int(i32::from(v.extract::<bool>()?)));
    }
    if v.is_instance_of::<pyo3::types::PyString>() {
        return Ok(Arg::Str(v.extract()?));
    }
    if is_sequence(v)? {
        let mut items = Vec::new();
        flatten(v, &mut items)?;
        if items
            .iter()
            .all(|i| i.is_instance_of::<pyo3::types::PyString>())
            && !items.is_empty()
        {
            return Ok(Arg::Strings(
                items.iter().map(|i| i.extract()).collect::<PyResult<_>>()?,
            ));
        }
        if items
            .iter()
            .all(|i| i.is_instance_of::<pyo3::types::PyInt>())
            && !items.is_empty()
        {
            return Ok(Arg::Ints(
                items.iter().map(|i| i.extract()).collect::<PyResult<_>>()?,
            ));
        }
        return Ok(Arg::Floats(
            items.iter().map(|i| i.extract()).collect::<PyResult<_>>()?,
        ));
    }
    if v.is_instance_of::<pyo3::types::PyInt>() {
        return Ok(Arg::Int(v.extract()?));
    }
    if let Ok(f) = v.extract::<f32>() {
        return Ok(Arg::Float(f));
    }
    Err(PyTypeError::new_err(format!(
        "can not pass {} to RenderMan",
        v.get_type().name()?
    )))
}

/// A parameter value, typed by its declaration.
pub fn param(v: &Bound<'_, PyAny>, ty: Type) -> PyResult<ParamData> {
    let mut items = Vec::new();
    flatten(v, &mut items)?;
    Ok(match ty {
        Type::String => {
            ParamData::Strings(items.iter().map(|i| i.extract()).collect::<PyResult<_>>()?)
        }
        Type::Integer => {
            ParamData::Ints(items.iter().map(|i| i.extract()).collect::<PyResult<_>>()?)
        }
        _ => ParamData::Floats(items.iter().map(|i| i.extract()).collect::<PyResult<_>>()?),
    })
}
