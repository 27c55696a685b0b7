//! `Display "name" "framebuffer"`: there is no window here, so the image goes to a PNG named
//! after the display (`name.png`, or `name` with its extension replaced by `.png`), and the
//! caller prints where it went.

use std::path::{Path, PathBuf};

/// Where a `framebuffer` display named `name` is written: `name` with extension `.png`.
pub fn framebuffer_path(name: &Path) -> PathBuf {
    name.with_extension("png")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framebuffer_path_replaces_or_adds_png_extension() {
        assert_eq!(
            framebuffer_path(Path::new("out/ri.tif")),
            PathBuf::from("out/ri.png")
        );
        assert_eq!(
            framebuffer_path(Path::new("sphere")),
            PathBuf::from("sphere.png")
        );
        assert_eq!(framebuffer_path(Path::new("a.png")), PathBuf::from("a.png"));
    }
}
