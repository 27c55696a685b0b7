//! `distantlight`, Listing 9.15: `solar(to - from, 0) { Cl = intensity * lightcolor; }`, and
//! `shadowdistant`, the same with `Cl *= 1 - shadow(shadowname, Ps, …)`.
//!
//! | name | type | default |
//! |---|---|---|
//! | intensity | float | 1 |
//! | lightcolor | color | 1 |
//! | from | point | "shader" (0,0,0) |
//! | to | point | "shader" (0,0,1) |
//! | shadowname, samples, blur, bias, width | (shadowdistant) | "", 16, 0.01, 0.01, 1 |
use super::shadow::Shadowing;
use crate::geometric::normalize_or_zero;
use crate::light::{Light, LightSamples};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;

pub(super) fn run(light: &Light, grid: &ShadingGrid, env: &ShadingEnv) -> LightSamples {
    let mut out = LightSamples::new(grid.len(), false);
    // solar's L is the direction light travels; the surface sees the reverse.
    let toward_light = normalize_or_zero(light.point("from") - light.point("to"));
    let cl = light.params.float("intensity") * light.params.vec3("lightcolor");
    let shadowing = Shadowing::new(light, env);
    if shadowing.casts() {
        out.shadow = vec![0.0; grid.len()];
    }
    for i in 0..grid.len() {
        out.l[i] = toward_light;
        let lit = shadowing.lit_fraction(grid, i, -toward_light);
        out.cl[i] = cl * lit;
        out.lit[i] = true;
        if let Some(s) = out.shadow.get_mut(i) {
            *s = 1.0 - lit;
        }
    }
    out
}
