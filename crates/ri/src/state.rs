//! The RI state machine: one method per request family, a block stack that recovers from
//! mismatched `Begin`/`End`, and frame hand-off at `WorldEnd`.
use crate::attributes::{Attributes, Light, Shader};
use crate::camera::Camera;
use crate::declarations::Declarations;
use crate::diagnostic::{Diagnostic, Diagnostics};
use crate::frame::{Frame, FramePrimitive};
use crate::motion::{segment, MotionKeys, MovingTransform};
use crate::options::{expand_search_path, DepthFilter, DisplaySpec, Options, QuantizeSpec};
use crate::paramlist;
use crate::solid::{SolidOp, SolidTree};
use crate::transform;
use glam::{DMat4, DVec3};
use illume_geom::{BuildContext, GeomError};
use illume_rib::{BasisSpec, Declaration, Handle, ParamList, Request, Span, Spanned};
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
enum BlockKind {
    Frame,
    World,
    Attribute,
    Transform,
    Solid,
    Motion,
}

impl BlockKind {
    fn begin(self) -> &'static str {
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

struct Block {
    kind: BlockKind,
    span: Span,
    attributes: Arc<Attributes>,
    ctm: DMat4,
    ctm_motion: Option<MovingTransform>,
    options: Option<Options>,
}

/// An open `MotionBegin` block: its times, the transform it started from, and what each of
/// its requests produced (one transformation or one primitive list per time).
struct OpenMotion {
    times: Vec<f64>,
    base: (DMat4, Option<MovingTransform>),
    transforms: Vec<(DMat4, Option<MovingTransform>)>,
    geometry: Vec<Vec<Box<dyn illume_geom::Primitive>>>,
    /// Span and name of the first request, for the block's errors.
    first: Option<(Span, String)>,
}

enum Recording {
    Object(Handle),
    Archive(String),
}

/// The RenderMan Interface state.
pub struct Ri {
    options: Options,
    attributes: Arc<Attributes>,
    /// Camera from the current (object) space, f64.
    ctm: DMat4,
    /// The current transformation's keys when it moves (`ctm` is the first key).
    ctm_motion: Option<MovingTransform>,
    camera_from_world: Option<DMat4>,
    /// The camera's keys when it moves (a motion block before `WorldBegin`).
    camera_motion: Option<MovingTransform>,
    motion: Option<OpenMotion>,
    blocks: Vec<Block>,
    declarations: Declarations,
    coordinate_systems: HashMap<String, DMat4>,
    lights: Vec<Light>,
    primitives: Vec<FramePrimitive>,
    /// This world's CSG solids, and the node each open `SolidBegin` stands for (a solid
    /// nested in a primitive solid stands for that primitive: its surfaces join it).
    solids: SolidTree,
    open_solids: Vec<u32>,
    frame_number: Option<i32>,
    camera: Option<Camera>,
    world_active: bool,
    recording: Option<(Recording, Span, Vec<Spanned<Request>>)>,
    objects: HashMap<Handle, Arc<Vec<Spanned<Request>>>>,
    archives: HashMap<String, Arc<Vec<Spanned<Request>>>>,
    frames: Vec<Frame>,
    diagnostics: Diagnostics,
    parser: Option<StreamParser>,
    texture_maker: Option<TextureMaker>,
    crop_override: Option<[f32; 4]>,
    frame_range: Option<(i32, i32)>,
    nesting: usize,
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
        if is_option(&value) && self.in_world() && !matches!(value, Request::Option { .. }) {
            self.diagnostics.error(
                &span,
                &name,
                "options can not change inside WorldBegin/WorldEnd (ignored)",
            );
            return;
        }
        if self.motion.is_some() && is_transform(&value) {
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
            ref r if is_option(r) => self.option(value, &span),
            ref r if is_geometry(r) => self.geometry(&value, &span),
            other => self.attribute_or_transform(other, &span),
        }
    }

    fn in_world(&self) -> bool {
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

    fn push_block(&mut self, kind: BlockKind, span: &Span) {
        self.blocks.push(Block {
            kind,
            span: span.clone(),
            attributes: self.attributes.clone(),
            ctm: self.ctm,
            ctm_motion: self.ctm_motion.clone(),
            options: (kind == BlockKind::Frame).then(|| self.options.clone()),
        });
    }

    fn end_block(&mut self, kind: BlockKind, span: &Span, name: &str) {
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

    fn pop_block(&mut self) {
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

    fn world_begin(&mut self, span: &Span) {
        if self.in_world() {
            self.diagnostics
                .error(span, "WorldBegin", "already inside a world block (ignored)");
            return;
        }
        self.push_block(BlockKind::World, span);
        let mut options = self.options.clone();
        if let Some(c) = self.crop_override {
            options.crop = c;
        }
        self.camera = Some(Camera::new(&options, self.ctm));
        self.camera_from_world = Some(self.ctm);
        self.camera_motion = self.ctm_motion.clone();
        self.coordinate_systems
            .insert("world".to_string(), self.ctm);
        self.world_active = match (self.frame_range, self.frame_number) {
            (Some((a, b)), Some(n)) => (a..=b).contains(&n),
            _ => true,
        };
        self.primitives.clear();
    }

    fn world_end(&mut self) {
        let Some(camera) = self.camera.take() else {
            return;
        };
        let mut options = self.options.clone();
        if let Some(c) = self.crop_override {
            options.crop = c;
        }
        let primitives = std::mem::take(&mut self.primitives);
        let solids = std::mem::take(&mut self.solids);
        self.open_solids.clear();
        if self.world_active {
            self.frames.push(Frame {
                number: self.frame_number,
                options,
                camera,
                lights: self.lights.clone(),
                primitives,
                solids,
                coordinate_systems: self
                    .coordinate_systems
                    .iter()
                    .map(|(k, v)| (k.clone(), *v))
                    .collect(),
            });
        }
        self.lights.clear();
        self.camera_from_world = None;
        self.camera_motion = None;
        self.coordinate_systems.remove("world");
        self.world_active = true;
    }

    // ---- options ---------------------------------------------------------------------

    fn option(&mut self, req: Request, span: &Span) {
        let name = req.name().to_string();
        let o = &mut self.options;
        use Request::*;
        match req {
            Format {
                xres,
                yres,
                pixel_aspect,
            } => {
                // Non-positive values mean "the device default" (RI Spec 3.2 `RiFormat`).
                o.xres = if xres > 0 { xres as u32 } else { 640 };
                o.yres = if yres > 0 { yres as u32 } else { 480 };
                o.pixel_aspect = if pixel_aspect > 0.0 {
                    pixel_aspect
                } else {
                    1.0
                };
                if xres > 65535 || yres > 65535 {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("resolution {xres}×{yres} is too large"),
                    );
                    o.xres = o.xres.min(65535);
                    o.yres = o.yres.min(65535);
                }
            }
            FrameAspectRatio(a) => {
                if a > 0.0 {
                    o.frame_aspect = Some(a);
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("expected a positive ratio, found {a}"),
                    );
                }
            }
            ScreenWindow {
                left,
                right,
                bottom,
                top,
            } => {
                if left == right || bottom == top {
                    self.diagnostics.error(
                        span,
                        &name,
                        "the window has zero width or height (ignored)",
                    );
                } else {
                    o.screen_window = Some([left, right, bottom, top]);
                }
            }
            CropWindow {
                xmin,
                xmax,
                ymin,
                ymax,
            } => {
                let c = [xmin, xmax, ymin, ymax].map(|v| v.clamp(0.0, 1.0));
                if c[0] >= c[1] || c[2] >= c[3] {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("empty window {xmin} {xmax} {ymin} {ymax} (ignored)"),
                    );
                } else {
                    o.crop = c;
                }
            }
            Projection { name: p, params } => {
                match p.as_str() {
                    "perspective" => {
                        let fov = paramlist::float(&params, "fov").unwrap_or(90.0);
                        if fov > 0.0 && fov < 180.0 {
                            o.projection = crate::options::Projection::Perspective { fov };
                        } else {
                            self.diagnostics.error(
                                span,
                                &name,
                                format!("fov must lie in (0, 180) degrees, found {fov}"),
                            );
                        }
                    }
                    "orthographic" | "none" => {
                        o.projection = crate::options::Projection::Orthographic
                    }
                    other => self.diagnostics.error(
                        span,
                        &name,
                        format!(
                            "unknown projection `{other}`, expected perspective or orthographic"
                        ),
                    ),
                }
                // RiProjection leaves the current transformation at identity.
                self.ctm = DMat4::IDENTITY;
                self.ctm_motion = None;
            }
            Clipping { near, far } => {
                if near > 0.0 && far > near {
                    o.near = near;
                    o.far = far;
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("expected 0 < near < far, found {near} {far}"),
                    );
                }
            }
            Shutter { open, close } => {
                if open.is_finite() && close.is_finite() && open <= close {
                    o.shutter = [open, close];
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("expected open ≤ close, found {open} {close}"),
                    );
                }
            }
            DepthOfField {
                fstop,
                focal_length,
                focal_distance,
            } => {
                // An infinite f-stop is the spec's way to ask for a pinhole camera.
                if fstop == f32::INFINITY {
                    o.depth_of_field = None;
                } else if fstop > 0.0
                    && focal_length > 0.0
                    && focal_distance > 0.0
                    && focal_length.is_finite()
                    && focal_distance.is_finite()
                {
                    o.depth_of_field = Some([fstop, focal_length, focal_distance]);
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!(
                            "expected positive fstop, focallength and focaldistance, found {fstop} {focal_length} {focal_distance}"
                        ),
                    );
                }
            }
            ClippingPlane { .. } | Imager { .. } | RelativeDetail(_) => {
                self.diagnostics
                    .warn(span, &name, "not supported yet (ignored)");
            }
            ColorSamples { n_rgb, .. } if n_rgb.len() != 9 => {
                self.diagnostics.warn(
                    span,
                    &name,
                    "only 3 RGB color samples are supported (ignored)",
                );
            }
            PixelVariance(v) => o.pixel_variance = v,
            PixelSamples { x, y } => {
                o.pixel_samples = [x.round().max(1.0) as u32, y.round().max(1.0) as u32];
                if o.pixel_samples[0] > 64 || o.pixel_samples[1] > 64 {
                    self.diagnostics.warn(
                        span,
                        &name,
                        "more than 64 samples per axis; clamped to 64",
                    );
                    o.pixel_samples = o.pixel_samples.map(|s| s.min(64));
                }
            }
            PixelFilter {
                name: f,
                xwidth,
                ywidth,
            } => {
                use illume_core::filter::{filter_names_list, FilterKind};
                if FilterKind::parse(&f).is_none() {
                    self.diagnostics.warn(
                        span,
                        &name,
                        format!(
                            "unknown filter `{f}`, using gaussian (expected one of {})",
                            filter_names_list()
                        ),
                    );
                    o.filter = ("gaussian".into(), xwidth.max(1.0), ywidth.max(1.0));
                } else if !(xwidth > 0.0 && ywidth > 0.0) {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("widths must be positive, found {xwidth} {ywidth}"),
                    );
                } else {
                    o.filter = (f, xwidth.min(16.0), ywidth.min(16.0));
                }
            }
            Exposure { gain, gamma } => {
                if gamma > 0.0 {
                    o.exposure = (gain, gamma);
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("gamma must be positive, found {gamma}"),
                    );
                }
            }
            Quantize {
                kind,
                one,
                min,
                max,
                dither,
            } => {
                let q = QuantizeSpec {
                    one,
                    min,
                    max,
                    dither,
                };
                match kind.as_str() {
                    "rgba" => o.quantize_rgba = q,
                    "z" => o.quantize_z = q,
                    other => self.diagnostics.error(
                        span,
                        &name,
                        format!("expected \"rgba\" or \"z\", found \"{other}\""),
                    ),
                }
            }
            Display {
                name: file,
                kind,
                mode,
                params,
            } => {
                let spec = DisplaySpec {
                    name: file.trim_start_matches('+').to_string(),
                    kind,
                    mode,
                    params,
                };
                if !file.starts_with('+') {
                    o.displays.clear();
                }
                o.displays.push(spec);
            }
            Hider { name: h, params } => {
                if h != "hidden" {
                    self.diagnostics.warn(
                        span,
                        &name,
                        format!("hider `{h}` not supported, using \"hidden\""),
                    );
                }
                for p in paramlist::names(&params)
                    .map(str::to_string)
                    .collect::<Vec<_>>()
                {
                    match p.as_str() {
                        "jitter" => {
                            o.jitter = paramlist::float(&params, "jitter").unwrap_or(1.0) != 0.0
                        }
                        "depthfilter" => {
                            let v = paramlist::string(&params, "depthfilter").unwrap_or_default();
                            o.depth_filter = match v.as_str() {
                                "min" => DepthFilter::Min,
                                "max" => DepthFilter::Max,
                                "average" => DepthFilter::Average,
                                "midpoint" => DepthFilter::Midpoint,
                                other => {
                                    self.diagnostics.error(
                                        span,
                                        &name,
                                        format!("depthfilter must be min, max, average or midpoint, found `{other}`"),
                                    );
                                    o.depth_filter
                                }
                            };
                        }
                        other => self.diagnostics.warn(
                            span,
                            &name,
                            format!("parameter \"{other}\" not supported (ignored)"),
                        ),
                    }
                }
            }
            Option { name: n, params } => self.user_option(&n, &params, span),
            _ => {}
        }
    }

    fn user_option(&mut self, name: &str, params: &ParamList, span: &Span) {
        let o = &mut self.options;
        for p in paramlist::names(params)
            .map(str::to_string)
            .collect::<Vec<_>>()
        {
            let f = paramlist::floats(params, &p).unwrap_or_default();
            let s = paramlist::string(params, &p);
            match (name, p.as_str()) {
                ("limits", "bucketsize") if f.len() == 2 && f[0] >= 1.0 && f[1] >= 1.0 => {
                    o.bucket_size = [f[0].min(1024.0) as u32, f[1].min(1024.0) as u32]
                }
                ("limits", "gridsize") if f.first().is_some_and(|&g| g >= 1.0) => {
                    o.grid_size = f[0] as u32
                }
                ("limits", "eyesplits") if f.first().is_some_and(|&g| g >= 0.0) => {
                    o.eye_splits = (f[0] as u32).min(32)
                }
                ("limits", "texturememory") if f.first().is_some_and(|&g| g >= 0.0) => {
                    o.texture_memory = f[0] as u32
                }
                (
                    "searchpath",
                    kind @ ("shader" | "texture" | "archive" | "resource" | "procedural"),
                ) => {
                    let Some(value) = s else {
                        self.diagnostics.error(
                            span,
                            "Option",
                            format!("searchpath \"{kind}\" expects a string"),
                        );
                        continue;
                    };
                    let default = vec![".".to_string()];
                    let expand = |prev: &Vec<String>| expand_search_path(&value, prev, &default);
                    match kind {
                        "shader" => o.shader_path = expand(&o.shader_path),
                        "texture" => o.texture_path = expand(&o.texture_path),
                        "procedural" => o.procedural_path = expand(&o.procedural_path),
                        "archive" => o.archive_path = expand(&o.archive_path),
                        _ => {
                            // "resource" covers every kind at once.
                            o.shader_path = expand(&o.shader_path);
                            o.texture_path = expand(&o.texture_path);
                            o.archive_path = expand(&o.archive_path);
                        }
                    }
                }
                ("shadow", "bias0") if !f.is_empty() => o.shadow_bias[0] = f[0],
                ("shadow", "bias1") if !f.is_empty() => o.shadow_bias[1] = f[0],
                ("shadow", "bias") if !f.is_empty() => o.shadow_bias = [f[0], f[0]],
                ("shading", "specularmodel") if s.is_some() => {
                    o.specular_model = s.unwrap_or_default()
                }
                (_, p) => self.diagnostics.warn(
                    span,
                    "Option",
                    format!("\"{name}\" \"{p}\" not supported or malformed (ignored)"),
                ),
            }
        }
    }

    // ---- attributes and transforms ----------------------------------------------------

    fn attrs(&mut self) -> &mut Attributes {
        Arc::make_mut(&mut self.attributes)
    }

    fn shader(&self, name: String, params: ParamList, span: &Span) -> Arc<Shader> {
        Arc::new(Shader {
            name,
            params,
            camera_from_shader: self.ctm,
            span: span.clone(),
        })
    }

    fn concat(&mut self, m: DMat4) {
        self.ctm *= m;
        if let Some(mm) = &self.ctm_motion {
            self.ctm_motion = Some(mm.then(m));
        }
    }

    /// The handedness of the current object space relative to (left-handed) camera space.
    fn current_is_rh(&self) -> bool {
        self.ctm.determinant() < 0.0
    }

    fn attribute_or_transform(&mut self, req: Request, span: &Span) {
        let name = req.name().to_string();
        use Request::*;
        match req {
            Color(c) | Opacity(c) if c.len() < 3 => self.diagnostics.error(
                span,
                &name,
                format!("expected 3 color samples, found {}", c.len()),
            ),
            Color(c) => self.attrs().color = [c[0], c[1], c[2]],
            Opacity(c) => self.attrs().opacity = [c[0], c[1], c[2]],
            TextureCoordinates(tc) => self.attrs().texture_coordinates = tc,
            ShadingRate(r) => {
                if r > 0.0 {
                    self.attrs().shading_rate = r;
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("expected a positive rate, found {r}"),
                    );
                }
            }
            ShadingInterpolation(kind) => match kind.as_str() {
                "smooth" => self.attrs().smooth_shading = true,
                "constant" => self.attrs().smooth_shading = false,
                other => self.diagnostics.error(
                    span,
                    &name,
                    format!("expected \"constant\" or \"smooth\", found \"{other}\""),
                ),
            },
            Matte(m) => self.attrs().matte = m,
            Sides(s) => {
                if s == 1 || s == 2 {
                    self.attrs().sides = s;
                } else {
                    self.diagnostics
                        .error(span, &name, format!("expected 1 or 2, found {s}"));
                }
            }
            Orientation(o) => {
                let rh = match o.as_str() {
                    "lh" => false,
                    "rh" => true,
                    "outside" => self.current_is_rh(),
                    "inside" => !self.current_is_rh(),
                    other => {
                        self.diagnostics.error(
                            span,
                            &name,
                            format!("expected lh, rh, inside or outside, found \"{other}\""),
                        );
                        return;
                    }
                };
                self.attrs().orientation_rh = rh;
            }
            ReverseOrientation => {
                let a = self.attrs();
                a.orientation_rh = !a.orientation_rh;
            }
            TrimCurve {
                ncurves,
                order,
                knot,
                min,
                max,
                n,
                u,
                v,
                w,
            } => {
                let args = illume_geom::TrimCurveArgs {
                    ncurves: &ncurves,
                    order: &order,
                    knot: &knot,
                    min: &min,
                    max: &max,
                    n: &n,
                    u: &u,
                    v: &v,
                    w: &w,
                };
                match illume_geom::TrimCurves::new(args) {
                    Ok(t) => self.attrs().trim_curves = (!t.is_empty()).then(|| Arc::new(t)),
                    Err(e) => self.diagnostics.error(span, &name, e),
                }
            }
            Basis {
                ubasis,
                ustep,
                vbasis,
                vstep,
            } => {
                let (Some(u), Some(v)) = (basis_matrix(&ubasis), basis_matrix(&vbasis)) else {
                    self.diagnostics.error(
                        span,
                        &name,
                        "unknown basis, expected bezier, b-spline, catmull-rom, hermite, power or 16 numbers",
                    );
                    return;
                };
                if ustep < 1 || vstep < 1 {
                    self.diagnostics.error(
                        span,
                        &name,
                        format!("steps must be positive, found {ustep} {vstep}"),
                    );
                    return;
                }
                self.attrs().basis = (u, ustep, v, vstep);
            }
            Surface { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().surface = Some(s);
            }
            Displacement { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().displacement = Some(s);
            }
            Atmosphere { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().atmosphere = Some(s);
            }
            Interior { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().interior = Some(s);
            }
            Exterior { name: n, params } => {
                let s = self.shader(n, params, span);
                self.attrs().exterior = Some(s);
            }
            Deformation { .. } | GeometricRepresentation(_) => {
                self.diagnostics
                    .warn(span, &name, "not supported yet (ignored)")
            }
            LightSource {
                name: n,
                handle,
                params,
            } => self.light(n, handle, params, false, span),
            AreaLightSource {
                name: n,
                handle,
                params,
            } => self.light(n, handle, params, true, span),
            Illuminate { handle, on } => {
                let Some(i) = self.lights.iter().position(|l| l.handle == handle) else {
                    self.diagnostics
                        .error(span, &name, format!("no light with handle {handle:?}"));
                    return;
                };
                let a = self.attrs();
                a.lights.retain(|&l| l != i);
                if on {
                    a.lights.push(i);
                }
            }
            Attribute { name: n, params } => self.user_attribute(&n, &params, span),
            Bound(_) => {}
            Detail(b) => {
                let ctm = self.ctm;
                self.attrs().detail = Some((b, ctm));
            }
            DetailRange(r) => {
                if r[0] <= r[1] && r[1] <= r[2] && r[2] <= r[3] {
                    self.attrs().detail_range = Some(r);
                } else {
                    self.diagnostics.error(
                        span,
                        &name,
                        "expected minvisible ≤ lowertransition ≤ uppertransition ≤ maxvisible",
                    );
                }
            }
            GeometricApproximation { kind, value } => {
                if kind == "flatness" {
                    self.attrs().flatness = Some(value);
                } else {
                    self.diagnostics.warn(
                        span,
                        &name,
                        format!("\"{kind}\" not supported (ignored)"),
                    );
                }
            }
            Identity => {
                self.ctm = self.camera_from_world.unwrap_or(DMat4::IDENTITY);
                self.ctm_motion = self.camera_motion.clone();
            }
            Transform(m) => {
                let m = transform::from_rib(&m);
                self.ctm = self.camera_from_world.unwrap_or(DMat4::IDENTITY) * m;
                self.ctm_motion = self.camera_motion.as_ref().map(|c| c.then(m));
            }
            ConcatTransform(m) => self.concat(transform::from_rib(&m)),
            Perspective(fov) => match transform::perspective(fov) {
                Some(m) => self.concat(m),
                None => self.diagnostics.error(
                    span,
                    &name,
                    format!("fov must lie in (0, 180), found {fov}"),
                ),
            },
            Translate(t) => self.concat(DMat4::from_translation(DVec3::from(t.map(f64::from)))),
            Rotate { angle, axis } => match transform::rotate(angle, axis) {
                Some(m) => self.concat(m),
                None => self.diagnostics.error(span, &name, "the axis is zero"),
            },
            Scale(s) => self.concat(DMat4::from_scale(DVec3::from(s.map(f64::from)))),
            Skew(a) => match transform::skew(&a) {
                Ok(m) => self.concat(m),
                Err(e) => self.diagnostics.error(span, &name, e),
            },
            CoordinateSystem(n) => {
                self.coordinate_systems.insert(n, self.ctm);
            }
            CoordSysTransform(n) => match self.named_space(&n) {
                Some(m) => (self.ctm, self.ctm_motion) = (m, None),
                None => self.diagnostics.error(
                    span,
                    &name,
                    format!("unknown coordinate system \"{n}\""),
                ),
            },
            other => {
                self.diagnostics
                    .error(span, other.name(), "request not handled here (internal)")
            }
        }
    }

    fn named_space(&self, name: &str) -> Option<DMat4> {
        match name {
            "camera" => Some(DMat4::IDENTITY),
            "current" | "object" => Some(self.ctm),
            "world" => self.camera_from_world.or(Some(DMat4::IDENTITY)),
            n => self.coordinate_systems.get(n).copied(),
        }
    }

    fn light(&mut self, name: String, handle: Handle, params: ParamList, area: bool, span: &Span) {
        let shader = (*self.shader(name, params, span)).clone();
        let light = Light {
            handle: handle.clone(),
            shader,
            area,
            shadows: self.attributes.light_shadows,
            samples: self.attributes.light_samples,
        };
        let index = match self.lights.iter().position(|l| l.handle == handle) {
            Some(i) => {
                self.lights[i] = light;
                i
            }
            None => {
                self.lights.push(light);
                self.lights.len() - 1
            }
        };
        let a = self.attrs();
        a.lights.retain(|&l| l != index);
        a.lights.push(index);
        if area {
            a.area_light = Some(index);
        }
    }

    fn user_attribute(&mut self, name: &str, params: &ParamList, span: &Span) {
        for p in paramlist::names(params)
            .map(str::to_string)
            .collect::<Vec<_>>()
        {
            let f = paramlist::float(params, &p);
            match (name, p.as_str()) {
                ("identifier", "name") => {
                    self.attrs().identifier = paramlist::string(params, "name")
                }
                ("displacementbound", "sphere") if f.is_some() => {
                    // The bound is given in "coordinatesystem" (object by default): scale it
                    // by the largest axis stretch of that space into camera space.
                    let space = paramlist::string(params, "coordinatesystem")
                        .unwrap_or_else(|| "object".to_string());
                    // "shader": the space the current Displacement was declared in.
                    let shader = self.attributes.displacement.as_ref();
                    let m = match space.as_str() {
                        "shader" => Some(shader.map_or(self.ctm, |s| s.camera_from_shader)),
                        s => self.named_space(s),
                    };
                    let m = m.unwrap_or_else(|| {
                        self.diagnostics.warn(
                            span,
                            "Attribute",
                            format!(
                                "\"displacementbound\": unknown coordinatesystem \"{space}\"; using object space"
                            ),
                        );
                        self.ctm
                    });
                    let stretch = [m.x_axis, m.y_axis, m.z_axis]
                        .iter()
                        .map(|a| a.truncate().length())
                        .fold(0.0, f64::max);
                    self.attrs().displacement_bound =
                        (f64::from(f.unwrap_or(0.0)) * stretch) as f32;
                }
                ("displacementbound", "coordinatesystem") => {}
                ("dice", "binary") => self.attrs().dice_binary = f.unwrap_or(0.0) != 0.0,
                ("light", "shadows") => match on_off(params, &p) {
                    Some(on) => self.attrs().light_shadows = on,
                    None => self.diagnostics.error(
                        span,
                        "Attribute",
                        "\"light\" \"shadows\": expected \"on\" or \"off\"",
                    ),
                },
                ("light", "nsamples") => match f {
                    Some(n) if n >= 1.0 && n.is_finite() => {
                        self.attrs().light_samples = (n as u32).min(4096)
                    }
                    _ => self.diagnostics.error(
                        span,
                        "Attribute",
                        "\"light\" \"nsamples\": expected a positive count",
                    ),
                },
                ("visibility", "transmission") | ("render", "casts_shadows") => {
                    match casts_shadows(params, &p) {
                        Some(c) => self.attrs().casts_shadows = c,
                        None => self.diagnostics.error(
                            span,
                            "Attribute",
                            format!(
                                "\"{name}\" \"{p}\": expected \"opaque\", \"Os\", \"shader\", \"transparent\", \"none\" or 0/1"
                            ),
                        ),
                    }
                }
                (_, p) => self.diagnostics.warn(
                    span,
                    "Attribute",
                    format!("\"{name}\" \"{p}\" not supported (ignored)"),
                ),
            }
        }
    }

    // ---- solids --------------------------------------------------------------------------

    /// Opens a CSG node under the innermost open solid. The caller pushes the block, so
    /// `SolidEnd` and block recovery pop `open_solids` in step with the block stack.
    fn solid_begin(&mut self, op: &str, span: &Span) {
        let op = SolidOp::from_token(op).unwrap_or_else(|| {
            self.diagnostics.error(
                span,
                "SolidBegin",
                format!("unknown operation `{op}` (treated as \"union\")"),
            );
            SolidOp::Union
        });
        let parent = self.open_solids.last().copied();
        let node = match parent {
            Some(p) if self.is_primitive_solid(p) => {
                self.diagnostics.warn(
                    span,
                    "SolidBegin",
                    "a primitive solid can not contain solids: this block's surfaces join the enclosing primitive solid",
                );
                p
            }
            _ => self.solids.add(op, parent),
        };
        self.open_solids.push(node);
    }

    /// The primitive solid the next geometry bounds: the open primitive solid, or, for a
    /// surface directly inside a union/intersection/difference, a primitive solid of its own.
    fn solid_leaf(&mut self) -> Option<u32> {
        let top = *self.open_solids.last()?;
        Some(if self.is_primitive_solid(top) {
            top
        } else {
            self.solids.add(SolidOp::Primitive, Some(top))
        })
    }

    fn is_primitive_solid(&self, node: u32) -> bool {
        self.solids
            .nodes
            .get(node as usize)
            .is_some_and(|n| n.op == SolidOp::Primitive)
    }

    // ---- geometry ------------------------------------------------------------------------

    fn geometry(&mut self, req: &Request, span: &Span) {
        if !self.in_world() {
            self.diagnostics.error(
                span,
                req.name(),
                "geometry is only valid inside WorldBegin/WorldEnd (ignored)",
            );
            return;
        }
        if !self.world_active || !self.detail_visible() {
            return;
        }
        if let Some(m) = &self.motion {
            // One key of a deforming primitive, built under the transform at its time.
            let ctm = match (m.times.get(m.geometry.len()), &self.ctm_motion) {
                (Some(&t), Some(mm)) => mm.at(t),
                _ => self.ctm,
            };
            let prims = self.build_geometry(req, span, ctm).unwrap_or_default();
            let m = self.motion.as_mut().expect("checked above");
            m.first
                .get_or_insert((span.clone(), req.name().to_string()));
            m.geometry.push(prims);
            return;
        }
        match self.ctm_motion.clone() {
            None => {
                let prims = self.build_geometry(req, span, self.ctm).unwrap_or_default();
                self.push_primitives(vec![0.0], vec![prims], span, req.name());
            }
            Some(mm) => {
                // A moving transform (or camera): the primitive is built at every key.
                let mut keys = Vec::new();
                for m in &mm.mats {
                    match self.build_geometry(req, span, *m) {
                        Some(p) => keys.push(p),
                        None => return,
                    }
                }
                self.push_primitives(mm.times.clone(), keys, span, req.name());
            }
        }
    }

    /// Builds a geometry request under `camera_from_object`; `None` (reported) when it fails.
    fn build_geometry(
        &mut self,
        req: &Request,
        span: &Span,
        camera_from_object: DMat4,
    ) -> Option<Vec<Box<dyn illume_geom::Primitive>>> {
        let decls = &self.declarations;
        let lookup = |n: &str| decls.get(n);
        let a = &self.attributes;
        let mut blobby_warnings = Vec::new();
        let ctx = BuildContext {
            camera_from_object,
            declarations: &lookup,
            basis: a.basis,
            texture_coordinates: a.texture_coordinates,
            trim_curves: a.trim_curves.clone(),
        };
        let built = match req {
            Request::Blobby {
                nleaf,
                code,
                floats,
                strings,
                params,
            } => {
                let args = illume_geom::blobby::BlobbyArgs {
                    nleaf: *nleaf,
                    code,
                    floats,
                    strings,
                };
                let rate = f64::from(a.shading_rate);
                let cells_for = |b: [f32; 6]| {
                    let extent = self
                        .raster_bound(&b, camera_from_object)
                        .map(|r| (r[1] - r[0]).max(r[3] - r[2]));
                    illume_geom::blobby::cells_for_raster_size(extent, rate)
                };
                illume_geom::blobby::build_blobby(&args, params, &ctx, &cells_for).map(
                    |(prims, warnings)| {
                        blobby_warnings = warnings;
                        prims
                    },
                )
            }
            _ => illume_geom::build(req, &ctx),
        };
        for w in blobby_warnings {
            self.diagnostics.warn(span, req.name(), w);
        }
        match built {
            Ok(prims) => Some(prims),
            Err(GeomError::Unsupported(what)) => {
                self.diagnostics.warn(
                    span,
                    req.name(),
                    format!("{what} not supported yet (skipped)"),
                );
                None
            }
            Err(GeomError::Invalid { message, .. }) => {
                self.diagnostics.error(span, req.name(), message);
                None
            }
        }
    }

    /// Adds the primitives of one request: `keys[k]` is what it built at `times[k]`. Keys of
    /// different topology (another primitive count) can not be interpolated: an error, and the
    /// first key is used.
    fn push_primitives(
        &mut self,
        times: Vec<f64>,
        keys: Vec<Vec<Box<dyn illume_geom::Primitive>>>,
        span: &Span,
        name: &str,
    ) {
        let mut keys = keys.into_iter();
        let Some(first) = keys.next() else { return };
        let mut later: Vec<Vec<Box<dyn illume_geom::Primitive>>> = keys.collect();
        if later.iter().any(|k| k.len() != first.len()) {
            self.diagnostics.error(
                span,
                name,
                "the motion keys differ in topology (not interpolated: the first key is used)",
            );
            later.clear();
        }
        let mut later: Vec<_> = later.into_iter().map(Vec::into_iter).collect();
        let solid = self.solid_leaf();
        for p in first {
            let motion = (!later.is_empty()).then(|| MotionKeys {
                times: times.iter().map(|&t| t as f32).collect(),
                later: later
                    .iter_mut()
                    .map(|k| k.next().expect("same length checked"))
                    .collect(),
            });
            self.primitives.push(FramePrimitive {
                primitive: p,
                attributes: self.attributes.clone(),
                span: span.clone(),
                solid,
                motion,
            });
        }
    }

    // ---- motion blocks ---------------------------------------------------------------------

    fn motion_begin(&mut self, times: Vec<f32>, span: &Span) {
        self.push_block(BlockKind::Motion, span);
        if self.motion.is_some() {
            self.diagnostics.error(
                span,
                "MotionBegin",
                "motion blocks can not nest (its requests apply as if outside it)",
            );
            return;
        }
        let sorted = times.windows(2).all(|w| w[0] <= w[1]);
        if times.is_empty() || !sorted || times.iter().any(|t| !t.is_finite()) {
            self.diagnostics.error(
                span,
                "MotionBegin",
                "expected one or more increasing times (its requests apply as if outside it)",
            );
            return;
        }
        self.motion = Some(OpenMotion {
            times: times.iter().map(|&t| f64::from(t)).collect(),
            base: (self.ctm, self.ctm_motion.clone()),
            transforms: Vec::new(),
            geometry: Vec::new(),
            first: None,
        });
    }

    /// The k-th transformation of a motion block: applied to the transform the block started
    /// from, kept for `MotionEnd`.
    fn motion_transform(&mut self, req: Request, span: &Span) {
        let Some(m) = self.motion.as_mut() else {
            return;
        };
        m.first
            .get_or_insert((span.clone(), req.name().to_string()));
        let (ctm, motion) = m.base.clone();
        self.ctm = ctm;
        self.ctm_motion = motion;
        self.attribute_or_transform(req, span);
        let result = (self.ctm, self.ctm_motion.take());
        let m = self.motion.as_mut().expect("checked above");
        m.transforms.push(result);
        (self.ctm, self.ctm_motion) = m.base.clone();
    }

    /// `MotionEnd`: the block's transformations become one moving transform, its primitives one
    /// moving primitive each.
    fn motion_end(&mut self, _span: &Span) {
        let Some(m) = self.motion.take() else { return };
        let n = m.times.len();
        let Some((span, name)) = m.first else { return };
        if !m.transforms.is_empty() && !m.geometry.is_empty() {
            self.diagnostics.error(
                &span,
                &name,
                "a motion block holds either transformations or primitives, not both (the first of each is used)",
            );
        }
        let count = m.transforms.len().max(m.geometry.len());
        if count != n && (m.geometry.is_empty() || m.transforms.is_empty()) {
            self.diagnostics.error(
                &span,
                &name,
                format!("MotionBegin gave {n} times but the block holds {count} requests (the first is used)"),
            );
        }
        let mut transforms = m.transforms;
        if transforms.len() == n && m.geometry.is_empty() {
            let at = |k: usize, t: f64| {
                let (c, mm): &(DMat4, Option<MovingTransform>) = &transforms[k];
                mm.as_ref().map_or(*c, |mm| mm.at(t))
            };
            let mut times = m.times.clone();
            for (_, mm) in &transforms {
                times.extend(mm.iter().flat_map(|mm| mm.times.iter().copied()));
            }
            let moving = MovingTransform::sampled(times, |t| {
                let (k, w) = segment(&m.times, t);
                if n == 1 {
                    at(0, t)
                } else {
                    at(k, t) * (1.0 - w) + at(k + 1, t) * w
                }
            });
            self.ctm = moving.mats[0];
            // Keys that all agree (motion blocks that cancel, as in Aqsis' transmb_test) are
            // no motion: the primitives stay on the hider's fast path.
            let moves = moving.mats.iter().any(|m| *m != moving.mats[0]);
            self.ctm_motion = moves.then_some(moving);
        } else if !transforms.is_empty() {
            (self.ctm, self.ctm_motion) = transforms.swap_remove(0);
        }
        let mut geometry = m.geometry;
        if geometry.len() == n && transforms.is_empty() {
            self.push_primitives(m.times, geometry, &span, &name);
        } else if !geometry.is_empty() {
            let first = geometry.swap_remove(0);
            self.push_primitives(vec![0.0], vec![first], &span, &name);
        }
    }

    /// Raster-space bound of an object-space box, for level of detail and delayed archives;
    /// `None` when the box reaches behind the eye (treated as "large and on screen").
    fn raster_bound(&self, b: &[f32; 6], camera_from_object: DMat4) -> Option<[f64; 4]> {
        let cam = self.camera.as_ref()?;
        let mut r = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for i in 0..8 {
            let p = DVec3::new(
                b[i & 1].into(),
                b[2 + ((i >> 1) & 1)].into(),
                b[4 + ((i >> 2) & 1)].into(),
            );
            let c = camera_from_object.transform_point3(p);
            if cam.is_perspective() && c.z <= cam.near {
                return None;
            }
            let q = cam.raster_from_camera(c)?;
            r = [r[0].min(q.x), r[1].max(q.x), r[2].min(q.y), r[3].max(q.y)];
        }
        Some(r)
    }

    /// `DetailRange` (RI Spec 3.2 §4.2.9) as a hard switch: the primitive is drawn when the
    /// raster area of the `Detail` bound lies in `[minvisible, maxvisible)`.
    fn detail_visible(&self) -> bool {
        let (Some((bound, m)), Some(range)) =
            (self.attributes.detail, self.attributes.detail_range)
        else {
            return true;
        };
        let area = match self.raster_bound(&bound, m) {
            Some(r) => (r[1] - r[0]) * (r[3] - r[2]),
            None => f64::INFINITY,
        };
        area >= f64::from(range[0]) && area < f64::from(range[3])
    }

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

fn is_option(r: &Request) -> bool {
    use Request::*;
    matches!(
        r,
        Format { .. }
            | FrameAspectRatio(_)
            | ScreenWindow { .. }
            | CropWindow { .. }
            | Projection { .. }
            | Clipping { .. }
            | ClippingPlane { .. }
            | DepthOfField { .. }
            | Shutter { .. }
            | PixelVariance(_)
            | PixelSamples { .. }
            | PixelFilter { .. }
            | Exposure { .. }
            | Imager { .. }
            | Quantize { .. }
            | Display { .. }
            | Hider { .. }
            | ColorSamples { .. }
            | RelativeDetail(_)
            | Option { .. }
    )
}

/// The transformation requests a motion block may hold.
fn is_transform(r: &Request) -> bool {
    use Request::*;
    matches!(
        r,
        Identity
            | Transform(_)
            | ConcatTransform(_)
            | Perspective(_)
            | Translate(_)
            | Rotate { .. }
            | Scale(_)
            | Skew(_)
            | CoordSysTransform(_)
    )
}

fn is_geometry(r: &Request) -> bool {
    use Request::*;
    matches!(
        r,
        Polygon { .. }
            | GeneralPolygon { .. }
            | PointsPolygons { .. }
            | PointsGeneralPolygons { .. }
            | Patch { .. }
            | PatchMesh { .. }
            | NuPatch { .. }
            | Sphere { .. }
            | Cone { .. }
            | Cylinder { .. }
            | Hyperboloid { .. }
            | Paraboloid { .. }
            | Disk { .. }
            | Torus { .. }
            | Points { .. }
            | Curves { .. }
            | SubdivisionMesh { .. }
            | Blobby { .. }
            | Geometry { .. }
    )
}

/// The named bases of RI Spec 3.2 §5.2.1 (row order) with their default steps ignored here;
/// `Basis` carries explicit steps.
fn basis_matrix(b: &BasisSpec) -> Option<[f32; 16]> {
    let s = 1.0 / 6.0;
    Some(match b {
        BasisSpec::Matrix(m) => *m,
        BasisSpec::Named(n) => match n.as_str() {
            "bezier" => crate::attributes::BEZIER,
            "b-spline" | "bspline" => [
                -s,
                3.0 * s,
                -3.0 * s,
                s,
                3.0 * s,
                -6.0 * s,
                3.0 * s,
                0.0,
                -3.0 * s,
                0.0,
                3.0 * s,
                0.0,
                s,
                4.0 * s,
                s,
                0.0,
            ],
            "catmull-rom" | "catmullrom" => [
                -0.5, 1.5, -1.5, 0.5, 1.0, -2.5, 2.0, -0.5, -0.5, 0.0, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0,
            ],
            "hermite" => [
                2.0, 1.0, -2.0, 1.0, -3.0, -2.0, 3.0, -1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0,
            ],
            "power" => [
                1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
            ],
            _ => return None,
        },
    })
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

/// `"on"`/`"off"` (or 1/0) for `Attribute "light" "shadows"`.
fn on_off(params: &ParamList, name: &str) -> Option<bool> {
    if let Some(s) = paramlist::string(params, name) {
        return match s.as_str() {
            "on" => Some(true),
            "off" => Some(false),
            _ => None,
        };
    }
    paramlist::float(params, name).map(|f| f != 0.0)
}

/// Whether geometry casts shadows under BMRT's `"visibility" "transmission"` /
/// `"render" "casts_shadows"` values (or PRMan's integer `transmission`). "Os" and "shader"
/// (partial transmission) are treated as opaque: shadow rays do not run shaders here.
fn casts_shadows(params: &ParamList, name: &str) -> Option<bool> {
    if let Some(s) = paramlist::string(params, name) {
        return match s.as_str() {
            "opaque" | "Os" | "shader" | "shade" => Some(true),
            "transparent" | "none" => Some(false),
            _ => None,
        };
    }
    paramlist::float(params, name).map(|f| f != 0.0)
}
