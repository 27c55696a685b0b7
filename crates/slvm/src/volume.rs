//! Volume shaders in the Shading Language (`Atmosphere`, and `Interior`/`Exterior` once rays
//! are traced): a `volume` shader runs over a grid *after* its surface shader, with `Ci`/`Oi`
//! set to what the surface left, `P` the surface point, `I` the ray from the eye `E` to it, and
//! writes the attenuated `Ci`/`Oi`.
//!
//! The book's smoke pattern (ray-march from `P` back toward `E`, gathering light with
//! `illuminance(Pmarch)` and `shadow()` at each step) needs the lights evaluated at points that
//! are not the grid's: a surface shader's lights run once per grid at `P` (`LightCache`), so a
//! volume shader is given a [`Relight`] hook and every `illuminance` whose position differs from
//! the grid's `P` re-runs the lights there through it.
use crate::exec::Messages;
use crate::instance::{SlInstance, SlStats};
use crate::lights::Lights;
use crate::value::{Slot, Value};
use glam::Vec3;
use illume_shade::{LightSamples, ShadingEnv, ShadingGrid};
use illume_sl::ast::Global;

/// Runs the primitive's lights at arbitrary camera-space points, for `illuminance(Pmarch)`
/// inside a volume shader.
pub trait Relight {
    /// One `LightSamples` of `p.len()` points per light of the [`Lights`] the shader was given,
    /// in the same order (an answer of another length is refused and the grid's own samples
    /// used, with a warning).
    fn relight(&self, p: &[Vec3]) -> Vec<LightSamples>;
}

impl SlInstance {
    /// Runs a volume shader over `grid`: reads the surface's `grid.ci`/`grid.oi` as `Ci`/`Oi`
    /// and writes the attenuated values back (non-finite results leave the point as the surface
    /// shaded it). `lights` are the grid's lights at `P`; `relight` (if any) evaluates them
    /// elsewhere. `eye` is `E`: the camera origin for an `Atmosphere` (`None`), the ray's
    /// origin for an `Interior`/`Exterior` on a traced ray (so marching from `P` toward `E`
    /// stays on the ray's segment).
    pub fn shade_volume(
        &self,
        grid: &mut ShadingGrid,
        lights: &Lights,
        relight: Option<&dyn Relight>,
        env: &ShadingEnv,
        messages: Messages,
        eye: Option<Vec3>,
    ) -> SlStats {
        let n = grid.len();
        let (ci, oi) = {
            let g: &ShadingGrid = grid;
            let mut exec = crate::Exec::new(&self.shader.program, g, env, lights);
            exec.messages = messages;
            exec.relight = relight;
            if let Some(e) = eye {
                exec.set_global(Global::E, Value::triple(e));
            }
            exec.set_global(Global::Ci, Value::Triple(Slot::varying(g.ci.clone())));
            exec.set_global(Global::Oi, Value::Triple(Slot::varying(g.oi.clone())));
            let params = self.params_for(&mut exec, g);
            exec.run_shader(self.shader.id, params);
            Self::report_problems(&exec, env, self.name());
            (
                crate::instance::triple_vec(exec.global(Global::Ci), n),
                crate::instance::triple_vec(exec.global(Global::Oi), n),
            )
        };
        let mut stats = SlStats::default();
        for i in 0..n {
            if ci[i].is_finite() && oi[i].is_finite() {
                grid.ci[i] = ci[i];
                grid.oi[i] = oi[i];
            } else {
                stats.nonfinite += 1;
            }
        }
        stats
    }
}
