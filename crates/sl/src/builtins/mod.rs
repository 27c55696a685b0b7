//! The built-in function table (RI Specification 3.2, chapter 15, plus the message-passing and
//! renderer-information calls), with every overload.
//!
//! Written as one compact text table — one overload per line, `ret name(params)` — because
//! the spec's own function list reads that way and a reviewer can compare the two line by line.
//! Type letters:
//!
//! | letter | meaning |
//! |---|---|
//! | `f c p v n m s` | float, color, point, vector, normal, matrix, string |
//! | `V` | void (return only) |
//! | `T` | one of float/color/point/vector/normal, the same at every `T` of the overload |
//! | `G` | one of point/vector/normal, the same at every `G` |
//! | `R` | return type chosen from context: float, color, point or vector (`noise`, …) |
//! | `A` | any type, taken from the argument (message passing's result variable) |
//! | `*` | any type (printf/format arguments) |
//!
//! Prefix `o` marks an `output` parameter, suffix `[]` an array of any length, suffix `...`
//! a last parameter that may appear any number of times, including none (so `min(f,f,f...)`
//! takes two or more floats and `spline(f,T,T,T,T,T...)` four or more knots), and a trailing
//! `~` after the
//! parameter list allows `"name", value` optional-parameter pairs.
//!
//! `transform` takes any geometric type and keeps it (a normal is transformed as a normal, as
//! PRMan and Aqsis do) rather than RI 3.2's point-only form, so `transform ("world", N)` does
//! not silently turn a normal into a point; `vtransform`/`ntransform` remain.
//!
//! The ray-tracing calls follow BMRT (`trace`, `visibility` as float or colour,
//! `rayhittest`, `fulltrace`) and PRMan 11 (`transmission`, `occlusion(P, N, samples)` with
//! optional `"maxdist"`).
//!
//! `arraylength` (PRMan's, not RI 3.2's) is included because functions taking `float a[]`
//! need it to loop over their argument.
//!
//! Built-ins that are inherently varying (they read the grid or the lights, e.g. `diffuse`,
//! `Du`, `noise` of a varying point is varying anyway) are listed in
//! [`BuiltinId::is_inherently_varying`].
//!
//! Each table line's name is resolved to its [`BuiltinId`] when the table is parsed, so the
//! checker resolves a call's name once and the executor dispatches on the id.

mod id;

pub use id::{BuiltinId, Family};

use crate::types::BaseType;
use std::sync::OnceLock;

/// A parameter or return slot of a table overload.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// A concrete type.
    Fixed(BaseType),
    /// `T`: float or triple, bound per call.
    Generic,
    /// `G`: point/vector/normal, bound per call.
    Geometric,
    /// `R`: return chosen from context.
    ContextReturn,
    /// `A` / `*`: any type, the argument's.
    Any,
}

/// One parameter of a table overload.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParamSpec {
    /// Its type slot.
    pub slot: Slot,
    /// `o` prefix: written through.
    pub output: bool,
    /// `[]` suffix: an array of any length.
    pub array: bool,
    /// `...` suffix: may appear any number of times (including none).
    pub repeat: bool,
}

/// One overload of a built-in.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Overload {
    /// Function name.
    pub name: &'static str,
    /// The built-in this overload belongs to.
    pub id: BuiltinId,
    /// Return slot (`Fixed(Void)` for none).
    pub ret: Slot,
    /// Parameters in order.
    pub params: Vec<ParamSpec>,
    /// Optional `"name", value` pairs may follow the parameters.
    pub pairs: bool,
}

/// The table (see the module documentation for the notation).
const TABLE: &str = "
f radians(f)
f degrees(f)
f sin(f)
f asin(f)
f cos(f)
f acos(f)
f tan(f)
f atan(f)
f atan(f,f)
f pow(f,f)
T pow(T,T)
f exp(f)
T exp(T)
f sqrt(f)
T sqrt(T)
f inversesqrt(f)
f log(f)
f log(f,f)
f mod(f,f)
T mod(T,T)
f abs(f)
T abs(T)
f sign(f)
f floor(f)
T floor(T)
f ceil(f)
T ceil(T)
f round(f)
T round(T)
f min(f,f,f...)
T min(T,T,T...)
f max(f,f,f...)
T max(T,T,T...)
f clamp(f,f,f)
T clamp(T,T,T)
f mix(f,f,f)
T mix(T,T,f)
T mix(T,T,T)
f step(f,f)
f smoothstep(f,f,f)
f filterstep(f,f)~
f filterstep(f,f,f)~
T spline(f,T,T,T,T,T...)
T spline(s,f,T,T,T,T,T...)
T spline(f,T[])
T spline(s,f,T[])
R noise(f)
R noise(f,f)
R noise(p)
R noise(p,f)
R pnoise(f,f)
R pnoise(f,f,f,f)
R pnoise(p,p)
R pnoise(p,f,p,f)
R cellnoise(f)
R cellnoise(f,f)
R cellnoise(p)
R cellnoise(p,f)
R random()
f xcomp(G)
f ycomp(G)
f zcomp(G)
V setxcomp(oG,f)
V setycomp(oG,f)
V setzcomp(oG,f)
f comp(c,f)
f comp(G,f)
f comp(m,f,f)
V setcomp(oc,f,f)
V setcomp(oG,f,f)
V setcomp(om,f,f,f)
f length(v)
v normalize(v)
n normalize(n)
f distance(p,p)
f ptlined(p,p,p)
p rotate(p,f,p,p)
f area(p)
G faceforward(G,v)
G faceforward(G,v,v)
v reflect(v,v)
v refract(v,v,f)
V fresnel(v,n,f,of,of)
V fresnel(v,n,f,of,of,ov,ov)
G transform(s,G)
G transform(s,s,G)
G transform(m,G)
G transform(s,m,G)
v vtransform(s,v)
v vtransform(s,s,v)
v vtransform(m,v)
v vtransform(s,m,v)
n ntransform(s,n)
n ntransform(s,s,n)
n ntransform(m,n)
n ntransform(s,m,n)
f depth(p)
n calculatenormal(p)
c ctransform(s,c)
c ctransform(s,s,c)
f determinant(m)
m translate(m,v)
m rotate(m,f,v)
m scale(m,p)
s concat(s,s...)
V printf(s,*...)
s format(s,*...)
f match(s,s)
c ambient()
c diffuse(n)
c specular(n,v,f)
c specularbrdf(v,n,v,f)
c phong(n,v,f)
c trace(p,v)
R visibility(p,p)
f rayhittest(p,v,op,on)
c fulltrace(p,v,of,op,on,op,ov)
c transmission(p,p)~
f occlusion(p,n,f)~
f textureinfo(s,s,oA)
f surface(s,oA)
f displacement(s,oA)
f lightsource(s,oA)
f atmosphere(s,oA)
f incident(s,oA)
f opposite(s,oA)
f attribute(s,oA)
f option(s,oA)
f rendererinfo(s,oA)
T Du(T)
T Dv(T)
T Deriv(T,f)
f arraylength(A[])
";

fn parse_slot(s: &str) -> Slot {
    match s {
        "f" => Slot::Fixed(BaseType::Float),
        "c" => Slot::Fixed(BaseType::Color),
        "p" => Slot::Fixed(BaseType::Point),
        "v" => Slot::Fixed(BaseType::Vector),
        "n" => Slot::Fixed(BaseType::Normal),
        "m" => Slot::Fixed(BaseType::Matrix),
        "s" => Slot::Fixed(BaseType::String),
        "V" => Slot::Fixed(BaseType::Void),
        "T" => Slot::Generic,
        "G" => Slot::Geometric,
        "R" => Slot::ContextReturn,
        _ => Slot::Any, // "A", "*"
    }
}

fn parse_line(line: &'static str) -> Option<Overload> {
    let (ret, rest) = line.split_once(' ')?;
    let (name, rest) = rest.split_once('(')?;
    let (params, tail) = rest.split_once(')')?;
    let params = params
        .split(',')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let output = p.starts_with('o');
            let p = p.trim_start_matches('o');
            let repeat = p.ends_with("...");
            let p = p.trim_end_matches("...");
            let array = p.ends_with("[]");
            let p = p.trim_end_matches("[]");
            ParamSpec {
                slot: parse_slot(p),
                output,
                array,
                repeat,
            }
        })
        .collect();
    Some(Overload {
        id: BuiltinId::from_name(name)?,
        name,
        ret: parse_slot(ret),
        params,
        pairs: tail.contains('~'),
    })
}

/// Every overload in the table.
pub fn all() -> &'static [Overload] {
    static CELL: OnceLock<Vec<Overload>> = OnceLock::new();
    CELL.get_or_init(|| TABLE.lines().filter_map(parse_line).collect())
}

/// The overloads of one name (empty if it is not a built-in).
pub fn overloads(name: &str) -> impl Iterator<Item = &'static Overload> + '_ {
    all().iter().filter(move |o| o.name == name)
}

/// The overloads of one built-in, in table order.
pub fn overloads_of(id: BuiltinId) -> impl Iterator<Item = &'static Overload> {
    all().iter().filter(move |o| o.id == id)
}

/// True when `name` is a built-in function (including the texture family, which the parser
/// turns into [`crate::ast::TextureCall`]).
pub fn is_builtin(name: &str) -> bool {
    BuiltinId::from_name(name).is_some()
        || matches!(name, "texture" | "environment" | "shadow" | "bump")
}

/// The value of the predeclared constant `PI`.
pub const PI: f64 = std::f64::consts::PI;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_table_line_parses() {
        let lines = TABLE.lines().filter(|l| !l.trim().is_empty()).count();
        assert_eq!(all().len(), lines);
    }

    #[test]
    fn every_id_has_an_overload_and_every_overload_its_id() {
        for &id in BuiltinId::ALL {
            assert!(overloads_of(id).next().is_some(), "{id:?} has no overload");
        }
        assert!(all().iter().all(|o| o.id.name() == o.name));
    }

    #[test]
    fn fresnel_has_its_two_output_forms() {
        let f: Vec<_> = overloads("fresnel").collect();
        assert_eq!(f.len(), 2);
        assert_eq!(f[1].params.iter().filter(|p| p.output).count(), 4);
        assert!(f[1].params[6].output && f[1].params[6].slot == Slot::Fixed(BaseType::Vector));
    }

    #[test]
    fn spline_knots_repeat_and_filterstep_takes_pairs() {
        let s = overloads("spline").next().unwrap();
        assert!(s.params.last().unwrap().repeat);
        assert!(overloads("filterstep").all(|o| o.pairs));
        assert!(overloads("spline").any(|o| o.params.iter().any(|p| p.array)));
    }
}
