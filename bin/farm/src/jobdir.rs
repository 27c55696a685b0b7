//! The job directory (`scene.farm/` beside the scene by default): what was asked for
//! (`farm.conf`), the generated scripts and `Make*` RIBs, tile files, done markers, Slurm
//! job ids (`jobs`) and logs. Everything a task writes lands here under a temporary name and
//! is renamed, so a killed task never leaves a file that looks finished.
//!
//! ```text
//! farm.conf                     scene, working directory, tile grid, frame range
//! jobs                          one line per sbatch: stage, job id, submit time (s), array
//! scripts/{setup,passes,tiles,merge}.sh
//! make/<frame>.rib              the Make* requests a pass task runs after its pass frames
//! tiles/<nx>x<ny>/<frame>/x<col>y<row>.tile
//! done/<stage>.<frame>          written when a pass task or a frame's merge finished
//! errors/<stage>.<task name>   render exited 1 (rendered with errors; output kept): log paths
//! logs/<stage>_<job>_<task>.out
//! ```

use crate::error::{io_error, FarmError};
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// What `farm submit` was asked to do; `merge` and `status` re-derive the plan from it.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    pub scene: PathBuf,
    /// Where `render` runs (relative paths in the RIB resolve here), the submit directory.
    pub cwd: PathBuf,
    pub tiles: (u32, u32),
    pub frames: Option<(i32, i32)>,
}

#[derive(Clone, Debug)]
pub struct JobDir {
    pub root: PathBuf,
}

/// `--frames a-b` or `n`.
pub fn parse_frame_range(s: &str) -> Option<(i32, i32)> {
    let s = s.trim();
    // A leading '-' is a negative first number, not the separator.
    let split = s
        .char_indices()
        .skip(1)
        .find(|&(_, c)| c == '-')
        .map(|(i, _)| i);
    match split {
        Some(i) => {
            let (a, b) = (s[..i].trim().parse().ok()?, s[i + 1..].trim().parse().ok()?);
            (a <= b).then_some((a, b))
        }
        None => s.parse().ok().map(|n| (n, n)),
    }
}

/// `4x4` (columns x rows).
pub fn parse_grid(s: &str) -> Option<(u32, u32)> {
    let (a, b) = s.trim().split_once(['x', 'X'])?;
    let (a, b): (u32, u32) = (a.trim().parse().ok()?, b.trim().parse().ok()?);
    (a >= 1 && b >= 1 && a <= 4096 && b <= 4096).then_some((a, b))
}

impl JobDir {
    /// `dir/scene.farm` for `dir/scene.rib`.
    pub fn beside(scene: &Path) -> JobDir {
        JobDir {
            root: scene.with_extension("farm"),
        }
    }

    pub fn config_path(&self) -> PathBuf {
        self.root.join("farm.conf")
    }
    pub fn jobs_path(&self) -> PathBuf {
        self.root.join("jobs")
    }
    pub fn script(&self, stage: &str) -> PathBuf {
        self.root.join("scripts").join(format!("{stage}.sh"))
    }
    pub fn make_rib(&self, label: &str) -> PathBuf {
        self.root.join("make").join(format!("{label}.rib"))
    }
    pub fn done(&self, stage: &str, label: &str) -> PathBuf {
        self.root.join("done").join(format!("{stage}.{label}"))
    }
    pub fn logs(&self) -> PathBuf {
        self.root.join("logs")
    }
    pub fn errors(&self) -> PathBuf {
        self.root.join("errors")
    }

    pub fn write_config(&self, c: &Config) -> Result<(), FarmError> {
        let frames = c
            .frames
            .map_or("all".to_string(), |(a, b)| format!("{a}-{b}"));
        let text = format!(
            "# written by farm submit; farm merge and farm status read it\nscene={}\ncwd={}\ntiles={}x{}\nframes={frames}\n",
            c.scene.display(),
            c.cwd.display(),
            c.tiles.0,
            c.tiles.1
        );
        write_atomically(&self.config_path(), text.as_bytes())
    }

    pub fn read_config(&self) -> Result<Config, FarmError> {
        let path = self.config_path();
        let text = std::fs::read_to_string(&path).map_err(|e| {
            FarmError::Usage(format!(
                "{}: {e} (not a farm job directory? run farm submit first)",
                path.display()
            ))
        })?;
        let bad =
            |what: &str| FarmError::Usage(format!("{}: bad or missing {what}", path.display()));
        let get = |key: &str| {
            text.lines()
                .filter_map(|l| l.split_once('='))
                .find(|(k, _)| k.trim() == key)
                .map(|(_, v)| v.trim().to_string())
        };
        let frames = get("frames").ok_or_else(|| bad("frames"))?;
        Ok(Config {
            scene: get("scene").ok_or_else(|| bad("scene"))?.into(),
            cwd: get("cwd").ok_or_else(|| bad("cwd"))?.into(),
            tiles: get("tiles")
                .as_deref()
                .and_then(parse_grid)
                .ok_or_else(|| bad("tiles"))?,
            frames: if frames == "all" {
                None
            } else {
                Some(parse_frame_range(&frames).ok_or_else(|| bad("frames"))?)
            },
        })
    }
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// `output` exists and is at least as new as every input (the `make` rule; an input that
/// cannot be read counts as new, so its output is redone).
pub fn up_to_date(output: &Path, inputs: &[&Path]) -> bool {
    let Some(out) = modified(output) else {
        return false;
    };
    inputs.iter().all(|i| modified(i).is_some_and(|t| t <= out))
}

/// Writes `bytes` to `path` through a temporary name in the same directory (the displays'
/// writer, `illume_imageio::write_atomically`), creating the directory first.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), FarmError> {
    use std::io::Write;
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(io_error(dir))?;
    }
    let io = |source| illume_imageio::ImageError::Io {
        path: path.display().to_string(),
        source,
    };
    illume_imageio::write_atomically(path, |w| w.write_all(bytes).map_err(io)).map_err(
        |e| match e {
            illume_imageio::ImageError::Io { path, source } => FarmError::Io { path, source },
            other => FarmError::Io {
                path: path.display().to_string(),
                source: std::io::Error::other(other.to_string()),
            },
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges_and_grids_parse() {
        assert_eq!(parse_frame_range("1-100"), Some((1, 100)));
        assert_eq!(parse_frame_range("7"), Some((7, 7)));
        assert_eq!(parse_frame_range("-3--1"), Some((-3, -1)));
        assert_eq!(parse_frame_range("5-2"), None);
        assert_eq!(parse_frame_range("a-b"), None);
        assert_eq!(parse_grid("4x4"), Some((4, 4)));
        assert_eq!(parse_grid("3X2"), Some((3, 2)));
        assert_eq!(parse_grid("0x4"), None);
        assert_eq!(parse_grid("4"), None);
    }

    #[test]
    fn config_round_trips() {
        let root = std::env::temp_dir().join(format!("illume-farm-conf-{}", std::process::id()));
        let dir = JobDir { root: root.clone() };
        let c = Config {
            scene: "/a/b c.rib".into(),
            cwd: "/a".into(),
            tiles: (4, 3),
            frames: Some((2, 9)),
        };
        dir.write_config(&c).unwrap();
        assert_eq!(dir.read_config().unwrap(), c);
        std::fs::remove_dir_all(&root).unwrap();
    }
}
