//! The argument signature of every request (RI Spec 3.2 chapter "RIB binding"), in both
//! directions: [`build`] turns the arguments read after a request name into a typed
//! [`Request`], and [`emit`] walks a `Request` back into arguments for the ASCII and binary
//! writers. Keeping both in one file keeps them each other's inverse.
//!
//! Leniency follows PRMan and real exporters: wherever the spec has N numbers, `N` scalars and
//! one `[N]` array are both accepted; where it has an array, a lone scalar is accepted; integral
//! floats are accepted for integers.
use crate::request::{BasisSpec, Handle, Param, ParamList, Request, Value};
use std::io;

/// One argument as read: a scalar or a bracketed (or binary) array.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Arg {
    Int(i32),
    Float(f32),
    Str(String),
    Array(Value),
}

impl Arg {
    fn describe(&self) -> String {
        match self {
            Arg::Int(i) => format!("number {i}"),
            Arg::Float(f) => format!("number {f}"),
            Arg::Str(s) => format!("string \"{}\"", s.escape_debug()),
            Arg::Array(Value::Strings(v)) => format!("array of {} strings", v.len()),
            Arg::Array(v) => format!("array of {} numbers", v.len()),
        }
    }

    fn number(&self) -> Option<f32> {
        match *self {
            Arg::Int(i) => Some(i as f32),
            Arg::Float(f) => Some(f),
            _ => None,
        }
    }

    /// The argument as a parameter value: a bare scalar is a one-element array.
    pub(crate) fn into_value(self) -> Value {
        match self {
            Arg::Int(i) => Value::Ints(vec![i]),
            Arg::Float(f) => Value::Floats(vec![f]),
            Arg::Str(s) => Value::Strings(vec![s]),
            Arg::Array(v) => v,
        }
    }
}

/// Why the arguments do not fit the request.
#[derive(Debug, PartialEq)]
pub(crate) enum SignatureError {
    /// Not a request of RI 3.2: the caller warns and keeps the arguments.
    Unknown(Vec<Arg>),
    Bad(String),
}

impl From<String> for SignatureError {
    fn from(s: String) -> Self {
        SignatureError::Bad(s)
    }
}

type Res<T> = Result<T, String>;

fn integral(f: f32) -> Option<i32> {
    (f.fract() == 0.0 && f.abs() <= i32::MAX as f32).then_some(f as i32)
}

/// A cursor over the arguments of one request.
struct Args {
    items: std::iter::Peekable<std::vec::IntoIter<Arg>>,
}

impl Args {
    fn found(&mut self) -> String {
        self.items
            .peek()
            .map_or_else(|| "end of request".to_string(), Arg::describe)
    }

    fn next_or(&mut self, expected: &str) -> Res<Arg> {
        match self.items.next() {
            Some(a) => Ok(a),
            None => Err(format!("expected {expected}, found end of request")),
        }
    }

    /// `N` numbers as `N` scalars or one `[N]` array.
    fn floats<const N: usize>(&mut self) -> Res<[f32; N]> {
        let mut out = [0f32; N];
        if let Some(Arg::Array(v)) = self.items.peek() {
            let found = v.len();
            let floats = v.as_floats().filter(|f| f.len() == N);
            return match floats {
                Some(f) => {
                    self.items.next();
                    out.copy_from_slice(&f);
                    Ok(out)
                }
                None if matches!(v, Value::Strings(_)) => Err(format!(
                    "expected {N} numbers, found array of {found} strings"
                )),
                None => Err(format!("expected {N} numbers, found array of {found}")),
            };
        }
        for (k, slot) in out.iter_mut().enumerate() {
            match self.items.peek().and_then(Arg::number) {
                Some(f) => {
                    *slot = f;
                    self.items.next();
                }
                None if N == 1 => return Err(format!("expected a number, found {}", self.found())),
                None => return Err(format!("expected {N} numbers, found {k}")),
            }
        }
        Ok(out)
    }

    fn float(&mut self) -> Res<f32> {
        Ok(self.floats::<1>()?[0])
    }

    fn int(&mut self) -> Res<i32> {
        let found = self.found();
        match self.items.peek() {
            Some(&Arg::Int(i)) => {
                self.items.next();
                Ok(i)
            }
            Some(&Arg::Float(f)) if integral(f).is_some() => {
                self.items.next();
                Ok(integral(f).unwrap_or_default())
            }
            _ => Err(format!("expected an integer, found {found}")),
        }
    }

    fn bool(&mut self) -> Res<bool> {
        Ok(self.int()? != 0)
    }

    fn string(&mut self) -> Res<String> {
        let found = self.found();
        match self.next_or("a string")? {
            Arg::Str(s) => Ok(s),
            Arg::Array(Value::Strings(mut v)) if v.len() == 1 => Ok(v.pop().unwrap_or_default()),
            _ => Err(format!("expected a string, found {found}")),
        }
    }

    fn handle(&mut self) -> Res<Handle> {
        let found = self.found();
        match self.next_or("a handle (number or string)")? {
            Arg::Int(i) => Ok(Handle::Int(i)),
            Arg::Float(f) if integral(f).is_some() => Ok(Handle::Int(integral(f).unwrap_or(0))),
            Arg::Str(s) => Ok(Handle::Str(s)),
            _ => Err(format!(
                "expected a handle (number or string), found {found}"
            )),
        }
    }

    fn int_array(&mut self) -> Res<Vec<i32>> {
        let found = self.found();
        let bad = || format!("expected an array of integers, found {found}");
        match self.next_or("an array of integers")? {
            Arg::Int(i) => Ok(vec![i]),
            Arg::Array(Value::Ints(v)) => Ok(v),
            Arg::Array(Value::Floats(v)) => {
                v.iter().map(|&f| integral(f).ok_or_else(bad)).collect()
            }
            _ => Err(bad()),
        }
    }

    fn float_array(&mut self) -> Res<Vec<f32>> {
        let found = self.found();
        match self.next_or("an array of numbers")? {
            Arg::Int(i) => Ok(vec![i as f32]),
            Arg::Float(f) => Ok(vec![f]),
            Arg::Array(Value::Floats(v)) => Ok(v),
            Arg::Array(Value::Ints(v)) => Ok(v.into_iter().map(|i| i as f32).collect()),
            _ => Err(format!("expected an array of numbers, found {found}")),
        }
    }

    fn string_array(&mut self) -> Res<Vec<String>> {
        let found = self.found();
        match self.next_or("an array of strings")? {
            Arg::Str(s) => Ok(vec![s]),
            Arg::Array(Value::Strings(v)) => Ok(v),
            Arg::Array(v) if v.is_empty() => Ok(Vec::new()),
            _ => Err(format!("expected an array of strings, found {found}")),
        }
    }

    /// Every number up to the parameter list, as one array or as scalars (`Color`, `MotionBegin`).
    fn float_list(&mut self) -> Res<Vec<f32>> {
        if let Some(Arg::Array(_)) = self.items.peek() {
            return self.float_array();
        }
        let mut out = Vec::new();
        while let Some(f) = self.items.peek().and_then(Arg::number) {
            out.push(f);
            self.items.next();
        }
        if out.is_empty() {
            return Err(format!("expected numbers, found {}", self.found()));
        }
        Ok(out)
    }

    fn basis(&mut self) -> Res<BasisSpec> {
        match self.items.peek() {
            Some(Arg::Str(_)) => Ok(BasisSpec::Named(self.string()?)),
            Some(Arg::Array(Value::Strings(_))) => Ok(BasisSpec::Named(self.string()?)),
            Some(Arg::Array(_)) => Ok(BasisSpec::Matrix(self.floats::<16>()?)),
            _ => Err(format!(
                "expected a basis name or 16 numbers, found {}",
                self.found()
            )),
        }
    }

    /// `"name" value` pairs to the end of the request.
    fn params(&mut self) -> Res<ParamList> {
        let mut out = Vec::new();
        while let Some(arg) = self.items.next() {
            let name = match arg {
                Arg::Str(s) => s,
                Arg::Array(Value::Strings(mut v)) if v.len() == 1 => v.pop().unwrap_or_default(),
                other => {
                    return Err(format!(
                        "expected a parameter name, found {}",
                        other.describe()
                    ))
                }
            };
            match self.items.next() {
                Some(v) => out.push(Param {
                    name,
                    value: v.into_value(),
                }),
                None => return Err(format!("parameter \"{name}\" has no value")),
            }
        }
        Ok(out)
    }

    fn end(&mut self) -> Res<()> {
        match self.items.next() {
            None => Ok(()),
            Some(a) => Err(format!("unexpected extra argument: {}", a.describe())),
        }
    }
}

/// Builds the typed request named `name` from its arguments.
pub(crate) fn build(name: &str, args: Vec<Arg>) -> Result<Request, SignatureError> {
    use Request as R;
    let mut a = Args {
        items: args.into_iter().peekable(),
    };
    let a = &mut a;
    macro_rules! named {
        ($v:ident) => {
            R::$v {
                name: a.string()?,
                params: a.params()?,
            }
        };
    }
    let req = match name {
        "version" => R::Version(a.float()?),
        "Declare" => R::Declare {
            name: a.string()?,
            declaration: a.string()?,
        },
        "ErrorHandler" => R::ErrorHandler(a.string()?),
        "FrameBegin" => R::FrameBegin(a.int()?),
        "FrameEnd" => R::FrameEnd,
        "WorldBegin" => R::WorldBegin,
        "WorldEnd" => R::WorldEnd,
        "AttributeBegin" => R::AttributeBegin,
        "AttributeEnd" => R::AttributeEnd,
        "TransformBegin" => R::TransformBegin,
        "TransformEnd" => R::TransformEnd,
        "SolidBegin" => R::SolidBegin(a.string()?),
        "SolidEnd" => R::SolidEnd,
        "ObjectBegin" => R::ObjectBegin(a.handle()?),
        "ObjectEnd" => R::ObjectEnd,
        "ObjectInstance" => R::ObjectInstance(a.handle()?),
        "MotionBegin" => R::MotionBegin(a.float_list()?),
        "MotionEnd" => R::MotionEnd,
        "ArchiveBegin" => named!(ArchiveBegin),
        "ArchiveEnd" => R::ArchiveEnd,
        "ReadArchive" => named!(ReadArchive),
        "Format" => R::Format {
            xres: a.int()?,
            yres: a.int()?,
            pixel_aspect: a.float()?,
        },
        "FrameAspectRatio" => R::FrameAspectRatio(a.float()?),
        "ScreenWindow" => {
            let [left, right, bottom, top] = a.floats()?;
            R::ScreenWindow {
                left,
                right,
                bottom,
                top,
            }
        }
        "CropWindow" => {
            let [xmin, xmax, ymin, ymax] = a.floats()?;
            R::CropWindow {
                xmin,
                xmax,
                ymin,
                ymax,
            }
        }
        "Projection" => named!(Projection),
        "Clipping" => {
            let [near, far] = a.floats()?;
            R::Clipping { near, far }
        }
        "ClippingPlane" => {
            let [x, y, z, nx, ny, nz] = a.floats()?;
            R::ClippingPlane {
                x,
                y,
                z,
                nx,
                ny,
                nz,
            }
        }
        // With no arguments DepthOfField turns depth of field off (a pinhole camera, RI 3.2
        // §4.1.3: an infinite fstop), as PRMan and Aqsis read it.
        "DepthOfField" if a.items.peek().is_none() => R::DepthOfField {
            fstop: f32::INFINITY,
            focal_length: 0.0,
            focal_distance: 0.0,
        },
        "DepthOfField" => {
            let [fstop, focal_length, focal_distance] = a.floats()?;
            R::DepthOfField {
                fstop,
                focal_length,
                focal_distance,
            }
        }
        "Shutter" => {
            let [open, close] = a.floats()?;
            R::Shutter { open, close }
        }
        "PixelVariance" => R::PixelVariance(a.float()?),
        "PixelSamples" => {
            let [x, y] = a.floats()?;
            R::PixelSamples { x, y }
        }
        "PixelFilter" => R::PixelFilter {
            name: a.string()?,
            xwidth: a.float()?,
            ywidth: a.float()?,
        },
        "Exposure" => {
            let [gain, gamma] = a.floats()?;
            R::Exposure { gain, gamma }
        }
        "Imager" => named!(Imager),
        "Quantize" => R::Quantize {
            kind: a.string()?,
            one: a.int()?,
            min: a.int()?,
            max: a.int()?,
            dither: a.float()?,
        },
        "Display" => R::Display {
            name: a.string()?,
            kind: a.string()?,
            mode: a.string()?,
            params: a.params()?,
        },
        "Hider" => named!(Hider),
        "ColorSamples" => R::ColorSamples {
            n_rgb: a.float_array()?,
            rgb_n: a.float_array()?,
        },
        "RelativeDetail" => R::RelativeDetail(a.float()?),
        "Option" => named!(Option),
        "Attribute" => named!(Attribute),
        "Color" => R::Color(a.float_list()?),
        "Opacity" => R::Opacity(a.float_list()?),
        "TextureCoordinates" => R::TextureCoordinates(a.floats()?),
        "LightSource" => R::LightSource {
            name: a.string()?,
            handle: a.handle()?,
            params: a.params()?,
        },
        "AreaLightSource" => R::AreaLightSource {
            name: a.string()?,
            handle: a.handle()?,
            params: a.params()?,
        },
        "Illuminate" => R::Illuminate {
            handle: a.handle()?,
            on: a.bool()?,
        },
        "Surface" => named!(Surface),
        "Displacement" => named!(Displacement),
        "Atmosphere" => named!(Atmosphere),
        "Interior" => named!(Interior),
        "Exterior" => named!(Exterior),
        "Deformation" => named!(Deformation),
        "ShadingRate" => R::ShadingRate(a.float()?),
        "ShadingInterpolation" => R::ShadingInterpolation(a.string()?),
        "Matte" => R::Matte(a.bool()?),
        "Bound" => R::Bound(a.floats()?),
        "Detail" => R::Detail(a.floats()?),
        "DetailRange" => R::DetailRange(a.floats()?),
        "GeometricApproximation" => R::GeometricApproximation {
            kind: a.string()?,
            value: a.float()?,
        },
        "GeometricRepresentation" => R::GeometricRepresentation(a.string()?),
        "Orientation" => R::Orientation(a.string()?),
        "ReverseOrientation" => R::ReverseOrientation,
        "Sides" => R::Sides(a.int()?),
        "Identity" => R::Identity,
        "Transform" => R::Transform(a.floats()?),
        "ConcatTransform" => R::ConcatTransform(a.floats()?),
        "Perspective" => R::Perspective(a.float()?),
        "Translate" => R::Translate(a.floats()?),
        "Rotate" => {
            let [angle, x, y, z] = a.floats()?;
            R::Rotate {
                angle,
                axis: [x, y, z],
            }
        }
        "Scale" => R::Scale(a.floats()?),
        "Skew" => R::Skew(a.floats()?),
        "CoordinateSystem" => R::CoordinateSystem(a.string()?),
        "CoordSysTransform" => R::CoordSysTransform(a.string()?),
        "Polygon" => R::Polygon {
            params: a.params()?,
        },
        "GeneralPolygon" => R::GeneralPolygon {
            nverts: a.int_array()?,
            params: a.params()?,
        },
        "PointsPolygons" => R::PointsPolygons {
            nverts: a.int_array()?,
            verts: a.int_array()?,
            params: a.params()?,
        },
        "PointsGeneralPolygons" => R::PointsGeneralPolygons {
            nloops: a.int_array()?,
            nverts: a.int_array()?,
            verts: a.int_array()?,
            params: a.params()?,
        },
        "Basis" => R::Basis {
            ubasis: a.basis()?,
            ustep: a.int()?,
            vbasis: a.basis()?,
            vstep: a.int()?,
        },
        "Patch" => R::Patch {
            kind: a.string()?,
            params: a.params()?,
        },
        "PatchMesh" => R::PatchMesh {
            kind: a.string()?,
            nu: a.int()?,
            uwrap: a.string()?,
            nv: a.int()?,
            vwrap: a.string()?,
            params: a.params()?,
        },
        "NuPatch" => R::NuPatch {
            nu: a.int()?,
            uorder: a.int()?,
            uknot: a.float_array()?,
            umin: a.float()?,
            umax: a.float()?,
            nv: a.int()?,
            vorder: a.int()?,
            vknot: a.float_array()?,
            vmin: a.float()?,
            vmax: a.float()?,
            params: a.params()?,
        },
        "TrimCurve" => R::TrimCurve {
            ncurves: a.int_array()?,
            order: a.int_array()?,
            knot: a.float_array()?,
            min: a.float_array()?,
            max: a.float_array()?,
            n: a.int_array()?,
            u: a.float_array()?,
            v: a.float_array()?,
            w: a.float_array()?,
        },
        "Sphere" => {
            let [radius, zmin, zmax, thetamax] = a.floats()?;
            R::Sphere {
                radius,
                zmin,
                zmax,
                thetamax,
                params: a.params()?,
            }
        }
        "Cone" => {
            let [height, radius, thetamax] = a.floats()?;
            R::Cone {
                height,
                radius,
                thetamax,
                params: a.params()?,
            }
        }
        "Cylinder" => {
            let [radius, zmin, zmax, thetamax] = a.floats()?;
            R::Cylinder {
                radius,
                zmin,
                zmax,
                thetamax,
                params: a.params()?,
            }
        }
        "Hyperboloid" => {
            let [x1, y1, z1, x2, y2, z2, thetamax] = a.floats()?;
            R::Hyperboloid {
                point1: [x1, y1, z1],
                point2: [x2, y2, z2],
                thetamax,
                params: a.params()?,
            }
        }
        "Paraboloid" => {
            let [rmax, zmin, zmax, thetamax] = a.floats()?;
            R::Paraboloid {
                rmax,
                zmin,
                zmax,
                thetamax,
                params: a.params()?,
            }
        }
        "Disk" => {
            let [height, radius, thetamax] = a.floats()?;
            R::Disk {
                height,
                radius,
                thetamax,
                params: a.params()?,
            }
        }
        "Torus" => {
            let [major_radius, minor_radius, phimin, phimax, thetamax] = a.floats()?;
            R::Torus {
                major_radius,
                minor_radius,
                phimin,
                phimax,
                thetamax,
                params: a.params()?,
            }
        }
        "Points" => R::Points {
            params: a.params()?,
        },
        "Curves" => R::Curves {
            kind: a.string()?,
            nvertices: a.int_array()?,
            wrap: a.string()?,
            params: a.params()?,
        },
        "SubdivisionMesh" => {
            let scheme = a.string()?;
            let nvertices = a.int_array()?;
            let vertices = a.int_array()?;
            // Tags are optional: the parameter list starts with a bare string, tags with `[`.
            let tagged = matches!(a.items.peek(), Some(Arg::Array(_)));
            let (tags, nargs, intargs, floatargs) = if tagged {
                (
                    a.string_array()?,
                    a.int_array()?,
                    a.int_array()?,
                    a.float_array()?,
                )
            } else {
                Default::default()
            };
            R::SubdivisionMesh {
                scheme,
                nvertices,
                vertices,
                tags,
                nargs,
                intargs,
                floatargs,
                params: a.params()?,
            }
        }
        "Blobby" => R::Blobby {
            nleaf: a.int()?,
            code: a.int_array()?,
            floats: a.float_array()?,
            strings: a.string_array()?,
            params: a.params()?,
        },
        "Procedural" => R::Procedural {
            name: a.string()?,
            args: a.string_array()?,
            bound: a.floats()?,
        },
        "Geometry" => R::Geometry {
            kind: a.string()?,
            params: a.params()?,
        },
        "MakeTexture" | "MakeBump" => {
            let (picture, texture, swrap, twrap, filter) = (
                a.string()?,
                a.string()?,
                a.string()?,
                a.string()?,
                a.string()?,
            );
            let [swidth, twidth] = a.floats()?;
            let params = a.params()?;
            if name == "MakeTexture" {
                R::MakeTexture {
                    picture,
                    texture,
                    swrap,
                    twrap,
                    filter,
                    swidth,
                    twidth,
                    params,
                }
            } else {
                R::MakeBump {
                    picture,
                    texture,
                    swrap,
                    twrap,
                    filter,
                    swidth,
                    twidth,
                    params,
                }
            }
        }
        "MakeLatLongEnvironment" => R::MakeLatLongEnvironment {
            picture: a.string()?,
            texture: a.string()?,
            filter: a.string()?,
            swidth: a.float()?,
            twidth: a.float()?,
            params: a.params()?,
        },
        "MakeCubeFaceEnvironment" => R::MakeCubeFaceEnvironment {
            faces: [
                a.string()?,
                a.string()?,
                a.string()?,
                a.string()?,
                a.string()?,
                a.string()?,
            ],
            texture: a.string()?,
            fov: a.float()?,
            filter: a.string()?,
            swidth: a.float()?,
            twidth: a.float()?,
            params: a.params()?,
        },
        "MakeShadow" => R::MakeShadow {
            picture: a.string()?,
            texture: a.string()?,
            params: a.params()?,
        },
        _ => return Err(SignatureError::Unknown(a.items.by_ref().collect())),
    };
    a.end()?;
    Ok(req)
}

/// Where [`emit`] sends a request: the ASCII printer and the binary writer.
pub(crate) trait Sink {
    fn name(&mut self, name: &str) -> io::Result<()>;
    fn int(&mut self, v: i32) -> io::Result<()>;
    fn float(&mut self, v: f32) -> io::Result<()>;
    fn string(&mut self, s: &str) -> io::Result<()>;
    fn ints(&mut self, v: &[i32]) -> io::Result<()>;
    fn floats(&mut self, v: &[f32]) -> io::Result<()>;
    fn strings(&mut self, v: &[String]) -> io::Result<()>;
    fn structure(&mut self, text: &str) -> io::Result<()>;
    /// After the last argument of a request.
    fn end(&mut self) -> io::Result<()>;

    fn value(&mut self, v: &Value) -> io::Result<()> {
        match v {
            Value::Ints(v) => self.ints(v),
            Value::Floats(v) => self.floats(v),
            Value::Strings(v) => self.strings(v),
        }
    }

    /// A float array whose type the signature fixes (`Color`, `Transform`, knots): unlike a
    /// parameter value it needs no float marker, so the ASCII printer may write `1` for `1.0`.
    fn number_array(&mut self, v: &[f32]) -> io::Result<()> {
        self.floats(v)
    }

    fn scalars(&mut self, v: &[f32]) -> io::Result<()> {
        v.iter().try_for_each(|&f| self.float(f))
    }

    fn handle(&mut self, h: &Handle) -> io::Result<()> {
        match h {
            Handle::Int(i) => self.int(*i),
            Handle::Str(s) => self.string(s),
        }
    }

    fn basis(&mut self, b: &BasisSpec) -> io::Result<()> {
        match b {
            BasisSpec::Named(n) => self.string(n),
            BasisSpec::Matrix(m) => self.number_array(m),
        }
    }

    fn params(&mut self, params: &[Param]) -> io::Result<()> {
        for p in params {
            self.string(&p.name)?;
            self.value(&p.value)?;
        }
        Ok(())
    }
}

/// Sends `req` to `s` in the argument order [`build`] reads back.
pub(crate) fn emit<S: Sink>(req: &Request, s: &mut S) -> io::Result<()> {
    use Request as R;
    if let R::StructureComment(text) = req {
        return s.structure(text);
    }
    s.name(req.name())?;
    match req {
        R::StructureComment(_) => {}
        R::Version(v) => s.float(*v)?,
        R::Declare { name, declaration } => {
            s.string(name)?;
            s.string(declaration)?;
        }
        R::ErrorHandler(n)
        | R::SolidBegin(n)
        | R::ShadingInterpolation(n)
        | R::GeometricRepresentation(n)
        | R::Orientation(n)
        | R::CoordinateSystem(n)
        | R::CoordSysTransform(n) => s.string(n)?,
        R::Unknown { args, .. } => args.iter().try_for_each(|v| s.value(v))?,
        R::FrameBegin(i) | R::Sides(i) => s.int(*i)?,
        R::FrameEnd
        | R::WorldBegin
        | R::WorldEnd
        | R::AttributeBegin
        | R::AttributeEnd
        | R::TransformBegin
        | R::TransformEnd
        | R::SolidEnd
        | R::ObjectEnd
        | R::MotionEnd
        | R::ArchiveEnd
        | R::ReverseOrientation
        | R::Identity => {}
        R::ObjectBegin(h) | R::ObjectInstance(h) => s.handle(h)?,
        R::MotionBegin(t) => s.number_array(t)?,
        R::ArchiveBegin { name, params }
        | R::ReadArchive { name, params }
        | R::Projection { name, params }
        | R::Imager { name, params }
        | R::Hider { name, params }
        | R::Option { name, params }
        | R::Attribute { name, params }
        | R::Surface { name, params }
        | R::Displacement { name, params }
        | R::Atmosphere { name, params }
        | R::Interior { name, params }
        | R::Exterior { name, params }
        | R::Deformation { name, params }
        | R::Patch { kind: name, params }
        | R::Geometry { kind: name, params } => {
            s.string(name)?;
            s.params(params)?;
        }
        R::Format {
            xres,
            yres,
            pixel_aspect,
        } => {
            s.int(*xres)?;
            s.int(*yres)?;
            s.float(*pixel_aspect)?;
        }
        R::FrameAspectRatio(v)
        | R::PixelVariance(v)
        | R::RelativeDetail(v)
        | R::ShadingRate(v)
        | R::Perspective(v) => s.float(*v)?,
        R::ScreenWindow {
            left,
            right,
            bottom,
            top,
        } => s.scalars(&[*left, *right, *bottom, *top])?,
        R::CropWindow {
            xmin,
            xmax,
            ymin,
            ymax,
        } => s.scalars(&[*xmin, *xmax, *ymin, *ymax])?,
        R::Clipping { near, far } => s.scalars(&[*near, *far])?,
        R::ClippingPlane {
            x,
            y,
            z,
            nx,
            ny,
            nz,
        } => s.scalars(&[*x, *y, *z, *nx, *ny, *nz])?,
        R::DepthOfField {
            fstop,
            focal_length,
            focal_distance,
        } if fstop.is_finite() => s.scalars(&[*fstop, *focal_length, *focal_distance])?,
        R::DepthOfField { .. } => {}
        R::Shutter { open, close } => s.scalars(&[*open, *close])?,
        R::PixelSamples { x, y } => s.scalars(&[*x, *y])?,
        R::PixelFilter {
            name,
            xwidth,
            ywidth,
        } => {
            s.string(name)?;
            s.scalars(&[*xwidth, *ywidth])?;
        }
        R::Exposure { gain, gamma } => s.scalars(&[*gain, *gamma])?,
        R::Quantize {
            kind,
            one,
            min,
            max,
            dither,
        } => {
            s.string(kind)?;
            s.int(*one)?;
            s.int(*min)?;
            s.int(*max)?;
            s.float(*dither)?;
        }
        R::Display {
            name,
            kind,
            mode,
            params,
        } => {
            s.string(name)?;
            s.string(kind)?;
            s.string(mode)?;
            s.params(params)?;
        }
        R::ColorSamples { n_rgb, rgb_n } => {
            s.number_array(n_rgb)?;
            s.number_array(rgb_n)?;
        }
        R::Color(c) | R::Opacity(c) => s.number_array(c)?,
        R::TextureCoordinates(st) => s.scalars(st)?,
        R::LightSource {
            name,
            handle,
            params,
        }
        | R::AreaLightSource {
            name,
            handle,
            params,
        } => {
            s.string(name)?;
            s.handle(handle)?;
            s.params(params)?;
        }
        R::Illuminate { handle, on } => {
            s.handle(handle)?;
            s.int(i32::from(*on))?;
        }
        R::Matte(m) => s.int(i32::from(*m))?,
        R::Bound(b) | R::Detail(b) => s.number_array(b)?,
        R::DetailRange(d) => s.scalars(d)?,
        R::GeometricApproximation { kind, value } => {
            s.string(kind)?;
            s.float(*value)?;
        }
        R::Transform(m) | R::ConcatTransform(m) => s.number_array(m)?,
        R::Translate(v) | R::Scale(v) => s.scalars(v)?,
        R::Rotate { angle, axis } => {
            s.float(*angle)?;
            s.scalars(axis)?;
        }
        R::Skew(v) => s.scalars(v)?,
        R::Polygon { params } | R::Points { params } => s.params(params)?,
        R::GeneralPolygon { nverts, params } => {
            s.ints(nverts)?;
            s.params(params)?;
        }
        R::PointsPolygons {
            nverts,
            verts,
            params,
        } => {
            s.ints(nverts)?;
            s.ints(verts)?;
            s.params(params)?;
        }
        R::PointsGeneralPolygons {
            nloops,
            nverts,
            verts,
            params,
        } => {
            s.ints(nloops)?;
            s.ints(nverts)?;
            s.ints(verts)?;
            s.params(params)?;
        }
        R::Basis {
            ubasis,
            ustep,
            vbasis,
            vstep,
        } => {
            s.basis(ubasis)?;
            s.int(*ustep)?;
            s.basis(vbasis)?;
            s.int(*vstep)?;
        }
        R::PatchMesh {
            kind,
            nu,
            uwrap,
            nv,
            vwrap,
            params,
        } => {
            s.string(kind)?;
            s.int(*nu)?;
            s.string(uwrap)?;
            s.int(*nv)?;
            s.string(vwrap)?;
            s.params(params)?;
        }
        R::NuPatch {
            nu,
            uorder,
            uknot,
            umin,
            umax,
            nv,
            vorder,
            vknot,
            vmin,
            vmax,
            params,
        } => {
            s.int(*nu)?;
            s.int(*uorder)?;
            s.number_array(uknot)?;
            s.scalars(&[*umin, *umax])?;
            s.int(*nv)?;
            s.int(*vorder)?;
            s.number_array(vknot)?;
            s.scalars(&[*vmin, *vmax])?;
            s.params(params)?;
        }
        R::TrimCurve {
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
            s.ints(ncurves)?;
            s.ints(order)?;
            s.number_array(knot)?;
            s.number_array(min)?;
            s.number_array(max)?;
            s.ints(n)?;
            s.number_array(u)?;
            s.number_array(v)?;
            s.number_array(w)?;
        }
        R::Sphere {
            radius: a,
            zmin: b,
            zmax: c,
            thetamax: d,
            params,
        }
        | R::Cylinder {
            radius: a,
            zmin: b,
            zmax: c,
            thetamax: d,
            params,
        }
        | R::Paraboloid {
            rmax: a,
            zmin: b,
            zmax: c,
            thetamax: d,
            params,
        } => {
            s.scalars(&[*a, *b, *c, *d])?;
            s.params(params)?;
        }
        R::Cone {
            height,
            radius,
            thetamax,
            params,
        }
        | R::Disk {
            height,
            radius,
            thetamax,
            params,
        } => {
            s.scalars(&[*height, *radius, *thetamax])?;
            s.params(params)?;
        }
        R::Hyperboloid {
            point1,
            point2,
            thetamax,
            params,
        } => {
            s.scalars(point1)?;
            s.scalars(point2)?;
            s.float(*thetamax)?;
            s.params(params)?;
        }
        R::Torus {
            major_radius,
            minor_radius,
            phimin,
            phimax,
            thetamax,
            params,
        } => {
            s.scalars(&[*major_radius, *minor_radius, *phimin, *phimax, *thetamax])?;
            s.params(params)?;
        }
        R::Curves {
            kind,
            nvertices,
            wrap,
            params,
        } => {
            s.string(kind)?;
            s.ints(nvertices)?;
            s.string(wrap)?;
            s.params(params)?;
        }
        R::SubdivisionMesh {
            scheme,
            nvertices,
            vertices,
            tags,
            nargs,
            intargs,
            floatargs,
            params,
        } => {
            s.string(scheme)?;
            s.ints(nvertices)?;
            s.ints(vertices)?;
            s.strings(tags)?;
            s.ints(nargs)?;
            s.ints(intargs)?;
            s.number_array(floatargs)?;
            s.params(params)?;
        }
        R::Blobby {
            nleaf,
            code,
            floats,
            strings,
            params,
        } => {
            s.int(*nleaf)?;
            s.ints(code)?;
            s.number_array(floats)?;
            s.strings(strings)?;
            s.params(params)?;
        }
        R::Procedural { name, args, bound } => {
            s.string(name)?;
            s.strings(args)?;
            s.number_array(bound)?;
        }
        R::MakeTexture {
            picture,
            texture,
            swrap,
            twrap,
            filter,
            swidth,
            twidth,
            params,
        }
        | R::MakeBump {
            picture,
            texture,
            swrap,
            twrap,
            filter,
            swidth,
            twidth,
            params,
        } => {
            for t in [picture, texture, swrap, twrap, filter] {
                s.string(t)?;
            }
            s.scalars(&[*swidth, *twidth])?;
            s.params(params)?;
        }
        R::MakeLatLongEnvironment {
            picture,
            texture,
            filter,
            swidth,
            twidth,
            params,
        } => {
            for t in [picture, texture, filter] {
                s.string(t)?;
            }
            s.scalars(&[*swidth, *twidth])?;
            s.params(params)?;
        }
        R::MakeCubeFaceEnvironment {
            faces,
            texture,
            fov,
            filter,
            swidth,
            twidth,
            params,
        } => {
            for t in faces.iter().chain([texture]) {
                s.string(t)?;
            }
            s.float(*fov)?;
            s.string(filter)?;
            s.scalars(&[*swidth, *twidth])?;
            s.params(params)?;
        }
        R::MakeShadow {
            picture,
            texture,
            params,
        } => {
            s.string(picture)?;
            s.string(texture)?;
            s.params(params)?;
        }
    }
    s.end()
}
