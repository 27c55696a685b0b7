//! The one place the executor calls the `illume-sl` front end: file → checked program.
use illume_sl::ast::Program;
use illume_sl::PpOptions;
use std::path::{Path, PathBuf};

/// Compiles `path` to a checked program (`#include` searched next to the including file, then
/// in `include_dirs` in order); the error is every diagnostic rendered as
/// `file:line:col: error: message`, one per line.
pub fn compile_path(path: &Path, include_dirs: &[PathBuf]) -> Result<Program, String> {
    let opts = PpOptions {
        include_dirs: include_dirs.to_vec(),
        ..PpOptions::default()
    };
    let compiled = illume_sl::compile_file(path, &opts);
    if compiled.has_errors() {
        return Err(compiled.render_diagnostics().trim_end().to_string());
    }
    Ok(with_files(compiled))
}

/// Compiles source text (`name` is used in diagnostics), for tests and benchmarks.
pub fn compile_source(name: &str, text: &str) -> Result<Program, String> {
    let compiled = illume_sl::compile_str(name, text, &PpOptions::default());
    if compiled.has_errors() {
        return Err(compiled.render_diagnostics().trim_end().to_string());
    }
    Ok(with_files(compiled))
}

/// The program with the paths of the files it was read from (for run-time diagnostics).
fn with_files(compiled: illume_sl::Compiled) -> Program {
    let mut program = compiled.program;
    program.files = compiled.sources.files.into_iter().map(|f| f.path).collect();
    program
}
