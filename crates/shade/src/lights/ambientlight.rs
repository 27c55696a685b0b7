//! `ambientlight`, Listing 9.14: `Cl = intensity * lightcolor; L = 0`.
//!
//! | name | type | default |
//! |---|---|---|
//! | intensity | float | 1 |
//! | lightcolor | color | 1 |
use crate::light::{Light, LightSamples};
use crate::shadinggrid::ShadingGrid;

pub(super) fn run(light: &Light, grid: &ShadingGrid) -> LightSamples {
    let mut out = LightSamples::new(grid.len(), true);
    let cl = light.params.float("intensity") * light.params.vec3("lightcolor");
    out.cl.iter_mut().for_each(|c| *c = cl);
    out.lit.iter_mut().for_each(|l| *l = true);
    out
}
