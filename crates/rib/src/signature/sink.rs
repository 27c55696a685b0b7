//! The writer interface [`emit`](super::emit) drives: the ASCII printer and the binary
//! writer each implement the primitive methods; the shared shapes are default methods.
use crate::request::{BasisSpec, Handle, Param, Value};
use std::io;

/// Where [`emit`] sends a request: the ASCII printer and the binary writer.
pub(crate) trait Sink {
    fn name(&mut self, name: &str) -> io::Result<()>;
    fn int(&mut self, v: i32) -> io::Result<()>;
    fn float(&mut self, v: f32) -> io::Result<()>;
    fn string(&mut self, s: &str) -> io::Result<()>;
    fn ints(&mut self, v: &[i32]) -> io::Result<()>;
    fn floats(&mut self, v: &[f32]) -> io::Result<()>;
    fn strings(&mut self, v: &[String]) -> io::Result<()>;
    fn structure(&mut self, text: &str) -> io::Result<()>;
    /// After the last argument of a request.
    fn end(&mut self) -> io::Result<()>;

    fn value(&mut self, v: &Value) -> io::Result<()> {
        match v {
            Value::Ints(v) => self.ints(v),
            Value::Floats(v) => self.floats(v),
            Value::Strings(v) => self.strings(v),
        }
    }

    /// A float array whose type the signature fixes (`Color`, `Transform`, knots): unlike a
    /// parameter value it needs no float marker, so the ASCII printer may write `1` for `1.0`.
    fn number_array(&mut self, v: &[f32]) -> io::Result<()> {
        self.floats(v)
    }

    fn scalars(&mut self, v: &[f32]) -> io::Result<()> {
        v.iter().try_for_each(|&f| self.float(f))
    }

    fn handle(&mut self, h: &Handle) -> io::Result<()> {
        match h {
            Handle::Int(i) => self.int(*i),
            Handle::Str(s) => self.string(s),
        }
    }

    fn basis(&mut self, b: &BasisSpec) -> io::Result<()> {
        match b {
            BasisSpec::Named(n) => self.string(n),
            BasisSpec::Matrix(m) => self.number_array(m),
        }
    }

    fn params(&mut self, params: &[Param]) -> io::Result<()> {
        for p in params {
            self.string(&p.name)?;
            self.value(&p.value)?;
        }
        Ok(())
    }
}
