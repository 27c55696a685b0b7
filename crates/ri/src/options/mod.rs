//! Frame options with the defaults of RI Spec 3.2 Table 4.1 (and the PRMan `Option`s that real
//! scenes rely on: limits, searchpath, shadow).
use crate::attributes::Shader;
use crate::diagnostic::Diagnostics;
use illume_rib::{ParamList, Request, Span};

mod camera;
mod display;
mod hider;
mod limits;
mod user;

pub(crate) use limits::check_vertices;
pub use limits::{declared_vertices, Limits};

#[derive(Clone, Debug, PartialEq)]
pub enum Projection {
    /// `fov` in degrees, spanning the shorter screen axis.
    Perspective {
        fov: f32,
    },
    Orthographic,
}

/// `Hider "hidden" "depthfilter"`: how the depths of a pixel's samples combine into its z.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DepthFilter {
    Min,
    Max,
    Average,
    /// Average of the nearest and second-nearest surface at each sample (shadow maps).
    Midpoint,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct DisplaySpec {
    pub name: String,
    /// `tiff`, `file`, `png`, `openexr`, `zfile`, `framebuffer`, …
    pub kind: String,
    /// `rgb`, `rgba`, `a`, `z`, `rgbz`, …, or comma-separated variables
    /// (`"rgba,__diffuse,N"`, `"varying color __spec"`): see the driver's `aov.rs`.
    pub mode: String,
    pub params: ParamList,
    /// The `Declare`d types of the mode's variable names at the time of the `Display` (inline
    /// declarations and built-in globals are resolved by the driver).
    pub declared: Vec<(String, illume_rib::Declaration)>,
}

/// A `DisplayChannel` (PRMan): an output variable declared once, with the display parameters
/// (`"filter"`, `"filterwidth"`, `"quantize"`, `"dither"`) every display naming it inherits.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayChannel {
    pub name: String,
    pub declaration: illume_rib::Declaration,
    pub params: ParamList,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuantizeSpec {
    pub one: i32,
    pub min: i32,
    pub max: i32,
    pub dither: f32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    pub xres: u32,
    pub yres: u32,
    pub pixel_aspect: f32,
    /// `FrameAspectRatio`; `None` means `xres·pixel_aspect / yres`.
    pub frame_aspect: Option<f32>,
    /// `ScreenWindow` left right bottom top; `None` means derived from the frame aspect.
    pub screen_window: Option<[f32; 4]>,
    /// `CropWindow` xmin xmax ymin ymax in NDC.
    pub crop: [f32; 4],
    pub projection: Projection,
    pub near: f32,
    pub far: f32,
    /// `PixelSamples` x y.
    pub pixel_samples: [u32; 2],
    pub pixel_variance: f32,
    /// `PixelFilter` name, xwidth, ywidth.
    pub filter: (String, f32, f32),
    /// A program's own filter function, tabulated by the C binding (`filter` then names the
    /// nearest standard kernel, which RIB output writes). A `PixelFilter` request clears it.
    pub filter_table: Option<std::sync::Arc<illume_core::filter::FilterTable>>,
    /// `Exposure` gain, gamma.
    pub exposure: (f32, f32),
    pub quantize_rgba: QuantizeSpec,
    pub quantize_z: QuantizeSpec,
    pub displays: Vec<DisplaySpec>,
    /// `DisplayChannel`s declared so far (a later declaration of a name replaces it).
    pub display_channels: Vec<DisplayChannel>,
    pub jitter: bool,
    pub depth_filter: DepthFilter,
    /// `Option "limits" "bucketsize"`, pixels. The default is 32 × 16, not PRMan's 16 × 16:
    /// a bucket samples its pixels and a filter's reach around them, so a micropolygon near a
    /// bucket's edge is set up and tested by every bucket whose reach it touches, and wider
    /// buckets repeat that less (eleventh session, callgrind at 2× Format: −2.7% instructions
    /// on `rib/sphere.rib`, −9% on `rib/bench/transform_blur.rib`, whose moving micropolygons
    /// reach far). The height stays 16: a band's rows (and a column block's) are that tall.
    /// The price: a bucket's samples and visible points, per thread (+1.8 MB peak RSS at
    /// 640×480 `rib/bench/spotlight.rib`, 4×4 samples). The image is the same bits.
    pub bucket_size: [u32; 2],
    pub grid_size: u32,
    pub eye_splits: u32,
    /// Kilobytes, as PRMan's `texturememory`.
    pub texture_memory: u32,
    /// The other `Option "limits"` values (image size, samples, vertices, nesting, …).
    pub limits: Limits,
    pub shader_path: Vec<String>,
    pub texture_path: Vec<String>,
    pub archive_path: Vec<String>,
    pub procedural_path: Vec<String>,
    /// `Option "shadow" "bias0"/"bias1"` (`"bias"` sets both).
    pub shadow_bias: [f32; 2],
    /// `Option "shading" "string specularmodel"` (DESIGN.md: "prman" switches the exponent).
    pub specular_model: String,
    /// `Option "trace" "maxdepth"`: how many `trace()` bounces a ray may take (BMRT's
    /// default 2: a mirror sees a mirror's reflection, then black).
    pub trace_max_depth: u32,
    /// `Shutter` open, close (default 0 0: no motion blur).
    pub shutter: [f32; 2],
    /// `DepthOfField` fstop, focallength, focaldistance; `None` is a pinhole camera.
    pub depth_of_field: Option<[f32; 3]>,
    /// `Imager name params` (RI Spec 3.2 §4.1.4): run on every pixel after the pixel filter,
    /// before exposure and quantization. `None` (the default, or `Imager "null"`) runs none.
    /// Imagers work in raster space, so `camera_from_shader` is the identity.
    pub imager: Option<Shader>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            xres: 640,
            yres: 480,
            pixel_aspect: 1.0,
            frame_aspect: None,
            screen_window: None,
            crop: [0.0, 1.0, 0.0, 1.0],
            projection: Projection::Orthographic,
            near: f32::EPSILON,
            far: f32::INFINITY,
            pixel_samples: [2, 2],
            pixel_variance: 0.0,
            filter: ("gaussian".into(), 2.0, 2.0),
            filter_table: None,
            exposure: (1.0, 1.0),
            quantize_rgba: QuantizeSpec {
                one: 255,
                min: 0,
                max: 255,
                dither: 0.5,
            },
            quantize_z: QuantizeSpec {
                one: 0,
                min: 0,
                max: 0,
                dither: 0.0,
            },
            displays: Vec::new(),
            display_channels: Vec::new(),
            jitter: true,
            depth_filter: DepthFilter::Min,
            bucket_size: [32, 16],
            grid_size: 256,
            eye_splits: 10,
            texture_memory: 8192,
            limits: Limits::default(),
            shader_path: vec![".".into()],
            texture_path: vec![".".into()],
            archive_path: vec![".".into()],
            procedural_path: vec![".".into()],
            shadow_bias: [0.225, 0.225],
            specular_model: "prman".into(),
            trace_max_depth: 2,
            shutter: [0.0, 0.0],
            depth_of_field: None,
            imager: None,
        }
    }
}

impl Options {
    /// The frame aspect ratio in effect.
    pub fn frame_aspect(&self) -> f32 {
        self.frame_aspect.unwrap_or_else(|| {
            illume_core::spaces::frame_aspect(self.xres, self.yres, self.pixel_aspect)
        })
    }

    /// The screen window in effect: the spec's default is `[-a,a]×[-1,1]` for `a ≥ 1`,
    /// else `[-1,1]×[-1/a,1/a]`.
    pub fn screen_window(&self) -> [f32; 4] {
        if let Some(w) = self.screen_window {
            return w;
        }
        illume_core::spaces::default_screen_window(self.frame_aspect())
    }

    /// The crop window in pixels, half-open `[x0,x1)×[y0,y1)`, rounded as RI Spec 3.2
    /// `RiCropWindow` says (`ceil(xres·xmin)` to `ceil(xres·xmax) − 1`).
    pub fn crop_pixels(&self) -> [u32; 4] {
        let [x0, x1, y0, y1] = self.crop;
        let f = |v: f32, res: u32| ((res as f32 * v).ceil().max(0.0) as u32).min(res);
        [
            f(x0, self.xres),
            f(x1, self.xres),
            f(y0, self.yres),
            f(y1, self.yres),
        ]
    }
}

impl Options {
    /// Applies one option request (RI Spec 3.2 §4.1). Bad values are reported to
    /// `diagnostics` and leave the option as it was.
    pub(crate) fn apply(&mut self, req: Request, span: &Span, diagnostics: &mut Diagnostics) {
        let name = req.name().to_string();
        use Request::*;
        match req {
            Format { .. } | FrameAspectRatio(_) | ScreenWindow { .. } | CropWindow { .. } => {
                self.screen_option(req, span, diagnostics)
            }
            Projection { .. } | Clipping { .. } | Shutter { .. } | DepthOfField { .. } => {
                self.camera_option(req, span, diagnostics)
            }
            Imager { name: n, params } => {
                self.imager = (n != "null" && !n.is_empty()).then(|| Shader {
                    name: n,
                    params,
                    camera_from_shader: glam::DMat4::IDENTITY,
                    span: span.clone(),
                });
            }
            ClippingPlane { .. } | RelativeDetail(_) => {
                diagnostics.warn(span, &name, "not supported yet (ignored)");
            }
            ColorSamples { n_rgb, .. } if n_rgb.len() != 9 => {
                diagnostics.warn(
                    span,
                    &name,
                    "only 3 RGB color samples are supported (ignored)",
                );
            }
            PixelVariance(_)
            | PixelSamples { .. }
            | PixelFilter { .. }
            | Exposure { .. }
            | Quantize { .. }
            | Display { .. }
            | DisplayChannel { .. } => self.display_option(req, span, diagnostics),
            Hider { name: h, params } => self.hider(&name, &h, &params, span, diagnostics),
            Option { name: n, params } => self.user_option(&n, &params, span, diagnostics),
            _ => {}
        }
    }
}

/// Expands a `searchpath` value: `:`-separated; `&` is the previous value, `@` the default.
pub fn expand_search_path(value: &str, previous: &[String], default: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for part in value.split(':').filter(|p| !p.is_empty()) {
        match part {
            "&" => out.extend(previous.iter().cloned()),
            "@" => out.extend(default.iter().cloned()),
            p => out.push(p.to_string()),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_screen_window_follows_frame_aspect() {
        let o = Options::default();
        let a = 640.0 / 480.0;
        assert_eq!(o.screen_window(), [-a, a, -1.0, 1.0]);
        let tall = Options {
            xres: 100,
            yres: 200,
            ..Options::default()
        };
        assert_eq!(tall.screen_window(), [-1.0, 1.0, -2.0, 2.0]);
    }

    #[test]
    fn crop_windows_tile_without_gaps() {
        let mut o = Options {
            crop: [0.0, 0.5, 0.0, 0.5],
            ..Options::default()
        };
        let a = o.crop_pixels();
        o.crop = [0.5, 1.0, 0.5, 1.0];
        let b = o.crop_pixels();
        assert_eq!(a, [0, 320, 0, 240]);
        assert_eq!(b, [320, 640, 240, 480]);
    }

    #[test]
    fn search_path_expands_previous_and_default() {
        let p = expand_search_path("/a:&:@", &["/old".into()], &[".".into()]);
        assert_eq!(p, vec!["/a", "/old", "."]);
    }
}
