//! Fuzzes the PRMan zfile reader (either byte order), the matrices included.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let magic = illume_imageio::ZFILE_MAGIC;
    if !(data.starts_with(&magic.to_le_bytes()) || data.starts_with(&magic.to_be_bytes())) {
        return;
    }
    let path = illume_fuzz::scratch_file("zfile", data);
    if let Ok((img, _matrices)) = illume_imageio::read_zfile(&path) {
        assert_eq!(
            img.data.len(),
            img.width as usize * img.height as usize * img.channels.len()
        );
    }
});
