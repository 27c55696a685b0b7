//! The RI state machine: one method per request family, a block stack that recovers from
//! mismatched `Begin`/`End`, and frame hand-off at `WorldEnd`.
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
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A stream of parsed requests (a RIB file, an archive, a `RunProgram`'s output).
pub type RequestSource = Box<dyn Iterator<Item = Result<Spanned<Request>, Diagnostic>>>;

/// Turns bytes into requests; `name` is the file name spans will carry. The RIB parser lives
/// in `illume-rib`; the caller plugs it in so `ReadArchive`, `DelayedReadArchive` and
/// `RunProgram` can read files.
pub type StreamParser = Box<dyn Fn(Box<dyn Read>, &str) -> RequestSource>;

/// Builds a texture for `MakeTexture`/`MakeShadow`/… (`illume-texture` plugs in here).
pub type TextureMaker = Box<dyn FnMut(&Request, &Options) -> Result<(), String>>;

/// Nested reads (archives including archives) beyond this depth are an error, not a stack
/// overflow.
const MAX_NESTING: usize = 64;

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

pub(crate) enum Recording {
    Object(Handle),
    Archive(String),
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
    /// This world's CSG solids, and the node each open `SolidBegin` stands for (a solid
    /// nested in a primitive solid stands for that primitive: its surfaces join it).
    pub(crate) solids: SolidTree,
    pub(crate) open_solids: Vec<u32>,
    pub(crate) frame_number: Option<i32>,
    pub(crate) camera: Option<Camera>,
    pub(crate) world_active: bool,
    pub(crate) recording: Option<(Recording, Span, Vec<Spanned<Request>>)>,
    pub(crate) objects: HashMap<Handle, Arc<Vec<Spanned<Request>>>>,
    pub(crate) archives: HashMap<String, Arc<Vec<Spanned<Request>>>>,
    pub(crate) frames: Vec<Frame>,
    pub(crate) diagnostics: Diagnostics,
    pub(crate) parser: Option<StreamParser>,
    pub(crate) texture_maker: Option<TextureMaker>,
    pub(crate) crop_override: Option<[f32; 4]>,
    pub(crate) frame_range: Option<(i32, i32)>,
    pub(crate) nesting: usize,
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
            solids: SolidTree::default(),
            open_solids: Vec::new(),
            frame_number: None,
            camera: None,
            world_active: true,
            recording: None,
            objects: HashMap::new(),
            archives: HashMap::new(),
            frames: Vec::new(),
            diagnostics: Diagnostics::default(),
            parser: Some(Box::new(default_parser)),
            texture_maker: None,
            crop_override: None,
            frame_range: None,
            nesting: 0,
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
            self.diagnostics.error(
                &span,
                "ObjectBegin",
                "definition never closed (missing End)",
            );
        }
        while let Some(top) = self.blocks.last() {
            let (kind, span) = (top.kind, top.span.clone());
            self.diagnostics.error(
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
            self.diagnostics.error(
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
                Ok(d) => self.declarations.declare(&n, d),
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
            ObjectEnd | ArchiveEnd => {
                self.diagnostics
                    .error(&span, &name, "no matching Begin is open (ignored)")
            }
            ObjectBegin(_) | ArchiveBegin { .. } => unreachable!("handled by record"),
            ObjectInstance(h) => self.object_instance(&h, &span),
            ReadArchive { name: file, .. } => self.read_archive(&file, &span),
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
                self.options.apply(value, &span, &mut self.diagnostics);
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

    /// While inside `ObjectBegin`/`ArchiveBegin`, requests are stored, not executed.
    fn record(&mut self, req: &Spanned<Request>) -> bool {
        match (&req.value, &mut self.recording) {
            (Request::ObjectBegin(h), None) => {
                self.recording = Some((Recording::Object(h.clone()), req.span.clone(), vec![]));
                true
            }
            (Request::ArchiveBegin { name, .. }, None) => {
                self.recording = Some((Recording::Archive(name.clone()), req.span.clone(), vec![]));
                true
            }
            (Request::ObjectEnd, Some((Recording::Object(_), ..)))
            | (Request::ArchiveEnd, Some((Recording::Archive(_), ..))) => {
                let Some((rec, _, reqs)) = self.recording.take() else {
                    return true;
                };
                match rec {
                    Recording::Object(h) => {
                        self.objects.insert(h, Arc::new(reqs));
                    }
                    Recording::Archive(n) => {
                        self.archives.insert(n, Arc::new(reqs));
                    }
                }
                true
            }
            (Request::ObjectBegin(_) | Request::ArchiveBegin { .. }, Some(_)) => {
                self.diagnostics.error(
                    &req.span,
                    req.value.name(),
                    "definitions can not nest (ignored)",
                );
                true
            }
            (Request::ObjectEnd | Request::ArchiveEnd, Some((open, span, _))) => {
                let expected = match open {
                    Recording::Object(_) => "ObjectEnd",
                    Recording::Archive(_) => "ArchiveEnd",
                };
                let msg = format!("expected {expected} to close the definition at {span}");
                self.diagnostics.error(&req.span, req.value.name(), msg);
                self.recording = None;
                true
            }
            (_, Some((_, _, reqs))) => {
                reqs.push(req.clone());
                true
            }
            (_, None) => false,
        }
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
            self.diagnostics.error(span, name, msg);
            return;
        };
        while self.blocks.len() > pos + 1 {
            let top = self.blocks.last().expect("len > pos + 1");
            let msg = format!(
                "{} at {} is still open; closing it first",
                top.kind.begin(),
                top.span
            );
            self.diagnostics.error(span, name, msg);
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

    // ---- options ---------------------------------------------------------------------

    // ---- attributes and transforms ----------------------------------------------------

    // ---- solids --------------------------------------------------------------------------

    // ---- geometry ------------------------------------------------------------------------

    // ---- motion blocks ---------------------------------------------------------------------

    // ---- archives, instances, procedurals -------------------------------------------------

    fn object_instance(&mut self, h: &Handle, span: &Span) {
        let Some(reqs) = self.objects.get(h).cloned() else {
            self.diagnostics.error(
                span,
                "ObjectInstance",
                format!("no object with handle {h:?}"),
            );
            return;
        };
        self.replay(&reqs, span, "ObjectInstance");
    }

    fn replay(&mut self, reqs: &[Spanned<Request>], span: &Span, what: &str) {
        if self.nesting >= MAX_NESTING {
            self.diagnostics
                .error(span, what, "nested too deeply (recursive archive?)");
            return;
        }
        self.nesting += 1;
        let depth = self.blocks.len();
        self.push_block(BlockKind::Attribute, span);
        for r in reqs {
            self.request(r.clone());
        }
        self.close_to(depth, span, what);
        self.nesting -= 1;
    }

    /// Closes blocks an archive left open, so it can not leak state into its reader.
    fn close_to(&mut self, depth: usize, span: &Span, what: &str) {
        while self.blocks.len() > depth + 1 {
            let b = self.blocks.last().expect("len > depth + 1");
            let msg = format!("{} at {} left open; closed", b.kind.begin(), b.span);
            self.diagnostics.error(span, what, msg);
            self.pop_block();
        }
        if self.blocks.len() > depth {
            self.pop_block();
        }
    }

    fn resolve(&self, file: &str, span: &Span) -> Option<PathBuf> {
        let p = Path::new(file);
        if p.is_absolute() || p.exists() {
            return Some(p.to_path_buf());
        }
        let base = Path::new(&*span.file).parent().map(Path::to_path_buf);
        self.options
            .archive_path
            .iter()
            .map(|d| Path::new(d).join(file))
            .chain(base.map(|b| b.join(file)))
            .find(|c| c.exists())
    }

    fn read_archive(&mut self, file: &str, span: &Span) {
        if let Some(reqs) = self.archives.get(file).cloned() {
            self.replay(&reqs, span, "ReadArchive");
            return;
        }
        let Some(path) = self.resolve(file, span) else {
            self.diagnostics.error(
                span,
                "ReadArchive",
                format!("can not find \"{file}\" (searched the archive searchpath and the including file's directory)"),
            );
            return;
        };
        match std::fs::File::open(&path) {
            Ok(f) => self.read_stream(
                Box::new(std::io::BufReader::new(f)),
                &path.display().to_string(),
                span,
                "ReadArchive",
            ),
            Err(e) => {
                self.diagnostics
                    .error(span, "ReadArchive", format!("{}: {e}", path.display()))
            }
        }
    }

    fn read_stream(&mut self, reader: Box<dyn Read>, name: &str, span: &Span, what: &str) {
        let Some(parser) = self.parser.as_ref() else {
            self.diagnostics
                .error(span, what, "no RIB parser is plugged in to read archives");
            return;
        };
        if self.nesting >= MAX_NESTING {
            self.diagnostics
                .error(span, what, "nested too deeply (recursive archive?)");
            return;
        }
        let source = parser(reader, name);
        self.nesting += 1;
        let depth = self.blocks.len();
        self.push_block(BlockKind::Attribute, span);
        self.run(source);
        self.close_to(depth, span, what);
        self.nesting -= 1;
    }

    fn procedural(&mut self, kind: &str, args: &[String], bound: &[f32; 6], span: &Span) {
        if !self.in_world() {
            self.diagnostics.error(
                span,
                "Procedural",
                "only valid inside WorldBegin/WorldEnd (ignored)",
            );
            return;
        }
        if !self.world_active {
            return;
        }
        let on_screen = match self.raster_bound(bound, self.ctm) {
            None => true,
            Some(r) => {
                let cam = self.camera.as_ref().expect("in world");
                let margin = f64::from(self.options.filter.1.max(self.options.filter.2));
                let [x0, x1, y0, y1] = cam.crop.map(f64::from);
                r[1] >= x0 - margin
                    && r[0] <= x1 + margin
                    && r[3] >= y0 - margin
                    && r[2] <= y1 + margin
            }
        };
        match kind {
            "DelayedReadArchive" => {
                let Some(file) = args.first() else {
                    self.diagnostics
                        .error(span, "Procedural", "DelayedReadArchive expects a file name");
                    return;
                };
                if on_screen {
                    self.read_archive(file, span);
                }
            }
            "RunProgram" => {
                if on_screen {
                    let detail = self
                        .raster_bound(bound, self.ctm)
                        .map_or(f64::INFINITY, |r| (r[1] - r[0]) * (r[3] - r[2]));
                    self.run_program(args, detail, span);
                }
            }
            "DynamicLoad" => self.diagnostics.error(
                span,
                "Procedural",
                "DynamicLoad is unsupported: Illume does not load native code; use RunProgram or DelayedReadArchive",
            ),
            other => self.diagnostics.error(
                span,
                "Procedural",
                format!("unknown procedural \"{other}\", expected DelayedReadArchive, RunProgram or DynamicLoad"),
            ),
        }
    }

    /// `Procedural "RunProgram" ["prog args" "data"]`: the program reads `detail data` lines on
    /// stdin and answers each with RIB ending in a 0xFF byte (RI Spec 3.2 §5.7).
    fn run_program(&mut self, args: &[String], detail: f64, span: &Span) {
        use std::io::Write;
        use std::process::{Command, Stdio};
        let (Some(prog), data) = (args.first(), args.get(1).cloned().unwrap_or_default()) else {
            self.diagnostics
                .error(span, "Procedural", "RunProgram expects a program name");
            return;
        };
        let mut words = prog.split_whitespace();
        let Some(exe) = words.next() else {
            self.diagnostics
                .error(span, "Procedural", "RunProgram: empty program name");
            return;
        };
        let exe_path = self
            .options
            .procedural_path
            .iter()
            .map(|d| Path::new(d).join(exe))
            .find(|p| p.is_file())
            .unwrap_or_else(|| PathBuf::from(exe));
        let child = Command::new(&exe_path)
            .args(words)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn();
        let mut child = match child {
            Ok(c) => c,
            Err(e) => {
                self.diagnostics
                    .error(span, "Procedural", format!("RunProgram \"{exe}\": {e}"));
                return;
            }
        };
        if let Some(mut stdin) = child.stdin.take() {
            let _ = writeln!(stdin, "{detail} {data}");
        }
        let output = match child.wait_with_output() {
            Ok(o) => o,
            Err(e) => {
                self.diagnostics
                    .error(span, "Procedural", format!("RunProgram \"{exe}\": {e}"));
                return;
            }
        };
        let mut bytes = output.stdout;
        while bytes.last() == Some(&0xFF) {
            bytes.pop();
        }
        self.read_stream(
            Box::new(std::io::Cursor::new(bytes)),
            &format!("{exe} (RunProgram)"),
            span,
            "Procedural",
        );
    }

    fn make_texture(&mut self, req: &Request, span: &Span) {
        match self.texture_maker.as_mut() {
            Some(maker) => {
                if let Err(e) = maker(req, &self.options) {
                    self.diagnostics.error(span, req.name(), e);
                }
            }
            None => self.diagnostics.warn(
                span,
                req.name(),
                "texture making not supported yet (skipped)",
            ),
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
        span: d.span,
        request: d.request,
        message: d.message,
    }
}
