//! From the rendered float image to the frame's `Display`s through `illume-imageio`.
//! No `Display` means `ri.tif` (rgba); `framebuffer` writes a PNG named after the display.
use crate::Rendered;
use illume_imageio::{
    write_display_cropped, write_tiff_tiled, DepthMatrices, Image, ImageError, Quantize,
};
use illume_reyes::{column_block_width, AovLayout};
use illume_ri::{transform, DisplaySpec, Frame};
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum DisplayError {
    #[error("Display \"{name}\": unknown mode \"{mode}\"")]
    Mode { name: String, mode: String },
    #[error("Display \"{name}\": {message}")]
    Channels { name: String, message: String },
    #[error(transparent)]
    Image(#[from] ImageError),
    #[error(transparent)]
    Shadow(#[from] illume_texture::TextureError),
}

/// What was written, so the CLI can say where a `framebuffer` went.
#[derive(Clone, Debug, PartialEq)]
pub struct WrittenDisplay {
    pub path: PathBuf,
    pub kind: String,
    pub framebuffer: bool,
}

/// The float image for one display mode (`rgb`, `rgba`, `a`, `z`, `rgbz`, `rgbaz`).
pub fn display_image(r: &Rendered, mode: &str) -> Option<Image> {
    let letters: Vec<char> = mode.chars().collect();
    if letters.is_empty() || letters.iter().any(|c| !"rgbaz".contains(*c)) {
        return None;
    }
    let mut data = Vec::with_capacity((r.width * r.height) as usize * letters.len());
    for (px, z) in r.rgba.chunks_exact(4).zip(&r.z) {
        for c in &letters {
            data.push(match c {
                'r' => px[0],
                'g' => px[1],
                'b' => px[2],
                'a' => px[3],
                _ => *z,
            });
        }
    }
    Some(Image {
        width: r.width,
        height: r.height,
        channels: letters.iter().map(|c| c.to_string()).collect(),
        data,
    })
}

/// Writes every display of `frame` from the whole rendered image `r`.
pub fn write_displays(frame: &Frame, r: &Rendered) -> Vec<Result<WrittenDisplay, DisplayError>> {
    plan_displays(frame, &r.aov_layout)
        .into_iter()
        .map(|plan| plan?.write(frame, r))
        .collect()
}

/// The displays a frame writes: its `Display`s, or `ri.tif` (rgba) when it names none.
pub(crate) fn frame_displays(frame: &Frame) -> Vec<DisplaySpec> {
    if frame.options.displays.is_empty() {
        vec![DisplaySpec {
            name: "ri.tif".into(),
            kind: "tiff".into(),
            mode: "rgba".into(),
            ..Default::default()
        }]
    } else {
        frame.options.displays.clone()
    }
}

/// One display, decided before any pixel exists: file, kind, channels and quantization.
/// Whether a mode is valid depends only on the mode and the variables the hider carries, so
/// the decision is the same for a whole image ([`write_displays`]) and for streamed rows.
pub(crate) struct DisplayPlan {
    pub(crate) name: String,
    pub(crate) path: PathBuf,
    /// The file kind written (`framebuffer` writes `png`).
    pub(crate) kind: String,
    pub(crate) framebuffer: bool,
    /// `Display "shadow"`: a shadow map (.sm) from depth, whatever the mode says.
    pub(crate) shadow: bool,
    /// Letters of `rgbaz`, or the display's mode items (arbitrary output variables).
    channels: Channels,
    pub(crate) quantize: Quantize,
}

enum Channels {
    Letters(String),
    /// Output variables and the display's exposure (gain, gamma) for their colour channels.
    Items(Vec<crate::aov::ModeItem>, (f32, f32)),
}

/// A plan per display of `frame`, in order; `layout` is what the hider carries.
pub(crate) fn plan_displays(
    frame: &Frame,
    layout: &AovLayout,
) -> Vec<Result<DisplayPlan, DisplayError>> {
    // Every variable the hider carried, as the mode parser's last source of types.
    let rendered_vars: crate::aov::SlOutputs = layout
        .channels
        .iter()
        .map(|c| (c.name.clone(), c.components, c.colour))
        .collect();
    frame_displays(frame)
        .iter()
        .map(|d| plan_display(frame, d, &rendered_vars))
        .collect()
}

fn plan_display(
    frame: &Frame,
    d: &DisplaySpec,
    rendered_vars: &crate::aov::SlOutputs,
) -> Result<DisplayPlan, DisplayError> {
    let shadow = d.kind == "shadow";
    let mode = if shadow { "z" } else { d.mode.as_str() };
    let framebuffer = d.kind == "framebuffer";
    let mut non_colour = false;
    let channels = if is_letters(mode) {
        Channels::Letters(mode.to_string())
    } else if mode.contains(',') || !mode.is_empty() {
        let items = crate::aov::mode_items(d, frame, rendered_vars).map_err(|message| {
            DisplayError::Channels {
                name: d.name.clone(),
                message,
            }
        })?;
        non_colour = crate::aov_display::has_non_colour(&items);
        let exposure = crate::aov_display::display_exposure(d, frame.options.exposure);
        Channels::Items(items, exposure)
    } else {
        return Err(DisplayError::Mode {
            name: d.name.clone(),
            mode: d.mode.clone(),
        });
    };
    let (path, kind) = if framebuffer {
        let p = PathBuf::from(&d.name);
        let p = if p.extension().is_some_and(|e| e == "png") {
            p
        } else {
            p.with_extension("png")
        };
        (p, "png".to_string())
    } else {
        (PathBuf::from(&d.name), d.kind.clone())
    };
    let q = if d.mode == "z" {
        frame.options.quantize_z
    } else {
        frame.options.quantize_rgba
    };
    let q = Quantize {
        one: q.one,
        min: q.min,
        max: q.max,
        dither: q.dither,
    };
    // Depth and non-colour variables are never quantized, dithered or clamped.
    let quantize = if non_colour {
        Quantize::FLOAT
    } else {
        crate::aov_display::display_quantize(d, q)
    };
    Ok(DisplayPlan {
        name: d.name.clone(),
        path,
        kind,
        framebuffer,
        shadow,
        channels,
        quantize,
    })
}

/// Whether `mode` is a group of `rgbaz` letters ([`display_image`]'s modes).
fn is_letters(mode: &str) -> bool {
    !mode.is_empty() && mode.chars().all(|c| "rgbaz".contains(c))
}

impl DisplayPlan {
    /// The display's float image of the pixels in `r` (a whole crop or a band of its rows).
    pub(crate) fn image(&self, r: &Rendered) -> Result<Image, DisplayError> {
        match &self.channels {
            Channels::Letters(mode) => display_image(r, mode).ok_or_else(|| DisplayError::Mode {
                name: self.name.clone(),
                mode: mode.clone(),
            }),
            Channels::Items(items, exposure) => {
                let kind = if self.framebuffer {
                    "png"
                } else {
                    self.kind.as_str()
                };
                crate::aov_display::aov_image(r, items, &kind.to_ascii_lowercase(), *exposure)
                    .map_err(|message| DisplayError::Channels {
                        name: self.name.clone(),
                        message,
                    })
            }
        }
    }

    /// Whether rows can go to the file as they arrive (TIFF strips); other kinds are written
    /// from a whole-frame buffer at the end.
    pub(crate) fn streams(&self) -> bool {
        !self.shadow && matches!(self.kind.to_ascii_lowercase().as_str(), "tiff" | "file")
    }

    /// The tile width of the display's file for a crop window `width` pixels wide: a TIFF of
    /// a window rendered in column blocks is tiled a block wide, so that its blocks can be
    /// written as they arrive (`DisplayStream`) and the whole-image file is the same bytes.
    pub(crate) fn tile_width(&self, width: u32) -> Option<u32> {
        column_block_width(width).filter(|_| self.streams())
    }

    /// Writes the display from the whole rendered crop `r`.
    pub(crate) fn write(self, frame: &Frame, r: &Rendered) -> Result<WrittenDisplay, DisplayError> {
        let image = self.image(r)?;
        if self.shadow {
            let opts = illume_texture::MakeOptions {
                source: "Display \"shadow\"".into(),
                ..Default::default()
            };
            illume_texture::make_shadow(&image, &depth_matrices(frame), &self.path, &opts)?;
        } else {
            // Dither is keyed on full-frame pixels, so crops rendered apart (`--crop`,
            // render farms) quantize exactly as the same pixels of a full render.
            let depth = depth_matrices(frame);
            let origin = [r.x0, r.y0];
            match self.tile_width(image.width) {
                Some(w) => write_tiff_tiled(&self.path, &image, self.quantize, origin, w)?,
                None => write_display_cropped(
                    &self.path,
                    &self.kind,
                    &image,
                    self.quantize,
                    Some(&depth),
                    origin,
                )?,
            }
        }
        Ok(self.written())
    }

    pub(crate) fn written(self) -> WrittenDisplay {
        WrittenDisplay {
            path: self.path,
            kind: self.kind,
            framebuffer: self.framebuffer,
        }
    }
}

/// The camera's matrices `zfile`, `shadow` and `openexr` record.
fn depth_matrices(frame: &Frame) -> DepthMatrices {
    let cam = &frame.camera;
    DepthMatrices {
        world_to_screen: transform::to_rib(&cam.screen_from_world()),
        world_to_camera: transform::to_rib(&cam.camera_from_world),
    }
}
