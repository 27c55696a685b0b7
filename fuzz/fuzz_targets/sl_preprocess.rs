//! Fuzzes the Shading Language lexer and preprocessor (`#define` with and without parameters,
//! `#if`/`#ifdef` nesting, macro expansion) on arbitrary text.
#![no_main]
use illume_sl::{preprocess::preprocess_str, PpOptions, SourceMap};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    // `#include` resolves relative names against the file's directory: keep that a directory
    // with nothing in it to include.
    let name = illume_fuzz::scratch_path("sl-dir").join("fuzz.sl");
    let mut map = SourceMap::new();
    let mut diags = Vec::new();
    let opts = PpOptions::default();
    let _ = preprocess_str(&mut map, &name.to_string_lossy(), &text, &opts, &mut diags);
    for d in &diags {
        // Every diagnostic must render (its span points into a registered file).
        let _ = d.render(&map).to_string();
    }
});
