//! The implementation-specific `Attribute` request (RI Spec 3.2 §4.2.10): identifier,
//! displacement bound, dicing, light sampling and shadow visibility.
use crate::paramlist;
use crate::state::Ri;
use illume_rib::{ParamList, Span};

impl Ri {
    pub(crate) fn user_attribute(&mut self, name: &str, params: &ParamList, span: &Span) {
        for p in paramlist::names(params)
            .map(str::to_string)
            .collect::<Vec<_>>()
        {
            let f = paramlist::float(params, &p);
            match (name, p.as_str()) {
                ("identifier", "name") => {
                    self.attrs().identifier = paramlist::string(params, "name")
                }
                ("displacementbound", "sphere") if f.is_some() => {
                    // The bound is given in "coordinatesystem" (object by default): scale it
                    // by the largest axis stretch of that space into camera space.
                    let space = paramlist::string(params, "coordinatesystem")
                        .unwrap_or_else(|| "object".to_string());
                    // "shader": the space the current Displacement was declared in.
                    let shader = self.attributes.displacement.as_ref();
                    let m = match space.as_str() {
                        "shader" => Some(shader.map_or(self.ctm, |s| s.camera_from_shader)),
                        s => self.named_space(s),
                    };
                    let m = m.unwrap_or_else(|| {
                        self.diagnostics.warn(
                            span,
                            "Attribute",
                            format!(
                                "\"displacementbound\": unknown coordinatesystem \"{space}\"; using object space"
                            ),
                        );
                        self.ctm
                    });
                    let stretch = [m.x_axis, m.y_axis, m.z_axis]
                        .iter()
                        .map(|a| a.truncate().length())
                        .fold(0.0, f64::max);
                    self.attrs().displacement_bound =
                        (f64::from(f.unwrap_or(0.0)) * stretch) as f32;
                }
                ("displacementbound", "coordinatesystem") => {}
                ("dice", "binary") => self.attrs().dice_binary = f.unwrap_or(0.0) != 0.0,
                ("light", "shadows") => match on_off(params, &p) {
                    Some(on) => self.attrs().light_shadows = on,
                    None => self.diagnostics.error(
                        span,
                        "Attribute",
                        "\"light\" \"shadows\": expected \"on\" or \"off\"",
                    ),
                },
                ("light", "nsamples") => match f {
                    Some(n) if n >= 1.0 && n.is_finite() => {
                        self.attrs().light_samples = (n as u32).min(4096)
                    }
                    _ => self.diagnostics.error(
                        span,
                        "Attribute",
                        "\"light\" \"nsamples\": expected a positive count",
                    ),
                },
                ("visibility", "transmission") | ("render", "casts_shadows") => {
                    match casts_shadows(params, &p) {
                        Some(c) => {
                            self.attrs().casts_shadows = c;
                            self.attrs().transmission_os = matches!(
                                paramlist::string(params, &p).as_deref(),
                                Some("Os" | "shader" | "shade")
                            );
                        }
                        None => self.diagnostics.error(
                            span,
                            "Attribute",
                            format!(
                                "\"{name}\" \"{p}\": expected \"opaque\", \"Os\", \"shader\", \"transparent\", \"none\" or 0/1"
                            ),
                        ),
                    }
                }
                ("visibility", "trace" | "reflection") if f.is_some() => {
                    self.attrs().visible_to_rays = f.unwrap_or(1.0) != 0.0
                }
                ("render", "visibility") if f.is_some() => {
                    // BMRT's bit set: 1 camera, 2 reflection rays, 4 shadow rays.
                    let bits = f.unwrap_or(7.0) as u32;
                    self.attrs().visible_to_rays = bits & 2 != 0;
                    self.attrs().casts_shadows = bits & 4 != 0;
                }
                (_, p) => self.diagnostics.warn(
                    span,
                    "Attribute",
                    format!("\"{name}\" \"{p}\" not supported (ignored)"),
                ),
            }
        }
    }
}

/// `"on"`/`"off"` (or 1/0) for `Attribute "light" "shadows"`.
fn on_off(params: &ParamList, name: &str) -> Option<bool> {
    if let Some(s) = paramlist::string(params, name) {
        return match s.as_str() {
            "on" => Some(true),
            "off" => Some(false),
            _ => None,
        };
    }
    paramlist::float(params, name).map(|f| f != 0.0)
}

/// Whether geometry casts shadows under BMRT's `"visibility" "transmission"` /
/// `"render" "casts_shadows"` values (or PRMan's integer `transmission`). "Os" and "shader"
/// (partial transmission) cast; the built-in lights' shadow rays treat them as opaque, SL's
/// `transmission()` as `1 − Os` (see `Attributes::transmission_os`).
fn casts_shadows(params: &ParamList, name: &str) -> Option<bool> {
    if let Some(s) = paramlist::string(params, name) {
        return match s.as_str() {
            "opaque" | "Os" | "shader" | "shade" => Some(true),
            "transparent" | "none" => Some(false),
            _ => None,
        };
    }
    paramlist::float(params, name).map(|f| f != 0.0)
}
