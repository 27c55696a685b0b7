//! Variables: the frames of shader bodies and user functions, reads and masked writes of
//! variables and array elements, `output` arguments written back.

use super::Exec;
use crate::value::{Mask, Slot, Value};
use illume_sl::ast::{Expr, ExprKind, LValue, Owner, VarId, VarRef};
use illume_sl::types::Type;

impl Exec<'_> {
    pub(super) fn var_type(&self, slot: VarId) -> Type {
        let f = self.frames.last().expect("a frame runs");
        self.prog
            .vars(f.owner)
            .get(slot.0 as usize)
            .map_or(Type::FLOAT, |v| v.ty)
    }

    pub(super) fn frame_index(&self, owner: Owner) -> Option<usize> {
        self.frames.iter().rposition(|f| f.owner == owner)
    }

    pub(super) fn read_var(&self, r: VarRef) -> Value {
        match r {
            VarRef::Global(g) => self.global(g).clone(),
            VarRef::Slot(s) => self
                .frames
                .last()
                .and_then(|f| f.vars.get(s.0 as usize))
                .cloned()
                .unwrap_or(Value::float(0.0)),
            VarRef::Outer { owner, var } => self
                .frame_index(owner)
                .and_then(|k| self.frames[k].vars.get(var.0 as usize))
                .cloned()
                .unwrap_or(Value::float(0.0)),
        }
    }

    pub(super) fn var_mut(&mut self, r: VarRef) -> Option<&mut Value> {
        match r {
            VarRef::Global(g) => Some(self.global_mut(g)),
            VarRef::Slot(s) => self
                .frames
                .last_mut()
                .and_then(|f| f.vars.get_mut(s.0 as usize)),
            VarRef::Outer { owner, var } => {
                let k = self.frame_index(owner)?;
                self.frames[k].vars.get_mut(var.0 as usize)
            }
        }
    }

    /// Writes `v` to `target` (a variable or one array element) at the running points.
    pub(super) fn write(&mut self, target: &LValue, v: &Value, mask: &Mask) {
        let Some(r) = target.var else {
            return;
        };
        let index = target.index.as_ref().map(|e| self.eval_float(e, mask));
        let n = self.n;
        let Some(dst) = self.var_mut(r) else {
            return;
        };
        match (index, dst) {
            (None, dst) => dst.assign(v, Some(mask), n),
            (Some(idx), Value::Array(elems)) => write_element(elems, &idx, v, mask, n),
            (Some(_), _) => {}
        }
    }

    pub(super) fn read_lvalue(&mut self, target: &LValue, mask: &Mask) -> Value {
        let Some(r) = target.var else {
            return Value::float(0.0);
        };
        let v = self.read_var(r);
        match &target.index {
            None => v,
            Some(i) => {
                let idx = self.eval_float(i, mask);
                read_element(&v, &idx, self.n).unwrap_or(Value::float(0.0))
            }
        }
    }

    /// Writes an `output` argument of a built-in back to the caller's variable.
    pub(crate) fn write_back(&mut self, arg: &Expr, v: &Value, mask: &Mask) {
        if let Some(target) = lvalue_of(arg) {
            self.write(&target, v, mask);
        }
    }
}

/// The assignable target an `output` argument names.
pub(super) fn lvalue_of(arg: &Expr) -> Option<LValue> {
    match &arg.kind {
        ExprKind::Var(u) => Some(LValue {
            name: u.name.clone(),
            span: arg.span,
            index: None,
            var: u.var,
        }),
        ExprKind::Index { array, index } => match &array.kind {
            ExprKind::Var(u) => Some(LValue {
                name: u.name.clone(),
                span: arg.span,
                index: Some(index.clone()),
                var: u.var,
            }),
            _ => None,
        },
        _ => None,
    }
}

/// `a[i]` with a uniform or per-point index (truncated, clamped to the array).
pub(super) fn read_element(a: &Value, idx: &Slot<f32>, n: usize) -> Option<Value> {
    let Value::Array(elems) = a else {
        return None;
    };
    if elems.is_empty() {
        return None;
    }
    let clampi = |x: f32| (x.max(0.0) as usize).min(elems.len() - 1);
    match idx {
        Slot::Uniform(i) => Some(elems[clampi(*i)].clone()),
        Slot::Varying(ix) => {
            let mut out = elems[0].clone();
            for (k, e) in elems.iter().enumerate().skip(1) {
                let m = Mask::from_bits(ix.iter().map(|&i| clampi(i) == k).collect());
                if !m.none() {
                    out.assign(e, Some(&m), n);
                }
            }
            Some(out)
        }
    }
}

fn write_element(elems: &mut [Value], idx: &Slot<f32>, v: &Value, mask: &Mask, n: usize) {
    if elems.is_empty() {
        return;
    }
    let len = elems.len();
    let clampi = |x: f32| (x.max(0.0) as usize).min(len - 1);
    match idx {
        Slot::Uniform(i) => elems[clampi(*i)].assign(v, Some(mask), n),
        Slot::Varying(ix) => {
            for (k, e) in elems.iter_mut().enumerate() {
                let m =
                    Mask::from_bits((0..n).map(|i| mask.get(i) && clampi(ix[i]) == k).collect());
                if !m.none() {
                    e.assign(v, Some(&m), n);
                }
            }
        }
    }
}
