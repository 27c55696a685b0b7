//! Fuzzes the Shading Language parser: preprocessed tokens of arbitrary text, parsed with
//! error recovery (the checker is `sl_compile`'s).
#![no_main]
use illume_sl::{parser::parse, preprocess::preprocess_str, PpOptions, SourceMap};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let name = illume_fuzz::scratch_path("sl-dir").join("fuzz.sl");
    let mut map = SourceMap::new();
    let mut diags = Vec::new();
    let tokens = preprocess_str(
        &mut map,
        &name.to_string_lossy(),
        &text,
        &PpOptions::default(),
        &mut diags,
    );
    let _ = parse(&tokens, &mut diags);
    for d in &diags {
        let _ = d.render(&map).to_string();
    }
});
