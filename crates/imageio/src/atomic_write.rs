//! Writing a display through a temporary name in the same directory, then renaming it.
//!
//! A render that is interrupted (or fails half-way through encoding) must never leave a truncated
//! image under the name the user asked for: a texture pipeline would pick it up as a real input.
//! The rename is atomic on POSIX file systems because source and target share a directory.
//!
//! Temporary files being written are listed in [`IN_FLIGHT`], so a process stopped by a signal
//! (`render`'s SIGINT/SIGTERM handler) removes them with [`remove_temporary_files`] before it
//! exits: nothing is left behind, under either name.

use crate::ImageError;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporary files being written now. The final rename happens under this lock, so a signal
/// handler that takes it sees each display either complete under its name or still temporary
/// (and removes it), never half renamed.
static IN_FLIGHT: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn in_flight() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    IN_FLIGHT.lock().unwrap_or_else(|p| p.into_inner())
}

/// Removes every temporary file still being written and returns how many there were. Meant
/// for a signal handler right before the process exits: the lock is kept until then (the
/// guard is leaked), so no writer renames a file afterwards.
pub fn remove_temporary_files() -> usize {
    let mut files = in_flight();
    let n = files.len();
    for f in files.drain(..) {
        let _ = std::fs::remove_file(f);
    }
    std::mem::forget(files);
    n
}

/// A file being written under its temporary name across many calls (streamed displays):
/// [`AtomicFile::commit`] renames it into place; dropping it uncommitted removes it.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    writer: Option<BufWriter<std::fs::File>>,
}

impl AtomicFile {
    /// Creates the temporary file beside `path` (listed in [`IN_FLIGHT`] until it is renamed
    /// or removed). A read-only `path` is an error, as for [`write_atomically`].
    pub fn create(path: &Path) -> Result<AtomicFile, ImageError> {
        refuse_read_only(path)?;
        let tmp = temporary_path(path);
        let file = {
            let mut files = in_flight();
            let file = std::fs::File::create(&tmp).map_err(|e| io_err(path, e))?;
            files.push(tmp.clone());
            file
        };
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

    /// Flushes, syncs and renames the file to its real name (under the [`IN_FLIGHT`] lock, as
    /// [`write_atomically`] does).
    pub fn commit(mut self) -> Result<(), ImageError> {
        let path = self.path.clone();
        let mut writer = self.writer.take().expect("AtomicFile committed twice");
        let result = writer.flush().and_then(|()| writer.get_ref().sync_all());
        drop(writer);
        let mut files = in_flight();
        files.retain(|f| *f != self.tmp);
        result
            .and_then(|()| std::fs::rename(&self.tmp, &path))
            .map_err(|e| io_err(&path, e))
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Not committed (an error, or a render pass that starts over): leave nothing behind.
        let mut files = in_flight();
        files.retain(|f| *f != self.tmp);
        if self.writer.take().is_some() || self.tmp.exists() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// A rename would silently replace a read-only file; PRMan's drivers refuse to open it.
fn refuse_read_only(path: &Path) -> Result<(), ImageError> {
    if std::fs::metadata(path).is_ok_and(|m| m.permissions().readonly()) {
        return Err(io_err(
            path,
            std::io::Error::new(
                std::io::ErrorKind::PermissionDenied,
                "the file is read-only (not replaced)",
            ),
        ));
    }
    Ok(())
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
    refuse_read_only(path)?;
    let file = {
        let mut files = in_flight();
        let file = std::fs::File::create(&tmp).map_err(io_err)?;
        files.push(tmp.clone());
        file
    };
    let mut writer = BufWriter::new(file);
    let result = encode(&mut writer).and_then(|()| {
        writer.flush().map_err(io_err)?;
        writer.get_ref().sync_all().map_err(io_err)
    });
    drop(writer);
    let mut files = in_flight();
    files.retain(|f| *f != tmp);
    let renamed = result.and_then(|()| std::fs::rename(&tmp, path).map_err(io_err));
    if renamed.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    renamed
}

#[cfg(test)]
mod tests {
    use super::*;

    fn put(w: &mut BufWriter<std::fs::File>, bytes: &[u8]) -> Result<(), ImageError> {
        w.write_all(bytes).map_err(|source| ImageError::Io {
            path: "test".into(),
            source,
        })
    }

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("illume-atomic-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// A writer error half-way (what a full disk gives) leaves neither the target nor the
    /// temporary file, and the error names the target.
    #[test]
    fn failed_encode_leaves_nothing_and_names_the_file() {
        let d = scratch("fail");
        let target = d.join("out.tif");
        let e = write_atomically(&target, |w| {
            put(w, &[0u8; 10000])?;
            Err(ImageError::Io {
                path: target.display().to_string(),
                source: std::io::Error::other("No space left on device (injected)"),
            })
        })
        .unwrap_err();
        assert!(e.to_string().contains("out.tif"), "{e}");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn read_only_target_is_an_error_and_kept() {
        let d = scratch("ro");
        let target = d.join("keep.png");
        std::fs::write(&target, b"old").unwrap();
        let mut perm = std::fs::metadata(&target).unwrap().permissions();
        perm.set_readonly(true);
        std::fs::set_permissions(&target, perm).unwrap();
        let e = write_atomically(&target, |w| put(w, b"new")).unwrap_err();
        assert!(e.to_string().contains("keep.png"), "{e}");
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn in_flight_list_is_empty_after_writes() {
        let d = scratch("list");
        write_atomically(&d.join("a.bin"), |w| put(w, b"x")).unwrap();
        assert!(!in_flight().iter().any(|f| f.starts_with(&d)));
        assert_eq!(std::fs::read(d.join("a.bin")).unwrap(), b"x");
        let _ = std::fs::remove_dir_all(&d);
    }
}
