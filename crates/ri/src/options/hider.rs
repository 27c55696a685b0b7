//! The `Hider` option (RI Spec 3.2 §4.1.3).
use crate::diagnostic::Diagnostics;
use crate::options::{DepthFilter, Options};
use crate::paramlist;
use illume_rib::{ParamList, Span};

impl Options {
    /// `Hider "hidden"` and its parameters (`jitter`, `depthfilter`); other hiders fall back
    /// to "hidden".
    pub(crate) fn hider(
        &mut self,
        name: &str,
        h: &str,
        params: &ParamList,
        span: &Span,
        diagnostics: &mut Diagnostics,
    ) {
        let o = self;
        if h != "hidden" {
            diagnostics.warn(
                span,
                name,
                format!("hider `{h}` not supported, using \"hidden\""),
            );
        }
        for p in paramlist::names(params)
            .map(str::to_string)
            .collect::<Vec<_>>()
        {
            match p.as_str() {
                "jitter" => o.jitter = paramlist::float(params, "jitter").unwrap_or(1.0) != 0.0,
                "depthfilter" => {
                    let v = paramlist::string(params, "depthfilter").unwrap_or_default();
                    o.depth_filter = match v.as_str() {
                        "min" => DepthFilter::Min,
                        "max" => DepthFilter::Max,
                        "average" => DepthFilter::Average,
                        "midpoint" => DepthFilter::Midpoint,
                        other => {
                            diagnostics.error(
                                span,
                                name,
                                format!("depthfilter must be min, max, average or midpoint, found `{other}`"),
                            );
                            o.depth_filter
                        }
                    };
                }
                other => diagnostics.warn(
                    span,
                    name,
                    format!("parameter \"{other}\" not supported (ignored)"),
                ),
            }
        }
    }
}
