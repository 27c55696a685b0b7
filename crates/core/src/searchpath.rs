//! Finding a file on an `Option "searchpath"` list (RI Spec 3.2 §4.1.4; PRMan's `texture`,
//! `shader`, `archive`, `procedural` and `resource` paths). The list itself is parsed by the RI
//! state (`&` for the previous value, `@` for the default); this is the lookup every consumer
//! shares, so a texture, a `MakeTexture` input and a shader are found by the same rule.
use std::path::{Path, PathBuf};

/// The first `dir/name` on `searchpath` that is a file; an absolute `name` only if it is a file
/// itself. `None` when nothing matches: callers then use `name` as given, relative to the
/// working directory, so a file beside the scene is still found when the path omits `"."`.
pub fn find(name: &str, searchpath: &[String]) -> Option<PathBuf> {
    if name.is_empty() {
        return None;
    }
    let path = Path::new(name);
    if path.is_absolute() {
        return path.is_file().then(|| path.to_path_buf());
    }
    searchpath
        .iter()
        .map(|dir| Path::new(dir).join(name))
        .find(|p| p.is_file())
}

/// [`find`], else `name` unchanged.
pub fn resolve(name: &str, searchpath: &[String]) -> String {
    find(name, searchpath)
        .map(|p| p.to_string_lossy().into_owned())
        .unwrap_or_else(|| name.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_directory_holding_the_file_wins_and_misses_fall_back_to_the_name() {
        let root = std::env::temp_dir().join(format!("illume-searchpath-{}", std::process::id()));
        let (a, b) = (root.join("a"), root.join("b"));
        std::fs::create_dir_all(&a).unwrap();
        std::fs::create_dir_all(&b).unwrap();
        std::fs::write(b.join("map.tif"), b"x").unwrap();
        std::fs::write(a.join("both.tif"), b"x").unwrap();
        std::fs::write(b.join("both.tif"), b"x").unwrap();
        let path = vec![a.display().to_string(), b.display().to_string()];
        assert_eq!(find("map.tif", &path), Some(b.join("map.tif")));
        assert_eq!(find("both.tif", &path), Some(a.join("both.tif")));
        assert_eq!(find("none.tif", &path), None);
        assert_eq!(resolve("none.tif", &path), "none.tif");
        assert_eq!(find("", &path), None);
        // An absolute name is not joined to the path.
        let abs = b.join("map.tif").display().to_string();
        assert_eq!(
            find(&abs, &[a.display().to_string()]),
            Some(b.join("map.tif"))
        );
        let _ = std::fs::remove_dir_all(&root);
    }
}
