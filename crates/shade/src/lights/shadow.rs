//! The shadow-map part of the shadow lights (Listing 9.19's
//! `atten *= 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur, "bias", bias)`).
use crate::light::Light;
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use crate::texturelookup::ShadowOptions;
use glam::{DMat4, Vec3};

pub(super) struct Shadowing<'a> {
    env: &'a ShadingEnv<'a>,
    /// One map, or six cube faces (+x −x +y −y +z −z) for `shadowpoint`.
    maps: Vec<String>,
    options: ShadowOptions,
    world_from_camera: DMat4,
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
        }
    }

    /// `1 - shadow(...)` at grid point `i`; `l_light` (light → point, camera space) picks the
    /// cube face. No map, or a map that cannot be read (warned once), is unshadowed.
    pub fn lit_fraction(&self, grid: &ShadingGrid, i: usize, l_light: Vec3) -> f32 {
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
        let p = grid.p[i];
        let (eu, ev) = (grid.dpdu[i] * grid.du, grid.dpdv[i] * grid.dv);
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
