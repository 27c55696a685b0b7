//! The grid value model: every Shading Language value is either *uniform* (one value for the
//! whole grid, computed once) or *varying* (one value per grid point, structure of arrays).
//! Operations on uniform operands stay uniform, so uniform work runs once per grid (RI 3.2 §11.1).
use glam::{DMat4, Vec3};
use std::sync::Arc;

/// One quantity over a grid: a single value shared by every point, or one value per point.
/// The per-point values are shared (`Arc`): reading a variable, passing it to a built-in or
/// assigning it whole costs a reference count, not a copy; writers copy only when the lanes
/// are shared ([`Slot::lanes_mut`]), and operators reuse a temporary's lanes in place.
#[derive(Clone, Debug, PartialEq)]
pub enum Slot<T> {
    Uniform(T),
    Varying(Arc<Vec<T>>),
}

impl<T: Clone> Slot<T> {
    /// Per-point values.
    pub fn varying(v: Vec<T>) -> Slot<T> {
        Slot::Varying(Arc::new(v))
    }

    /// The value at grid point `i` (the shared value when uniform).
    #[inline]
    pub fn at(&self, i: usize) -> &T {
        match self {
            Slot::Uniform(x) => x,
            Slot::Varying(v) => &v[i],
        }
    }

    pub fn is_uniform(&self) -> bool {
        matches!(self, Slot::Uniform(_))
    }

    /// The per-point values, expanding a uniform value to `n` copies.
    pub fn to_varying(&self, n: usize) -> Vec<T> {
        match self {
            Slot::Uniform(x) => vec![x.clone(); n],
            Slot::Varying(v) => v.to_vec(),
        }
    }

    /// The per-point values for writing: a uniform value expanded to `n` copies, shared lanes
    /// copied first (copy on write), unshared ones written in place.
    pub fn lanes_mut(&mut self, n: usize) -> &mut Vec<T> {
        if let Slot::Uniform(x) = self {
            *self = Slot::varying(vec![x.clone(); n]);
        }
        match self {
            Slot::Varying(v) => Arc::make_mut(v),
            Slot::Uniform(_) => unreachable!("made varying above"),
        }
    }

    /// `f` applied point by point; uniform in, uniform out (evaluated once).
    pub fn map<R>(&self, f: impl Fn(&T) -> R) -> Slot<R> {
        match self {
            Slot::Uniform(x) => Slot::Uniform(f(x)),
            Slot::Varying(v) => Slot::Varying(Arc::new(v.iter().map(f).collect())),
        }
    }

    /// `f` applied point by point to a value of the same type, in place when the lanes are
    /// not shared (a temporary of the expression being evaluated): no allocation then.
    pub fn map_owned(self, f: impl Fn(&T) -> T) -> Slot<T> {
        match self {
            Slot::Uniform(x) => Slot::Uniform(f(&x)),
            Slot::Varying(mut v) => match Arc::get_mut(&mut v) {
                Some(lanes) => {
                    for x in lanes.iter_mut() {
                        *x = f(x);
                    }
                    Slot::Varying(v)
                }
                None => Slot::Varying(Arc::new(v.iter().map(f).collect())),
            },
        }
    }

    /// Writes `src` into `self` at the points `mask` runs (all points when `mask` is `None`):
    /// the masked assignment of a varying conditional. A uniform target written under a partial
    /// mask, or from a varying source, becomes varying.
    pub fn assign(&mut self, src: &Slot<T>, mask: Option<&Mask>, n: usize) {
        match (mask, src) {
            (None, _) => *self = src.clone(),
            (Some(m), _) if m.all() => *self = src.clone(),
            (Some(m), _) => {
                let dst = self.lanes_mut(n);
                for i in m.active() {
                    dst[i] = src.at(i).clone();
                }
            }
        }
    }
}

/// `f(a, b)` point by point: uniform only when both operands are. The uniform/varying cases
/// are split outside the loop so each loop is a plain pass over slices.
pub fn zip2<A: Clone, B: Clone, R>(
    a: &Slot<A>,
    b: &Slot<B>,
    n: usize,
    f: impl Fn(&A, &B) -> R,
) -> Slot<R> {
    Slot::Varying(Arc::new(match (a, b) {
        (Slot::Uniform(x), Slot::Uniform(y)) => return Slot::Uniform(f(x, y)),
        (Slot::Varying(x), Slot::Varying(y)) => {
            x[..n].iter().zip(&y[..n]).map(|(x, y)| f(x, y)).collect()
        }
        (Slot::Varying(x), Slot::Uniform(y)) => x[..n].iter().map(|x| f(x, y)).collect(),
        (Slot::Uniform(x), Slot::Varying(y)) => y[..n].iter().map(|y| f(x, y)).collect(),
    }))
}

/// `a = f(a, b)` point by point, writing into `a`'s lanes when they are not shared (a
/// temporary): the operators' path that allocates nothing.
pub fn zip2_owned<A: Clone, B: Clone>(
    a: Slot<A>,
    b: &Slot<B>,
    n: usize,
    f: impl Fn(&A, &B) -> A,
) -> Slot<A> {
    match a {
        Slot::Varying(mut x) => match Arc::get_mut(&mut x) {
            Some(lanes) => {
                match b {
                    Slot::Uniform(y) => lanes[..n].iter_mut().for_each(|x| *x = f(x, y)),
                    Slot::Varying(y) => lanes[..n]
                        .iter_mut()
                        .zip(&y[..n])
                        .for_each(|(x, y)| *x = f(x, y)),
                }
                Slot::Varying(x)
            }
            None => zip2(&Slot::Varying(x), b, n, f),
        },
        a => zip2(&a, b, n, f),
    }
}

/// `f(a, b, c)` point by point: uniform only when every operand is.
pub fn zip3<A: Clone, B: Clone, C: Clone, R>(
    a: &Slot<A>,
    b: &Slot<B>,
    c: &Slot<C>,
    n: usize,
    f: impl Fn(&A, &B, &C) -> R,
) -> Slot<R> {
    match (a, b, c) {
        (Slot::Uniform(x), Slot::Uniform(y), Slot::Uniform(z)) => Slot::Uniform(f(x, y, z)),
        _ => Slot::Varying(Arc::new(
            (0..n).map(|i| f(a.at(i), b.at(i), c.at(i))).collect(),
        )),
    }
}

/// A Shading Language value over a grid. `color`, `point`, `vector` and `normal` share one
/// representation (three floats); the checked AST knows which it is. Matrices are `f64`
/// (DESIGN.md: transforms in `f64`), stored in glam's column-vector convention: the SL
/// `transform(m, p)` (`p·m` with row vectors) is `m.transform_point3(p)` here.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Float(Slot<f32>),
    Triple(Slot<Vec3>),
    Matrix(Slot<DMat4>),
    String(Slot<Arc<str>>),
    Array(Vec<Value>),
    /// The value of a `void` expression (a call to a function returning nothing).
    Void,
}

impl Value {
    pub fn float(x: f32) -> Value {
        Value::Float(Slot::Uniform(x))
    }

    pub fn triple(x: Vec3) -> Value {
        Value::Triple(Slot::Uniform(x))
    }

    pub fn string(s: &str) -> Value {
        Value::String(Slot::Uniform(Arc::from(s)))
    }

    /// True when the whole value is one per grid (arrays: every element).
    pub fn is_uniform(&self) -> bool {
        match self {
            Value::Float(s) => s.is_uniform(),
            Value::Triple(s) => s.is_uniform(),
            Value::Matrix(s) => s.is_uniform(),
            Value::String(s) => s.is_uniform(),
            Value::Array(a) => a.iter().all(Value::is_uniform),
            Value::Void => true,
        }
    }

    /// The float slot, promoting nothing (the checker made promotions explicit).
    pub fn as_float(&self) -> Option<&Slot<f32>> {
        match self {
            Value::Float(s) => Some(s),
            _ => None,
        }
    }

    pub fn as_triple(&self) -> Option<&Slot<Vec3>> {
        match self {
            Value::Triple(s) => Some(s),
            _ => None,
        }
    }

    pub fn as_matrix(&self) -> Option<&Slot<DMat4>> {
        match self {
            Value::Matrix(s) => Some(s),
            _ => None,
        }
    }

    pub fn as_string(&self) -> Option<&Slot<Arc<str>>> {
        match self {
            Value::String(s) => Some(s),
            _ => None,
        }
    }

    /// Masked assignment (see [`Slot::assign`]); arrays element by element. Values of different
    /// kinds replace the target outright (the checker rules that out for well-typed programs).
    pub fn assign(&mut self, src: &Value, mask: Option<&Mask>, n: usize) {
        match (self, src) {
            (Value::Float(d), Value::Float(s)) => d.assign(s, mask, n),
            (Value::Triple(d), Value::Triple(s)) => d.assign(s, mask, n),
            (Value::Matrix(d), Value::Matrix(s)) => d.assign(s, mask, n),
            (Value::String(d), Value::String(s)) => d.assign(s, mask, n),
            (Value::Array(d), Value::Array(s)) if d.len() == s.len() => {
                for (d, s) in d.iter_mut().zip(s) {
                    d.assign(s, mask, n);
                }
            }
            (d, s) => *d = s.clone(),
        }
    }
}

/// The running state of a grid: which points execute the current statement (RI 3.2 §11.1: a
/// varying `if`, loop or `illuminance` runs its body only at the points where it holds).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mask {
    bits: Vec<bool>,
    count: usize,
}

impl Mask {
    /// Every point of an `n`-point grid running.
    pub fn all_on(n: usize) -> Mask {
        Mask {
            bits: vec![true; n],
            count: n,
        }
    }

    pub fn from_bits(bits: Vec<bool>) -> Mask {
        let count = bits.iter().filter(|&&b| b).count();
        Mask { bits, count }
    }

    /// The points of `self` where the varying condition `cond` holds (non-zero), and the
    /// points where it does not: the two branches of an `if`/`else`.
    pub fn split(&self, cond: &Slot<f32>) -> (Mask, Mask) {
        let on: Vec<bool> = (0..self.bits.len())
            .map(|i| self.bits[i] && *cond.at(i) != 0.0)
            .collect();
        let off: Vec<bool> = (0..self.bits.len())
            .map(|i| self.bits[i] && *cond.at(i) == 0.0)
            .collect();
        (Mask::from_bits(on), Mask::from_bits(off))
    }

    /// `self` without the points of `other` (a `break` or `continue` retires them).
    pub fn minus(&self, other: &Mask) -> Mask {
        Mask::from_bits(
            self.bits
                .iter()
                .zip(&other.bits)
                .map(|(&a, &b)| a && !b)
                .collect(),
        )
    }

    /// Points in either mask.
    pub fn union(&self, other: &Mask) -> Mask {
        Mask::from_bits(
            self.bits
                .iter()
                .zip(&other.bits)
                .map(|(&a, &b)| a || b)
                .collect(),
        )
    }

    pub fn len(&self) -> usize {
        self.bits.len()
    }

    pub fn is_empty(&self) -> bool {
        self.bits.is_empty()
    }

    /// Whether point `i` runs.
    #[inline]
    pub fn get(&self, i: usize) -> bool {
        self.bits[i]
    }

    /// How many points run.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Every point runs.
    pub fn all(&self) -> bool {
        self.count == self.bits.len()
    }

    /// No point runs: the statement is skipped entirely.
    pub fn none(&self) -> bool {
        self.count == 0
    }

    /// The indices of the running points.
    pub fn active(&self) -> impl Iterator<Item = usize> + '_ {
        self.bits
            .iter()
            .enumerate()
            .filter(|(_, &b)| b)
            .map(|(i, _)| i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_operands_stay_uniform() {
        let a = Slot::Uniform(2.0f32);
        let b = Slot::Uniform(3.0f32);
        assert_eq!(zip2(&a, &b, 100, |x, y| x * y), Slot::Uniform(6.0));
        let c = Slot::varying(vec![1.0f32, 2.0]);
        assert_eq!(zip2(&a, &c, 2, |x, y| x * y), Slot::varying(vec![2.0, 4.0]));
    }

    #[test]
    fn masked_assignment_touches_only_running_points() {
        let mut x = Value::float(0.0);
        let mask = Mask::from_bits(vec![true, false, true]);
        x.assign(&Value::float(5.0), Some(&mask), 3);
        assert_eq!(x, Value::Float(Slot::varying(vec![5.0, 0.0, 5.0])));
        // A full mask keeps a uniform assignment uniform.
        let mut y = Value::float(0.0);
        y.assign(&Value::float(5.0), Some(&Mask::all_on(3)), 3);
        assert_eq!(y, Value::float(5.0));
    }

    #[test]
    fn split_partitions_the_running_points() {
        let m = Mask::from_bits(vec![true, true, false, true]);
        let cond = Slot::varying(vec![1.0, 0.0, 1.0, 2.0]);
        let (on, off) = m.split(&cond);
        assert_eq!(on.active().collect::<Vec<_>>(), vec![0, 3]);
        assert_eq!(off.active().collect::<Vec<_>>(), vec![1]);
        assert_eq!(on.union(&off), m);
        assert_eq!(m.minus(&on), off);
    }
}
