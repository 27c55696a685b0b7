//! The Python module `illume`: `illume.Ri()`, prman's Python interface (`ri.Begin("__render")`
//! or a RIB file name, `ri.Sphere(1, -1, 1, 360)`, `ri.Surface("plastic", {"Ks": 0.5})`), and
//! `illume.render(path_or_rib) -> numpy array`. Calls go to the same `illume-session` as the C
//! binding, so Python, C and RIB render alike.
#![forbid(unsafe_code)]

mod convert;

use illume_session::{Call, RiError, Session};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// Requests whose RIB form has no positional arguments: prman's counts (`Polygon(nverts, …)`,
/// `Points(npoints, …)`) are dropped.
const COUNT_ONLY: &[&str] = &["Polygon", "Points"];

/// prman's filter names (`ri.GaussianFilter`) are the RIB names.
const FILTERS: &[(&str, &str)] = &[
    ("BoxFilter", "box"),
    ("TriangleFilter", "triangle"),
    ("GaussianFilter", "gaussian"),
    ("CatmullRomFilter", "catmull-rom"),
    ("SincFilter", "sinc"),
];

/// A RenderMan Interface context, as prman's `prman.Ri()`.
#[pyclass(unsendable)]
struct Ri {
    session: Option<Session>,
    handler: Option<Py<PyAny>>,
    /// Every problem reported so far: (code, severity, message).
    #[pyo3(get)]
    errors: Vec<(i32, i32, String)>,
}

#[pymethods]
#[allow(non_snake_case)] // prman's method names: ri.Begin, ri.Sphere
impl Ri {
    #[new]
    fn new() -> Ri {
        Ri {
            session: None,
            handler: None,
            errors: Vec::new(),
        }
    }

    /// `Begin("__render")` (or `Begin()`) renders in-process; a file name writes RIB.
    #[pyo3(signature = (name=None))]
    fn Begin(&mut self, py: Python<'_>, name: Option<&str>) -> PyResult<()> {
        let target = match name {
            None | Some("__render") => illume_session::target_for(None),
            n => illume_session::target_for(n),
        };
        match Session::begin(target.as_deref()) {
            Ok(s) => self.session = Some(s),
            Err(e) => self.dispatch(py, vec![e])?,
        }
        Ok(())
    }

    fn End(&mut self, py: Python<'_>) -> PyResult<()> {
        let errors = match self.session.take() {
            Some(s) => s.end(),
            None => vec![not_started("End")],
        };
        self.dispatch(py, errors)
    }

    /// `ErrorHandler(callable(code, severity, message))`; `None` prints to stderr.
    fn ErrorHandler(&mut self, handler: Option<Py<PyAny>>) {
        self.handler = handler;
    }

    /// `Declare(name, declaration)` returns the name, as in C.
    fn Declare(&mut self, py: Python<'_>, name: &str, declaration: &str) -> PyResult<String> {
        let mut call = Call::new("Declare");
        call.args = vec![
            illume_session::Arg::Str(name.into()),
            illume_session::Arg::Str(declaration.into()),
        ];
        self.send(py, call)?;
        Ok(name.to_string())
    }

    /// Any other request: `ri.Name(*positional, params_dict)`. `LightSource`,
    /// `AreaLightSource` and `ObjectBegin` return their handle.
    fn __getattr__(slf: Bound<'_, Self>, name: &str) -> PyResult<Py<PyAny>> {
        let py = slf.py();
        if let Some((_, rib)) = FILTERS.iter().find(|(f, _)| *f == name) {
            return Ok(rib.into_pyobject(py)?.into_any().unbind());
        }
        if name.starts_with('_') || !name.starts_with(|c: char| c.is_ascii_uppercase()) {
            return Err(pyo3::exceptions::PyAttributeError::new_err(
                name.to_string(),
            ));
        }
        let request = name.to_string();
        let me = slf.unbind();
        let f = move |args: &Bound<'_, PyTuple>,
                      _kw: Option<&Bound<'_, PyDict>>|
              -> PyResult<Py<PyAny>> {
            let py = args.py();
            let mut ri = me.borrow_mut(py);
            ri.request(py, &request, args)
        };
        Ok(pyo3::types::PyCFunction::new_closure(py, None, None, f)?
            .into_any()
            .unbind())
    }
}

impl Ri {
    fn request(
        &mut self,
        py: Python<'_>,
        name: &str,
        args: &Bound<'_, PyTuple>,
    ) -> PyResult<Py<PyAny>> {
        let mut call = Call::new(name);
        let mut positional: Vec<Bound<'_, PyAny>> = args.iter().collect();
        let params = match positional.last() {
            Some(last) if last.is_instance_of::<PyDict>() => positional.pop(),
            _ => None,
        };
        if COUNT_ONLY.contains(&name)
            && positional
                .first()
                .is_some_and(|a| a.extract::<i64>().is_ok())
        {
            positional.remove(0);
        }
        let mut handle = None;
        if matches!(name, "LightSource" | "AreaLightSource" | "ObjectBegin") {
            let h = self.session.as_mut().map_or(0, |s| s.new_handle());
            handle = Some(h);
            let at = usize::from(name != "ObjectBegin");
            positional.insert(at.min(positional.len()), h.into_pyobject(py)?.into_any());
        }
        for a in &positional {
            call.args.push(convert::arg(a)?);
        }
        if let Some(dict) = params {
            let dict = dict.cast::<PyDict>()?;
            for (k, v) in dict.iter() {
                let token: String = k.extract()?;
                let decl = match &self.session {
                    Some(s) => s.declaration(&token),
                    None => Err(String::new()),
                };
                match decl {
                    Ok(d) => call.params.push((token, convert::param(&v, d.ty)?)),
                    Err(m) if !m.is_empty() => call.problems.push(RiError::new(
                        illume_session::errors::RIE_BADTOKEN,
                        illume_session::errors::RIE_ERROR,
                        format!("Ri{name}: {m} (skipped)"),
                    )),
                    Err(_) => {}
                }
            }
        }
        self.send(py, call)?;
        Ok(match handle {
            Some(h) => h.into_pyobject(py)?.into_any().unbind(),
            None => py.None(),
        })
    }

    fn send(&mut self, py: Python<'_>, call: Call) -> PyResult<()> {
        let errors = match &mut self.session {
            Some(s) => {
                s.send(call);
                s.take_errors()
            }
            None => vec![not_started(&call.name)],
        };
        self.dispatch(py, errors)
    }

    /// Hands problems to the Python handler (or stderr); a handler's exception propagates.
    fn dispatch(&mut self, py: Python<'_>, errors: Vec<RiError>) -> PyResult<()> {
        for e in errors {
            self.errors.push((e.code, e.severity, e.message.clone()));
            match &self.handler {
                Some(h) => {
                    h.call1(py, (e.code, e.severity, e.message))?;
                }
                None => eprintln!("illume: {}", e.message),
            }
        }
        Ok(())
    }
}

fn not_started(name: &str) -> RiError {
    RiError::new(
        illume_session::errors::RIE_NOTSTARTED,
        illume_session::errors::RIE_ERROR,
        format!("Ri{name}: called before Begin (ignored)"),
    )
}

/// Renders RIB (a file name or the RIB text) and returns the last frame as a float32 numpy
/// array of shape (height, width, 4), premultiplied RGBA, top row first.
#[pyfunction]
fn render(py: Python<'_>, source: &str) -> PyResult<Py<PyAny>> {
    let source = source.to_string();
    let (mut frames, errors) = py.detach(|| illume_session::render_rib(&source));
    for e in &errors {
        eprintln!("illume: {}", e.message);
    }
    let Some(frame) = frames.pop() else {
        return Err(PyRuntimeError::new_err(format!(
            "no frame rendered{}",
            errors
                .first()
                .map_or(String::new(), |e| format!(": {}", e.message))
        )));
    };
    let bytes: Vec<u8> = frame.rgba.iter().flat_map(|f| f.to_le_bytes()).collect();
    let numpy = py.import("numpy")?;
    let array = numpy.call_method1("frombuffer", (pyo3::types::PyBytes::new(py, &bytes), "<f4"))?;
    let shaped = array.call_method1("reshape", ((frame.height, frame.width, 4),))?;
    Ok(shaped.call_method0("copy")?.unbind())
}

#[pymodule]
#[pyo3(name = "illume")]
fn illume_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Ri>()?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    Ok(())
}
