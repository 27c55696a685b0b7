//! The picture readers' targets: `read_image` on bytes with one format's magic, so each target
//! stays on its own decoder, and `read_zfile`. Errors are fine; panics, hangs and huge
//! allocations are the bugs.
use super::scratch_file;

/// Reads one image through `read_image` if `data` starts with one of `magics`.
fn read_image_if(data: &[u8], magics: &[&[u8]], tag: &str) -> Option<illume_imageio::Image> {
    if !magics.iter().any(|m| data.starts_with(m)) {
        return None;
    }
    let path = scratch_file(tag, data);
    let image = illume_imageio::read_image(&path).ok();
    if let Some(img) = &image {
        assert_whole(img);
    }
    image
}

/// Every reader promises width × height × channels samples.
fn assert_whole(img: &illume_imageio::Image) {
    assert_eq!(
        img.data.len(),
        img.width as usize * img.height as usize * img.channels.len()
    );
}

/// The TIFF decoder (classic TIFF, either byte order): strips and tiles, every compression and
/// predictor; nothing the header claims is allocated before the raster limits check it.
pub fn read_tiff(data: &[u8]) {
    read_image_if(data, &[b"II*\0", b"MM\0*"], "tiff");
}

/// The PNG and JPEG readers (PNG or JPEG signature).
pub fn read_png(data: &[u8]) {
    read_image_if(data, &[&[0x89, b'P', b'N', b'G'], &[0xFF, 0xD8]], "png");
}

/// The OpenEXR reader: scanline and tiled files, any compression, first layer, largest level.
pub fn read_exr(data: &[u8]) {
    read_image_if(data, &[&[0x76, 0x2f, 0x31, 0x01]], "exr");
}

/// The PRMan zfile reader (either byte order), the matrices included.
pub fn read_zfile(data: &[u8]) {
    let magic = illume_imageio::ZFILE_MAGIC;
    if !(data.starts_with(&magic.to_le_bytes()) || data.starts_with(&magic.to_be_bytes())) {
        return;
    }
    let path = scratch_file("zfile", data);
    if let Ok((img, _matrices)) = illume_imageio::read_zfile(&path) {
        assert_whole(&img);
    }
}
