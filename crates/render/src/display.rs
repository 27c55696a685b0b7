//! From the rendered float image to the frame's `Display`s through `illume-imageio`.
//! No `Display` means `ri.tif` (rgba); `framebuffer` writes a PNG named after the display.
use crate::Rendered;
use illume_imageio::{write_display_cropped, DepthMatrices, Image, ImageError, Quantize};
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

pub fn write_displays(frame: &Frame, r: &Rendered) -> Vec<Result<WrittenDisplay, DisplayError>> {
    let default = [DisplaySpec {
        name: "ri.tif".into(),
        kind: "tiff".into(),
        mode: "rgba".into(),
        ..Default::default()
    }];
    // Every variable the hider carried, as the mode parser's last source of types.
    let rendered_vars: crate::aov::SlOutputs = r
        .aov_layout
        .channels
        .iter()
        .map(|c| (c.name.clone(), c.components, c.colour))
        .collect();
    let displays = if frame.options.displays.is_empty() {
        &default[..]
    } else {
        &frame.options.displays[..]
    };
    let cam = &frame.camera;
    let depth = DepthMatrices {
        world_to_screen: transform::to_rib(&cam.screen_from_world()),
        world_to_camera: transform::to_rib(&cam.camera_from_world),
    };
    displays
        .iter()
        .map(|d| {
            // `Display "shadow"` writes a shadow map (.sm) directly from depth, whatever the
            // mode says: the same file `MakeShadow` makes from a zfile.
            let shadow = d.kind == "shadow";
            let mode = if shadow { "z" } else { d.mode.as_str() };
            let framebuffer = d.kind == "framebuffer";
            let letters = display_image(r, mode);
            let mut non_colour = false;
            let image = match letters {
                Some(image) => image,
                None if mode.contains(',') || !mode.is_empty() => {
                    let channels = |message| DisplayError::Channels {
                        name: d.name.clone(),
                        message,
                    };
                    let items =
                        crate::aov::mode_items(d, frame, &rendered_vars).map_err(channels)?;
                    non_colour = crate::aov_display::has_non_colour(&items);
                    let kind = if framebuffer { "png" } else { d.kind.as_str() };
                    let exposure = crate::aov_display::display_exposure(d, frame.options.exposure);
                    crate::aov_display::aov_image(r, &items, &kind.to_ascii_lowercase(), exposure)
                        .map_err(channels)?
                }
                None => {
                    return Err(DisplayError::Mode {
                        name: d.name.clone(),
                        mode: d.mode.clone(),
                    })
                }
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
            let q = if non_colour {
                Quantize::FLOAT
            } else {
                crate::aov_display::display_quantize(d, q)
            };
            if shadow {
                let opts = illume_texture::MakeOptions {
                    source: "Display \"shadow\"".into(),
                    ..Default::default()
                };
                illume_texture::make_shadow(&image, &depth, &path, &opts)?;
            } else {
                // Dither is keyed on full-frame pixels, so crops rendered apart (`--crop`,
                // render farms) quantize exactly as the same pixels of a full render.
                write_display_cropped(&path, &kind, &image, q, Some(&depth), [r.x0, r.y0])?;
            }
            Ok(WrittenDisplay {
                path,
                kind,
                framebuffer,
            })
        })
        .collect()
}
