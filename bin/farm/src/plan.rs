//! From a scene and what was asked (tile grid, frame range) to the farm's task lists. The
//! index of a task in its list is its Slurm array index, stable across resubmissions, so a
//! second `farm submit` can run only the tasks whose outputs are missing.

use crate::jobdir::{up_to_date, Config, JobDir};
use crate::scene::{frame_label, BeautyFrame, Scene};
use crate::tiles::{tile_windows, TileWindow};
use illume_rib::Request;
use std::path::PathBuf;

/// A group's passes and `Make*` steps, run whole, once, before any tile.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTask {
    pub label: String,
    pub frames: Vec<Option<i32>>,
    pub make: Vec<Request>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct TileTask {
    pub frame: Option<i32>,
    pub label: String,
    pub window: TileWindow,
    /// Relative to the job directory.
    pub file: PathBuf,
}

/// A beauty frame and the tiles it is merged from.
#[derive(Clone, Debug, PartialEq)]
pub struct MergeFrame {
    pub label: String,
    pub beauty: BeautyFrame,
    /// Indices into [`Plan::tiles`].
    pub tiles: Vec<usize>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Plan {
    pub setup: Vec<Request>,
    pub passes: Vec<PassTask>,
    pub tiles: Vec<TileTask>,
    pub frames: Vec<MergeFrame>,
}

fn selected(range: Option<(i32, i32)>, number: Option<i32>) -> bool {
    match (range, number) {
        (Some((a, b)), Some(n)) => (a..=b).contains(&n),
        _ => true,
    }
}

pub fn plan(scene: &Scene, grid: (u32, u32), range: Option<(i32, i32)>) -> Plan {
    let mut p = Plan {
        setup: scene.setup.clone(),
        ..Plan::default()
    };
    for group in &scene.groups {
        let key = match &group.beauty {
            Some(b) => b.number,
            None => group.passes.last().and_then(|f| f.number),
        };
        if !selected(range, key) {
            continue;
        }
        let label = group.label();
        if !group.passes.is_empty() || !group.make.is_empty() {
            p.passes.push(PassTask {
                label: label.clone(),
                frames: group.passes.iter().map(|f| f.number).collect(),
                make: group.make.clone(),
            });
        }
        let Some(b) = &group.beauty else { continue };
        let first = p.tiles.len();
        let grid_dir = format!("{}x{}", grid.0, grid.1);
        for window in tile_windows(b.xres, b.yres, b.crop, grid.0, grid.1) {
            let file = PathBuf::from("tiles")
                .join(&grid_dir)
                .join(&label)
                .join(format!("{}.tile", window.name()));
            p.tiles.push(TileTask {
                frame: b.number,
                label: label.clone(),
                window,
                file,
            });
        }
        p.frames.push(MergeFrame {
            label: frame_label(b.number),
            beauty: b.clone(),
            tiles: (first..p.tiles.len()).collect(),
        });
    }
    p
}

/// Which tasks still have work: their outputs are missing or older than the scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Todo {
    pub setup: bool,
    pub passes: Vec<usize>,
    pub tiles: Vec<usize>,
    /// Indices into [`Plan::frames`].
    pub merges: Vec<usize>,
}

pub fn todo(plan: &Plan, dir: &JobDir, config: &Config) -> Todo {
    let scene = config.scene.as_path();
    let tiles: Vec<usize> = (0..plan.tiles.len())
        .filter(|&i| !up_to_date(&dir.root.join(&plan.tiles[i].file), &[scene]))
        .collect();
    let merges = (0..plan.frames.len())
        .filter(|&i| {
            let f = &plan.frames[i];
            let inputs: Vec<PathBuf> = f
                .tiles
                .iter()
                .map(|&t| dir.root.join(&plan.tiles[t].file))
                .collect();
            let mut refs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
            refs.push(scene);
            !up_to_date(&dir.done("merge", &f.label), &refs)
        })
        .collect();
    Todo {
        setup: !plan.setup.is_empty() && !up_to_date(&dir.done("setup", "all"), &[scene]),
        passes: (0..plan.passes.len())
            .filter(|&i| !up_to_date(&dir.done("passes", &plan.passes[i].label), &[scene]))
            .collect(),
        tiles,
        merges,
    }
}
