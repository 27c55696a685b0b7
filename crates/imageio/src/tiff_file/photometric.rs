//! Photometric interpretation: channel names, alpha association, palettes and white-is-zero.

use super::ifd::Ifd;
use super::read::PixelFormat;
use super::samples::SampleKind;
use super::*;
use crate::{format_error, Image, ImageError};
use std::path::Path;

/// Names the decoded samples and interprets them as colour: premultiplies unassociated alpha,
/// expands a palette, inverts white-is-zero grey.
pub(super) fn interpret_channels(
    ifd: &Ifd,
    path: &Path,
    format: &PixelFormat,
    mut out: Vec<f32>,
    max_value: f64,
) -> Result<Image, ImageError> {
    let PixelFormat {
        width,
        height,
        spp,
        bits,
        kind,
        photometric,
        ..
    } = *format;
    let nc = spp as usize;
    let (w, h) = (width as usize, height as usize);
    let extra = ifd.uints(TAG_EXTRA_SAMPLES, 64)?.unwrap_or_default();
    let description = ifd.ascii(TAG_IMAGE_DESCRIPTION);
    let mut channels = channel_names(photometric, nc, &extra);
    if let Some(names) = description
        .as_deref()
        .and_then(|d| d.strip_prefix(DESCRIPTION_PREFIX))
    {
        let names: Vec<String> = names.split(',').map(|s| s.trim().to_string()).collect();
        if names.len() == nc {
            channels = names;
        }
    }
    // Unassociated alpha (ExtraSamples 2): premultiply, so every reader returns associated
    // colour (as OpenImageIO does).
    let first_extra = nc - extra.len().min(nc);
    if let Some(a) = channels.iter().position(|c| c == "a") {
        if a >= first_extra && extra.get(a - first_extra) == Some(&2) {
            for px in out.chunks_exact_mut(nc) {
                let alpha = px[a];
                for (c, v) in px.iter_mut().enumerate() {
                    if c != a && channels[c] != "z" {
                        *v *= alpha;
                    }
                }
            }
        }
    }
    if photometric == 3 {
        return expand_palette(ifd, path, w, h, nc, bits, &out, max_value);
    }
    if photometric == 0 && kind != SampleKind::Float {
        // WhiteIsZero: invert the grey sample.
        for px in out.chunks_exact_mut(nc) {
            px[0] = 1.0 - px[0];
        }
    }
    Ok(Image {
        width: width as u32,
        height: height as u32,
        channels,
        data: out,
    })
}

/// Default channel names from the photometric interpretation and `ExtraSamples`.
fn channel_names(photometric: u64, nc: usize, extra: &[u64]) -> Vec<String> {
    let color = photometric == 2 && nc >= 3;
    let mut names: Vec<String> = if color {
        vec!["r".into(), "g".into(), "b".into()]
    } else {
        vec!["y".into()]
    };
    let first_extra = names.len();
    let mut have_alpha = false;
    let mut have_z = false;
    for i in first_extra..nc {
        let declared = extra.get(i - first_extra).copied();
        let name = match declared {
            Some(1) | Some(2) if !have_alpha => {
                have_alpha = true;
                "a".to_string()
            }
            // No ExtraSamples tag (old renderers): the first extra is alpha, the next depth.
            None if !have_alpha => {
                have_alpha = true;
                "a".to_string()
            }
            _ if !have_z && (declared.is_none() || declared == Some(0)) => {
                have_z = true;
                "z".to_string()
            }
            _ => format!("channel{i}"),
        };
        names.push(name);
    }
    names
}

#[allow(clippy::too_many_arguments)]
fn expand_palette(
    ifd: &Ifd,
    path: &Path,
    w: usize,
    h: usize,
    nc: usize,
    bits: u64,
    indices: &[f32],
    max_value: f64,
) -> Result<Image, ImageError> {
    let n = 1usize << bits.min(16);
    let map = ifd
        .uints(TAG_COLOR_MAP, 3 * n as u64)?
        .ok_or_else(|| format_error(path, "TIFF palette image: expected a ColorMap, found none"))?;
    if map.len() < 3 * n {
        return Err(format_error(
            path,
            format!(
                "TIFF ColorMap: expected {} entries, found {}",
                3 * n,
                map.len()
            ),
        ));
    }
    let mut data = Vec::with_capacity(w * h * 3);
    for px in indices.chunks_exact(nc) {
        let i = ((px[0] as f64 * max_value).round() as usize).min(n - 1);
        for c in 0..3 {
            data.push(map[c * n + i] as f32 / 65535.0);
        }
    }
    Ok(Image {
        width: w as u32,
        height: h as u32,
        channels: vec!["r".into(), "g".into(), "b".into()],
        data,
    })
}
