//! The RI state machine: the `Ri` struct, the block stack that recovers from mismatched
//! `Begin`/`End`, and the dispatch of each request to its family's module (options in
//! `options/`, attributes in `attributes/`, transformations in `transform.rs`, lights,
//! geometry, motion, solids, archives, procedurals, texture making, frames).
use crate::archive::{Recording, Scope};
use crate::attributes::{Attributes, Light};
use crate::camera::Camera;
use crate::declarations::Declarations;
use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::frame::{Frame, FramePrimitive};
use crate::motion::{MovingTransform, OpenMotion};
use crate::options::Options;
use crate::solid::SolidTree;
use glam::DMat4;
use illume_rib::{Declaration, Handle, Request, Span, Spanned};
use std::collections::HashMap;
use std::io::Read;
use std::sync::Arc;

pub use crate::make_texture::TextureMaker;

/// A stream of parsed requests (a RIB file, an archive, a `RunProgram`'s output).
pub type RequestSource = Box<dyn Iterator<Item = Result<Spanned<Request>, Diagnostic>>>;

/// Turns bytes into requests; `name` is the file name spans will carry. The RIB parser lives
/// in `illume-rib`; the caller plugs it in so `ReadArchive`, `DelayedReadArchive` and
/// `RunProgram` can read files.
pub type StreamParser = Box<dyn Fn(Box<dyn Read>, &str) -> RequestSource>;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BlockKind {
    Frame,
    World,
    Attribute,
    Transform,
    Solid,
    Motion,
}

impl BlockKind {
    pub(crate) fn begin(self) -> &'static str {
        match self {
            BlockKind::Frame => "FrameBegin",
            BlockKind::World => "WorldBegin",
            BlockKind::Attribute => "AttributeBegin",
            BlockKind::Transform => "TransformBegin",
            BlockKind::Solid => "SolidBegin",
            BlockKind::Motion => "MotionBegin",
        }
    }
}

pub(crate) struct Block {
    pub(crate) kind: BlockKind,
    pub(crate) span: Span,
    pub(crate) attributes: Arc<Attributes>,
    pub(crate) ctm: DMat4,
    pub(crate) ctm_motion: Option<MovingTransform>,
    pub(crate) options: Option<Options>,
}

/// The RenderMan Interface state.
pub struct Ri {
    pub(crate) options: Options,
    pub(crate) attributes: Arc<Attributes>,
    /// Camera from the current (object) space, f64.
    pub(crate) ctm: DMat4,
    /// The current transformation's keys when it moves (`ctm` is the first key).
    pub(crate) ctm_motion: Option<MovingTransform>,
    pub(crate) camera_from_world: Option<DMat4>,
    /// The camera's keys when it moves (a motion block before `WorldBegin`).
    pub(crate) camera_motion: Option<MovingTransform>,
    pub(crate) motion: Option<OpenMotion>,
    pub(crate) blocks: Vec<Block>,
    pub(crate) declarations: Declarations,
    pub(crate) coordinate_systems: HashMap<String, DMat4>,
    pub(crate) lights: Vec<Light>,
    pub(crate) primitives: Vec<FramePrimitive>,
    /// Instances gathered into one frame primitive (`instance_batch.rs`), not pushed yet.
    pub(crate) instance_run: Option<crate::instance_batch::InstanceRun>,
    /// This world's CSG solids, and the node each open `SolidBegin` stands for (a solid
    /// nested in a primitive solid stands for that primitive: its surfaces join it).
    pub(crate) solids: SolidTree,
    pub(crate) open_solids: Vec<u32>,
    pub(crate) frame_number: Option<i32>,
    pub(crate) camera: Option<Camera>,
    pub(crate) world_active: bool,
    pub(crate) recording: Option<(Recording, Span, Vec<Spanned<Request>>)>,
    pub(crate) objects: HashMap<Handle, Arc<Vec<Spanned<Request>>>>,
    /// The objects whose instances share one definition (see `instance.rs`).
    pub(crate) shared_objects: HashMap<Handle, Arc<crate::instance::SharedObject>>,
    /// `declarations` as the shared objects and deferred meshes keep them (until a `Declare`).
    pub(crate) declarations_shared: Option<Arc<Declarations>>,
    pub(crate) archives: HashMap<String, Arc<Vec<Spanned<Request>>>>,
    pub(crate) frames: Vec<Frame>,
    pub(crate) diagnostics: Diagnostics,
    pub(crate) parser: Option<StreamParser>,
    pub(crate) texture_maker: Option<TextureMaker>,
    pub(crate) crop_override: Option<[f32; 4]>,
    pub(crate) frame_range: Option<(i32, i32)>,
    pub(crate) nesting: usize,
    /// This world's memory estimate so far, and whether it went over the limit (`memory.rs`).
    pub(crate) frame_bytes: u64,
    pub(crate) memory_exceeded: bool,
}

impl Default for Ri {
    fn default() -> Self {
        Ri::new()
    }
}

impl Ri {
    pub fn new() -> Ri {
        Ri {
            options: Options::default(),
            attributes: Arc::new(Attributes::default()),
            ctm: DMat4::IDENTITY,
            ctm_motion: None,
            camera_from_world: None,
            camera_motion: None,
            motion: None,
            blocks: Vec::new(),
            declarations: Declarations::default(),
            coordinate_systems: HashMap::new(),
            lights: Vec::new(),
            primitives: Vec::new(),
            instance_run: None,
            solids: SolidTree::default(),
            open_solids: Vec::new(),
            frame_number: None,
            camera: None,
            world_active: true,
            recording: None,
            objects: HashMap::new(),
            shared_objects: HashMap::new(),
            declarations_shared: None,
            archives: HashMap::new(),
            frames: Vec::new(),
            diagnostics: Diagnostics::default(),
            parser: Some(Box::new(default_parser)),
            texture_maker: None,
            crop_override: None,
            frame_range: None,
            nesting: 0,
            frame_bytes: 0,
            memory_exceeded: false,
        }
    }

    /// Plugs in the RIB parser used for `ReadArchive`, `DelayedReadArchive` and `RunProgram`.
    pub fn set_parser(&mut self, parser: StreamParser) {
        self.parser = Some(parser);
    }

    /// Plugs in the texture builder for `MakeTexture` and friends.
    pub fn set_texture_maker(&mut self, maker: TextureMaker) {
        self.texture_maker = Some(maker);
    }

    /// Puts a program's tabulated filter function in place of the current `PixelFilter`'s
    /// kernel (the C binding's user `RtFilterFunc`; a later `PixelFilter` request clears it).
    pub fn set_filter_table(
        &mut self,
        table: Option<std::sync::Arc<illume_core::filter::FilterTable>>,
    ) {
        self.options.filter_table = table;
    }

    /// Replaces every frame's `CropWindow` (the `render --crop` flag).
    pub fn set_crop_override(&mut self, crop: Option<[f32; 4]>) {
        self.crop_override = crop;
    }

    /// Only frames numbered `a..=b` are built (the `render --frames` flag); others are parsed
    /// and skipped.
    pub fn set_frame_range(&mut self, range: Option<(i32, i32)>) {
        self.frame_range = range;
    }

    pub fn options(&self) -> &Options {
        &self.options
    }

    pub fn attributes(&self) -> &Attributes {
        &self.attributes
    }

    /// Camera from the current object space.
    pub fn current_transform(&self) -> DMat4 {
        self.ctm
    }

    pub fn declarations(&self) -> &Declarations {
        &self.declarations
    }

    /// Frames completed since the last call.
    pub fn take_frames(&mut self) -> Vec<Frame> {
        std::mem::take(&mut self.frames)
    }

    pub fn drain_diagnostics(&mut self) -> Vec<Diagnostic> {
        self.diagnostics.drain()
    }

    pub fn error_count(&self) -> usize {
        self.diagnostics.error_count()
    }

    /// Reports a diagnostic from outside (the parser, the hider) so counts and de-duplication
    /// stay in one place.
    pub fn report(&mut self, d: Diagnostic) {
        self.diagnostics.push(d);
    }

    /// Feeds every request of a source (parse errors become diagnostics).
    pub fn run(&mut self, source: RequestSource) {
        for item in source {
            match item {
                Ok(req) => self.request(req),
                Err(d) => self.diagnostics.push(d),
            }
        }
    }

    /// End of input: closes blocks left open (an error each), so a truncated file still
    /// renders what it described.
    pub fn finish(&mut self) {
        if let Some((_, span, _)) = self.recording.take() {
            self.diagnostics.error_kind(
                crate::ErrorKind::Nesting,
                &span,
                "ObjectBegin",
                "definition never closed (missing End)",
            );
        }
        while let Some(top) = self.blocks.last() {
            let (kind, span) = (top.kind, top.span.clone());
            self.diagnostics.error_kind(
                crate::ErrorKind::Nesting,
                &span,
                kind.begin(),
                "block never closed before the end of the input",
            );
            self.pop_block();
        }
    }

    /// Processes one request.
    pub fn request(&mut self, req: Spanned<Request>) {
        if self.record(&req) {
            return;
        }
        let Spanned { span, value } = req;
        let name = value.name().to_string();
        if value.is_option() && self.in_world() && !matches!(value, Request::Option { .. }) {
            self.diagnostics.error_kind(
                crate::ErrorKind::NotOptions,
                &span,
                &name,
                "options can not change inside WorldBegin/WorldEnd (ignored)",
            );
            return;
        }
        if self.motion.is_some() && value.is_transform() {
            self.motion_transform(value, &span);
            return;
        }
        use Request::*;
        match value {
            StructureComment(_) | Version(_) | ErrorHandler(_) | Unknown { .. } => {}
            Declare {
                name: n,
                declaration,
            } => match Declaration::parse(&declaration) {
                Ok(d) => {
                    self.declarations.declare(&n, d);
                    self.declarations_shared = None;
                }
                Err(e) => self.diagnostics.error(&span, &name, format!("{n}: {e}")),
            },
            FrameBegin(n) => {
                self.push_block(BlockKind::Frame, &span);
                self.frame_number = Some(n);
            }
            WorldBegin => self.world_begin(&span),
            AttributeBegin => self.push_block(BlockKind::Attribute, &span),
            TransformBegin => self.push_block(BlockKind::Transform, &span),
            SolidBegin(op) => {
                self.solid_begin(&op, &span);
                self.push_block(BlockKind::Solid, &span);
            }
            MotionBegin(times) => self.motion_begin(times, &span),
            FrameEnd => self.end_block(BlockKind::Frame, &span, &name),
            WorldEnd => self.end_block(BlockKind::World, &span, &name),
            AttributeEnd => self.end_block(BlockKind::Attribute, &span, &name),
            TransformEnd => self.end_block(BlockKind::Transform, &span, &name),
            SolidEnd => self.end_block(BlockKind::Solid, &span, &name),
            MotionEnd => self.end_block(BlockKind::Motion, &span, &name),
            ObjectEnd | ArchiveEnd => self.diagnostics.error_kind(
                crate::ErrorKind::Nesting,
                &span,
                &name,
                "no matching Begin is open (ignored)",
            ),
            ObjectBegin(_) | ArchiveBegin { .. } => unreachable!("handled by record"),
            ObjectInstance(h) => self.object_instance(&h, &span),
            ReadArchive { name: file, .. } => self.read_archive(&file, &span, Scope::Inline),
            MakeTexture { .. }
            | MakeBump { .. }
            | MakeLatLongEnvironment { .. }
            | MakeCubeFaceEnvironment { .. }
            | MakeShadow { .. } => self.make_texture(&value, &span),
            Procedural {
                name: kind,
                args,
                bound,
            } => self.procedural(&kind, &args, &bound, &span),
            ref r if r.is_option() => {
                let projection = matches!(r, Projection { .. });
                let display = matches!(r, Display { .. });
                self.options.apply(value, &span, &mut self.diagnostics);
                if display {
                    // AOV names take the types `Declare` gave them by the time of the Display.
                    if let Some(d) = self.options.displays.last_mut() {
                        d.declared = d
                            .mode
                            .split(',')
                            .map(str::trim)
                            .filter_map(|n| Some((n.to_string(), self.declarations.get(n)?)))
                            .collect();
                    }
                }
                if projection {
                    // RiProjection leaves the current transformation at identity.
                    self.ctm = DMat4::IDENTITY;
                    self.ctm_motion = None;
                }
            }
            ref r if r.is_geometry() => self.geometry(&value, &span),
            ref r if r.is_transform() || matches!(r, CoordinateSystem(_)) => {
                self.transform_request(value, &span)
            }
            other => self.attribute(other, &span),
        }
    }

    pub(crate) fn in_world(&self) -> bool {
        self.camera.is_some()
    }

    pub(crate) fn push_block(&mut self, kind: BlockKind, span: &Span) {
        self.blocks.push(Block {
            kind,
            span: span.clone(),
            attributes: self.attributes.clone(),
            ctm: self.ctm,
            ctm_motion: self.ctm_motion.clone(),
            options: (kind == BlockKind::Frame).then(|| self.options.clone()),
        });
    }

    pub(crate) fn end_block(&mut self, kind: BlockKind, span: &Span, name: &str) {
        let Some(pos) = self.blocks.iter().rposition(|b| b.kind == kind) else {
            let msg = format!("no matching {} is open (ignored)", kind.begin());
            self.diagnostics
                .error_kind(crate::ErrorKind::Nesting, span, name, msg);
            return;
        };
        while self.blocks.len() > pos + 1 {
            let top = self.blocks.last().expect("len > pos + 1");
            let msg = format!(
                "{} at {} is still open; closing it first",
                top.kind.begin(),
                top.span
            );
            self.diagnostics
                .error_kind(crate::ErrorKind::Nesting, span, name, msg);
            self.pop_block();
        }
        self.pop_block();
    }

    pub(crate) fn pop_block(&mut self) {
        let Some(b) = self.blocks.pop() else { return };
        match b.kind {
            BlockKind::Transform => (self.ctm, self.ctm_motion) = (b.ctm, b.ctm_motion),
            BlockKind::Solid => {
                self.open_solids.pop();
            }
            BlockKind::Motion => self.motion_end(&b.span),
            BlockKind::Attribute => {
                (self.ctm, self.ctm_motion) = (b.ctm, b.ctm_motion);
                self.attributes = b.attributes;
            }
            BlockKind::World => {
                self.world_end();
                (self.ctm, self.ctm_motion) = (b.ctm, b.ctm_motion);
                self.attributes = b.attributes;
            }
            BlockKind::Frame => {
                (self.ctm, self.ctm_motion) = (b.ctm, b.ctm_motion);
                self.attributes = b.attributes;
                if let Some(o) = b.options {
                    self.options = o;
                }
                self.frame_number = None;
            }
        }
    }
}

/// The `illume-rib` parser, with its diagnostics carried over.
fn default_parser(reader: Box<dyn Read>, name: &str) -> RequestSource {
    Box::new(illume_rib::Parser::new(reader, name).map(|r| r.map_err(from_rib_diagnostic)))
}

/// Converts a parser diagnostic into the RI one (same fields, same printed form).
pub fn from_rib_diagnostic(d: illume_rib::Diagnostic) -> Diagnostic {
    Diagnostic {
        severity: match d.severity {
            illume_rib::Severity::Warning => crate::Severity::Warning,
            illume_rib::Severity::Error => crate::Severity::Error,
        },
        kind: crate::ErrorKind::Syntax,
        span: d.span,
        request: d.request,
        message: d.message,
    }
}
