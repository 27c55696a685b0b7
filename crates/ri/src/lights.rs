//! Light sources in the RI state (RI Spec 3.2 §4.2.3): the frame's light list, indexed by
//! handle, and the current attributes' set of lights that are on.
use crate::attributes::Light;
use crate::state::Ri;
use illume_rib::{Handle, ParamList, Request, Span};

impl Ri {
    /// `LightSource`, `AreaLightSource` and `Illuminate` (RI Spec 3.2 §4.2.3).
    pub(crate) fn light_request(&mut self, req: Request, span: &Span) {
        let name = req.name().to_string();
        use Request::*;
        match req {
            LightSource {
                name: n,
                handle,
                params,
            } => self.light(n, handle, params, false, span),
            AreaLightSource {
                name: n,
                handle,
                params,
            } => self.light(n, handle, params, true, span),
            Illuminate { handle, on } => {
                let Some(i) = self.lights.iter().position(|l| l.handle == handle) else {
                    self.diagnostics.error_kind(
                        crate::ErrorKind::BadHandle,
                        span,
                        &name,
                        format!("no light with handle {handle:?}"),
                    );
                    return;
                };
                let a = self.attrs();
                a.lights.retain(|&l| l != i);
                if on {
                    a.lights.push(i);
                }
            }
            other => self.diagnostics.error_kind(
                crate::ErrorKind::Bug,
                span,
                other.name(),
                "request not handled here (internal)",
            ),
        }
    }

    pub(crate) fn light(
        &mut self,
        name: String,
        handle: Handle,
        params: ParamList,
        area: bool,
        span: &Span,
    ) {
        let shader = (*self.shader(name, params, span)).clone();
        let light = Light {
            handle: handle.clone(),
            shader,
            area,
            shadows: self.attributes.light_shadows,
            samples: self.attributes.light_samples,
        };
        let index = match self.lights.iter().position(|l| l.handle == handle) {
            Some(i) => {
                self.lights[i] = light;
                i
            }
            None => {
                self.lights.push(light);
                self.lights.len() - 1
            }
        };
        let a = self.attrs();
        a.lights.retain(|&l| l != index);
        a.lights.push(index);
        if area {
            a.area_light = Some(index);
        }
    }
}
