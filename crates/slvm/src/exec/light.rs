//! The lighting constructs: `illuminance` runs its body once per light for the points the
//! light reaches; `illuminate`/`solar` record which points a light shader lit.

use super::Exec;
use crate::lights::in_cone;
use crate::value::{Mask, Slot, Value};
use glam::Vec3;
use illume_sl::ast::{Global, Stmt};

impl Exec<'_> {
    /// `illuminate`/`solar` body: `L` set, run where the cone admits it, the lit points
    /// recorded for the surface.
    pub(super) fn emit(
        &mut self,
        l: Slot<Vec3>,
        cone: Option<(Slot<Vec3>, Slot<f32>)>,
        body: &Stmt,
        mask: &Mask,
    ) {
        let run = match &cone {
            Some((axis, angle)) => Mask::from_bits(
                (0..self.n)
                    .map(|i| mask.get(i) && in_cone(*l.at(i), *axis.at(i), *angle.at(i)))
                    .collect(),
            ),
            None => mask.clone(),
        };
        self.emission.directional = true;
        let n = self.n;
        self.global_mut(Global::L)
            .assign(&Value::Triple(l), Some(&run), n);
        if !run.none() {
            self.exec_stmt(body, &run);
        }
        let lit = match self.emission.lit.take() {
            Some(m) => m.union(&run),
            None => run,
        };
        self.emission.lit = Some(lit);
    }

    pub(super) fn exec_illuminance(&mut self, il: &illume_sl::ast::Illuminance, mask: &Mask) {
        let category = match &il.category {
            Some(c) => match self.eval(c, mask) {
                Value::String(s) => s.at(0).to_string(),
                _ => String::new(),
            },
            None => String::new(),
        };
        let position = self.eval_triple(&il.position, mask);
        let relit = self.relit(position);
        let cone = il.cone.as_ref().map(|c| {
            (
                self.eval_triple(&c.axis, mask),
                self.eval_float(&c.angle, mask),
            )
        });
        self.push_loop();
        let saved = (
            self.global(Global::L).clone(),
            self.global(Global::Cl).clone(),
            self.global(Global::Ol).clone(),
            self.current_light,
        );
        for k in 0..self.lights.lights.len() {
            let light = self.lights.lights[k];
            let s = relit.as_ref().map_or(light.samples, |r| &r[k]);
            if s.ambient || !self.lights.matches(k, &category) {
                continue;
            }
            let live = self.live(mask);
            if live.none() {
                break;
            }
            let m = Mask::from_bits(
                (0..self.n)
                    .map(|i| {
                        live.get(i)
                            && s.lit[i]
                            && cone
                                .as_ref()
                                .is_none_or(|(a, ang)| in_cone(s.l[i], *a.at(i), *ang.at(i)))
                    })
                    .collect(),
            );
            if m.none() {
                continue;
            }
            self.set_global(Global::L, Value::Triple(Slot::varying(s.l.clone())));
            self.set_global(Global::Cl, Value::Triple(Slot::varying(s.cl.clone())));
            self.set_global(Global::Ol, Value::Triple(Slot::varying(s.ol.clone())));
            self.current_light = Some(k);
            self.exec_stmt(&il.body, &m);
            if let Some(l) = self.frames.last_mut().and_then(|f| f.loops.last_mut()) {
                l.continued = Mask::from_bits(vec![false; l.continued.len()]);
            }
        }
        self.set_global(Global::L, saved.0);
        self.set_global(Global::Cl, saved.1);
        self.set_global(Global::Ol, saved.2);
        self.current_light = saved.3;
        self.pop_loop();
    }
}

impl Exec<'_> {
    /// The lights re-run at `position` through the volume shader's [`crate::Relight`] hook, when
    /// there is one and `position` is not the grid's `P` (where the grid's samples already are).
    fn relit(&mut self, position: Slot<Vec3>) -> Option<Vec<illume_shade::LightSamples>> {
        let relight = self.relight?;
        let p = position.to_varying(self.n);
        if p == self.grid.p {
            return None;
        }
        let samples = relight.relight(&p);
        if samples.len() != self.lights.lights.len() || samples.iter().any(|s| s.l.len() != self.n)
        {
            self.problem(format!(
                "illuminance: the lights re-run at another position gave {} lights, expected {}; \
                 using the grid's",
                samples.len(),
                self.lights.lights.len()
            ));
            return None;
        }
        Some(samples)
    }
}
