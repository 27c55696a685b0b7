//! Finding shaders by name on the shader searchpath and compiling each `.sl` once per run.
//!
//! Lookup rule (README "Shading Language"): for `Surface "name"` (and `Displacement`,
//! `LightSource`, `AreaLightSource`) the renderer looks for `name.sl` in each directory of
//! `Option "searchpath" "shader"` in order (relative entries against the working directory;
//! the default is `.`), then in the directory of the RIB file that made the request. The first
//! file found wins, over the built-in shader of the same name too; when none is found the
//! built-in (or `defaultsurface`) is used. `#include "x.h"` is searched next to the including
//! file, then in those same directories (searchpath, then the RIB's directory): shader
//! libraries keep their headers beside or above their `.sl` files (K-3D's `k3d_*.h`, Advanced
//! RenderMan's `noises.h`), and a renderer that compiles on first use has no `slc -I` to be
//! told where. A file is compiled on first use and cached by path, include directories and
//! modification time for the rest of the run; compile errors are returned (the renderer warns
//! once with their `file:line:col` and falls back to the built-in).
use crate::exec::CompiledShader;
use illume_sl::ast::{Program, ShaderId};
use illume_sl::types::ShaderKind;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::SystemTime;

/// The outcome of compiling one file: the program, or the rendered diagnostics.
type Compiled = Result<Arc<Program>, String>;

/// A file and the include directories it was compiled with.
type CacheKey = (PathBuf, Vec<PathBuf>);

/// A cache of compiled `.sl` files keyed by path and modification time.
#[derive(Default)]
pub struct ShaderLibrary {
    cache: Mutex<HashMap<CacheKey, (Option<SystemTime>, Compiled)>>,
}

impl ShaderLibrary {
    pub fn new() -> ShaderLibrary {
        ShaderLibrary::default()
    }

    /// The process-wide library (`render` compiles each file once per run).
    pub fn global() -> &'static ShaderLibrary {
        static LIB: OnceLock<ShaderLibrary> = OnceLock::new();
        LIB.get_or_init(ShaderLibrary::new)
    }

    /// The first `name.sl` on `searchpath`, then in `request_dir`.
    pub fn find(name: &str, searchpath: &[String], request_dir: Option<&Path>) -> Option<PathBuf> {
        if name.is_empty() {
            return None;
        }
        let file = if name.ends_with(".sl") {
            name.to_string()
        } else {
            format!("{name}.sl")
        };
        if Path::new(&file).is_absolute() {
            let p = PathBuf::from(&file);
            return p.is_file().then_some(p);
        }
        searchpath
            .iter()
            .map(|d| Path::new(d).join(&file))
            .chain(request_dir.map(|d| d.join(&file)))
            .find(|p| p.is_file())
    }

    /// Compiles `path` with `#include` searched in `include_dirs` after the including file's
    /// directory (or returns the cached result while its mtime is unchanged).
    pub fn compile(&self, path: &Path, include_dirs: &[PathBuf]) -> Compiled {
        let mtime = std::fs::metadata(path).and_then(|m| m.modified()).ok();
        let key = (path.to_path_buf(), include_dirs.to_vec());
        if let Ok(cache) = self.cache.lock() {
            if let Some((t, c)) = cache.get(&key) {
                if *t == mtime {
                    return c.clone();
                }
            }
        }
        let result = crate::frontend::compile_path(path, include_dirs).map(Arc::new);
        if let Ok(mut cache) = self.cache.lock() {
            cache.insert(key, (mtime, result.clone()));
        }
        result
    }

    /// Looks `name` up and compiles it. `None`: no file (use the built-in). `Some(Err)`: the
    /// file exists but does not compile, or defines no `kind` shader.
    pub fn load(
        &self,
        name: &str,
        kind: ShaderKind,
        searchpath: &[String],
        request_dir: Option<&Path>,
    ) -> Option<Result<CompiledShader, String>> {
        let path = Self::find(name, searchpath, request_dir)?;
        let include_dirs: Vec<PathBuf> = searchpath
            .iter()
            .map(PathBuf::from)
            .chain(request_dir.map(Path::to_path_buf))
            .collect();
        Some(self.compile(&path, &include_dirs).and_then(|program| {
            pick_shader(&program, kind, name)
                .map(|id| CompiledShader {
                    program: program.clone(),
                    id,
                })
                .ok_or_else(|| {
                    format!(
                        "{}: defines no {kind} shader (named `{name}` or otherwise)",
                        path.display()
                    )
                })
        }))
    }
}

/// The shader of `kind` in `program`: the one named `name`, else the first of that kind.
pub fn pick_shader(program: &Program, kind: ShaderKind, name: &str) -> Option<ShaderId> {
    let base = Path::new(name)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(name);
    let of_kind = || {
        program
            .shaders
            .iter()
            .enumerate()
            .filter(|(_, s)| s.kind == kind)
    };
    of_kind()
        .find(|(_, s)| s.name == base)
        .or_else(|| of_kind().next())
        .map(|(k, _)| ShaderId(k as u32))
}

/// Compiles one `.sl` file with the `illume-sl` front end (`#include` next to the file only);
/// errors rendered as `file:line:col: error: …` lines.
pub fn compile_file(path: &Path) -> Result<Program, String> {
    crate::frontend::compile_path(path, &[])
}
