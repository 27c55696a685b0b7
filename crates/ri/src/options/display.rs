//! Display options (RI Spec 3.2 §4.1.2): sampling, the pixel filter, exposure, quantization
//! and the display list.
use crate::diagnostic::Diagnostics;
use crate::options::{DisplaySpec, Options, QuantizeSpec};
use illume_rib::{Request, Span};

impl Options {
    /// `PixelVariance`, `PixelSamples`, `PixelFilter`, `Exposure`, `Quantize` and `Display`.
    pub(crate) fn display_option(
        &mut self,
        req: Request,
        span: &Span,
        diagnostics: &mut Diagnostics,
    ) {
        let name = req.name().to_string();
        let o = self;
        use Request::*;
        match req {
            PixelVariance(v) => o.pixel_variance = v,
            PixelSamples { x, y } => {
                // `as` saturates: NaN becomes 0 (then 1), 1e30 becomes u32::MAX (then clamped).
                o.pixel_samples = [x.round().max(1.0) as u32, y.round().max(1.0) as u32];
                let max = o.limits.pixel_samples;
                if o.pixel_samples[0] > max || o.pixel_samples[1] > max {
                    diagnostics.warn(
                        span,
                        &name,
                        format!(
                            "{x}×{y} exceeds Option \"limits\" \"pixelsamples\" {max}; clamped to {max} per axis"
                        ),
                    );
                    o.pixel_samples = o.pixel_samples.map(|s| s.min(max));
                }
            }
            PixelFilter {
                name: f,
                xwidth,
                ywidth,
            } => {
                use illume_core::filter::{filter_names_list, FilterKind};
                o.filter_table = None;
                if FilterKind::parse(&f).is_none() {
                    diagnostics.warn(
                        span,
                        &name,
                        format!(
                            "unknown filter `{f}`, using gaussian (expected one of {})",
                            filter_names_list()
                        ),
                    );
                    o.filter = ("gaussian".into(), xwidth.max(1.0), ywidth.max(1.0));
                } else if !(xwidth > 0.0 && ywidth > 0.0) {
                    diagnostics.error(
                        span,
                        &name,
                        format!("widths must be positive, found {xwidth} {ywidth}"),
                    );
                } else {
                    o.filter = (f, xwidth.min(16.0), ywidth.min(16.0));
                }
            }
            Exposure { gain, gamma } => {
                if gamma > 0.0 {
                    o.exposure = (gain, gamma);
                } else {
                    diagnostics.error(
                        span,
                        &name,
                        format!("gamma must be positive, found {gamma}"),
                    );
                }
            }
            Quantize {
                kind,
                one,
                min,
                max,
                dither,
            } => {
                let q = QuantizeSpec {
                    one,
                    min,
                    max,
                    dither,
                };
                match kind.as_str() {
                    "rgba" => o.quantize_rgba = q,
                    "z" => o.quantize_z = q,
                    other => diagnostics.error(
                        span,
                        &name,
                        format!("expected \"rgba\" or \"z\", found \"{other}\""),
                    ),
                }
            }
            Display {
                name: file,
                kind,
                mode,
                params,
            } => {
                let spec = DisplaySpec {
                    name: file.trim_start_matches('+').to_string(),
                    kind,
                    mode,
                    params,
                    declared: Vec::new(),
                };
                if !file.starts_with('+') {
                    o.displays.clear();
                }
                o.displays.push(spec);
            }
            DisplayChannel { name: decl, params } => match illume_rib::Declaration::parse(&decl) {
                Ok(d) if d.name.is_some() && d.ty != illume_rib::Type::String => {
                    let channel = crate::options::DisplayChannel {
                        name: d.name.clone().unwrap_or_default(),
                        declaration: d,
                        params,
                    };
                    o.display_channels.retain(|c| c.name != channel.name);
                    o.display_channels.push(channel);
                }
                Ok(_) => diagnostics.error(
                    span,
                    &name,
                    format!("expected \"type name\" (e.g. \"color __diffuse\"), found \"{decl}\""),
                ),
                Err(e) => diagnostics.error(span, &name, format!("\"{decl}\": {e}")),
            },
            _ => {}
        }
    }
}
