//! The shadow part of the shadow lights (Listing 9.19's
//! `atten *= 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur, "bias", bias)`):
//! shadow-map lookups, or BMRT's ray-traced shadows when `shadowname` is `"raytrace"` or the
//! light was declared under `Attribute "light" "shadows" ["on"]`.
//!
//! Ray-traced: one ray toward the light, or with `"raytrace"` and `blur > 0`, `samples` rays
//! jittered (stratified, per point) over a cone of half-angle `blur` radians around it; the
//! lit fraction is the share of rays that get through. `bias` is not used: the offset comes
//! from the renderer's tessellation bound (`ShadingEnv::ray_offset`).
use super::LightKind;
use crate::light::Light;
use crate::occlusion::{point_random, ray_origin, stratified};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use crate::texturelookup::ShadowOptions;
use glam::{DMat4, DVec3, Vec3};

pub(super) struct Shadowing<'a> {
    env: &'a ShadingEnv<'a>,
    /// One map, or six cube faces (+x −x +y −y +z −z) for `shadowpoint`.
    maps: Vec<String>,
    options: ShadowOptions,
    world_from_camera: DMat4,
    /// Shadow rays instead of maps: (rays per point, cone half-angle).
    rays: Option<(u32, f64)>,
    /// `solar` light: rays are directions without an end.
    distant: bool,
}

impl<'a> Shadowing<'a> {
    pub fn new(light: &Light, env: &'a ShadingEnv<'a>) -> Shadowing<'a> {
        let p = &light.params;
        let mut maps = Vec::new();
        let faces = ["sfpx", "sfnx", "sfpy", "sfny", "sfpz", "sfnz"];
        if faces.iter().any(|f| !p.string(f).is_empty()) {
            maps = faces.iter().map(|f| p.string(f).to_string()).collect();
        } else if !p.string("shadowname").is_empty() {
            maps.push(p.string("shadowname").to_string());
        }
        Shadowing {
            env,
            maps,
            options: ShadowOptions {
                samples: p.float("samples"),
                blur: p.float("blur"),
                bias: p.float("bias"),
                width: p.float("width"),
            },
            world_from_camera: env.camera_from_world.inverse(),
            rays: ray_settings(light),
            distant: matches!(light.kind, LightKind::Distant | LightKind::ShadowDistant),
        }
    }

    /// Whether the light casts shadows at all (a map or shadow rays): only then does it
    /// export `__shadow`.
    pub fn casts(&self) -> bool {
        self.rays.is_some() || self.maps.iter().any(|m| !m.is_empty())
    }

    /// `1 - shadow(...)` at grid point `i`; `l_light` (light → point, camera space) picks the
    /// cube face. No map, or a map that cannot be read (warned once), is unshadowed.
    pub fn lit_fraction(&self, grid: &ShadingGrid, i: usize, l_light: Vec3) -> f32 {
        if let Some((n, blur)) = self.rays {
            return self.traced_fraction(grid, i, l_light, n, blur);
        }
        let name = match self.maps.len() {
            0 => return 1.0,
            1 => &self.maps[0],
            _ => {
                let d = self
                    .world_from_camera
                    .transform_vector3(l_light.as_dvec3())
                    .abs();
                let w = self.world_from_camera.transform_vector3(l_light.as_dvec3());
                let axis = if d.x >= d.y && d.x >= d.z {
                    0
                } else if d.y >= d.z {
                    1
                } else {
                    2
                };
                let negative = w[axis] < 0.0;
                &self.maps[2 * axis + negative as usize]
            }
        };
        if name.is_empty() {
            return 1.0;
        }
        let Some(textures) = self.env.textures else {
            self.env.warn(&format!(
                "shadow map `{name}`: no texture system; unshadowed"
            ));
            return 1.0;
        };
        let (eu, ev) = (grid.dpdu[i] * grid.du, grid.dpdv[i] * grid.dv);
        // Centred on the shaded point (see `ShadingGrid::centred_footprint`).
        let p = grid.p[i] - 0.5 * (eu + ev);
        let corners = [p, p + eu, p + ev, p + eu + ev].map(|c| {
            self.world_from_camera
                .transform_point3(c.as_dvec3())
                .as_vec3()
        });
        match textures.shadow(name, corners, &self.options) {
            Some(s) if s.is_finite() => 1.0 - s.clamp(0.0, 1.0),
            Some(_) => 1.0,
            None => {
                self.env
                    .warn(&format!("shadow map `{name}` not found; unshadowed"));
                1.0
            }
        }
    }
}

impl Shadowing<'_> {
    /// The share of `n` shadow rays from point `i` toward the light that nothing blocks.
    fn traced_fraction(
        &self,
        grid: &ShadingGrid,
        i: usize,
        l_light: Vec3,
        n: u32,
        blur: f64,
    ) -> f32 {
        let Some(occlusion) = self.env.occlusion else {
            return 1.0;
        };
        // toward the light: a direction for solar lights, the vector to the light otherwise.
        let toward = -l_light.as_dvec3();
        let origin = ray_origin(grid, i, toward, self.env);
        let (target, t_max) = if self.distant {
            (toward, f64::INFINITY)
        } else {
            // Re-aim from the pushed-off origin; stop just short of the light itself.
            (grid.p[i].as_dvec3() + toward - origin, 1.0 - 1e-6)
        };
        if n <= 1 || blur <= 0.0 {
            return if occlusion.occluded(origin, target, t_max) {
                0.0
            } else {
                1.0
            };
        }
        let len = target.length();
        if !(len > 0.0 && len.is_finite()) {
            return 1.0;
        }
        let w = target / len;
        let a = w.any_orthonormal_vector();
        let b = w.cross(a);
        let spread = blur.min(1.5).tan();
        let stream = self.env.seed ^ 0x51ed_270b;
        let mut lit = 0u32;
        for k in 0..n {
            let (u, v) = stratified(k, n, point_random(grid.p[i], k, stream));
            // Uniform over the disk of radius tan(blur) one unit along the axis.
            let (r, phi) = (spread * u.sqrt(), std::f64::consts::TAU * v);
            let d: DVec3 = (w + a * (r * phi.cos()) + b * (r * phi.sin())) * len;
            if !occlusion.occluded(origin, d, t_max) {
                lit += 1;
            }
        }
        lit as f32 / n as f32
    }
}

/// `Some((rays, blur))` when the light's shadows are ray traced.
fn ray_settings(light: &Light) -> Option<(u32, f64)> {
    let p = &light.params;
    if p.string("shadowname") == "raytrace" {
        let n = p.float("samples");
        let n = if n.is_finite() {
            n.clamp(1.0, 1024.0) as u32
        } else {
            1
        };
        let blur = f64::from(p.float("blur")).max(0.0);
        return Some((n, if blur.is_finite() { blur } else { 0.0 }));
    }
    light.raytraced.then_some((1, 0.0))
}
