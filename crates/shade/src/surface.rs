//! Surface shader instances and grid shading.
use crate::error::ShadeError;
use crate::light::{Light, LightCache};
use crate::materials::{SurfaceContext, SurfaceKind};
use crate::parameters::ShaderParams;
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::Vec3;
use illume_rib::Param;

/// A bound surface shader (`Surface "name" params…`).
#[derive(Clone, Debug, PartialEq)]
pub struct Surface {
    pub(crate) name: String,
    pub(crate) kind: SurfaceKind,
    pub(crate) params: ShaderParams,
}

impl Surface {
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The RI fallback for unknown surfaces: `defaultsurface` with its defaults.
    pub fn default_surface() -> Surface {
        surface("defaultsurface", &[])
            .map(|(s, _)| s)
            .expect("built in")
    }

    /// The built-in surface shader names.
    pub fn names() -> &'static [&'static str] {
        &SurfaceKind::NAMES
    }
}

/// Binds surface shader `name` with `params` (names may carry inline declarations). Returns the
/// shader and the warnings for parameters of the wrong type or count (those are ignored), or
/// [`ShadeError::UnknownShader`].
pub fn surface(name: &str, params: &[Param]) -> Result<(Surface, Vec<String>), ShadeError> {
    let kind = SurfaceKind::from_name(name).ok_or_else(|| ShadeError::UnknownShader {
        kind: "surface",
        name: name.to_string(),
        known: SurfaceKind::NAMES.join(", "),
    })?;
    let (params, warnings) = ShaderParams::bind(name, &kind.params(), params, false);
    Ok((
        Surface {
            name: name.to_string(),
            kind,
            params,
        },
        warnings,
    ))
}

/// Shades `grid` with `surface` under `lights`: runs each light once over the grid (the
/// [`LightCache`] every illuminance loop reads), then the surface, then `Oi = Os; Ci = Os * C`
/// as every listing ends. Any non-finite result is replaced by black (`Ci`) / opaque (`Oi`) so
/// no NaN reaches a pixel (the formulas are guarded; this is a last line). Returns how many
/// points had to be repaired, for the hider's `--stats`.
pub fn shade_surface(
    surface: &Surface,
    grid: &mut ShadingGrid,
    lights: &[&Light],
    env: &ShadingEnv,
) -> ShadeStats {
    let cache = LightCache::run(lights, grid, env);
    shade_surface_with(surface, grid, &cache, env)
}

/// What [`shade_surface`] reports about one grid.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadeStats {
    /// Grid points whose `Ci` or `Oi` came out NaN/Inf and were replaced (black / opaque).
    pub nonfinite: usize,
}

/// [`shade_surface`] with lights already run (e.g. to inspect or reuse the cache).
pub fn shade_surface_with(
    surface: &Surface,
    grid: &mut ShadingGrid,
    cache: &LightCache,
    env: &ShadingEnv,
) -> ShadeStats {
    let mut stats = ShadeStats::default();
    let color = {
        let ctx = SurfaceContext::new(grid, cache, env, &surface.params);
        surface.kind.shade(&ctx)
    };
    for (i, c) in color.into_iter().enumerate() {
        let os = grid.os[i];
        let ci = c * os;
        stats.nonfinite += (!os.is_finite() || !ci.is_finite()) as usize;
        grid.oi[i] = if os.is_finite() { os } else { Vec3::ONE };
        grid.ci[i] = if ci.is_finite() { ci } else { Vec3::ZERO };
    }
    stats
}
