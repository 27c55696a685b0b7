//! Illuminance loops over the cached lights (chapter 9 §9.3–9.4) and the built-in functions
//! defined by them: `ambient()`, `diffuse()`, `specular()` (Listing 9.10), `phong()`.
use crate::light::{Light, LightCache};
use crate::lighting;
use crate::shadingenv::SpecularModel;
use glam::Vec3;

/// Whether a light with `__category` list `light_categories` takes part in
/// `illuminance(category, …)`: `""` takes every light; `"name"` lights whose comma-separated
/// list contains `name`; `"-name"` lights whose list does not.
pub fn category_matches(category: &str, light_categories: &str) -> bool {
    let category = category.trim();
    if category.is_empty() {
        return true;
    }
    let has = |c: &str| light_categories.split(',').any(|x| x.trim() == c);
    match category.strip_prefix('-') {
        Some(excluded) => !has(excluded.trim()),
        None => has(category),
    }
}

/// The gathering cone of `illuminance(P, axis, angle)`: lights with `L` within `angle` of
/// `axis`. A zero `L` (light at the point) is inside every cone of angle ≥ π/2.
fn in_cone(l: Vec3, axis: Vec3, angle: f32) -> bool {
    if angle >= std::f32::consts::PI {
        return true;
    }
    let (l, axis) = (l.as_dvec3(), axis.as_dvec3());
    l.dot(axis) >= (angle as f64).cos() * l.length() * axis.length()
}

/// An illuminance loop's selection: an optional category and an optional `(axis, angle)` cone.
#[derive(Clone, Copy, Debug, Default)]
pub struct Illuminance<'s> {
    pub category: &'s str,
    pub cone: Option<(Vec3, f32)>,
}

impl Illuminance<'static> {
    /// `illuminance (P, N, PI/2)` over every category: the loop of the built-in `diffuse()`,
    /// `specular()` and the chapter's `LocIllum*` functions.
    pub fn hemisphere(n: Vec3) -> Illuminance<'static> {
        Illuminance {
            category: "",
            cone: Some((n, std::f32::consts::FRAC_PI_2)),
        }
    }
}

impl<'l> LightCache<'l> {
    /// Runs an illuminance loop at point `i`: `body(light, L, Cl)` for each non-ambient light
    /// whose `illuminate`/`solar` cone included the point, that matches the category, and whose
    /// `L` is inside the cone.
    pub fn illuminance(
        &self,
        i: usize,
        sel: Illuminance,
        mut body: impl FnMut(&Light, Vec3, Vec3),
    ) {
        for (light, s) in &self.lights {
            if s.ambient || !s.lit[i] || !category_matches(sel.category, light.category()) {
                continue;
            }
            if let Some((axis, angle)) = sel.cone {
                if !in_cone(s.l[i], axis, angle) {
                    continue;
                }
            }
            body(light, s.l[i], s.cl[i]);
        }
    }

    /// `ambient()`: the sum of `Cl` of the lights with no direction.
    pub fn ambient(&self, i: usize) -> Vec3 {
        self.lights
            .iter()
            .filter(|(_, s)| s.ambient)
            .map(|(_, s)| s.cl[i])
            .sum()
    }

    /// `diffuse(N)`, Listing 9.10: `Σ Cl (1 - __nondiffuse) (N · normalize(L))` over
    /// `illuminance(P, N, PI/2)`. `n` unit.
    pub fn diffuse(&self, i: usize, n: Vec3) -> Vec3 {
        let mut c = Vec3::ZERO;
        let sel = Illuminance::hemisphere(n);
        self.illuminance(i, sel, |light, l, cl| {
            c += cl * ((1.0 - light.nondiffuse()) * lighting::diffuse_term(n, l));
        });
        c
    }

    /// `specular(N, V, roughness)`, Listing 9.10 with the exponent of `model`:
    /// `Σ Cl (1 - __nonspecular) max(0, N·H)^e`.
    pub fn specular(
        &self,
        i: usize,
        n: Vec3,
        v: Vec3,
        roughness: f32,
        model: SpecularModel,
    ) -> Vec3 {
        let mut c = Vec3::ZERO;
        let sel = Illuminance::hemisphere(n);
        self.illuminance(i, sel, |light, l, cl| {
            c += cl
                * ((1.0 - light.nonspecular()) * lighting::blinn_phong(n, v, l, roughness, model));
        });
        c
    }

    /// RI `phong(N, V, size)`: `Σ Cl (1 - __nonspecular) max(0, R·normalize(L))^size`.
    pub fn phong(&self, i: usize, n: Vec3, v: Vec3, size: f32) -> Vec3 {
        let mut c = Vec3::ZERO;
        let sel = Illuminance::hemisphere(n);
        self.illuminance(i, sel, |light, l, cl| {
            c += cl * ((1.0 - light.nonspecular()) * lighting::phong_term(n, v, l, size));
        });
        c
    }

    /// `LocIllumOrenNayar(N, V, roughness)`, Listing 9.11 (lights with `__nondiffuse ≥ 1`
    /// skipped, the rest scaled by `1 - __nondiffuse`).
    pub fn oren_nayar(&self, i: usize, n: Vec3, v: Vec3, roughness: f32) -> Vec3 {
        let mut c = Vec3::ZERO;
        let sel = Illuminance::hemisphere(n);
        self.illuminance(i, sel, |light, l, cl| {
            let nondiff = light.nondiffuse();
            if nondiff < 1.0 {
                c += (1.0 - nondiff) * cl * lighting::oren_nayar_term(n, v, l, roughness);
            }
        });
        c
    }

    /// `LocIllumWardAnisotropic(N, V, xdir, xroughness, yroughness)`, Listing 9.12.
    pub fn ward_anisotropic(
        &self,
        i: usize,
        n: Vec3,
        v: Vec3,
        xdir: Vec3,
        xroughness: f32,
        yroughness: f32,
    ) -> Vec3 {
        let mut c = Vec3::ZERO;
        let sel = Illuminance::hemisphere(n);
        self.illuminance(i, sel, |light, l, cl| {
            let nonspec = light.nonspecular();
            if nonspec < 1.0 {
                c += cl
                    * ((1.0 - nonspec)
                        * lighting::ward_anisotropic_term(n, v, l, xdir, xroughness, yroughness));
            }
        });
        c
    }

    /// `LocIllumGlossy(N, V, roughness, sharpness)`, Listing 9.13.
    pub fn glossy(&self, i: usize, n: Vec3, v: Vec3, roughness: f32, sharpness: f32) -> Vec3 {
        let mut c = Vec3::ZERO;
        let sel = Illuminance::hemisphere(n);
        self.illuminance(i, sel, |light, l, cl| {
            let nonspec = light.nonspecular();
            if nonspec < 1.0 {
                c += cl * ((1.0 - nonspec) * lighting::glossy_term(n, v, l, roughness, sharpness));
            }
        });
        c
    }
}
