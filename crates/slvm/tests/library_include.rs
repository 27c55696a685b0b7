//! `#include` in shaders found on the searchpath: headers are searched next to the including
//! file, then in the searchpath's directories (the way K-3D's library keeps `k3d_*.h` one level
//! above `surface/k3d_brick.sl`).
use illume_sl::types::ShaderKind;
use illume_slvm::library::ShaderLibrary;
use std::path::PathBuf;

/// A fresh directory `lib/` with `lib/pattern.h` and `lib/surface/striped.sl` including it.
fn library(tag: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("illume-libinc-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(root.join("surface")).unwrap();
    std::fs::write(
        root.join("pattern.h"),
        "float stripes(float x) { return mod(floor(x * 4), 2); }\n",
    )
    .unwrap();
    std::fs::write(
        root.join("surface/striped.sl"),
        "#include \"pattern.h\"\nsurface striped() { Ci = color(stripes(s)); Oi = Os; }\n",
    )
    .unwrap();
    root
}

#[test]
fn includes_are_found_on_the_shader_searchpath() {
    let root = library("found");
    let path = vec![
        root.join("surface").display().to_string(),
        root.display().to_string(),
    ];
    let loaded = ShaderLibrary::new().load("striped", ShaderKind::Surface, &path, None);
    let compiled = loaded.expect("striped.sl is on the searchpath");
    assert!(compiled.is_ok(), "{:?}", compiled.err());
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_header_outside_every_searchpath_directory_is_an_error_naming_it() {
    let root = library("missing");
    let path = vec![root.join("surface").display().to_string()];
    let loaded = ShaderLibrary::new().load("striped", ShaderKind::Surface, &path, None);
    let Err(err) = loaded.expect("striped.sl is on the searchpath") else {
        panic!("pattern.h is not next to the shader nor on the searchpath");
    };
    assert!(err.contains("pattern.h"), "{err}");
    assert!(err.contains("striped.sl:1:"), "{err}");
    let _ = std::fs::remove_dir_all(&root);
}
