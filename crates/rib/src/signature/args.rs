//! The cursor [`Args`] over the arguments of one request, and the lenient coercions of the
//! module docs: `N` scalars or one `[N]` array, a lone scalar for an array, integral floats
//! for integers.
use super::{integral, Arg, Res};
use crate::request::{BasisSpec, Handle, Param, ParamList, Value};

/// A cursor over the arguments of one request.
pub(super) struct Args {
    pub(super) items: std::iter::Peekable<std::vec::IntoIter<Arg>>,
}

impl Args {
    pub(super) fn found(&mut self) -> String {
        self.items
            .peek()
            .map_or_else(|| "end of request".to_string(), Arg::describe)
    }

    pub(super) fn next_or(&mut self, expected: &str) -> Res<Arg> {
        match self.items.next() {
            Some(a) => Ok(a),
            None => Err(format!("expected {expected}, found end of request")),
        }
    }

    /// `N` numbers as `N` scalars or one `[N]` array.
    pub(super) fn floats<const N: usize>(&mut self) -> Res<[f32; N]> {
        let mut out = [0f32; N];
        if let Some(Arg::Array(v)) = self.items.peek() {
            let found = v.len();
            let floats = v.as_floats().filter(|f| f.len() == N);
            return match floats {
                Some(f) => {
                    self.items.next();
                    out.copy_from_slice(&f);
                    Ok(out)
                }
                None if matches!(v, Value::Strings(_)) => Err(format!(
                    "expected {N} numbers, found array of {found} strings"
                )),
                None => Err(format!("expected {N} numbers, found array of {found}")),
            };
        }
        for (k, slot) in out.iter_mut().enumerate() {
            match self.items.peek().and_then(Arg::number) {
                Some(f) => {
                    *slot = f;
                    self.items.next();
                }
                None if N == 1 => return Err(format!("expected a number, found {}", self.found())),
                None => return Err(format!("expected {N} numbers, found {k}")),
            }
        }
        Ok(out)
    }

    pub(super) fn float(&mut self) -> Res<f32> {
        Ok(self.floats::<1>()?[0])
    }

    pub(super) fn int(&mut self) -> Res<i32> {
        let found = self.found();
        match self.items.peek() {
            Some(&Arg::Int(i)) => {
                self.items.next();
                Ok(i)
            }
            Some(&Arg::Float(f)) if integral(f).is_some() => {
                self.items.next();
                Ok(integral(f).unwrap_or_default())
            }
            _ => Err(format!("expected an integer, found {found}")),
        }
    }

    pub(super) fn bool(&mut self) -> Res<bool> {
        Ok(self.int()? != 0)
    }

    pub(super) fn string(&mut self) -> Res<String> {
        let found = self.found();
        match self.next_or("a string")? {
            Arg::Str(s) => Ok(s),
            Arg::Array(Value::Strings(mut v)) if v.len() == 1 => Ok(v.pop().unwrap_or_default()),
            _ => Err(format!("expected a string, found {found}")),
        }
    }

    pub(super) fn handle(&mut self) -> Res<Handle> {
        let found = self.found();
        match self.next_or("a handle (number or string)")? {
            Arg::Int(i) => Ok(Handle::Int(i)),
            Arg::Float(f) if integral(f).is_some() => Ok(Handle::Int(integral(f).unwrap_or(0))),
            Arg::Str(s) => Ok(Handle::Str(s)),
            _ => Err(format!(
                "expected a handle (number or string), found {found}"
            )),
        }
    }

    pub(super) fn int_array(&mut self) -> Res<Vec<i32>> {
        let found = self.found();
        let bad = || format!("expected an array of integers, found {found}");
        match self.next_or("an array of integers")? {
            Arg::Int(i) => Ok(vec![i]),
            Arg::Array(Value::Ints(v)) => Ok(v),
            Arg::Array(Value::Floats(v)) => {
                v.iter().map(|&f| integral(f).ok_or_else(bad)).collect()
            }
            _ => Err(bad()),
        }
    }

    pub(super) fn float_array(&mut self) -> Res<Vec<f32>> {
        let found = self.found();
        match self.next_or("an array of numbers")? {
            Arg::Int(i) => Ok(vec![i as f32]),
            Arg::Float(f) => Ok(vec![f]),
            Arg::Array(Value::Floats(v)) => Ok(v),
            Arg::Array(Value::Ints(v)) => Ok(v.into_iter().map(|i| i as f32).collect()),
            _ => Err(format!("expected an array of numbers, found {found}")),
        }
    }

    pub(super) fn string_array(&mut self) -> Res<Vec<String>> {
        let found = self.found();
        match self.next_or("an array of strings")? {
            Arg::Str(s) => Ok(vec![s]),
            Arg::Array(Value::Strings(v)) => Ok(v),
            Arg::Array(v) if v.is_empty() => Ok(Vec::new()),
            _ => Err(format!("expected an array of strings, found {found}")),
        }
    }

    /// Every number up to the parameter list, as one array or as scalars (`Color`, `MotionBegin`).
    pub(super) fn float_list(&mut self) -> Res<Vec<f32>> {
        if let Some(Arg::Array(_)) = self.items.peek() {
            return self.float_array();
        }
        let mut out = Vec::new();
        while let Some(f) = self.items.peek().and_then(Arg::number) {
            out.push(f);
            self.items.next();
        }
        if out.is_empty() {
            return Err(format!("expected numbers, found {}", self.found()));
        }
        Ok(out)
    }

    pub(super) fn basis(&mut self) -> Res<BasisSpec> {
        match self.items.peek() {
            Some(Arg::Str(_)) => Ok(BasisSpec::Named(self.string()?)),
            Some(Arg::Array(Value::Strings(_))) => Ok(BasisSpec::Named(self.string()?)),
            Some(Arg::Array(_)) => Ok(BasisSpec::Matrix(self.floats::<16>()?)),
            _ => Err(format!(
                "expected a basis name or 16 numbers, found {}",
                self.found()
            )),
        }
    }

    /// `"name" value` pairs to the end of the request.
    pub(super) fn params(&mut self) -> Res<ParamList> {
        let mut out = Vec::new();
        while let Some(arg) = self.items.next() {
            let name = match arg {
                Arg::Str(s) => s,
                Arg::Array(Value::Strings(mut v)) if v.len() == 1 => v.pop().unwrap_or_default(),
                other => {
                    return Err(format!(
                        "expected a parameter name, found {}",
                        other.describe()
                    ))
                }
            };
            match self.items.next() {
                Some(v) => out.push(Param {
                    name,
                    value: v.into_value(),
                }),
                None => return Err(format!("parameter \"{name}\" has no value")),
            }
        }
        Ok(out)
    }

    pub(super) fn end(&mut self) -> Res<()> {
        match self.items.next() {
            None => Ok(()),
            Some(a) => Err(format!("unexpected extra argument: {}", a.describe())),
        }
    }
}
