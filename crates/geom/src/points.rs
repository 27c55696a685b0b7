//! `Points` (RI Spec 3.2 §5.7 "Points"): one camera-facing disk per point, diameter `width`
//! (varying, per point) or `constantwidth` (default 1), both in object-space units.
//!
//! "Camera-facing" is parallel to the image plane: such a disk projects to an exact circle in
//! both orthographic and perspective views. Each disk is its own [`Parametric`] surface
//! (`u` around, `v` from the centre to the rim), so the hider dices it like any quadric; its
//! normal `dPdu × dPdv` points back at the camera (−z).
use crate::parametric::{default_st, with_default_st, Interp, Parametric, Surface, SurfaceVar};
use crate::primvar::{camera_values, is_position, resolve, ClassCounts, PrimVar, PrimVarData};
use crate::{Bound, BuildContext, GeomError, Primitive};
use glam::{DMat3, DMat4, DVec3};
use illume_rib::{Class, ParamList, Value};
use std::f64::consts::TAU;
use std::sync::Arc;

/// A disk of radius `r` centred at `c`, parallel to the image plane (camera space).
#[derive(Clone, Debug, PartialEq)]
pub struct PointDisk {
    pub c: DVec3,
    pub r: f64,
}

impl Surface for PointDisk {
    fn eval(&self, u: f64, v: f64) -> [DVec3; 3] {
        let (s, c) = (TAU * u).sin_cos();
        let rho = self.r * v;
        [
            self.c + DVec3::new(rho * c, rho * s, 0.0),
            DVec3::new(-rho * s * TAU, rho * c * TAU, 0.0),
            DVec3::new(self.r * c, self.r * s, 0.0),
        ]
    }

    fn bound(&self, _u: [f64; 2], _v: [f64; 2]) -> Bound {
        let d = DVec3::new(self.r, self.r, 0.0);
        Bound::from_dpoints([self.c - d, self.c + d])
    }
}

/// How much object-space lengths grow in camera space: the cube root of the volume scale
/// (exact for uniform scales, the geometric mean of the axis stretches otherwise).
pub(crate) fn width_scale(m: &DMat4) -> f64 {
    DMat3::from_mat4(*m).determinant().abs().cbrt()
}

/// Number of values a "P" parameter holds / 3, before resolution needs the counts.
pub(crate) fn count_of_p(params: &ParamList) -> usize {
    params
        .iter()
        .find(|p| p.name == "P" || p.name.ends_with(" P"))
        .map_or(0, |p| match &p.value {
            Value::Floats(v) => v.len() / 3,
            Value::Ints(v) => v.len() / 3,
            Value::Strings(_) => 0,
        })
}

/// Builds a `Points` request.
pub fn build_points(
    params: &ParamList,
    ctx: &BuildContext,
) -> Result<Vec<Box<dyn Primitive>>, GeomError> {
    let invalid = |message: String| GeomError::Invalid {
        request: "Points".to_string(),
        message,
    };
    let n = count_of_p(params);
    let counts = ClassCounts {
        uniform: 1,
        varying: n,
        vertex: n,
        facevarying: n,
    };
    let vars = resolve("Points", params, ctx.declarations, &counts, ctx.warnings)?;
    let m = &ctx.camera_from_object;
    let p = vars
        .iter()
        .find(|v| v.name == "P")
        .ok_or_else(|| invalid("needs \"P\"".to_string()))?;
    let centres = camera_values(p, m);
    let widths = widths(&vars, n, width_scale(m)).map_err(invalid)?;
    let st = default_st(
        &ctx.texture_coordinates,
        [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]],
    );
    let others: Vec<(&PrimVar, Vec<f64>)> = vars
        .iter()
        .filter(|v| !is_position(v) && !matches!(v.name.as_str(), "width" | "constantwidth"))
        .filter(|v| matches!(v.data, PrimVarData::Floats(_)))
        .map(|v| (v, camera_values(v, m)))
        .collect();
    let mut out: Vec<Box<dyn Primitive>> = Vec::with_capacity(n);
    for (k, c) in centres.chunks_exact(3).enumerate() {
        let c = DVec3::new(c[0], c[1], c[2]);
        let r = 0.5 * widths[k];
        if !c.is_finite() || !r.is_finite() {
            return Err(invalid(format!("point {k} is not finite")));
        }
        if r <= 0.0 {
            continue;
        }
        let svars = others
            .iter()
            .map(|(v, values)| {
                let size = v.element_size();
                let i = if matches!(v.class, Class::Constant | Class::Uniform) {
                    0
                } else {
                    k
                };
                SurfaceVar {
                    name: v.name.clone(),
                    ty: v.ty,
                    components: size,
                    interp: Interp::Constant(values[i * size..(i + 1) * size].to_vec()),
                }
            })
            .collect();
        out.push(Box::new(Parametric::new(
            Arc::new(PointDisk { c, r }),
            Arc::new(with_default_st(svars, st.clone())),
        )));
    }
    Ok(out)
}

/// Camera-space diameters from `width` (one per point) or `constantwidth` (default 1).
pub(crate) fn widths(vars: &[PrimVar], n: usize, scale: f64) -> Result<Vec<f64>, String> {
    let find = |name: &str| {
        vars.iter()
            .find(|v| v.name == name && v.element_size() == 1)
    };
    let w: Vec<f64> = if let Some(w) = find("width").filter(|w| w.floats().len() == n) {
        w.floats().iter().map(|&x| f64::from(x) * scale).collect()
    } else {
        let c = find("constantwidth").map_or(1.0, |c| c.floats().first().copied().unwrap_or(1.0));
        vec![f64::from(c) * scale; n]
    };
    if w.iter().any(|x| !x.is_finite() || *x < 0.0) {
        return Err("widths must be finite and not negative".to_string());
    }
    Ok(w)
}
