//! The global variables of a run (RI 3.2 §11.2), loaded from the grid only when first read or
//! written: a shader that never names `dPdu` or `s` does not pay for copying them, which at
//! 64×64 points is most of the fixed cost of a run.

use super::{gidx, zero_of, Exec};
use crate::value::{Slot, Value};
use glam::Vec3;
use illume_shade::ShadingGrid;
use illume_sl::ast::Global;
use std::cell::OnceCell;

/// One cell per entry of [`Global::ALL`], empty until first used.
pub(super) fn unloaded() -> Vec<OnceCell<Value>> {
    Global::ALL.iter().map(|_| OnceCell::new()).collect()
}

/// A global's value at the start of a run: the grid's (P, N, Ng, I, s, t, …; `Ci = 0`, and
/// `Oi = Os` as PRMan, BMRT and Aqsis start it: a surface shader that sets only `Ci` is opaque
/// there, and real shaders such as Aqsis's regression `test.sl`/`mxmatch.sl` rely on it;
/// starting at 0 made them transparent, so front and back surfaces summed).
fn initial(grid: &ShadingGrid, g: Global) -> Value {
    let tv = |v: &Vec<Vec3>| Value::Triple(Slot::varying(v.clone()));
    let fv = |v: &Vec<f32>| Value::Float(Slot::varying(v.clone()));
    match g {
        Global::P | Global::Ps => tv(&grid.p),
        Global::N => tv(&grid.n),
        Global::Ng => tv(&grid.ng),
        Global::I => tv(&grid.i),
        Global::dPdu => tv(&grid.dpdu),
        Global::dPdv => tv(&grid.dpdv),
        Global::Cs => tv(&grid.cs),
        Global::Os | Global::Oi => tv(&grid.os),
        Global::s => fv(&grid.s),
        Global::t => fv(&grid.t),
        Global::u => fv(&grid.u),
        Global::v => fv(&grid.v),
        Global::du => Value::float(grid.du),
        Global::dv => Value::float(grid.dv),
        Global::ncomps => Value::float(3.0),
        Global::alpha => Value::float(1.0),
        Global::Ol => Value::triple(Vec3::ONE),
        g => zero_of(g.ty()),
    }
}

impl Exec<'_> {
    pub fn global(&self, g: Global) -> &Value {
        self.globals[gidx(g)].get_or_init(|| initial(self.grid, g))
    }

    pub fn set_global(&mut self, g: Global, v: Value) {
        self.globals[gidx(g)] = OnceCell::from(v);
    }

    /// The global's final value, moved out of the run (loaded first if never used): what the
    /// entry points hand back to the grid without copying.
    pub fn take_global(&mut self, g: Global) -> Value {
        self.global_mut(g);
        self.globals[gidx(g)].take().expect("loaded above")
    }

    /// The global for writing (loaded first: a masked write keeps the other points' values).
    pub(super) fn global_mut(&mut self, g: Global) -> &mut Value {
        let k = gidx(g);
        let grid = self.grid;
        self.globals[k].get_or_init(|| initial(grid, g));
        self.globals[k].get_mut().expect("initialised above")
    }
}
