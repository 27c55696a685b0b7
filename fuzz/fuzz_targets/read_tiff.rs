//! Fuzzes the TIFF decoder (`read_image` on bytes with a classic TIFF signature): strips and
//! tiles, every compression and predictor. It must return an image or an error, never panic,
//! hang or allocate what the header claims before checking it against the raster limits.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    illume_fuzz::read_image_if(data, &[b"II*\0", b"MM\0*"], "tiff");
});
