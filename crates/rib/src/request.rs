//! The typed RIB request stream: one variant per request of the RI Specification 3.2.
//!
//! Requests keep what the file said, not what it means: parameter names stay as written
//! (`"uniform float Ks"`), numbers stay `f32`/`i32`, handles stay numbers or strings. Resolving
//! declarations, defaults and graphics state is `illume-ri`'s job. Positional arguments the spec
//! types as `RtFloat` are `f32`; where the spec allows an array in place of scalars (e.g.
//! `Color [r g b]`, `Transform [16]`), the parser accepts both and fills the same variant.
//!
//! Conventions for future additions: a variant is named after the request exactly as RIB spells
//! it; `params: ParamList` is always the last field.

/// A parameter value as read: RIB arrays are homogeneous, a bare scalar is a one-element array.
/// An array with only integer literals is `Ints`; the consumer widens it to floats when the
/// declaration says `float`/`point`/… (ASCII RIB cannot tell `1` from `1.0` by type).
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Ints(Vec<i32>),
    Floats(Vec<f32>),
    Strings(Vec<String>),
}

impl Value {
    /// The numbers as floats (ints widened); `None` for strings.
    pub fn as_floats(&self) -> Option<Vec<f32>> {
        match self {
            Value::Ints(v) => Some(v.iter().map(|&i| i as f32).collect()),
            Value::Floats(v) => Some(v.clone()),
            Value::Strings(_) => None,
        }
    }

    /// Number of elements (scalars or strings).
    pub fn len(&self) -> usize {
        match self {
            Value::Ints(v) => v.len(),
            Value::Floats(v) => v.len(),
            Value::Strings(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One `"name" value` pair of a parameter list. `name` is the token as written, possibly with
/// an inline declaration (`"varying color Cs"`); see [`crate::Declaration::split_inline`].
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub name: String,
    pub value: Value,
}

pub type ParamList = Vec<Param>;

/// Light and object handles: RIB 3.2 uses integer sequence numbers; RIB 3.3/PRMan files also
/// use strings. A re-used handle replaces the old light (PRMan behaviour).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Handle {
    Int(i32),
    Str(String),
}

/// `Basis` takes a predefined basis name or an explicit 4×4 matrix.
#[derive(Clone, Debug, PartialEq)]
pub enum BasisSpec {
    /// `bezier`, `b-spline`, `catmull-rom`, `hermite`, `power` (unknown names are kept for `ri`
    /// to report).
    Named(String),
    Matrix([f32; 16]),
}

/// Every RIB request of RI Specification 3.2 (plus the metadata RIB carries).
#[derive(Clone, Debug, PartialEq)]
pub enum Request {
    // ---- metadata and stream control --------------------------------------------------
    /// A `##` structural comment (`##RenderMan RIB`, `##Include file`, `##Frames 5`), text after `##`.
    StructureComment(String),
    /// `version 3.03`
    Version(f32),
    Declare {
        name: String,
        declaration: String,
    },
    ErrorHandler(String),
    /// A request name the parser does not know (vendor extension); its arguments were skipped.
    /// Reported as a warning by the parser; kept so `catrib` can pass it through.
    Unknown {
        name: String,
        args: Vec<Value>,
    },

    // ---- blocks -------------------------------------------------------------------------
    FrameBegin(i32),
    FrameEnd,
    WorldBegin,
    WorldEnd,
    AttributeBegin,
    AttributeEnd,
    TransformBegin,
    TransformEnd,
    SolidBegin(String),
    SolidEnd,
    ObjectBegin(Handle),
    ObjectEnd,
    ObjectInstance(Handle),
    MotionBegin(Vec<f32>),
    MotionEnd,
    ArchiveBegin {
        name: String,
        params: ParamList,
    },
    ArchiveEnd,
    ReadArchive {
        name: String,
        params: ParamList,
    },

    // ---- options ------------------------------------------------------------------------
    Format {
        xres: i32,
        yres: i32,
        pixel_aspect: f32,
    },
    FrameAspectRatio(f32),
    ScreenWindow {
        left: f32,
        right: f32,
        bottom: f32,
        top: f32,
    },
    CropWindow {
        xmin: f32,
        xmax: f32,
        ymin: f32,
        ymax: f32,
    },
    Projection {
        name: String,
        params: ParamList,
    },
    Clipping {
        near: f32,
        far: f32,
    },
    ClippingPlane {
        x: f32,
        y: f32,
        z: f32,
        nx: f32,
        ny: f32,
        nz: f32,
    },
    DepthOfField {
        fstop: f32,
        focal_length: f32,
        focal_distance: f32,
    },
    Shutter {
        open: f32,
        close: f32,
    },
    PixelVariance(f32),
    PixelSamples {
        x: f32,
        y: f32,
    },
    PixelFilter {
        name: String,
        xwidth: f32,
        ywidth: f32,
    },
    Exposure {
        gain: f32,
        gamma: f32,
    },
    Imager {
        name: String,
        params: ParamList,
    },
    Quantize {
        kind: String,
        one: i32,
        min: i32,
        max: i32,
        dither: f32,
    },
    Display {
        name: String,
        kind: String,
        mode: String,
        params: ParamList,
    },
    Hider {
        name: String,
        params: ParamList,
    },
    /// PRMan's `DisplayChannel "color __diffuse" "filter" "box" …`: declares an output channel
    /// (type and name in `name`) that displays may name in their mode.
    DisplayChannel {
        name: String,
        params: ParamList,
    },
    ColorSamples {
        n_rgb: Vec<f32>,
        rgb_n: Vec<f32>,
    },
    RelativeDetail(f32),
    Option {
        name: String,
        params: ParamList,
    },

    // ---- attributes ---------------------------------------------------------------------
    Attribute {
        name: String,
        params: ParamList,
    },
    /// `Color r g b` (or `[r g b]`); more values when `ColorSamples` says so.
    Color(Vec<f32>),
    Opacity(Vec<f32>),
    TextureCoordinates([f32; 8]),
    LightSource {
        name: String,
        handle: Handle,
        params: ParamList,
    },
    AreaLightSource {
        name: String,
        handle: Handle,
        params: ParamList,
    },
    Illuminate {
        handle: Handle,
        on: bool,
    },
    Surface {
        name: String,
        params: ParamList,
    },
    Displacement {
        name: String,
        params: ParamList,
    },
    Atmosphere {
        name: String,
        params: ParamList,
    },
    Interior {
        name: String,
        params: ParamList,
    },
    Exterior {
        name: String,
        params: ParamList,
    },
    Deformation {
        name: String,
        params: ParamList,
    },
    ShadingRate(f32),
    ShadingInterpolation(String),
    Matte(bool),
    Bound([f32; 6]),
    Detail([f32; 6]),
    DetailRange([f32; 4]),
    GeometricApproximation {
        kind: String,
        value: f32,
    },
    GeometricRepresentation(String),
    Orientation(String),
    ReverseOrientation,
    Sides(i32),

    // ---- transformations ----------------------------------------------------------------
    Identity,
    /// 16 numbers in RIB (row-vector) order.
    Transform([f32; 16]),
    ConcatTransform([f32; 16]),
    Perspective(f32),
    Translate([f32; 3]),
    Rotate {
        angle: f32,
        axis: [f32; 3],
    },
    Scale([f32; 3]),
    /// angle, dx1 dy1 dz1, dx2 dy2 dz2
    Skew([f32; 7]),
    CoordinateSystem(String),
    CoordSysTransform(String),

    // ---- geometry -----------------------------------------------------------------------
    Polygon {
        params: ParamList,
    },
    GeneralPolygon {
        nverts: Vec<i32>,
        params: ParamList,
    },
    PointsPolygons {
        nverts: Vec<i32>,
        verts: Vec<i32>,
        params: ParamList,
    },
    PointsGeneralPolygons {
        nloops: Vec<i32>,
        nverts: Vec<i32>,
        verts: Vec<i32>,
        params: ParamList,
    },
    Basis {
        ubasis: BasisSpec,
        ustep: i32,
        vbasis: BasisSpec,
        vstep: i32,
    },
    /// `Patch "bilinear"|"bicubic" ...`
    Patch {
        kind: String,
        params: ParamList,
    },
    PatchMesh {
        kind: String,
        nu: i32,
        uwrap: String,
        nv: i32,
        vwrap: String,
        params: ParamList,
    },
    NuPatch {
        nu: i32,
        uorder: i32,
        uknot: Vec<f32>,
        umin: f32,
        umax: f32,
        nv: i32,
        vorder: i32,
        vknot: Vec<f32>,
        vmin: f32,
        vmax: f32,
        params: ParamList,
    },
    TrimCurve {
        ncurves: Vec<i32>,
        order: Vec<i32>,
        knot: Vec<f32>,
        min: Vec<f32>,
        max: Vec<f32>,
        n: Vec<i32>,
        u: Vec<f32>,
        v: Vec<f32>,
        w: Vec<f32>,
    },
    Sphere {
        radius: f32,
        zmin: f32,
        zmax: f32,
        thetamax: f32,
        params: ParamList,
    },
    Cone {
        height: f32,
        radius: f32,
        thetamax: f32,
        params: ParamList,
    },
    Cylinder {
        radius: f32,
        zmin: f32,
        zmax: f32,
        thetamax: f32,
        params: ParamList,
    },
    Hyperboloid {
        point1: [f32; 3],
        point2: [f32; 3],
        thetamax: f32,
        params: ParamList,
    },
    Paraboloid {
        rmax: f32,
        zmin: f32,
        zmax: f32,
        thetamax: f32,
        params: ParamList,
    },
    Disk {
        height: f32,
        radius: f32,
        thetamax: f32,
        params: ParamList,
    },
    Torus {
        major_radius: f32,
        minor_radius: f32,
        phimin: f32,
        phimax: f32,
        thetamax: f32,
        params: ParamList,
    },
    Points {
        params: ParamList,
    },
    Curves {
        kind: String,
        nvertices: Vec<i32>,
        wrap: String,
        params: ParamList,
    },
    SubdivisionMesh {
        scheme: String,
        nvertices: Vec<i32>,
        vertices: Vec<i32>,
        tags: Vec<String>,
        nargs: Vec<i32>,
        intargs: Vec<i32>,
        floatargs: Vec<f32>,
        params: ParamList,
    },
    Blobby {
        nleaf: i32,
        code: Vec<i32>,
        floats: Vec<f32>,
        strings: Vec<String>,
        params: ParamList,
    },
    /// `Procedural "DelayedReadArchive" ["file"] [bound]`, `"RunProgram" ["prog" "args"]`, …
    Procedural {
        name: String,
        args: Vec<String>,
        bound: [f32; 6],
    },
    /// `Geometry "teapot"`
    Geometry {
        kind: String,
        params: ParamList,
    },

    // ---- texture-making -----------------------------------------------------------------
    MakeTexture {
        picture: String,
        texture: String,
        swrap: String,
        twrap: String,
        filter: String,
        swidth: f32,
        twidth: f32,
        params: ParamList,
    },
    MakeBump {
        picture: String,
        texture: String,
        swrap: String,
        twrap: String,
        filter: String,
        swidth: f32,
        twidth: f32,
        params: ParamList,
    },
    MakeLatLongEnvironment {
        picture: String,
        texture: String,
        filter: String,
        swidth: f32,
        twidth: f32,
        params: ParamList,
    },
    MakeCubeFaceEnvironment {
        /// px, nx, py, ny, pz, nz
        faces: [String; 6],
        texture: String,
        fov: f32,
        filter: String,
        swidth: f32,
        twidth: f32,
        params: ParamList,
    },
    MakeShadow {
        picture: String,
        texture: String,
        params: ParamList,
    },
}

impl Request {
    /// The request's name as RIB spells it (`"Sphere"`, `"MakeCubeFaceEnvironment"`).
    pub fn name(&self) -> &str {
        use Request::*;
        match self {
            StructureComment(_) => "##",
            Version(_) => "version",
            Declare { .. } => "Declare",
            ErrorHandler(_) => "ErrorHandler",
            Unknown { name, .. } => name,
            FrameBegin(_) => "FrameBegin",
            FrameEnd => "FrameEnd",
            WorldBegin => "WorldBegin",
            WorldEnd => "WorldEnd",
            AttributeBegin => "AttributeBegin",
            AttributeEnd => "AttributeEnd",
            TransformBegin => "TransformBegin",
            TransformEnd => "TransformEnd",
            SolidBegin(_) => "SolidBegin",
            SolidEnd => "SolidEnd",
            ObjectBegin(_) => "ObjectBegin",
            ObjectEnd => "ObjectEnd",
            ObjectInstance(_) => "ObjectInstance",
            MotionBegin(_) => "MotionBegin",
            MotionEnd => "MotionEnd",
            ArchiveBegin { .. } => "ArchiveBegin",
            ArchiveEnd => "ArchiveEnd",
            ReadArchive { .. } => "ReadArchive",
            Format { .. } => "Format",
            FrameAspectRatio(_) => "FrameAspectRatio",
            ScreenWindow { .. } => "ScreenWindow",
            CropWindow { .. } => "CropWindow",
            Projection { .. } => "Projection",
            Clipping { .. } => "Clipping",
            ClippingPlane { .. } => "ClippingPlane",
            DepthOfField { .. } => "DepthOfField",
            Shutter { .. } => "Shutter",
            PixelVariance(_) => "PixelVariance",
            PixelSamples { .. } => "PixelSamples",
            PixelFilter { .. } => "PixelFilter",
            Exposure { .. } => "Exposure",
            Imager { .. } => "Imager",
            Quantize { .. } => "Quantize",
            Display { .. } => "Display",
            Hider { .. } => "Hider",
            DisplayChannel { .. } => "DisplayChannel",
            ColorSamples { .. } => "ColorSamples",
            RelativeDetail(_) => "RelativeDetail",
            Option { .. } => "Option",
            Attribute { .. } => "Attribute",
            Color(_) => "Color",
            Opacity(_) => "Opacity",
            TextureCoordinates(_) => "TextureCoordinates",
            LightSource { .. } => "LightSource",
            AreaLightSource { .. } => "AreaLightSource",
            Illuminate { .. } => "Illuminate",
            Surface { .. } => "Surface",
            Displacement { .. } => "Displacement",
            Atmosphere { .. } => "Atmosphere",
            Interior { .. } => "Interior",
            Exterior { .. } => "Exterior",
            Deformation { .. } => "Deformation",
            ShadingRate(_) => "ShadingRate",
            ShadingInterpolation(_) => "ShadingInterpolation",
            Matte(_) => "Matte",
            Bound(_) => "Bound",
            Detail(_) => "Detail",
            DetailRange(_) => "DetailRange",
            GeometricApproximation { .. } => "GeometricApproximation",
            GeometricRepresentation(_) => "GeometricRepresentation",
            Orientation(_) => "Orientation",
            ReverseOrientation => "ReverseOrientation",
            Sides(_) => "Sides",
            Identity => "Identity",
            Transform(_) => "Transform",
            ConcatTransform(_) => "ConcatTransform",
            Perspective(_) => "Perspective",
            Translate(_) => "Translate",
            Rotate { .. } => "Rotate",
            Scale(_) => "Scale",
            Skew(_) => "Skew",
            CoordinateSystem(_) => "CoordinateSystem",
            CoordSysTransform(_) => "CoordSysTransform",
            Polygon { .. } => "Polygon",
            GeneralPolygon { .. } => "GeneralPolygon",
            PointsPolygons { .. } => "PointsPolygons",
            PointsGeneralPolygons { .. } => "PointsGeneralPolygons",
            Basis { .. } => "Basis",
            Patch { .. } => "Patch",
            PatchMesh { .. } => "PatchMesh",
            NuPatch { .. } => "NuPatch",
            TrimCurve { .. } => "TrimCurve",
            Sphere { .. } => "Sphere",
            Cone { .. } => "Cone",
            Cylinder { .. } => "Cylinder",
            Hyperboloid { .. } => "Hyperboloid",
            Paraboloid { .. } => "Paraboloid",
            Disk { .. } => "Disk",
            Torus { .. } => "Torus",
            Points { .. } => "Points",
            Curves { .. } => "Curves",
            SubdivisionMesh { .. } => "SubdivisionMesh",
            Blobby { .. } => "Blobby",
            Procedural { .. } => "Procedural",
            Geometry { .. } => "Geometry",
            MakeTexture { .. } => "MakeTexture",
            MakeBump { .. } => "MakeBump",
            MakeLatLongEnvironment { .. } => "MakeLatLongEnvironment",
            MakeCubeFaceEnvironment { .. } => "MakeCubeFaceEnvironment",
            MakeShadow { .. } => "MakeShadow",
        }
    }
}
