//! Writing a display through a temporary name in the same directory, then renaming it.
//!
//! A render that is interrupted (or fails half-way through encoding) must never leave a truncated
//! image under the name the user asked for: a texture pipeline would pick it up as a real input.
//! The rename is atomic on POSIX file systems because source and target share a directory.

use crate::ImageError;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// A file being written under its temporary name across many calls (streamed displays):
/// [`AtomicFile::commit`] renames it into place; dropping it uncommitted removes it.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    writer: Option<BufWriter<std::fs::File>>,
}

impl AtomicFile {
    /// Creates the temporary file beside `path`.
    pub fn create(path: &Path) -> Result<AtomicFile, ImageError> {
        let tmp = temporary_path(path);
        let file = std::fs::File::create(&tmp).map_err(|e| io_err(path, e))?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            tmp,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// The buffered writer (seekable: `BufWriter` flushes before it seeks).
    pub fn writer(&mut self) -> &mut BufWriter<std::fs::File> {
        self.writer.as_mut().expect("AtomicFile used after commit")
    }

    /// Flushes, syncs and renames the file to its real name.
    pub fn commit(mut self) -> Result<(), ImageError> {
        let path = self.path.clone();
        let mut writer = self.writer.take().expect("AtomicFile committed twice");
        let result = writer
            .flush()
            .and_then(|()| writer.get_ref().sync_all())
            .and_then(|()| {
                drop(writer);
                std::fs::rename(&self.tmp, &path)
            });
        result.map_err(|e| io_err(&path, e))
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Not committed (an error, or a render pass that starts over): leave nothing behind.
        if self.writer.take().is_some() || self.tmp.exists() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

fn io_err(path: &Path, source: std::io::Error) -> ImageError {
    ImageError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// The temporary name beside `path`: `.name.illume-tmp-<pid>` (hidden, unique per process).
fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "image".to_string());
    let tmp = format!(".{name}.illume-tmp-{}", std::process::id());
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(tmp),
        _ => PathBuf::from(tmp),
    }
}

/// Calls `encode` on a buffered writer to a temporary file, then renames it to `path`.
/// On any failure the temporary file is removed and `path` is left untouched.
pub fn write_atomically(
    path: &Path,
    encode: impl FnOnce(&mut BufWriter<std::fs::File>) -> Result<(), ImageError>,
) -> Result<(), ImageError> {
    let tmp = temporary_path(path);
    let io_err = |source: std::io::Error| ImageError::Io {
        path: path.display().to_string(),
        source,
    };
    let file = std::fs::File::create(&tmp).map_err(io_err)?;
    let mut writer = BufWriter::new(file);
    let result = encode(&mut writer).and_then(|()| {
        writer.flush().map_err(io_err)?;
        writer.get_ref().sync_all().map_err(io_err)
    });
    drop(writer);
    match result {
        Ok(()) => std::fs::rename(&tmp, path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io_err(e)
        }),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}
