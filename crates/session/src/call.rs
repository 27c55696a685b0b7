//! One Ri call as data: the request name, its positional arguments and its parameter list,
//! printed as a RIB line for the parser (one grammar for files and programs).
use crate::RiError;
use std::fmt::Write as _;

/// A positional argument as the C or Python binding received it.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    Float(f32),
    Int(i32),
    Str(String),
    Floats(Vec<f32>),
    Ints(Vec<i32>),
    Strings(Vec<String>),
}

/// A parameter's values, sized by its declaration and the primitive's [`Counts`].
#[derive(Clone, Debug, PartialEq)]
pub enum ParamData {
    Floats(Vec<f32>),
    Ints(Vec<i32>),
    Strings(Vec<String>),
}

/// How many values each storage class carries on a primitive (RI Spec 3.2 §5): `constant`
/// is always 1. `facevertex` uses `facevarying`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Counts {
    pub uniform: usize,
    pub varying: usize,
    pub vertex: usize,
    pub facevarying: usize,
}

impl Counts {
    /// Requests that are not primitives: every class holds one value.
    pub const ONE: Counts = Counts {
        uniform: 1,
        varying: 1,
        vertex: 1,
        facevarying: 1,
    };

    /// Values a parameter of `class` carries.
    pub fn of(&self, class: illume_rib::Class) -> usize {
        use illume_rib::Class::*;
        match class {
            Constant => 1,
            Uniform => self.uniform,
            Varying => self.varying,
            Vertex => self.vertex,
            FaceVarying | FaceVertex => self.facevarying,
        }
    }
}

/// One call: `Sphere 1 -1 1 360 "Cs" [1 0 0]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Call {
    /// The request name as RIB spells it (`Sphere`, `PointsPolygons`).
    pub name: String,
    pub args: Vec<Arg>,
    pub params: Vec<(String, ParamData)>,
    /// Problems found while collecting the call (skipped parameters); reported with it.
    pub problems: Vec<RiError>,
}

impl Call {
    pub fn new(name: &str) -> Call {
        Call {
            name: name.to_string(),
            ..Call::default()
        }
    }

    /// The call as one line of ASCII RIB.
    pub fn to_rib(&self) -> String {
        let mut s = self.name.clone();
        for a in &self.args {
            s.push(' ');
            match a {
                Arg::Float(f) => float(&mut s, *f),
                Arg::Int(i) => {
                    let _ = write!(s, "{i}");
                }
                Arg::Str(t) => string(&mut s, t),
                Arg::Floats(v) => array(&mut s, v, |s, f| float(s, *f)),
                Arg::Ints(v) => array(&mut s, v, |s, i| {
                    let _ = write!(s, "{i}");
                }),
                Arg::Strings(v) => array(&mut s, v, |s, t| string(s, t)),
            }
        }
        for (token, data) in &self.params {
            s.push(' ');
            string(&mut s, token);
            s.push(' ');
            match data {
                ParamData::Floats(v) => array(&mut s, v, |s, f| float(s, *f)),
                ParamData::Ints(v) => array(&mut s, v, |s, i| {
                    let _ = write!(s, "{i}");
                }),
                ParamData::Strings(v) => array(&mut s, v, |s, t| string(s, t)),
            }
        }
        s.push('\n');
        s
    }
}

/// Floats print in Rust's shortest round-trip form with a `.` or exponent, so the parser reads
/// back the same `f32` bits and never mistakes `1e30` for an integer.
fn float(s: &mut String, f: f32) {
    let _ = write!(s, "{f:?}");
}

/// A RIB string literal with C escapes (what the lexer reads back).
fn string(s: &mut String, t: &str) {
    s.push('"');
    for c in t.chars() {
        match c {
            '"' => s.push_str("\\\""),
            '\\' => s.push_str("\\\\"),
            '\n' => s.push_str("\\n"),
            '\t' => s.push_str("\\t"),
            c if (c as u32) < 0x20 => {
                let _ = write!(s, "\\{:03o}", c as u32);
            }
            c => s.push(c),
        }
    }
    s.push('"');
}

fn array<T>(s: &mut String, v: &[T], mut item: impl FnMut(&mut String, &T)) {
    s.push('[');
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        item(s, x);
    }
    s.push(']');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_round_trip_through_the_parser_bit_for_bit() {
        let values = [0.1f32, 1e30, -3.5e-20, 1.0, 16777217.0, f32::MIN_POSITIVE];
        let mut call = Call::new("Color");
        call.args.push(Arg::Floats(values[..3].to_vec()));
        let mut c2 = Call::new("Translate");
        c2.args = values[3..].iter().map(|&f| Arg::Float(f)).collect();
        for (call, want) in [(call, &values[..3]), (c2, &values[3..])] {
            let text = call.to_rib();
            let req = illume_rib::Parser::new(text.as_bytes(), "t")
                .next()
                .unwrap()
                .unwrap();
            let got: Vec<f32> = match req.value {
                illume_rib::Request::Color(c) => c,
                illume_rib::Request::Translate(t) => t.to_vec(),
                r => panic!("unexpected {r:?}"),
            };
            let bits = |v: &[f32]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(want), "{text}");
        }
    }

    #[test]
    fn strings_with_quotes_and_backslashes_survive() {
        let mut call = Call::new("Surface");
        call.args.push(Arg::Str("a\"b\\c\nd".into()));
        let req = illume_rib::Parser::new(call.to_rib().as_bytes(), "t")
            .next()
            .unwrap()
            .unwrap();
        match req.value {
            illume_rib::Request::Surface { name, .. } => assert_eq!(name, "a\"b\\c\nd"),
            r => panic!("unexpected {r:?}"),
        }
    }
}
