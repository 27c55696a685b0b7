//! The lights a surface's illuminance loops see: the built-in lights run by
//! `illume_shade::LightCache` and (later) Shading Language lights, viewed through one type so
//! `illuminance`, `diffuse()`, `specular()` and `lightsource()` treat both alike.
//!
//! The sums replicate `illume_shade`'s `LightCache::diffuse` / `specular` / `phong` exactly
//! (same kernels, same cone test in `f64`, same order), so an SL `plastic` calling `diffuse()`
//! gives the built-in's bits.
use crate::value::Value;
use glam::Vec3;
use illume_shade::{category_matches, Light, LightCache, LightSamples, ParamValue, SpecularModel};

/// Where a light's parameters live, for `lightsource()` message passing and `__category`.
#[derive(Clone, Copy)]
pub enum LightSource<'a> {
    Builtin(&'a Light),
    /// A Shading Language light: its parameters (by name) after it ran on this grid, then the
    /// RIB parameters of its request (`__category` and the like need no declaration).
    Sl {
        outputs: &'a [(String, Value)],
        request: &'a Light,
    },
}

/// One light evaluated over the grid.
#[derive(Clone, Copy)]
pub struct LightView<'a> {
    pub samples: &'a LightSamples,
    pub source: LightSource<'a>,
}

impl LightView<'_> {
    /// `lightsource(name, …)`: the light's parameter as a uniform value.
    pub fn param(&self, name: &str) -> Option<Value> {
        let builtin = |l: &Light| {
            l.param(name).map(|p| match p {
                ParamValue::Float(f) => Value::float(*f),
                ParamValue::Color(c) | ParamValue::Point(c) => Value::triple(*c),
                ParamValue::String(s) => Value::string(s),
            })
        };
        match self.source {
            LightSource::Builtin(l) => builtin(l),
            LightSource::Sl { outputs, request } => outputs
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, v)| v.clone())
                .or_else(|| builtin(request)),
        }
    }

    fn float_param(&self, name: &str) -> f32 {
        match self.param(name) {
            Some(Value::Float(s)) => *s.at(0),
            _ => 0.0,
        }
    }

    pub fn category(&self) -> String {
        match self.param("__category") {
            Some(Value::String(s)) => s.at(0).to_string(),
            _ => String::new(),
        }
    }

    pub fn nondiffuse(&self) -> f32 {
        self.float_param("__nondiffuse")
    }

    pub fn nonspecular(&self) -> f32 {
        self.float_param("__nonspecular")
    }
}

/// Every light of the grid, in the order the surface's loops visit them.
#[derive(Clone, Default)]
pub struct Lights<'a> {
    pub lights: Vec<LightView<'a>>,
}

/// The gathering cone test of `illume_shade`'s illuminance loop (copied rule: `angle ≥ π`
/// takes everything; otherwise `L·axis ≥ cos(angle)|L||axis|` in `f64`).
pub fn in_cone(l: Vec3, axis: Vec3, angle: f32) -> bool {
    if angle >= std::f32::consts::PI {
        return true;
    }
    let (l, axis) = (l.as_dvec3(), axis.as_dvec3());
    l.dot(axis) >= (angle as f64).cos() * l.length() * axis.length()
}

impl<'a> Lights<'a> {
    /// The built-in lights as run by `illume_shade`.
    pub fn from_cache(cache: &'a LightCache<'a>) -> Lights<'a> {
        Lights {
            lights: cache
                .lights
                .iter()
                .map(|(l, s)| LightView {
                    samples: s,
                    source: LightSource::Builtin(l),
                })
                .collect(),
        }
    }

    /// `Σ f(light, L, Cl)` over the lights of `illuminance(P, n, PI/2)` at point `i`.
    fn hemisphere(
        &self,
        i: usize,
        n: Vec3,
        mut f: impl FnMut(&LightView, Vec3, Vec3) -> Vec3,
    ) -> Vec3 {
        let mut c = Vec3::ZERO;
        for light in &self.lights {
            let s = light.samples;
            if s.ambient || !s.lit[i] || !in_cone(s.l[i], n, std::f32::consts::FRAC_PI_2) {
                continue;
            }
            c += f(light, s.l[i], s.cl[i]);
        }
        c
    }

    /// `ambient()`.
    pub fn ambient(&self, i: usize) -> Vec3 {
        self.lights
            .iter()
            .filter(|l| l.samples.ambient)
            .map(|l| l.samples.cl[i])
            .sum()
    }

    /// `diffuse(N)`, Listing 9.10.
    pub fn diffuse(&self, i: usize, n: Vec3) -> Vec3 {
        self.hemisphere(i, n, |light, l, cl| {
            cl * ((1.0 - light.nondiffuse()) * illume_shade::diffuse_term(n, l))
        })
    }

    /// `specular(N, V, roughness)`, Listing 9.10.
    pub fn specular(
        &self,
        i: usize,
        n: Vec3,
        v: Vec3,
        roughness: f32,
        model: SpecularModel,
    ) -> Vec3 {
        self.hemisphere(i, n, |light, l, cl| {
            cl * ((1.0 - light.nonspecular())
                * illume_shade::blinn_phong(n, v, l, roughness, model))
        })
    }

    /// `phong(N, V, size)`.
    pub fn phong(&self, i: usize, n: Vec3, v: Vec3, size: f32) -> Vec3 {
        self.hemisphere(i, n, |light, l, cl| {
            cl * ((1.0 - light.nonspecular()) * illume_shade::phong_term(n, v, l, size))
        })
    }

    /// Per light, `1 - share(light)`: `__nondiffuse`/`__nonspecular` looked up once per call
    /// of a grid built-in rather than once per point and light.
    fn keep(&self, share: impl Fn(&LightView<'a>) -> f32) -> Vec<f32> {
        self.lights.iter().map(|l| 1.0 - share(l)).collect()
    }

    /// `Σ Cl · keep · term(i, L)` over the lights of `illuminance(P, n(i), PI/2)` for every
    /// point: the grid form of [`Lights::hemisphere`], same sums in the same order.
    fn hemisphere_grid(
        &self,
        count: usize,
        keep: &[f32],
        n: impl Fn(usize) -> Vec3,
        term: impl Fn(usize, Vec3, Vec3) -> f32,
    ) -> Vec<Vec3> {
        (0..count)
            .map(|i| {
                let nn = n(i);
                let mut c = Vec3::ZERO;
                for (light, &k) in self.lights.iter().zip(keep) {
                    let s = light.samples;
                    if s.ambient || !s.lit[i] || !in_cone(s.l[i], nn, std::f32::consts::FRAC_PI_2) {
                        continue;
                    }
                    c += s.cl[i] * (k * term(i, nn, s.l[i]));
                }
                c
            })
            .collect()
    }

    /// `diffuse(N)` at every point, `n(i)` the unit normal: [`Lights::diffuse`]'s bits.
    pub fn diffuse_grid(&self, count: usize, n: impl Fn(usize) -> Vec3) -> Vec<Vec3> {
        let keep = self.keep(|l| l.nondiffuse());
        self.hemisphere_grid(count, &keep, n, |_, n, l| illume_shade::diffuse_term(n, l))
    }

    /// `specular(N, V, roughness)` at every point: [`Lights::specular`]'s bits.
    pub fn specular_grid(
        &self,
        count: usize,
        n: impl Fn(usize) -> Vec3,
        v: impl Fn(usize) -> Vec3,
        roughness: impl Fn(usize) -> f32,
        model: SpecularModel,
    ) -> Vec<Vec3> {
        let keep = self.keep(|l| l.nonspecular());
        self.hemisphere_grid(count, &keep, n, |i, n, l| {
            illume_shade::blinn_phong(n, v(i), l, roughness(i), model)
        })
    }

    /// `phong(N, V, size)` at every point: [`Lights::phong`]'s bits.
    pub fn phong_grid(
        &self,
        count: usize,
        n: impl Fn(usize) -> Vec3,
        v: impl Fn(usize) -> Vec3,
        size: impl Fn(usize) -> f32,
    ) -> Vec<Vec3> {
        let keep = self.keep(|l| l.nonspecular());
        self.hemisphere_grid(count, &keep, n, |i, n, l| {
            illume_shade::phong_term(n, v(i), l, size(i))
        })
    }

    /// Whether light `k` takes part in `illuminance(category, …)`.
    pub fn matches(&self, k: usize, category: &str) -> bool {
        category_matches(category, &self.lights[k].category())
    }
}
