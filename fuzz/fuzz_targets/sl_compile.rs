//! Fuzzes the whole Shading Language front end as `slc` and the renderer run it:
//! preprocess, parse, and (for programs without syntax errors) the type checker.
#![no_main]
use illume_sl::{compile_str, PpOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let name = illume_fuzz::scratch_path("sl-dir").join("fuzz.sl");
    let compiled = compile_str(&name.to_string_lossy(), &text, &PpOptions::default());
    let _ = compiled.render_diagnostics();
    let _ = compiled.into_program();
});
