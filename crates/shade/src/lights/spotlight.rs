//! `spotlight`, Listing 9.17, and `shadowspot`, Listing 9.19:
//!
//! ```text
//! A = normalize(to-from); cosoutside = cos(coneangle); cosinside = cos(coneangle-conedeltaangle)
//! illuminate (from, A, coneangle) {
//!     cosangle = (L.A)/length(L);
//!     atten = pow(cosangle, beamdistribution) / (L.L) * smoothstep(cosoutside, cosinside, cosangle)
//!     [atten *= 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur, "bias", bias)]
//!     Cl = atten * intensity * lightcolor;
//! }
//! ```
//!
//! | name | type | default |
//! |---|---|---|
//! | intensity | float | 1 |
//! | lightcolor | color | 1 |
//! | from | point | "shader" (0,0,0) |
//! | to | point | "shader" (0,0,1) |
//! | coneangle | float | radians(30) |
//! | conedeltaangle | float | radians(5) |
//! | beamdistribution | float | 2 |
//! | shadowname | string | "" (shadowspot) |
//! | samples, blur, bias | float | 16, 0.01, 0.01 (shadowspot) |
use super::inverse_square;
use super::shadow::Shadowing;
use crate::geometric::normalize_or_zero;
use crate::light::{Light, LightSamples};
use crate::mathfunctions::smoothstep;
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;

pub(super) fn run(light: &Light, grid: &ShadingGrid, env: &ShadingEnv) -> LightSamples {
    let mut out = LightSamples::new(grid.len(), false);
    let from = light.point("from");
    let axis = normalize_or_zero(light.point("to") - from);
    let coneangle = light.params.float("coneangle");
    let cosoutside = coneangle.cos();
    let cosinside = (coneangle - light.params.float("conedeltaangle")).cos();
    let beam = light.params.float("beamdistribution");
    let c = light.params.float("intensity") * light.params.vec3("lightcolor");
    let shadowing = Shadowing::new(light, env);
    if shadowing.casts() {
        out.shadow = vec![0.0; grid.len()];
    }
    for i in 0..grid.len() {
        let l_light = grid.p[i] - from;
        out.l[i] = -l_light;
        let r = l_light.length();
        // The illuminate cone: a point at the light (r = 0) has no direction and gets no light.
        if r.is_nan() || r <= 0.0 {
            continue;
        }
        let cosangle = (l_light.dot(axis) / r).clamp(-1.0, 1.0);
        if cosangle < cosoutside {
            continue;
        }
        out.lit[i] = true;
        // pow of a negative base is NaN in SL for non-integer beams; beyond 90° the beam is dark.
        let atten = cosangle.max(0.0).powf(beam) * smoothstep(cosoutside, cosinside, cosangle);
        let lit = shadowing.lit_fraction(grid, i, l_light);
        out.cl[i] = inverse_square(c * atten, l_light) * lit;
        if let Some(s) = out.shadow.get_mut(i) {
            *s = 1.0 - lit;
        }
    }
    out
}
