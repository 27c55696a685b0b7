//! Fuzzes the PNG and JPEG readers (`read_image` on bytes with a PNG or JPEG signature).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    illume_fuzz::read_image_if(data, &[&[0x89, b'P', b'N', b'G'], &[0xFF, 0xD8]], "png");
});
