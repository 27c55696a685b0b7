//! Shading attributes (RI Spec 3.2 §4.2.1–2, §4.2.4–5): color, opacity, shading rate and
//! interpolation, matte, texture coordinates, and the shaders bound to the geometry.
use crate::attributes::Shader;
use crate::state::Ri;
use illume_rib::{ParamList, Request, Span};
use std::sync::Arc;

impl Ri {
    /// The shading attributes of RI Spec 3.2 §4.2.1–2 and the shaders of §4.2.4–5.
    pub(crate) fn shading_attribute(&mut self, req: Request, span: &Span) {
        let name = req.name().to_string();
        use Request::*;
        match req {
            Color(c) | Opacity(c) if c.len() < 3 => self.diagnostics.error(
                span,
                &name,
                format!("expected 3 color samples, found {}", c.len()),
            ),
            Color(c) => self.attrs().color = [c[0], c[1], c[2]],
            Opacity(c) => self.attrs().opacity = [c[0], c[1], c[2]],
            TextureCoordinates(tc) => self.attrs().texture_coordinates = tc,
            ShadingRate(r) => {
                let floor = self.options.limits.min_shading_rate;
                if r >= floor {
                    self.attrs().shading_rate = r;
                } else if r > 0.0 {
                    // A rate of 1e-9 would dice every surface into ~10⁹ micropolygons per pixel.
                    self.diagnostics.warn(
                        span,
                        &name,
                        format!(
                            "{r} is below Option \"limits\" \"shadingrate\" {floor}; clamped to {floor}"
                        ),
                    );
                    self.attrs().shading_rate = floor;
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("expected a positive rate, found {r}"),
                    );
                }
            }
            ShadingInterpolation(kind) => match kind.as_str() {
                "smooth" => self.attrs().smooth_shading = true,
                "constant" => self.attrs().smooth_shading = false,
                other => self.diagnostics.error(
                    span,
                    &name,
                    format!("expected \"constant\" or \"smooth\", found \"{other}\""),
                ),
            },
            Matte(m) => self.attrs().matte = m,
            Surface { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().surface = Some(s);
            }
            Displacement { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().displacement = Some(s);
            }
            Atmosphere { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().atmosphere = Some(s);
            }
            Interior { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().interior = Some(s);
            }
            Exterior { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().exterior = Some(s);
            }
            Deformation { .. } => self
                .diagnostics
                .warn(span, &name, "not supported yet (ignored)"),
            other => self.diagnostics.error_kind(
                crate::ErrorKind::Bug,
                span,
                other.name(),
                "request not handled here (internal)",
            ),
        }
    }

    pub(crate) fn shader(&self, name: String, params: ParamList, span: &Span) -> Arc<Shader> {
        Arc::new(Shader {
            name,
            params,
            camera_from_shader: self.ctm,
            span: span.clone(),
        })
    }
}
