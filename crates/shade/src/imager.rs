//! Built-in imager shaders (RI Spec 3.2 §4.1.4 and Appendix A). An imager runs on each finished
//! pixel after the pixel filter and before exposure and quantization, seeing the pixel's
//! premultiplied colour `Ci` and its coverage `alpha`. The hider calls it per bucket on the
//! developed pixels, so it runs once per pixel whatever the thread count.
//!
//! * `background`: composites the pixel over a constant colour, `Ci = Ci + (1 − alpha)·bg`,
//!   and makes the pixel opaque (`alpha = 1`): the premultiplied "over" operator with an opaque
//!   backdrop.
//!
//!   | name | type | default |
//!   |---|---|---|
//!   | background | color | 1 1 1 |
//!   | bgcolor | color | 1 1 1 (another name for `background`; it wins when both are given) |
//!
//! * `clamptoalpha`: clamps each colour channel to `[0, alpha]`, so the premultiplied colour is
//!   valid (`Ci ≤ alpha`) before it is quantized or composited later. No parameters.
use crate::error::ShadeError;
use crate::parameters::{ParamValue, ShaderParams};
use glam::Vec3;
use illume_rib::Param;

/// A bound built-in imager.
#[derive(Clone, Debug, PartialEq)]
pub enum Imager {
    /// `background`: the backdrop colour.
    Background(Vec3),
    ClampToAlpha,
}

const NAMES: [&str; 2] = ["background", "clamptoalpha"];

/// Binds built-in imager `name`; unknown or ill-typed parameters come back as warnings (and
/// keep their defaults), an unknown name is an error.
pub fn imager(name: &str, params: &[Param]) -> Result<(Imager, Vec<String>), ShadeError> {
    match name {
        "background" => {
            let white = ParamValue::Color(Vec3::ONE);
            let specs = [("background", white.clone()), ("bgcolor", white)];
            let (bound, warnings) = ShaderParams::bind(name, &specs, params, false);
            let given = |n: &str| params.iter().any(|p| p.name.rsplit(' ').next() == Some(n));
            let colour = if given("bgcolor") {
                bound.vec3("bgcolor")
            } else {
                bound.vec3("background")
            };
            Ok((Imager::Background(colour), warnings))
        }
        "clamptoalpha" => {
            let (_, warnings) = ShaderParams::bind(name, &[], params, false);
            Ok((Imager::ClampToAlpha, warnings))
        }
        _ => Err(ShadeError::UnknownShader {
            kind: "imager",
            name: name.to_string(),
            known: NAMES.join(", "),
        }),
    }
}

impl Imager {
    /// Runs the imager on premultiplied RGBA pixels in place.
    pub fn apply(&self, rgba: &mut [[f32; 4]]) {
        match self {
            Imager::Background(bg) => {
                for px in rgba {
                    let uncovered = 1.0 - px[3];
                    for (c, b) in px[..3].iter_mut().zip(bg.to_array()) {
                        *c += uncovered * b;
                    }
                    px[3] = 1.0;
                }
            }
            Imager::ClampToAlpha => {
                for px in rgba {
                    let alpha = px[3].max(0.0);
                    for c in &mut px[..3] {
                        *c = c.clamp(0.0, alpha);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use illume_rib::Value;

    fn param(name: &str, v: &[f32]) -> Param {
        Param {
            name: name.into(),
            value: Value::Floats(v.to_vec()),
        }
    }

    #[test]
    fn background_is_premultiplied_over_an_opaque_colour() {
        let (im, w) = imager("background", &[param("color background", &[0.2, 0.4, 0.8])]).unwrap();
        assert!(w.is_empty(), "{w:?}");
        let mut px = [[0.1, 0.2, 0.3, 0.25], [0.0; 4], [0.5, 0.5, 0.5, 1.0]];
        im.apply(&mut px);
        let want = [
            [0.1 + 0.75 * 0.2, 0.2 + 0.75 * 0.4, 0.3 + 0.75 * 0.8, 1.0],
            [0.2, 0.4, 0.8, 1.0],
            [0.5, 0.5, 0.5, 1.0],
        ];
        for (a, b) in px.iter().flatten().zip(want.iter().flatten()) {
            assert!((a - b).abs() < 1e-6, "{px:?}");
        }
    }

    #[test]
    fn bgcolor_names_the_background_too() {
        let (im, _) = imager("background", &[param("color bgcolor", &[0.0, 1.0, 0.0])]).unwrap();
        assert_eq!(im, Imager::Background(Vec3::new(0.0, 1.0, 0.0)));
        let (im, _) = imager("background", &[]).unwrap();
        assert_eq!(im, Imager::Background(Vec3::ONE));
    }

    #[test]
    fn clamptoalpha_bounds_colour_by_coverage() {
        let (im, _) = imager("clamptoalpha", &[]).unwrap();
        let mut px = [[0.9, -0.1, 0.3, 0.5]];
        im.apply(&mut px);
        assert_eq!(px, [[0.5, 0.0, 0.3, 0.5]]);
    }

    #[test]
    fn an_unknown_imager_is_an_error() {
        assert!(imager("sepia", &[]).is_err());
    }
}
