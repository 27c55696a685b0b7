//! Camera options (RI Spec 3.2 §4.1.1): resolution and windows, projection, clipping, shutter
//! and depth of field.
use crate::diagnostic::Diagnostics;
use crate::options::Options;
use crate::paramlist;
use illume_rib::{Request, Span};

impl Options {
    /// `Format`, `FrameAspectRatio`, `ScreenWindow` and `CropWindow`: the image and the
    /// part of the screen it shows.
    pub(crate) fn screen_option(
        &mut self,
        req: Request,
        span: &Span,
        diagnostics: &mut Diagnostics,
    ) {
        let name = req.name().to_string();
        let o = self;
        use Request::*;
        match req {
            Format {
                xres,
                yres,
                pixel_aspect,
            } => {
                // Non-positive values mean "the device default" (RI Spec 3.2 `RiFormat`).
                o.xres = if xres > 0 { xres as u32 } else { 640 };
                o.yres = if yres > 0 { yres as u32 } else { 480 };
                o.pixel_aspect = if pixel_aspect > 0.0 {
                    pixel_aspect
                } else {
                    1.0
                };
                let (x, y) = o.limits.fit_resolution(o.xres, o.yres);
                if (x, y) != (o.xres, o.yres) {
                    diagnostics.error(
                        span,
                        &name,
                        format!(
                            "resolution {xres}×{yres} exceeds Option \"limits\" \"resolution\" {} \
                             or \"pixels\" {}: rendering {x}×{y} instead",
                            o.limits.resolution, o.limits.pixels
                        ),
                    );
                    (o.xres, o.yres) = (x, y);
                }
            }
            FrameAspectRatio(a) => {
                if a > 0.0 {
                    o.frame_aspect = Some(a);
                } else {
                    diagnostics.error(span, &name, format!("expected a positive ratio, found {a}"));
                }
            }
            ScreenWindow {
                left,
                right,
                bottom,
                top,
            } => {
                if left == right || bottom == top {
                    diagnostics.error(span, &name, "the window has zero width or height (ignored)");
                } else {
                    o.screen_window = Some([left, right, bottom, top]);
                }
            }
            CropWindow {
                xmin,
                xmax,
                ymin,
                ymax,
            } => {
                let c = [xmin, xmax, ymin, ymax].map(|v| v.clamp(0.0, 1.0));
                if c[0] >= c[1] || c[2] >= c[3] {
                    diagnostics.error(
                        span,
                        &name,
                        format!("empty window {xmin} {xmax} {ymin} {ymax} (ignored)"),
                    );
                } else {
                    o.crop = c;
                }
            }
            _ => {}
        }
    }

    /// `Projection`, `Clipping`, `Shutter` and `DepthOfField`: the camera model. (The
    /// caller resets the current transformation after `Projection`.)
    pub(crate) fn camera_option(
        &mut self,
        req: Request,
        span: &Span,
        diagnostics: &mut Diagnostics,
    ) {
        let name = req.name().to_string();
        let o = self;
        use Request::*;
        match req {
            Projection { name: p, params } => match p.as_str() {
                "perspective" => {
                    let fov = paramlist::float(&params, "fov").unwrap_or(90.0);
                    if fov > 0.0 && fov < 180.0 {
                        o.projection = crate::options::Projection::Perspective { fov };
                    } else {
                        diagnostics.error(
                            span,
                            &name,
                            format!("fov must lie in (0, 180) degrees, found {fov}"),
                        );
                    }
                }
                "orthographic" | "none" => o.projection = crate::options::Projection::Orthographic,
                other => diagnostics.error(
                    span,
                    &name,
                    format!("unknown projection `{other}`, expected perspective or orthographic"),
                ),
            },
            Clipping { near, far } => {
                if near > 0.0 && far > near {
                    o.near = near;
                    o.far = far;
                } else {
                    diagnostics.error(
                        span,
                        &name,
                        format!("expected 0 < near < far, found {near} {far}"),
                    );
                }
            }
            Shutter { open, close } => {
                if open.is_finite() && close.is_finite() && open <= close {
                    o.shutter = [open, close];
                } else {
                    diagnostics.error(
                        span,
                        &name,
                        format!("expected open ≤ close, found {open} {close}"),
                    );
                }
            }
            DepthOfField {
                fstop,
                focal_length,
                focal_distance,
            } => {
                // An infinite f-stop is the spec's way to ask for a pinhole camera.
                if fstop == f32::INFINITY {
                    o.depth_of_field = None;
                } else if fstop > 0.0
                    && focal_length > 0.0
                    && focal_distance > 0.0
                    && focal_length.is_finite()
                    && focal_distance.is_finite()
                {
                    o.depth_of_field = Some([fstop, focal_length, focal_distance]);
                } else {
                    diagnostics.error(
                        span,
                        &name,
                        format!(
                            "expected positive fstop, focallength and focaldistance, found {fstop} {focal_length} {focal_distance}"
                        ),
                    );
                }
            }
            _ => {}
        }
    }
}
