//! libFuzzer entry for [`illume_fuzz::sl_parse`] (the body lives in `src/`, where the stable
//! smoke test `tests/fuzz_smoke.rs` runs it too).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| illume_fuzz::sl_parse(data));
