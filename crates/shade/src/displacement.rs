//! Displacement shaders. The chapter has none; the RI 3.2 standard `bumpy` is built in:
//! `P += Km * texture(texturename, s, t) * normalize(N); N = calculatenormal(P)`.
//!
//! | name | type | default |
//! |---|---|---|
//! | Km | float | 1 |
//! | texturename | string | "" (no map: no displacement) |
use crate::error::ShadeError;
use crate::geometric::normalize_or_zero;
use crate::materials::environment::texture_colors;
use crate::parameters::{ParamValue, ShaderParams};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use illume_rib::Param;

/// A bound displacement shader.
#[derive(Clone, Debug, PartialEq)]
pub struct Displacement {
    name: String,
    params: ShaderParams,
}

impl Displacement {
    pub fn name(&self) -> &str {
        &self.name
    }
}

const NAMES: [&str; 1] = ["bumpy"];

/// Binds displacement shader `name` (`bumpy`); see [`crate::surface`] for the warnings.
pub fn displacement(
    name: &str,
    params: &[Param],
) -> Result<(Displacement, Vec<String>), ShadeError> {
    if !NAMES.contains(&name) {
        return Err(ShadeError::UnknownShader {
            kind: "displacement",
            name: name.to_string(),
            known: NAMES.join(", "),
        });
    }
    let specs = [
        ("Km", ParamValue::Float(1.0)),
        ("texturename", ParamValue::String(String::new())),
    ];
    let (params, warnings) = ShaderParams::bind(name, &specs, params, false);
    Ok((
        Displacement {
            name: name.to_string(),
            params,
        },
        warnings,
    ))
}

/// Runs `d` on the grid: moves `P` along `normalize(N)` and recomputes `N` from the displaced
/// grid (`calculatenormal`). A missing map warns once and leaves the grid unchanged.
pub fn displace(d: &Displacement, grid: &mut ShadingGrid, env: &ShadingEnv) {
    let name = d.params.string("texturename");
    if name.is_empty() {
        return;
    }
    let amp = texture_colors(env, grid, name, 1, 0.0);
    let km = d.params.float_on(grid, "Km");
    let km: Vec<f32> = (0..grid.len()).map(|i| km.at(i)).collect();
    let before = grid.n.clone();
    for i in 0..grid.len() {
        let a = km[i] * amp[i][0];
        if a.is_finite() {
            grid.p[i] += a * normalize_or_zero(grid.n[i]);
        }
    }
    grid.n = grid.calculatenormal(&before);
}
