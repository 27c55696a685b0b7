//! The jobs of a suite: every `jobs.cfg` under its root, in path order.
use crate::jobs_cfg::{self, RenderJobSpec};
use std::path::{Path, PathBuf};

/// One image to compare: a job renders once and may write several.
#[derive(Debug, Clone)]
pub struct Job {
    /// The report's key and the reference's stem (`Bug1031110`, `funcset8`); for a job with
    /// several output images, one `Job` per image shares the same render.
    pub name: String,
    /// The folder of its `jobs.cfg`, relative to the suite root (`RIBs/Bugs/Bug1031110`).
    pub cfg_dir: PathBuf,
    pub spec: RenderJobSpec,
    /// The output image names (relative to the working directory).
    pub images: Vec<String>,
}

impl Job {
    /// The working directory relative to the suite root.
    pub fn workdir(&self) -> PathBuf {
        self.cfg_dir.join(&self.spec.workingdir)
    }

    /// Whether `rib` is a program that prints RIB on stdout (anything not named `.rib`).
    pub fn is_program(&self) -> bool {
        !self.spec.rib.to_ascii_lowercase().ends_with(".rib")
    }

    /// `category/name` as `--only` matches it (`Bugs/Bug1031110/Bug1031110`).
    pub fn path_name(&self) -> String {
        let dir = self.cfg_dir.strip_prefix("RIBs").unwrap_or(&self.cfg_dir);
        format!("{}/{}", dir.display(), self.name)
    }
}

/// Reads every `jobs.cfg` under `root` (the top-level one only `include_cfg`s the tree, which
/// this walk covers) and returns the jobs sorted by folder, then file order.
pub fn load(root: &Path) -> Result<Vec<Job>, String> {
    let mut cfgs: Vec<PathBuf> = walkdir::WalkDir::new(root)
        .sort_by_file_name()
        .into_iter()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_type().is_file() && e.file_name() == "jobs.cfg")
        .map(|e| e.into_path())
        .collect();
    cfgs.sort();
    let mut jobs = Vec::new();
    for cfg in cfgs {
        let text = std::fs::read_to_string(&cfg).map_err(|e| format!("{}: {e}", cfg.display()))?;
        let cfg_dir = cfg
            .parent()
            .and_then(|d| d.strip_prefix(root).ok())
            .unwrap_or(Path::new(""))
            .to_path_buf();
        for spec in jobs_cfg::parse(&text, &cfg).map_err(|e| e.to_string())? {
            let images = if spec.outimagename.is_empty() {
                vec![with_tif(&spec.rib)]
            } else {
                spec.outimagename.clone()
            };
            for image in &images {
                let name = Path::new(image)
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_else(|| image.clone());
                jobs.push(Job {
                    name,
                    cfg_dir: cfg_dir.clone(),
                    spec: spec.clone(),
                    images: images.clone(),
                });
            }
        }
    }
    Ok(jobs)
}

/// `rib`'s file name with the extension replaced by `.tif` (`gen.py` → `gen.tif`).
fn with_tif(rib: &str) -> String {
    let name = Path::new(rib)
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| rib.to_string());
    match name.rfind('.') {
        Some(k) if k > 0 => format!("{}.tif", &name[..k]),
        _ => format!("{name}.tif"),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn output_name_replaces_the_suffix() {
        assert_eq!(super::with_tif("a/b.rib"), "b.tif");
        assert_eq!(super::with_tif("gen.py"), "gen.tif");
        assert_eq!(super::with_tif("noext"), "noext.tif");
    }
}
