//! OpenEXR: the `openexr`/`exr` display and the OpenEXR reader.
//!
//! Writing rule: EXR is a linear, high-dynamic-range format, so values are never quantized,
//! dithered or clamped. Colour and alpha are `half` (OpenEXR's usual pixel type, ample for
//! display-referred and most HDR images) unless the `Quantize` setting asks for float output
//! (`one == 0`, e.g. `Quantize "rgba" 0 0 0 0`), then 32-bit float. Depth (`Z`) is always
//! 32-bit float: half's 11-bit mantissa cannot hold camera depths for shadow lookups.
//! Channels are named `R`, `G`, `B`, `A`, `Z` (OpenEXR conventions); scanlines, ZIP compression.
//! Any other channel (an arbitrary output variable: `__diffuse.R`, `N.X`, `s`) keeps its name;
//! only colour channels (`.R .G .B`) follow the half/float rule, the rest are always float
//! (normals, positions and texture coordinates need the precision).
//! Given the camera's [`DepthMatrices`], the header records OpenEXR's standard `worldToCamera`
//! and `worldToNDC` attributes (Imath row-vector order, the same as RIB's), so compositors and
//! OpenImageIO can reproject the depth.
//!
//! Reading: scanline or tiled files, the first valid layer at its largest resolution level
//! (level 0 of a mip- or rip-map); names are lower-cased (`Y` → `y`) and ordered
//! r, g, b, a, z, then the rest alphabetically.

use crate::atomic_write::write_atomically;
use crate::raster_limits::check_size;
use crate::{format_error, DepthMatrices, Image, ImageError, Quantize};
use exr::prelude::*;
use std::path::Path;

/// Writes `image` as a scanline OpenEXR file (see the module documentation for the rule).
pub(crate) fn write_exr(
    path: &Path,
    image: &Image,
    quantize: Quantize,
    depth: Option<&DepthMatrices>,
) -> std::result::Result<(), ImageError> {
    let nc = image.channels.len();
    let float_color = quantize.one == 0;
    let mut list: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
    for (c, name) in image.channels.iter().enumerate() {
        let values = image.data.iter().skip(c).step_by(nc);
        let colour = matches!(name.as_str(), "r" | "g" | "b" | "a")
            || [".R", ".G", ".B"].iter().any(|s| name.ends_with(s));
        let samples = if !colour || float_color {
            FlatSamples::F32(values.copied().collect())
        } else {
            FlatSamples::F16(values.map(|&v| f16::from_f32(v)).collect())
        };
        let exr_name = if matches!(name.as_str(), "r" | "g" | "b" | "a" | "z") {
            name.to_ascii_uppercase()
        } else {
            name.clone()
        };
        let exr_name = Text::new_or_none(exr_name).ok_or_else(|| {
            format_error(
                path,
                format!("OpenEXR: expected a channel name under 256 bytes, found `{name}`"),
            )
        })?;
        list.push(AnyChannel::new(exr_name, samples));
    }
    let size = (image.width as usize, image.height as usize);
    let mut attributes = LayerAttributes::default();
    if let Some(d) = depth {
        attributes.world_to_camera = Some(d.world_to_camera);
        attributes.world_to_normalized_device = Some(world_to_ndc(&d.world_to_screen));
    }
    let layer = Layer::new(
        size,
        attributes,
        Encoding {
            compression: Compression::ZIP16,
            blocks: Blocks::ScanLines,
            line_order: LineOrder::Increasing,
        },
        AnyChannels::sort(list),
    );
    let exr_image = exr::image::Image::from_layer(layer);
    write_atomically(path, |w| {
        exr_image
            .write()
            .to_buffered(w)
            .map_err(|e| format_error(path, format!("OpenEXR encoder: {e}")))
    })
}

/// OpenEXR's `worldToNDC` from the zfile's world → `Np` matrix: see
/// [`illume_core::spaces::world_to_ndc_from_np`], the one home of the conversion.
pub use illume_core::spaces::world_to_ndc_from_np as world_to_ndc;

/// Rank of a channel name in the order images carry them.
fn channel_rank(name: &str) -> usize {
    ["r", "g", "b", "a", "z", "y"]
        .iter()
        .position(|&n| n == name)
        .unwrap_or(6)
}

/// Reads the first layer of an OpenEXR file at full resolution.
pub(crate) fn read_exr(path: &Path) -> std::result::Result<Image, ImageError> {
    // Check the header's size before any pixel is allocated.
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| format_error(path, format!("OpenEXR header: {e}")))?;
    let header = meta
        .headers
        .first()
        .ok_or_else(|| format_error(path, "OpenEXR: expected a layer, found none"))?;
    if header.deep {
        return Err(format_error(
            path,
            "OpenEXR: expected flat image data, found deep data",
        ));
    }
    let size = header.layer_size;
    check_size(
        path,
        size.0 as u64,
        size.1 as u64,
        header.channels.list.len() as u64,
    )?;
    // Decoded on this thread and behind `catch_unwind`: the exr crate's decoders can panic on
    // corrupt data (B44 subtracts with overflow under overflow checks, found by fuzzing), and a
    // panic in its decoder thread pool aborts the process; here it becomes an error.
    let decoded = std::panic::catch_unwind(|| {
        read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .first_valid_layer()
            .all_attributes()
            .non_parallel()
            .from_file(path)
    })
    .map_err(|_| format_error(path, "OpenEXR: the decoder failed on corrupt pixel data"))?;
    let image = decoded.map_err(|e| format_error(path, format!("OpenEXR: {e}")))?;
    let layer = image.layer_data;
    let (w, h) = (layer.size.0, layer.size.1);
    let mut channels: Vec<(String, &FlatSamples)> = layer
        .channel_data
        .list
        .iter()
        .map(|c| (c.name.to_string().to_ascii_lowercase(), &c.sample_data))
        .collect();
    channels.sort_by(|a, b| (channel_rank(&a.0), &a.0).cmp(&(channel_rank(&b.0), &b.0)));
    let nc = channels.len();
    let mut data = vec![0f32; w * h * nc];
    for (c, (_, samples)) in channels.iter().enumerate() {
        if samples.len() != w * h {
            return Err(format_error(
                path,
                format!(
                    "OpenEXR: expected {} samples per channel, found {} (subsampled channels are not supported)",
                    w * h,
                    samples.len()
                ),
            ));
        }
        for (i, v) in samples.values_as_f32().enumerate() {
            data[i * nc + c] = v;
        }
    }
    Ok(Image {
        width: w as u32,
        height: h as u32,
        channels: channels.into_iter().map(|(n, _)| n).collect(),
        data,
    })
}
