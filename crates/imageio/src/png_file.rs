//! PNG (the `png` and `framebuffer` displays) and the PNG/JPEG readers.
//!
//! PNG holds 8 or 16-bit unsigned samples in grey, grey+alpha, RGB or RGBA, and its alpha is
//! *unassociated* (PNG specification §12.8) while rendered colour is premultiplied: the writer
//! divides colour by alpha before quantizing (where alpha > 0) and the reader multiplies it back,
//! so `read_image` returns premultiplied colour for every format, as OpenImageIO does.
//!
//! The writer keeps the
//! colour and alpha channels (a `z` channel has no place in PNG and is dropped; a depth-only image
//! is an error), quantizes per [`Quantize`], and uses 16 bits when the setting is wider than 8 bits
//! or float. Reading goes through the `image` crate with its allocation limits set from
//! [`crate::MAX_SAMPLES`].

use crate::atomic_write::write_atomically;
use crate::quantize::{quantize_image, Samples};
use crate::raster_limits::{check_size, MAX_DIMENSION, MAX_SAMPLES};
use crate::{format_error, io_error, Image, ImageError, Quantize};
use std::path::Path;

/// Writes `image` as PNG. Channel layouts: `rgb`, `rgba`, one channel (grey), or one channel and
/// `a` (grey+alpha); other layouts keep their first three or four channels in order.
pub(crate) fn write_png(
    path: &Path,
    image: &Image,
    quantize: Quantize,
    origin: [u32; 2],
) -> Result<(), ImageError> {
    let image = image.select(|c| c != "z");
    if image.channels.is_empty() {
        return Err(format_error(
            path,
            "PNG display expected colour or alpha channels, found only depth (use zfile, tiff or openexr)",
        ));
    }
    let image = if image.channels.len() > 4 {
        let keep: Vec<String> = image.channels[..4].to_vec();
        image.select(|c| keep.iter().any(|k| k == c))
    } else {
        image
    };
    let quantize = match quantize.sample_depth() {
        crate::SampleDepth::Float => Quantize {
            one: 65535,
            min: 0,
            max: 65535,
            dither: 0.0,
        },
        _ => quantize,
    };
    let image = associate_alpha(image, false);
    let color = match image.channels.len() {
        1 => png::ColorType::Grayscale,
        2 => png::ColorType::GrayscaleAlpha,
        3 => png::ColorType::Rgb,
        _ => png::ColorType::Rgba,
    };
    let (depth, bytes) = match quantize_image(&image, quantize, origin) {
        Samples::U8(v) => (png::BitDepth::Eight, v),
        Samples::U16(v) => (
            png::BitDepth::Sixteen,
            v.iter().flat_map(|s| s.to_be_bytes()).collect(),
        ),
        Samples::F32(_) => unreachable!("float quantize replaced by 16-bit above"),
    };
    write_atomically(path, |w| {
        let to_err = |e: png::EncodingError| format_error(path, format!("PNG encoder: {e}"));
        let mut encoder = png::Encoder::new(w, image.width, image.height);
        encoder.set_color(color);
        encoder.set_depth(depth);
        // Renders are written once and viewed: favour speed over the last few percent of size.
        encoder.set_compression(png::Compression::Fast);
        let mut writer = encoder.write_header().map_err(to_err)?;
        writer.write_image_data(&bytes).map_err(to_err)?;
        writer.finish().map_err(to_err)
    })
}

/// Reads a PNG or JPEG file (grey → `y`, with alpha → `y,a`; colour → `r,g,b(,a)`).
pub(crate) fn read_png_or_jpeg(path: &Path) -> Result<Image, ImageError> {
    let reader = image::ImageReader::open(path)
        .map_err(|e| io_error(path, e))?
        .with_guessed_format()
        .map_err(|e| io_error(path, e))?;
    let mut reader = reader;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_DIMENSION);
    limits.max_image_height = Some(MAX_DIMENSION);
    limits.max_alloc = Some(MAX_SAMPLES * 2);
    reader.limits(limits);
    let decoded = reader
        .decode()
        .map_err(|e| format_error(path, format!("cannot decode: {e}")))?;
    let (w, h) = (decoded.width(), decoded.height());
    use image::DynamicImage as D;
    let (names, data): (&[&str], Vec<f32>) = match decoded {
        D::ImageLuma8(b) => (
            &["y"],
            b.into_raw().iter().map(|&v| v as f32 / 255.0).collect(),
        ),
        D::ImageLumaA8(b) => (&["y", "a"], norm8(&b.into_raw())),
        D::ImageRgb8(b) => (&["r", "g", "b"], norm8(&b.into_raw())),
        D::ImageRgba8(b) => (&["r", "g", "b", "a"], norm8(&b.into_raw())),
        D::ImageLuma16(b) => (&["y"], norm16(&b.into_raw())),
        D::ImageLumaA16(b) => (&["y", "a"], norm16(&b.into_raw())),
        D::ImageRgb16(b) => (&["r", "g", "b"], norm16(&b.into_raw())),
        D::ImageRgba16(b) => (&["r", "g", "b", "a"], norm16(&b.into_raw())),
        D::ImageRgb32F(b) => (&["r", "g", "b"], b.into_raw()),
        D::ImageRgba32F(b) => (&["r", "g", "b", "a"], b.into_raw()),
        other => (&["r", "g", "b", "a"], other.into_rgba32f().into_raw()),
    };
    check_size(path, w as u64, h as u64, names.len() as u64)?;
    let image = Image {
        width: w,
        height: h,
        channels: names.iter().map(|s| s.to_string()).collect(),
        data,
    };
    Ok(associate_alpha(image, true))
}

/// Multiplies (`premultiply`) or divides the non-alpha channels by alpha. Division leaves
/// pixels with alpha ≤ 0 unchanged (their colour cannot be recovered).
fn associate_alpha(mut image: Image, premultiply: bool) -> Image {
    let Some(a) = image.channel_index("a") else {
        return image;
    };
    let nc = image.channels.len();
    for px in image.data.chunks_exact_mut(nc) {
        let alpha = px[a];
        for (c, v) in px.iter_mut().enumerate() {
            if c == a {
                continue;
            }
            if premultiply {
                *v *= alpha;
            } else if alpha > 0.0 {
                *v /= alpha;
            }
        }
    }
    image
}

fn norm8(v: &[u8]) -> Vec<f32> {
    v.iter().map(|&s| s as f32 / 255.0).collect()
}

fn norm16(v: &[u16]) -> Vec<f32> {
    v.iter().map(|&s| s as f32 / 65535.0).collect()
}
