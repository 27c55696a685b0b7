//! What a farm needs to know about a RIB: its frames in file order, which of them are *passes*
//! (shadow/depth/environment images other frames read) and which are beauty frames to tile,
//! and the `Make*` requests that turn pass images into maps.
//!
//! A frame is a pass when every display it writes is a depth or shadow output (`zfile`,
//! `shadow`) or is read by a later `Make*` request (e.g. six cube faces for
//! `MakeCubeFaceEnvironment`). Passes and `Make*` requests belong to the next beauty frame: they
//! run once, whole, before its tiles (rib/pipelines/shadow/shadow_single.rib is one such
//! group). `Make*` requests before the first frame are the *setup* step every frame may need.

use crate::source_lines::SourceLines;
use illume_ri::{from_rib_diagnostic, Ri};
use illume_rib::{Request, Span};
use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{path}: {source}")]
    Open {
        path: String,
        source: std::io::Error,
    },
    #[error("{span}: error: farm needs a unique FrameBegin number for every frame of a RIB with several frames ({problem})")]
    FrameNumbers { span: Span, problem: String },
    #[error("{0}: no frames (nothing to render)")]
    Empty(String),
}

/// One frame a farm renders whole: its number (`None` for a lone frame without FrameBegin).
#[derive(Clone, Debug, PartialEq)]
pub struct PassFrame {
    pub number: Option<i32>,
}

/// A beauty frame to be tiled.
#[derive(Clone, Debug, PartialEq)]
pub struct BeautyFrame {
    pub number: Option<i32>,
    pub xres: u32,
    pub yres: u32,
    /// The frame's own `CropWindow` in pixels (x0, x1, y0, y1, ends exclusive): tiles split it.
    pub crop: [u32; 4],
}

/// A beauty frame with the passes and `Make*` steps that must run before it.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    pub passes: Vec<PassFrame>,
    pub make: Vec<Request>,
    /// `None` for passes left after the last beauty frame.
    pub beauty: Option<BeautyFrame>,
}

impl Group {
    /// `f0002`-style name used for files and logs.
    pub fn label(&self) -> String {
        let number = self
            .beauty
            .as_ref()
            .map(|b| b.number)
            .or_else(|| self.passes.last().map(|p| p.number))
            .flatten();
        frame_label(number)
    }
}

pub fn frame_label(number: Option<i32>) -> String {
    match number {
        Some(n) if n < 0 => format!("fm{:04}", -i64::from(n)),
        Some(n) => format!("f{n:04}"),
        None => "frame".to_string(),
    }
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// `Make*` before the first frame.
    pub setup: Vec<Request>,
    pub groups: Vec<Group>,
}

/// One frame as read, before classification.
struct FrameSeen {
    number: Option<i32>,
    span: Span,
    displays: Vec<(String, String)>,
    xres: u32,
    yres: u32,
    crop: [u32; 4],
}

enum Item {
    Frame(FrameSeen),
    Make(Request),
}

/// The files a `Make*` request reads.
pub fn make_inputs(req: &Request) -> Vec<&str> {
    match req {
        Request::MakeTexture { picture, .. }
        | Request::MakeBump { picture, .. }
        | Request::MakeLatLongEnvironment { picture, .. }
        | Request::MakeShadow { picture, .. } => vec![picture.as_str()],
        Request::MakeCubeFaceEnvironment { faces, .. } => {
            faces.iter().map(|f| f.as_str()).collect()
        }
        _ => Vec::new(),
    }
}

fn is_make(req: &Request) -> bool {
    matches!(
        req,
        Request::MakeTexture { .. }
            | Request::MakeBump { .. }
            | Request::MakeLatLongEnvironment { .. }
            | Request::MakeCubeFaceEnvironment { .. }
            | Request::MakeShadow { .. }
    )
}

/// A scene as read, with every diagnostic the RIB produced on the way (parser and RI state),
/// each carrying its source line so it prints as `render`'s parser does, caret and all.
pub struct SceneRead {
    pub diagnostics: Vec<illume_rib::Diagnostic>,
    pub scene: Result<Scene, SceneError>,
}

impl SceneRead {
    pub fn error_count(&self) -> usize {
        self.diagnostics.iter().filter(|d| d.is_error()).count()
    }
}

/// Reads the RIB at `path`, dropping its diagnostics (`merge` and `status` read a scene
/// `submit` already checked).
pub fn read_scene(path: &Path) -> Result<Scene, SceneError> {
    read_scene_checked(path).scene
}

/// Reads the RIB at `path` (through the same `Ri` state machine `render` uses, so `Format`,
/// `CropWindow`, archives and defaults resolve exactly as they will in the tiles) and keeps
/// what it said about the RIB, so `submit` can refuse a scene every task would fail on.
pub fn read_scene_checked(path: &Path) -> SceneRead {
    let mut lines = SourceLines::default();
    let scene = read_items(path, &mut lines);
    SceneRead {
        diagnostics: lines.diagnostics,
        scene,
    }
}

fn read_items(path: &Path, lines: &mut SourceLines) -> Result<Scene, SceneError> {
    let parser = illume_rib::open(path).map_err(|e| SceneError::Open {
        path: path.display().to_string(),
        source: e,
    })?;
    let mut ri = Ri::new();
    ri.set_texture_maker(Box::new(|_, _| Ok(())));
    let mut items = Vec::new();
    let mut world_spans = Vec::new();
    let collect = |ri: &mut Ri, items: &mut Vec<Item>, spans: &mut Vec<Span>| {
        for f in ri.take_frames() {
            let span = if spans.is_empty() {
                Span::new(path.display().to_string().into(), 1, 1, 0)
            } else {
                spans.remove(0)
            };
            let displays = if f.options.displays.is_empty() {
                vec![("ri.tif".to_string(), "tiff".to_string())]
            } else {
                f.options
                    .displays
                    .iter()
                    .map(|d| (d.name.clone(), d.kind.clone()))
                    .collect()
            };
            items.push(Item::Frame(FrameSeen {
                number: f.number,
                span,
                displays,
                xres: f.options.xres,
                yres: f.options.yres,
                crop: f.camera.crop,
            }));
        }
    };
    for item in parser {
        match item {
            Ok(req) => {
                if is_make(&req.value) {
                    items.push(Item::Make(req.value.clone()));
                }
                if matches!(req.value, Request::WorldBegin) {
                    world_spans.push(req.span.clone());
                }
                ri.request(req);
            }
            Err(d) => {
                lines.remember(&d);
                ri.report(from_rib_diagnostic(d));
            }
        }
        lines.keep(ri.drain_diagnostics());
        collect(&mut ri, &mut items, &mut world_spans);
    }
    ri.finish();
    lines.keep(ri.drain_diagnostics());
    collect(&mut ri, &mut items, &mut world_spans);
    check_frame_numbers(&items)?;
    let scene = classify(items);
    if scene.groups.is_empty() {
        return Err(SceneError::Empty(path.display().to_string()));
    }
    Ok(scene)
}

/// `render --frames n` picks frames by number, so several frames need distinct numbers.
fn check_frame_numbers(items: &[Item]) -> Result<(), SceneError> {
    let frames: Vec<&FrameSeen> = items
        .iter()
        .filter_map(|i| match i {
            Item::Frame(f) => Some(f),
            Item::Make(_) => None,
        })
        .collect();
    if frames.len() < 2 {
        return Ok(());
    }
    let mut seen = std::collections::HashSet::new();
    for f in frames {
        match f.number {
            None => {
                return Err(SceneError::FrameNumbers {
                    span: f.span.clone(),
                    problem: "this world has no FrameBegin".into(),
                })
            }
            Some(n) if !seen.insert(n) => {
                return Err(SceneError::FrameNumbers {
                    span: f.span.clone(),
                    problem: format!("frame {n} appears twice"),
                })
            }
            Some(_) => {}
        }
    }
    Ok(())
}

fn is_pass(frame: &FrameSeen, later_inputs: &std::collections::HashSet<&str>) -> bool {
    frame.displays.iter().all(|(name, kind)| {
        matches!(kind.to_ascii_lowercase().as_str(), "zfile" | "shadow")
            || later_inputs.contains(name.as_str())
    })
}

fn classify(items: Vec<Item>) -> Scene {
    // Inputs of the Make* requests after each item (frames feed only later Make* steps).
    let mut later: Vec<std::collections::HashSet<&str>> = vec![Default::default(); items.len()];
    let mut acc = std::collections::HashSet::new();
    for (i, item) in items.iter().enumerate().rev() {
        later[i] = acc.clone();
        if let Item::Make(req) = item {
            acc.extend(make_inputs(req));
        }
    }
    let passes: Vec<bool> = items
        .iter()
        .zip(&later)
        .map(|(item, later)| matches!(item, Item::Frame(f) if is_pass(f, later)))
        .collect();
    let mut scene = Scene::default();
    let mut current = Group {
        passes: Vec::new(),
        make: Vec::new(),
        beauty: None,
    };
    let mut any_frame = false;
    for (item, pass) in items.into_iter().zip(passes) {
        match item {
            Item::Make(req) if !any_frame => scene.setup.push(req),
            Item::Make(req) => current.make.push(req),
            Item::Frame(f) => {
                any_frame = true;
                if pass {
                    current.passes.push(PassFrame { number: f.number });
                } else {
                    current.beauty = Some(BeautyFrame {
                        number: f.number,
                        xres: f.xres,
                        yres: f.yres,
                        crop: f.crop,
                    });
                    scene.groups.push(std::mem::replace(
                        &mut current,
                        Group {
                            passes: Vec::new(),
                            make: Vec::new(),
                            beauty: None,
                        },
                    ));
                }
            }
        }
    }
    if !current.passes.is_empty() || !current.make.is_empty() {
        scene.groups.push(current);
    }
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_from(text: &str) -> Result<Scene, SceneError> {
        let dir = std::env::temp_dir().join(format!(
            "illume-farm-scene-{}-{}",
            std::process::id(),
            text.len()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.rib");
        std::fs::write(&path, text).unwrap();
        let s = read_scene(&path);
        std::fs::remove_dir_all(&dir).unwrap();
        s
    }

    const WORLD: &str = "WorldBegin Sphere 1 -1 1 360 WorldEnd\n";

    #[test]
    fn shadow_pipeline_groups_depth_pass_and_make_shadow_before_beauty() {
        let s = scene_from(&format!(
            "MakeTexture \"a.tif\" \"a.tx\" \"periodic\" \"periodic\" \"box\" 1 1\n\
             FrameBegin 1 Display \"d.z\" \"zfile\" \"z\" {WORLD} FrameEnd\n\
             MakeShadow \"d.z\" \"d.sm\"\n\
             FrameBegin 2 Format 64 32 1 Display \"b.tif\" \"tiff\" \"rgba\" {WORLD} FrameEnd\n\
             FrameBegin 11 Display \"face.tif\" \"tiff\" \"rgb\" {WORLD} FrameEnd\n\
             MakeCubeFaceEnvironment \"face.tif\" \"face.tif\" \"face.tif\" \"face.tif\" \"face.tif\" \"face.tif\" \"e.env\" 90 \"box\" 1 1\n\
             FrameBegin 3 CropWindow 0.5 1 0 1 Format 64 32 1 {WORLD} FrameEnd\n\
             FrameBegin 4 Display \"late.z\" \"zfile\" \"z\" {WORLD} FrameEnd\n"
        ))
        .unwrap();
        assert_eq!(s.setup.len(), 1);
        assert_eq!(s.groups.len(), 3);
        let g = &s.groups[0];
        assert_eq!(g.passes, vec![PassFrame { number: Some(1) }]);
        assert_eq!(g.make.len(), 1);
        assert_eq!(
            g.beauty,
            Some(BeautyFrame {
                number: Some(2),
                xres: 64,
                yres: 32,
                crop: [0, 64, 0, 32]
            })
        );
        assert_eq!(s.groups[1].passes, vec![PassFrame { number: Some(11) }]);
        assert_eq!(s.groups[1].beauty.as_ref().unwrap().crop, [32, 64, 0, 32]);
        assert_eq!(s.groups[2].passes, vec![PassFrame { number: Some(4) }]);
        assert_eq!(s.groups[2].beauty, None);
        assert_eq!(s.groups[2].label(), "f0004");
    }

    #[test]
    fn a_lone_unnumbered_frame_is_fine_but_repeated_numbers_are_refused() {
        let s = scene_from(&format!("Format 8 8 1 {WORLD}")).unwrap();
        assert_eq!(s.groups.len(), 1);
        assert_eq!(s.groups[0].beauty.as_ref().unwrap().number, None);
        let e = scene_from(&format!(
            "FrameBegin 1 {WORLD} FrameEnd\nFrameBegin 1 {WORLD} FrameEnd\n"
        ))
        .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("s.rib:3:") && text.contains("frame 1 appears twice"),
            "{text}"
        );
        assert!(scene_from("# nothing\n").is_err());
    }
}
