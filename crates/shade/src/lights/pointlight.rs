//! `pointlight`, Listing 9.16: `illuminate(from) { Cl = intensity * lightcolor / (L.L); }`, and
//! `shadowpoint`, the same shadowed by a cube of six shadow maps (`sfpx` … `sfnz`, the face
//! chosen by the dominant world axis of `L`) or one `shadowname`.
//!
//! | name | type | default |
//! |---|---|---|
//! | intensity | float | 1 |
//! | lightcolor | color | 1 |
//! | from | point | "shader" (0,0,0) |
//! | shadowname, samples, blur, bias, width | (shadowpoint) | "", 16, 0.01, 0.01, 1 |
//! | sfpx, sfnx, sfpy, sfny, sfpz, sfnz | string (shadowpoint) | "" |
use super::inverse_square;
use super::shadow::Shadowing;
use crate::light::{Light, LightSamples};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;

pub(super) fn run(light: &Light, grid: &ShadingGrid, env: &ShadingEnv) -> LightSamples {
    let mut out = LightSamples::new(grid.len(), false);
    let from = light.point("from");
    let c = light.params.float("intensity") * light.params.vec3("lightcolor");
    let shadowing = Shadowing::new(light, env);
    if shadowing.casts() {
        out.shadow = vec![0.0; grid.len()];
    }
    for i in 0..grid.len() {
        let l_light = grid.p[i] - from;
        out.l[i] = -l_light;
        let lit = shadowing.lit_fraction(grid, i, l_light);
        out.cl[i] = inverse_square(c, l_light) * lit;
        out.lit[i] = true;
        if let Some(s) = out.shadow.get_mut(i) {
            *s = 1.0 - lit;
        }
    }
    out
}
