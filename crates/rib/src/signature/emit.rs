//! Writing a [`Request`] back as arguments, in the order [`build`](super::build) reads them.
//! The small arms are grouped by argument shape; the long request families have their own
//! functions, which the exhaustive match in [`emit`] routes to.
use super::sink::Sink;
use crate::request::Request;
use std::io;
use Request as R;

/// Sends `req` to `s` in the argument order [`build`](super::build) reads back.
pub(crate) fn emit<S: Sink>(req: &Request, s: &mut S) -> io::Result<()> {
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
        | R::DisplayChannel { name, params }
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
        R::FrameAspectRatio(v)
        | R::PixelVariance(v)
        | R::RelativeDetail(v)
        | R::ShadingRate(v)
        | R::Perspective(v) => s.float(*v)?,
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
        R::Format { .. }
        | R::ScreenWindow { .. }
        | R::CropWindow { .. }
        | R::Clipping { .. }
        | R::ClippingPlane { .. }
        | R::DepthOfField { .. }
        | R::Shutter { .. }
        | R::PixelSamples { .. }
        | R::PixelFilter { .. }
        | R::Exposure { .. }
        | R::Quantize { .. }
        | R::Display { .. }
        | R::ColorSamples { .. } => options(req, s)?,
        R::Polygon { .. }
        | R::Points { .. }
        | R::GeneralPolygon { .. }
        | R::PointsPolygons { .. }
        | R::PointsGeneralPolygons { .. }
        | R::Basis { .. }
        | R::PatchMesh { .. }
        | R::NuPatch { .. }
        | R::TrimCurve { .. } => polygons_patches(req, s)?,
        R::Sphere { .. }
        | R::Cylinder { .. }
        | R::Paraboloid { .. }
        | R::Cone { .. }
        | R::Disk { .. }
        | R::Hyperboloid { .. }
        | R::Torus { .. }
        | R::Curves { .. }
        | R::SubdivisionMesh { .. }
        | R::Blobby { .. }
        | R::Procedural { .. } => other_geometry(req, s)?,
        R::MakeTexture { .. }
        | R::MakeBump { .. }
        | R::MakeLatLongEnvironment { .. }
        | R::MakeCubeFaceEnvironment { .. }
        | R::MakeShadow { .. } => textures(req, s)?,
    }
    s.end()
}

/// Options: camera, display and hider requests.
fn options<S: Sink>(req: &Request, s: &mut S) -> io::Result<()> {
    match req {
        R::Format {
            xres,
            yres,
            pixel_aspect,
        } => {
            s.int(*xres)?;
            s.int(*yres)?;
            s.float(*pixel_aspect)?;
        }
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
        // `emit` routes only the variants above here.
        _ => {}
    }
    Ok(())
}

/// Polygons and patches.
fn polygons_patches<S: Sink>(req: &Request, s: &mut S) -> io::Result<()> {
    match req {
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
        // `emit` routes only the variants above here.
        _ => {}
    }
    Ok(())
}

/// Quadrics, curves, subdivision meshes, blobbies and procedurals.
fn other_geometry<S: Sink>(req: &Request, s: &mut S) -> io::Result<()> {
    match req {
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
        // `emit` routes only the variants above here.
        _ => {}
    }
    Ok(())
}

/// Texture-making requests.
fn textures<S: Sink>(req: &Request, s: &mut S) -> io::Result<()> {
    match req {
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
        // `emit` routes only the variants above here.
        _ => {}
    }
    Ok(())
}
