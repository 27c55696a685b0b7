//! Building a typed [`Request`] from the arguments read after its name, one function per
//! request family so that each stays short; [`build`] asks them in turn.
use super::args::Args;
use super::{Arg, Res, SignatureError};
use crate::request::Request;
use Request as R;

/// A request that is a name followed by a parameter list (`Surface "plastic" "Ks" [.5]`).
macro_rules! named {
    ($a:ident, $v:ident) => {
        R::$v {
            name: $a.string()?,
            params: $a.params()?,
        }
    };
}

/// One request family: the typed request if `name` belongs to it, `None` (with no argument
/// consumed) if not.
type Family = fn(&str, &mut Args) -> Res<Option<Request>>;

/// Builds the typed request named `name` from its arguments.
pub(crate) fn build(name: &str, args: Vec<Arg>) -> Result<Request, SignatureError> {
    let mut a = Args {
        items: args.into_iter().peekable(),
    };
    let a = &mut a;
    let families: [Family; 7] = [
        structure,
        options,
        attributes,
        polygons_patches,
        quadrics,
        other_geometry,
        textures,
    ];
    for family in families {
        if let Some(req) = family(name, a)? {
            a.end()?;
            return Ok(req);
        }
    }
    Err(SignatureError::Unknown(a.items.by_ref().collect()))
}

/// Version, declarations and the block structure (`WorldBegin`, `ObjectBegin`, archives).
fn structure(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
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
        "ArchiveBegin" => named!(a, ArchiveBegin),
        "ArchiveEnd" => R::ArchiveEnd,
        "ReadArchive" => named!(a, ReadArchive),
        _ => return Ok(None),
    }))
}

/// Options: camera, display and hider requests that precede `WorldBegin`.
fn options(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
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
        "Projection" => named!(a, Projection),
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
        "Imager" => named!(a, Imager),
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
        "Hider" => named!(a, Hider),
        "DisplayChannel" => named!(a, DisplayChannel),
        "ColorSamples" => R::ColorSamples {
            n_rgb: a.float_array()?,
            rgb_n: a.float_array()?,
        },
        "RelativeDetail" => R::RelativeDetail(a.float()?),
        "Option" => named!(a, Option),
        _ => return Ok(None),
    }))
}

/// Attributes, shaders and transformations.
fn attributes(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
        "Attribute" => named!(a, Attribute),
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
        "Surface" => named!(a, Surface),
        "Displacement" => named!(a, Displacement),
        "Atmosphere" => named!(a, Atmosphere),
        "Interior" => named!(a, Interior),
        "Exterior" => named!(a, Exterior),
        "Deformation" => named!(a, Deformation),
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
        _ => return Ok(None),
    }))
}

/// Polygons and patches (`Basis` included, as it only shapes patches).
fn polygons_patches(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
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
        _ => return Ok(None),
    }))
}

/// The quadrics.
fn quadrics(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
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
        _ => return Ok(None),
    }))
}

/// Points, curves, subdivision meshes, blobbies, procedurals and `Geometry`.
fn other_geometry(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
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
        _ => return Ok(None),
    }))
}

/// Texture-making requests.
fn textures(name: &str, a: &mut Args) -> Res<Option<Request>> {
    Ok(Some(match name {
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
        _ => return Ok(None),
    }))
}
