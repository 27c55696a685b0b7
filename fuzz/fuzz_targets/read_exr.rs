//! Fuzzes the OpenEXR reader (`read_image` on bytes with the OpenEXR magic): scanline and
//! tiled files, any compression, first layer and largest level.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    illume_fuzz::read_image_if(data, &[&[0x76, 0x2f, 0x31, 0x01]], "exr");
});
