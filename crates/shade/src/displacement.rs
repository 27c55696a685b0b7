//! Displacement shaders. The chapter has none; three are built in, each moving `P` along
//! `normalize(N)` and then recomputing `N = calculatenormal(P)` (true displacement: the
//! silhouette moves, which is why the hider needs `Attribute "displacementbound"`).
//!
//! * `bumpy` (RI 3.2 standard): `P += Km * texture(texturename, s, t) * normalize(N)`.
//!
//!   | name | type | default |
//!   |---|---|---|
//!   | Km | float | 1 |
//!   | texturename | string | "" (no map: no displacement) |
//!
//! * `dented` (RI companion): six octaves of `abs(0.5 − noise)` in shader space,
//!   `magnitude = Σ |0.5 − noise(frequency·2ⁱ·Pshader)| / 2ⁱ` (below 1),
//!   `P -= Km * magnitude^power * normalize(N)`: dents, never bumps.
//!
//!   | name | type | default |
//!   |---|---|---|
//!   | Km | float | 1 |
//!   | power | float | 3 |
//!   | frequency | float | 1 |
//!
//! * `ripple` (Illume's, with a closed form for tests and bounds):
//!   `P += (offset + Km * sin(2π·(frequency·s + phase))) * normalize(N)`; with `frequency 0`
//!   and `phase 0` it is a constant displacement by `offset`. The largest displacement is
//!   `|offset| + |Km|`: that is the bound to give.
//!
//!   | name | type | default |
//!   |---|---|---|
//!   | Km | float | 0.1 |
//!   | frequency | float | 4 |
//!   | phase | float | 0 (in cycles) |
//!   | offset | float | 0 |
use crate::error::ShadeError;
use crate::geometric::normalize_or_zero;
use crate::materials::environment::texture_colors;
use crate::noise::noise;
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

const NAMES: [&str; 3] = ["bumpy", "dented", "ripple"];

/// Binds displacement shader `name` (`bumpy`, `dented`, `ripple`); see [`crate::surface`] for
/// the warnings.
pub fn displacement(
    name: &str,
    params: &[Param],
) -> Result<(Displacement, Vec<String>), ShadeError> {
    let specs: &[(&str, ParamValue)] = match name {
        "bumpy" => &[
            ("Km", ParamValue::Float(1.0)),
            ("texturename", ParamValue::String(String::new())),
        ],
        "dented" => &[
            ("Km", ParamValue::Float(1.0)),
            ("power", ParamValue::Float(3.0)),
            ("frequency", ParamValue::Float(1.0)),
        ],
        "ripple" => &[
            ("Km", ParamValue::Float(0.1)),
            ("frequency", ParamValue::Float(4.0)),
            ("phase", ParamValue::Float(0.0)),
            ("offset", ParamValue::Float(0.0)),
        ],
        _ => {
            return Err(ShadeError::UnknownShader {
                kind: "displacement",
                name: name.to_string(),
                known: NAMES.join(", "),
            })
        }
    };
    let (params, warnings) = ShaderParams::bind(name, specs, params, false);
    Ok((
        Displacement {
            name: name.to_string(),
            params,
        },
        warnings,
    ))
}

/// Runs `d` on the grid: moves `P` along `normalize(N)` by the shader's amount and recomputes
/// `N` from the displaced grid (`calculatenormal`). A non-finite amount leaves the point where
/// it was; `bumpy` with a missing map warns once and leaves the grid unchanged.
pub fn displace(d: &Displacement, grid: &mut ShadingGrid, env: &ShadingEnv) {
    let amount: Vec<f32> = match d.name.as_str() {
        "bumpy" => {
            let name = d.params.string("texturename");
            if name.is_empty() {
                return;
            }
            let amp = texture_colors(env, grid, name, 1, 0.0);
            let km = d.params.float_on(grid, "Km");
            (0..grid.len()).map(|i| km.at(i) * amp[i][0]).collect()
        }
        "dented" => dented(d, grid, env),
        "ripple" => {
            let km = d.params.float_on(grid, "Km");
            let freq = d.params.float_on(grid, "frequency");
            let phase = d.params.float_on(grid, "phase");
            let offset = d.params.float_on(grid, "offset");
            (0..grid.len())
                .map(|i| {
                    let cycles =
                        f64::from(freq.at(i)) * f64::from(grid.s[i]) + f64::from(phase.at(i));
                    let wave = (std::f64::consts::TAU * cycles).sin();
                    (f64::from(offset.at(i)) + f64::from(km.at(i)) * wave) as f32
                })
                .collect()
        }
        _ => return,
    };
    let before = grid.n.clone();
    for (i, a) in amount.into_iter().enumerate() {
        if a.is_finite() {
            grid.p[i] += a * normalize_or_zero(grid.n[i]);
        }
    }
    grid.n = grid.calculatenormal(&before);
}

/// `dented`'s signed amount per point (negative: into the surface).
fn dented(d: &Displacement, grid: &ShadingGrid, env: &ShadingEnv) -> Vec<f32> {
    let km = d.params.float_on(grid, "Km");
    let power = d.params.float_on(grid, "power");
    let freq = d.params.float_on(grid, "frequency");
    let shader_from_camera = env.camera_from("shader").unwrap_or_default().inverse();
    (0..grid.len())
        .map(|i| {
            let p = shader_from_camera
                .transform_point3(grid.p[i].as_dvec3())
                .as_vec3();
            let mut size = freq.at(i);
            let mut magnitude = 0.0f32;
            for octave in 0..6 {
                magnitude += (0.5 - noise(p * size)).abs() / (1u32 << octave) as f32;
                size *= 2.0;
            }
            -km.at(i) * magnitude.powf(power.at(i))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use illume_rib::Value;

    fn param(name: &str, v: f32) -> Param {
        Param {
            name: format!("uniform float {name}"),
            value: Value::Floats(vec![v]),
        }
    }

    /// A flat 5×5 grid in the z = 5 plane facing −z, with s = u across [0, 1].
    fn plane() -> ShadingGrid {
        let mut g = ShadingGrid::new(5, 5);
        for j in 0..5 {
            for i in 0..5 {
                let k = j * 5 + i;
                g.p[k] = Vec3::new(i as f32 * 0.25, j as f32 * 0.25, 5.0);
                g.n[k] = Vec3::new(0.0, 0.0, -2.0);
                g.s[k] = i as f32 * 0.25;
                g.t[k] = j as f32 * 0.25;
            }
        }
        g
    }

    #[test]
    fn ripple_moves_p_by_its_closed_form_along_n() {
        let (d, w) = displacement(
            "ripple",
            &[
                param("Km", 0.3),
                param("frequency", 1.5),
                param("offset", 0.05),
            ],
        )
        .unwrap();
        assert!(w.is_empty(), "{w:?}");
        let mut g = plane();
        displace(&d, &mut g, &ShadingEnv::new());
        for k in 0..g.len() {
            let s = f64::from(g.s[k]);
            let expected = 0.05 + 0.3 * (std::f64::consts::TAU * 1.5 * s).sin();
            // Along normalize(N) = −z.
            let moved = 5.0 - f64::from(g.p[k].z);
            assert!(
                (moved - expected).abs() < 1e-6,
                "s {s}: {moved} vs {expected}"
            );
            assert!(g.n[k].z < 0.0, "calculatenormal keeps the side");
        }
    }

    #[test]
    fn dented_only_dents_and_by_at_most_km() {
        let (d, _) = displacement("dented", &[param("Km", 0.2), param("frequency", 3.0)]).unwrap();
        let mut g = plane();
        let before = g.p.clone();
        displace(&d, &mut g, &ShadingEnv::new());
        let mut any = false;
        for (a, b) in before.iter().zip(&g.p) {
            let moved = b.z - a.z; // +z is into the surface (N is −z)
            assert!((0.0..=0.2).contains(&moved), "{moved}");
            any |= moved > 1e-4;
            assert_eq!((a.x, a.y), (b.x, b.y));
        }
        assert!(any, "some point moved");
    }

    #[test]
    fn unknown_names_are_refused_with_the_known_list() {
        let e = displacement("brickbump", &[]).unwrap_err().to_string();
        assert!(e.contains("brickbump") && e.contains("ripple"), "{e}");
    }
}
