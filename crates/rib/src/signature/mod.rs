//! The argument signature of every request (RI Spec 3.2 chapter "RIB binding"), in both
//! directions: [`build`] turns the arguments read after a request name into a typed
//! [`Request`], and [`emit`] walks a `Request` back into arguments for the ASCII and binary
//! writers. Keeping both in one module keeps them each other's inverse.
//!
//! Leniency follows PRMan and real exporters: wherever the spec has N numbers, `N` scalars and
//! one `[N]` array are both accepted; where it has an array, a lone scalar is accepted; integral
//! floats are accepted for integers.
//!
//! The module is split by concept: this file holds the argument type shared by both
//! directions, [`args`] the cursor that coerces arguments leniently, [`build`] the requests
//! built from arguments, [`sink`] the writer interface and [`emit`] the requests written back.
use crate::request::Value;

mod args;
mod build;
mod emit;
mod sink;

pub(crate) use build::build;
pub(crate) use emit::emit;
pub(crate) use sink::Sink;

/// One argument as read: a scalar or a bracketed (or binary) array.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Arg {
    Int(i32),
    Float(f32),
    Str(String),
    Array(Value),
}

impl Arg {
    fn describe(&self) -> String {
        match self {
            Arg::Int(i) => format!("number {i}"),
            Arg::Float(f) => format!("number {f}"),
            Arg::Str(s) => format!("string \"{}\"", s.escape_debug()),
            Arg::Array(Value::Strings(v)) => format!("array of {} strings", v.len()),
            Arg::Array(v) => format!("array of {} numbers", v.len()),
        }
    }

    fn number(&self) -> Option<f32> {
        match *self {
            Arg::Int(i) => Some(i as f32),
            Arg::Float(f) => Some(f),
            _ => None,
        }
    }

    /// The argument as a parameter value: a bare scalar is a one-element array.
    pub(crate) fn into_value(self) -> Value {
        match self {
            Arg::Int(i) => Value::Ints(vec![i]),
            Arg::Float(f) => Value::Floats(vec![f]),
            Arg::Str(s) => Value::Strings(vec![s]),
            Arg::Array(v) => v,
        }
    }
}

/// Why the arguments do not fit the request.
#[derive(Debug, PartialEq)]
pub(crate) enum SignatureError {
    /// Not a request of RI 3.2: the caller warns and keeps the arguments.
    Unknown(Vec<Arg>),
    Bad(String),
}

impl From<String> for SignatureError {
    fn from(s: String) -> Self {
        SignatureError::Bad(s)
    }
}

type Res<T> = Result<T, String>;

fn integral(f: f32) -> Option<i32> {
    (f.fract() == 0.0 && f.abs() <= i32::MAX as f32).then_some(f as i32)
}
