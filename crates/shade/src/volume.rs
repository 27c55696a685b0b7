//! Volume shaders (RI 3.2 §9 "Volume shaders", the standard `fog` and `depthcue`): they run on
//! a grid *after* its surface shader, see the premultiplied `Ci`/`Oi` the surface left and the
//! ray `I` from the eye `E` to `P`, and attenuate both toward a background colour. As
//! `Atmosphere` they run only where a surface was hit: the background stays as the hider
//! leaves it (RI 3.2: "atmosphere shaders are only applied to surfaces").
//!
//! * `fog` (RI 3.2 standard), `d = 1 − exp(−length(I)/distance)`:
//!   `Ci = mix(Ci, background, d)`, `Oi = mix(Oi, 1, d)`.
//!
//!   | name | type | default |
//!   |---|---|---|
//!   | distance | float | 1 |
//!   | background | color | 0 |
//!
//! * `depthcue` (RI 3.2 standard), `d = clamp((depth(P) − mindistance)/(maxdistance −
//!   mindistance), 0, 1)` with `depth()` the camera-space z mapped so the near clipping plane is
//!   0 and the far 1: `Ci = mix(Ci, background, d)`, `Oi = mix(Oi, 1, d)`.
//!
//!   | name | type | default |
//!   |---|---|---|
//!   | mindistance | float | 0 |
//!   | maxdistance | float | 1 |
//!   | background | color | 0 |
//!
//! * `null`: leaves `Ci`/`Oi` alone (as `Atmosphere "null"` switches a volume off).
use crate::error::ShadeError;
use crate::parameters::{ParamValue, ShaderParams};
use crate::shadingenv::ShadingEnv;
use crate::shadinggrid::ShadingGrid;
use glam::Vec3;
use illume_rib::Param;

/// A bound built-in volume shader.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    name: String,
    params: ShaderParams,
}

impl Volume {
    pub fn name(&self) -> &str {
        &self.name
    }
}

const NAMES: [&str; 3] = ["fog", "depthcue", "null"];

/// Binds volume shader `name` (`fog`, `depthcue`, `null`); parameter problems come back as
/// warnings, an unknown name as [`ShadeError::UnknownShader`].
pub fn volume(name: &str, params: &[Param]) -> Result<(Volume, Vec<String>), ShadeError> {
    let black = ParamValue::Color(Vec3::ZERO);
    let specs: Vec<(&str, ParamValue)> = match name {
        "fog" => vec![("distance", ParamValue::Float(1.0)), ("background", black)],
        "depthcue" => vec![
            ("mindistance", ParamValue::Float(0.0)),
            ("maxdistance", ParamValue::Float(1.0)),
            ("background", black),
        ],
        "null" => Vec::new(),
        _ => {
            return Err(ShadeError::UnknownShader {
                kind: "volume",
                name: name.to_string(),
                known: NAMES.join(", "),
            })
        }
    };
    let (params, warnings) = ShaderParams::bind(name, &specs, params, false);
    Ok((
        Volume {
            name: name.to_string(),
            params,
        },
        warnings,
    ))
}

/// `depth(P)` as the SL built-in computes it: 0 at the near plane, 1 at the far, 0 everywhere
/// when the far plane is infinite.
fn depth(env: &ShadingEnv, p: Vec3) -> f64 {
    let (near, far) = (f64::from(env.clipping.0), f64::from(env.clipping.1));
    let range = far - near;
    if range.is_finite() && range > 0.0 {
        (f64::from(p.z) - near) / range
    } else {
        0.0
    }
}

/// Runs `v` over the grid's `Ci`/`Oi` (in place). The blend is computed in `f64`; a
/// non-finite blend factor (a zero `distance`, equal min/max distances) leaves the point as
/// the surface shaded it.
pub fn run_volume(v: &Volume, grid: &mut ShadingGrid, env: &ShadingEnv) {
    let n = grid.len();
    let d: Vec<f64> = match v.name.as_str() {
        "fog" => {
            let dist = v.params.float_on(grid, "distance");
            (0..n)
                .map(|i| 1.0 - (-grid.i[i].as_dvec3().length() / f64::from(dist.at(i))).exp())
                .collect()
        }
        "depthcue" => {
            let (lo, hi) = (
                v.params.float_on(grid, "mindistance"),
                v.params.float_on(grid, "maxdistance"),
            );
            (0..n)
                .map(|i| {
                    let (lo, hi) = (f64::from(lo.at(i)), f64::from(hi.at(i)));
                    ((depth(env, grid.p[i]) - lo) / (hi - lo)).clamp(0.0, 1.0)
                })
                .collect()
        }
        _ => return,
    };
    let bg: Vec<Vec3> = {
        let b = v.params.vec3_on(grid, "background");
        (0..n).map(|i| b.at(i)).collect()
    };
    for (i, d) in d.into_iter().enumerate() {
        if !d.is_finite() {
            continue;
        }
        let mix = |a: Vec3, b: Vec3| (a.as_dvec3() * (1.0 - d) + b.as_dvec3() * d).as_vec3();
        grid.ci[i] = mix(grid.ci[i], bg[i]);
        grid.oi[i] = mix(grid.oi[i], Vec3::ONE);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use illume_rib::Value;

    fn float(name: &str, v: f32) -> Param {
        Param {
            name: name.to_string(),
            value: Value::Floats(vec![v]),
        }
    }

    fn color(name: &str, c: [f32; 3]) -> Param {
        Param {
            name: name.to_string(),
            value: Value::Floats(c.to_vec()),
        }
    }

    /// Four points at depths 1, 2, 5, 9 on the optical axis, Ci = (.8, .4, .2), Oi = 1.
    fn column() -> ShadingGrid {
        let mut g = ShadingGrid::new(4, 1);
        for (k, z) in [1.0f32, 2.0, 5.0, 9.0].into_iter().enumerate() {
            g.p[k] = Vec3::new(0.3 * k as f32, -0.2, z);
            g.ci[k] = Vec3::new(0.8, 0.4, 0.2);
            g.oi[k] = Vec3::ONE;
        }
        g.set_incident_from_p(false);
        g
    }

    #[test]
    fn fog_is_the_closed_form_exponential() {
        let (v, w) = volume(
            "fog",
            &[float("distance", 3.0), color("background", [0.1, 0.2, 0.9])],
        )
        .unwrap();
        assert!(w.is_empty(), "{w:?}");
        let mut g = column();
        let before = g.clone();
        run_volume(&v, &mut g, &ShadingEnv::new());
        for k in 0..4 {
            let t = (-before.p[k].as_dvec3().length() / 3.0).exp();
            let bg = [0.1f64, 0.2, 0.9];
            for (c, bg) in bg.into_iter().enumerate() {
                let want = bg + (f64::from(before.ci[k][c]) - bg) * t;
                assert!((f64::from(g.ci[k][c]) - want).abs() < 1e-6, "{k} {c}");
            }
            assert!((g.oi[k] - Vec3::ONE).abs().max_element() < 1e-6);
        }
    }

    #[test]
    fn fog_raises_the_opacity_of_a_transparent_surface() {
        let (v, _) = volume("fog", &[float("distance", 2.0)]).unwrap();
        let mut g = column();
        g.oi.iter_mut().for_each(|o| *o = Vec3::splat(0.25));
        run_volume(&v, &mut g, &ShadingEnv::new());
        let d = 1.0 - (-g.p[2].as_dvec3().length() / 2.0).exp();
        let want = 0.25 * (1.0 - d) + d;
        assert!((f64::from(g.oi[2].x) - want).abs() < 1e-6);
    }

    #[test]
    fn depthcue_is_linear_between_its_distances() {
        let (v, _) = volume(
            "depthcue",
            &[float("mindistance", 0.1), float("maxdistance", 0.7)],
        )
        .unwrap();
        let mut g = column();
        let env = ShadingEnv {
            clipping: (1.0, 11.0),
            ..ShadingEnv::new()
        };
        run_volume(&v, &mut g, &env);
        for (k, z) in [1.0f64, 2.0, 5.0, 9.0].into_iter().enumerate() {
            let depth = (z - 1.0) / 10.0;
            let d = ((depth - 0.1) / 0.6).clamp(0.0, 1.0);
            let want = 0.8 * (1.0 - d);
            assert!((f64::from(g.ci[k].x) - want).abs() < 1e-6, "{k}");
        }
    }

    #[test]
    fn null_and_degenerate_parameters_leave_the_surface_alone() {
        let mut g = column();
        let before = g.clone();
        let (v, _) = volume("null", &[]).unwrap();
        run_volume(&v, &mut g, &ShadingEnv::new());
        let (v, _) = volume("depthcue", &[float("maxdistance", 0.0)]).unwrap();
        run_volume(&v, &mut g, &ShadingEnv::new());
        assert_eq!(g, before);
        let e = volume("smoke", &[]).unwrap_err().to_string();
        assert!(e.contains("smoke") && e.contains("depthcue"), "{e}");
    }
}
