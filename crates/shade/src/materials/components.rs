//! The built-in materials' lighting components (issue 20), for the displays that name them:
//! `__ambient`, `__diffuse`, `__specular` and `__reflection` (environment map or traced). The
//! driver multiplies them by `Oi`, so for every built-in surface they add up to `Ci`: each
//! material writes only its `components()`, and `SurfaceKind::shade` is their sum
//! (`tests/aov.rs` checks the sum to 1e-5 for every built-in surface).
use super::SurfaceContext;
use crate::light::LightCache;
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use crate::surface::Surface;
use glam::Vec3;

/// The component names, in the order of [`Components::by_index`].
pub const COMPONENT_NAMES: [&str; 4] = ["__ambient", "__diffuse", "__specular", "__reflection"];

/// One grid's unpremultiplied components, one colour per point each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Components {
    pub ambient: Vec<Vec3>,
    pub diffuse: Vec<Vec3>,
    pub specular: Vec<Vec3>,
    pub reflection: Vec<Vec3>,
}

impl Components {
    pub(crate) fn new(n: usize) -> Components {
        Components {
            ambient: vec![Vec3::ZERO; n],
            diffuse: vec![Vec3::ZERO; n],
            specular: vec![Vec3::ZERO; n],
            reflection: vec![Vec3::ZERO; n],
        }
    }

    /// Their sum per point: the material's `Ci` before `Oi`.
    pub(crate) fn total(&self) -> Vec<Vec3> {
        (0..self.ambient.len())
            .map(|i| self.ambient[i] + self.diffuse[i] + self.specular[i] + self.reflection[i])
            .collect()
    }

    /// Each component multiplied by the opacity `oi` (the values the AOVs hold).
    pub fn times(mut self, oi: &[Vec3]) -> Components {
        for k in [
            &mut self.ambient,
            &mut self.diffuse,
            &mut self.specular,
            &mut self.reflection,
        ] {
            for (c, o) in k.iter_mut().zip(oi) {
                *c *= *o;
            }
        }
        self
    }

    /// The component named `COMPONENT_NAMES[k]`.
    pub fn by_index(&self, k: usize) -> Option<&[Vec3]> {
        match k {
            0 => Some(&self.ambient),
            1 => Some(&self.diffuse),
            2 => Some(&self.specular),
            3 => Some(&self.reflection),
            _ => None,
        }
    }
}

/// The components of `surface` over `grid` (lights already run into `cache`), before `Oi`.
/// Every built-in surface splits its colour (`constant`'s one term is `__ambient`; see each
/// material's file for which term goes where).
pub fn surface_components(
    surface: &Surface,
    grid: &ShadingGrid,
    cache: &LightCache,
    env: &ShadingEnv,
) -> Components {
    let ctx = SurfaceContext::new(grid, cache, env, &surface.params);
    surface.kind.components(&ctx)
}
