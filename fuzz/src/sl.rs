//! The Shading Language front end's targets: lexer and preprocessor, parser, and the whole
//! `compile_str` (checker included), on arbitrary text.
use super::scratch_path;
use illume_sl::{compile_str, parser::parse, preprocess::preprocess_str, PpOptions, SourceMap};

/// The name the source is compiled under: `#include` resolves relative names against the
/// file's directory, so it is a directory with nothing in it (it is never created).
fn source_name() -> String {
    scratch_path("sl-dir")
        .join("fuzz.sl")
        .to_string_lossy()
        .into_owned()
}

/// Lexer and preprocessor (`#define` with and without parameters, `#if`/`#ifdef` nesting,
/// macro expansion); every diagnostic must render (its span points into a registered file).
pub fn sl_preprocess(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let mut map = SourceMap::new();
    let mut diags = Vec::new();
    let opts = PpOptions::default();
    let _ = preprocess_str(&mut map, &source_name(), &text, &opts, &mut diags);
    for d in &diags {
        let _ = d.render(&map).to_string();
    }
}

/// Preprocessed tokens parsed with error recovery (the checker is [`sl_compile`]'s).
pub fn sl_parse(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let mut map = SourceMap::new();
    let mut diags = Vec::new();
    let opts = PpOptions::default();
    let tokens = preprocess_str(&mut map, &source_name(), &text, &opts, &mut diags);
    let _ = parse(&tokens, &mut diags);
    for d in &diags {
        let _ = d.render(&map).to_string();
    }
}

/// Everything `slc` and the renderer run: preprocess, parse, and (for programs without syntax
/// errors) the type checker.
pub fn sl_compile(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let compiled = compile_str(&source_name(), &text, &PpOptions::default());
    let _ = compiled.render_diagnostics();
    let _ = compiled.into_program();
}
