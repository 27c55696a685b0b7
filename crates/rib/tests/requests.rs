//! One row per request kind of RI Spec 3.2: the RIB text as users write it, the typed request
//! it must produce, and the check that the canonical printout reads back to the same request.
use illume_rib::{write_binary, BasisSpec, Handle, Param, Parser, Request as R, Value};
use std::collections::BTreeSet;

fn parse_one(text: &str) -> R {
    let items: Vec<_> = Parser::new(text.as_bytes(), "t.rib").collect();
    assert_eq!(items.len(), 1, "{text:?} gave {items:?}");
    match items.into_iter().next().unwrap() {
        Ok(r) => r.value,
        Err(d) => panic!("{text:?}: {d}"),
    }
}

fn p(name: &str, value: Value) -> Param {
    Param {
        name: name.into(),
        value,
    }
}
fn f(v: &[f32]) -> Value {
    Value::Floats(v.to_vec())
}
fn i(v: &[i32]) -> Value {
    Value::Ints(v.to_vec())
}
fn s(v: &[&str]) -> Value {
    Value::Strings(v.iter().map(|x| x.to_string()).collect())
}
fn st(x: &str) -> String {
    x.to_string()
}
fn strs(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}
fn m16() -> [f32; 16] {
    std::array::from_fn(|k| k as f32 * 0.5)
}
const M16: &str = "[0 .5 1 1.5 2 2.5 3 3.5 4 4.5 5 5.5 6 6.5 7 7.5]";

fn table() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
        (
            t("##RenderMan RIB-Structure 1.1"),
            R::StructureComment(st("RenderMan RIB-Structure 1.1")),
        ),
        (t("version 3.03"), R::Version(3.03)),
        (
            t(r#"Declare "Kd" "uniform float""#),
            R::Declare {
                name: st("Kd"),
                declaration: st("uniform float"),
            },
        ),
        (t(r#"ErrorHandler "print""#), R::ErrorHandler(st("print"))),
        (t("FrameBegin 1"), R::FrameBegin(1)),
        (t("FrameEnd"), R::FrameEnd),
        (t("WorldBegin"), R::WorldBegin),
        (t("WorldEnd"), R::WorldEnd),
        (t("AttributeBegin"), R::AttributeBegin),
        (t("AttributeEnd"), R::AttributeEnd),
        (t("TransformBegin"), R::TransformBegin),
        (t("TransformEnd"), R::TransformEnd),
        (t(r#"SolidBegin "union""#), R::SolidBegin(st("union"))),
        (t("SolidEnd"), R::SolidEnd),
        (t("ObjectBegin 2"), R::ObjectBegin(Handle::Int(2))),
        (t("ObjectEnd"), R::ObjectEnd),
        (
            t(r#"ObjectInstance "tree""#),
            R::ObjectInstance(Handle::Str(st("tree"))),
        ),
        (
            t("MotionBegin [0 0.5 1]"),
            R::MotionBegin(vec![0.0, 0.5, 1.0]),
        ),
        (t("MotionEnd"), R::MotionEnd),
        (
            t(r#"ArchiveBegin "a" "float x" 1"#),
            R::ArchiveBegin {
                name: st("a"),
                params: vec![p("float x", i(&[1]))],
            },
        ),
        (t("ArchiveEnd"), R::ArchiveEnd),
        (
            t(r#"ReadArchive "b.rib""#),
            R::ReadArchive {
                name: st("b.rib"),
                params: vec![],
            },
        ),
        (
            t("Format 640 480 1"),
            R::Format {
                xres: 640,
                yres: 480,
                pixel_aspect: 1.0,
            },
        ),
        (t("FrameAspectRatio 1.5"), R::FrameAspectRatio(1.5)),
        (
            t("ScreenWindow -1 1 -.75 .75"),
            R::ScreenWindow {
                left: -1.0,
                right: 1.0,
                bottom: -0.75,
                top: 0.75,
            },
        ),
        (
            t("CropWindow [0 .5 0 1]"),
            R::CropWindow {
                xmin: 0.0,
                xmax: 0.5,
                ymin: 0.0,
                ymax: 1.0,
            },
        ),
        (
            t(r#"Projection "perspective" "fov" [45]"#),
            R::Projection {
                name: st("perspective"),
                params: vec![p("fov", i(&[45]))],
            },
        ),
        (
            t("Clipping 0.1 1E+4"),
            R::Clipping {
                near: 0.1,
                far: 1e4,
            },
        ),
        (
            t("ClippingPlane 0 0 1 0 0 -1"),
            R::ClippingPlane {
                x: 0.0,
                y: 0.0,
                z: 1.0,
                nx: 0.0,
                ny: 0.0,
                nz: -1.0,
            },
        ),
        (
            t("DepthOfField 22 0.05 10"),
            R::DepthOfField {
                fstop: 22.0,
                focal_length: 0.05,
                focal_distance: 10.0,
            },
        ),
        (
            // No arguments: depth of field off (pinhole), an infinite fstop.
            t("DepthOfField"),
            R::DepthOfField {
                fstop: f32::INFINITY,
                focal_length: 0.0,
                focal_distance: 0.0,
            },
        ),
        (
            t("Shutter 0 1"),
            R::Shutter {
                open: 0.0,
                close: 1.0,
            },
        ),
        (t("PixelVariance 0.01"), R::PixelVariance(0.01)),
        (t("PixelSamples 4 4"), R::PixelSamples { x: 4.0, y: 4.0 }),
        (
            t(r#"PixelFilter "gaussian" 2 2"#),
            R::PixelFilter {
                name: st("gaussian"),
                xwidth: 2.0,
                ywidth: 2.0,
            },
        ),
        (
            t("Exposure 1 2.2"),
            R::Exposure {
                gain: 1.0,
                gamma: 2.2,
            },
        ),
        (
            t(r#"Imager "background" "color background" [1 1 1]"#),
            R::Imager {
                name: st("background"),
                params: vec![p("color background", i(&[1, 1, 1]))],
            },
        ),
        (
            t(r#"Quantize "rgba" 255 0 255 0.5"#),
            R::Quantize {
                kind: st("rgba"),
                one: 255,
                min: 0,
                max: 255,
                dither: 0.5,
            },
        ),
        (
            t(r#"Display "out.tif" "file" "rgba" "quality" 90"#),
            R::Display {
                name: st("out.tif"),
                kind: st("file"),
                mode: st("rgba"),
                params: vec![p("quality", i(&[90]))],
            },
        ),
        (
            t(r#"Hider "hidden" "jitter" [1]"#),
            R::Hider {
                name: st("hidden"),
                params: vec![p("jitter", i(&[1]))],
            },
        ),
        (
            t("ColorSamples [1 0 0 0 1 0] [1 0 0 1 0 0]"),
            R::ColorSamples {
                n_rgb: vec![1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
                rgb_n: vec![1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
            },
        ),
        (t("RelativeDetail 0.6"), R::RelativeDetail(0.6)),
        (
            t(r#"Option "searchpath" "shader" ["./:&"]"#),
            R::Option {
                name: st("searchpath"),
                params: vec![p("shader", s(&["./:&"]))],
            },
        ),
        (
            t(r#"Attribute "identifier" "name" "x""#),
            R::Attribute {
                name: st("identifier"),
                params: vec![p("name", s(&["x"]))],
            },
        ),
        (t("Color 1 0 0"), R::Color(vec![1.0, 0.0, 0.0])),
        (t("Opacity [.5 .5 .5]"), R::Opacity(vec![0.5, 0.5, 0.5])),
        (
            t("TextureCoordinates 0 0 1 0 0 1 1 1"),
            R::TextureCoordinates([0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0]),
        ),
        (
            t(r#"LightSource "spotlight" 1 "intensity" 2.5"#),
            R::LightSource {
                name: st("spotlight"),
                handle: Handle::Int(1),
                params: vec![p("intensity", f(&[2.5]))],
            },
        ),
        (
            t(r#"AreaLightSource "arealight" "key""#),
            R::AreaLightSource {
                name: st("arealight"),
                handle: Handle::Str(st("key")),
                params: vec![],
            },
        ),
        (
            t("Illuminate 1 0"),
            R::Illuminate {
                handle: Handle::Int(1),
                on: false,
            },
        ),
        (
            t(r#"Surface "plastic" "Ks" [.5] "uniform float roughness" .1"#),
            R::Surface {
                name: st("plastic"),
                params: vec![p("Ks", f(&[0.5])), p("uniform float roughness", f(&[0.1]))],
            },
        ),
        (
            t(r#"Displacement "dented""#),
            R::Displacement {
                name: st("dented"),
                params: vec![],
            },
        ),
        (
            t(r#"Atmosphere "fog" "distance" 10"#),
            R::Atmosphere {
                name: st("fog"),
                params: vec![p("distance", i(&[10]))],
            },
        ),
        (
            t(r#"Interior "water""#),
            R::Interior {
                name: st("water"),
                params: vec![],
            },
        ),
        (
            t(r#"Exterior "fog""#),
            R::Exterior {
                name: st("fog"),
                params: vec![],
            },
        ),
        (
            t(r#"Deformation "twist" "angle" 30"#),
            R::Deformation {
                name: st("twist"),
                params: vec![p("angle", i(&[30]))],
            },
        ),
        (t("ShadingRate 0.25"), R::ShadingRate(0.25)),
        (
            t(r#"ShadingInterpolation "smooth""#),
            R::ShadingInterpolation(st("smooth")),
        ),
        (t("Matte 1"), R::Matte(true)),
        (
            t("Bound [-1 1 -1 1 0 2]"),
            R::Bound([-1.0, 1.0, -1.0, 1.0, 0.0, 2.0]),
        ),
        (
            t("Detail -1 1 -1 1 0 2"),
            R::Detail([-1.0, 1.0, -1.0, 1.0, 0.0, 2.0]),
        ),
        (
            t("DetailRange 0 0 10 20"),
            R::DetailRange([0.0, 0.0, 10.0, 20.0]),
        ),
        (
            t(r#"GeometricApproximation "flatness" 0.5"#),
            R::GeometricApproximation {
                kind: st("flatness"),
                value: 0.5,
            },
        ),
        (
            t(r#"GeometricRepresentation "lines""#),
            R::GeometricRepresentation(st("lines")),
        ),
        (t(r#"Orientation "inside""#), R::Orientation(st("inside"))),
        (t("ReverseOrientation"), R::ReverseOrientation),
        (t("Sides 1"), R::Sides(1)),
        (t("Identity"), R::Identity),
        (format!("Transform {M16}"), R::Transform(m16())),
        (format!("ConcatTransform {M16}"), R::ConcatTransform(m16())),
        (t("Perspective 45"), R::Perspective(45.0)),
        (t("Translate 0 -4 5"), R::Translate([0.0, -4.0, 5.0])),
        (
            t("Rotate -40 1 0 0"),
            R::Rotate {
                angle: -40.0,
                axis: [1.0, 0.0, 0.0],
            },
        ),
        (t("Scale 1 1 -1"), R::Scale([1.0, 1.0, -1.0])),
        (
            t("Skew 45 0 1 0 1 0 0"),
            R::Skew([45.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0]),
        ),
        (
            t(r#"CoordinateSystem "lamp""#),
            R::CoordinateSystem(st("lamp")),
        ),
        (
            t(r#"CoordSysTransform "lamp""#),
            R::CoordSysTransform(st("lamp")),
        ),
        (
            t(r#"Polygon "P" [0 0 0 1 0 0 1 1 0]"#),
            R::Polygon {
                params: vec![p("P", i(&[0, 0, 0, 1, 0, 0, 1, 1, 0]))],
            },
        ),
        (
            t(r#"GeneralPolygon [3] "P" [0 0 0 1 0 0 1 1 0]"#),
            R::GeneralPolygon {
                nverts: vec![3],
                params: vec![p("P", i(&[0, 0, 0, 1, 0, 0, 1, 1, 0]))],
            },
        ),
        (
            t(r#"PointsPolygons [3] [0 1 2] "P" [0 0 0 1 0 0 1 1 .5]"#),
            R::PointsPolygons {
                nverts: vec![3],
                verts: vec![0, 1, 2],
                params: vec![p("P", f(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.5]))],
            },
        ),
        (
            t(r#"PointsGeneralPolygons [1] [3] [0 1 2] "P" [0 0 0 1 0 0 1 1 0]"#),
            R::PointsGeneralPolygons {
                nloops: vec![1],
                nverts: vec![3],
                verts: vec![0, 1, 2],
                params: vec![p("P", i(&[0, 0, 0, 1, 0, 0, 1, 1, 0]))],
            },
        ),
        (
            format!(r#"Basis "bezier" 3 {M16} 3"#),
            R::Basis {
                ubasis: BasisSpec::Named(st("bezier")),
                ustep: 3,
                vbasis: BasisSpec::Matrix(m16()),
                vstep: 3,
            },
        ),
        (
            t(r#"Patch "bilinear" "P" [0 0 0 1 0 0 0 1 0 1 1 0]"#),
            R::Patch {
                kind: st("bilinear"),
                params: vec![p("P", i(&[0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]))],
            },
        ),
        (
            t(r#"PatchMesh "bilinear" 2 "nonperiodic" 2 "periodic" "Pz" [1 2 3 4]"#),
            R::PatchMesh {
                kind: st("bilinear"),
                nu: 2,
                uwrap: st("nonperiodic"),
                nv: 2,
                vwrap: st("periodic"),
                params: vec![p("Pz", i(&[1, 2, 3, 4]))],
            },
        ),
        (
            t(
                r#"NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 "Pw" [0 0 0 1 1 0 0 1 0 1 0 1 1 1 0 1]"#,
            ),
            R::NuPatch {
                nu: 2,
                uorder: 2,
                uknot: vec![0.0, 0.0, 1.0, 1.0],
                umin: 0.0,
                umax: 1.0,
                nv: 2,
                vorder: 2,
                vknot: vec![0.0, 0.0, 1.0, 1.0],
                vmin: 0.0,
                vmax: 1.0,
                params: vec![p(
                    "Pw",
                    i(&[0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1, 1, 1, 0, 1]),
                )],
            },
        ),
        (
            t("TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]"),
            R::TrimCurve {
                ncurves: vec![1],
                order: vec![2],
                knot: vec![0.0, 0.0, 1.0, 1.0],
                min: vec![0.0],
                max: vec![1.0],
                n: vec![2],
                u: vec![0.0, 1.0],
                v: vec![0.0, 1.0],
                w: vec![1.0, 1.0],
            },
        ),
        (
            t("Sphere 1 -1 1 360"),
            R::Sphere {
                radius: 1.0,
                zmin: -1.0,
                zmax: 1.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Cone 2 1 270"),
            R::Cone {
                height: 2.0,
                radius: 1.0,
                thetamax: 270.0,
                params: vec![],
            },
        ),
        (
            t("Cylinder 1 0 2 360"),
            R::Cylinder {
                radius: 1.0,
                zmin: 0.0,
                zmax: 2.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Hyperboloid 1 0 0 0 1 1 360"),
            R::Hyperboloid {
                point1: [1.0, 0.0, 0.0],
                point2: [0.0, 1.0, 1.0],
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Paraboloid 1 0 2 360"),
            R::Paraboloid {
                rmax: 1.0,
                zmin: 0.0,
                zmax: 2.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Disk 0 1 360"),
            R::Disk {
                height: 0.0,
                radius: 1.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t("Torus 1 .25 0 360 360"),
            R::Torus {
                major_radius: 1.0,
                minor_radius: 0.25,
                phimin: 0.0,
                phimax: 360.0,
                thetamax: 360.0,
                params: vec![],
            },
        ),
        (
            t(r#"Points "P" [0 0 0] "constantwidth" [0.1]"#),
            R::Points {
                params: vec![p("P", i(&[0, 0, 0])), p("constantwidth", f(&[0.1]))],
            },
        ),
        (
            t(r#"Curves "cubic" [4] "nonperiodic" "P" [0 0 0 1 1 1 2 2 2 3 3 3]"#),
            R::Curves {
                kind: st("cubic"),
                nvertices: vec![4],
                wrap: st("nonperiodic"),
                params: vec![p("P", i(&[0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3]))],
            },
        ),
        (
            t(
                r#"SubdivisionMesh "catmull-clark" [4] [0 1 2 3] ["crease" "interpolateboundary"] [2 1 0 0] [0 1] [2.5] "P" [0 0 0 1 0 0 1 1 0 0 1 0]"#,
            ),
            R::SubdivisionMesh {
                scheme: st("catmull-clark"),
                nvertices: vec![4],
                vertices: vec![0, 1, 2, 3],
                tags: strs(&["crease", "interpolateboundary"]),
                nargs: vec![2, 1, 0, 0],
                intargs: vec![0, 1],
                floatargs: vec![2.5],
                params: vec![p("P", i(&[0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]))],
            },
        ),
        (
            t(r#"Blobby 1 [1001 0 0] [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] [] "Cs" [1 0 0]"#),
            R::Blobby {
                nleaf: 1,
                code: vec![1001, 0, 0],
                floats: (0..16)
                    .map(|k| if k % 5 == 0 { 1.0 } else { 0.0 })
                    .collect(),
                strings: vec![],
                params: vec![p("Cs", i(&[1, 0, 0]))],
            },
        ),
        (
            t(r#"Procedural "DelayedReadArchive" ["tree.rib"] [-1 1 -1 1 0 4]"#),
            R::Procedural {
                name: st("DelayedReadArchive"),
                args: strs(&["tree.rib"]),
                bound: [-1.0, 1.0, -1.0, 1.0, 0.0, 4.0],
            },
        ),
        (
            t(r#"Geometry "teapot""#),
            R::Geometry {
                kind: st("teapot"),
                params: vec![],
            },
        ),
        (
            t(r#"MakeTexture "a.tif" "a.tx" "periodic" "clamp" "gaussian" 2 2 "float bias" .1"#),
            R::MakeTexture {
                picture: st("a.tif"),
                texture: st("a.tx"),
                swrap: st("periodic"),
                twrap: st("clamp"),
                filter: st("gaussian"),
                swidth: 2.0,
                twidth: 2.0,
                params: vec![p("float bias", f(&[0.1]))],
            },
        ),
        (
            t(r#"MakeBump "b.tif" "b.tx" "black" "black" "box" 1 1"#),
            R::MakeBump {
                picture: st("b.tif"),
                texture: st("b.tx"),
                swrap: st("black"),
                twrap: st("black"),
                filter: st("box"),
                swidth: 1.0,
                twidth: 1.0,
                params: vec![],
            },
        ),
        (
            t(r#"MakeLatLongEnvironment "sky.tif" "sky.env" "gaussian" 2 2"#),
            R::MakeLatLongEnvironment {
                picture: st("sky.tif"),
                texture: st("sky.env"),
                filter: st("gaussian"),
                swidth: 2.0,
                twidth: 2.0,
                params: vec![],
            },
        ),
        (
            t(
                r#"MakeCubeFaceEnvironment "px.tif" "nx.tif" "py.tif" "ny.tif" "pz.tif" "nz.tif" "env.tx" 95 "gaussian" 2 2 "quality" 1"#,
            ),
            R::MakeCubeFaceEnvironment {
                faces: ["px", "nx", "py", "ny", "pz", "nz"].map(|x| format!("{x}.tif")),
                texture: st("env.tx"),
                fov: 95.0,
                filter: st("gaussian"),
                swidth: 2.0,
                twidth: 2.0,
                params: vec![p("quality", i(&[1]))],
            },
        ),
        (
            t(r#"MakeShadow "z.zfile" "z.shad""#),
            R::MakeShadow {
                picture: st("z.zfile"),
                texture: st("z.shad"),
                params: vec![],
            },
        ),
    ]
}

#[test]
fn table_covers_every_request_of_the_spec() {
    // 102 requests of RI 3.2 plus `##` comments; `Unknown` is not a request of the spec.
    let names: BTreeSet<String> = table().iter().map(|(_, r)| r.name().to_string()).collect();
    assert_eq!(names.len(), 103, "{names:?}");
}

#[test]
fn every_request_kind_parses_to_its_typed_request() {
    for (text, expected) in table() {
        assert_eq!(parse_one(&text), expected, "parsing {text:?}");
    }
}

#[test]
fn every_request_kind_survives_ascii_printing() {
    for (text, expected) in table() {
        let printed = illume_rib::to_ascii(&expected);
        assert!(!printed.contains('\n'), "one line per request: {printed:?}");
        assert_eq!(
            parse_one(&printed),
            expected,
            "{text:?} printed as {printed:?}"
        );
    }
}

#[test]
fn every_request_kind_survives_binary_encoding() {
    for (text, expected) in table() {
        let mut bytes = Vec::new();
        write_binary(&expected, &mut bytes).unwrap();
        let back: Vec<_> = Parser::new(&bytes[..], "t.rib").collect();
        assert_eq!(back.len(), 1, "{text:?}: {back:?}");
        assert_eq!(back[0].as_ref().unwrap().value, expected, "{text:?}");
    }
}

#[test]
fn scalars_and_arrays_are_interchangeable_where_the_spec_allows() {
    let pairs = [
        ("Color [1 0 0]", "Color 1 0 0"),
        ("Sphere [1 -1 1 360]", "Sphere 1 -1 1 360"),
        (r#"Surface "x" "Ka" .5"#, r#"Surface "x" "Ka" [.5]"#),
        ("MotionBegin 0 1", "MotionBegin [0 1]"),
        (
            r#"GeneralPolygon 3 "P" [0 0 0 1 0 0 1 1 0]"#,
            r#"GeneralPolygon [3] "P" [0 0 0 1 0 0 1 1 0]"#,
        ),
        (
            r#"Procedural "RunProgram" "gen" [0 1 0 1 0 1]"#,
            r#"Procedural "RunProgram" ["gen"] [0 1 0 1 0 1]"#,
        ),
        ("Translate [1 2 3]", "Translate 1 2 3"),
        ("Format 640.0 480 1", "Format 640 480 1"),
    ];
    for (a, b) in pairs {
        assert_eq!(parse_one(a), parse_one(b), "{a} vs {b}");
    }
}

#[test]
fn number_forms_of_the_spec_all_read() {
    let r = parse_one("Surface \"x\" \"v\" [1 -.5 1.e-3 1E+4 +2 -7 .25e1]");
    assert_eq!(
        r,
        R::Surface {
            name: st("x"),
            params: vec![p("v", f(&[1.0, -0.5, 1e-3, 1e4, 2.0, -7.0, 2.5]))]
        }
    );
}

#[test]
fn comments_inside_arrays_and_between_parameters_are_skipped() {
    let text = "Surface \"plastic\" # the shader\n  \"Ks\" [ .5 # specular\n ] # end\n \"Kd\" # diffuse\n [1]\n";
    assert_eq!(
        parse_one(text),
        R::Surface {
            name: st("plastic"),
            params: vec![p("Ks", f(&[0.5])), p("Kd", i(&[1]))]
        }
    );
}

#[test]
fn string_escapes_follow_c() {
    let r = parse_one("Attribute \"a\" \"s\" \"q\\\"b\\\\n\\n\\t\\101\\\nz\"");
    assert_eq!(
        r,
        R::Attribute {
            name: st("a"),
            params: vec![p("s", s(&["q\"b\\n\n\tAz"]))]
        }
    );
}

#[test]
fn subdivision_mesh_tags_are_optional() {
    let r = parse_one(r#"SubdivisionMesh "loop" [3] [0 1 2] "P" [0 0 0 1 0 0 0 1 0]"#);
    let R::SubdivisionMesh { tags, params, .. } = r else {
        panic!("{r:?}")
    };
    assert!(tags.is_empty());
    assert_eq!(params.len(), 1);
}

#[test]
fn structure_comments_keep_their_text_and_plain_comments_vanish() {
    let items: Vec<R> = Parser::new(
        "##RenderMan RIB\n# plain\nWorldBegin ##Include x.rib\n".as_bytes(),
        "t",
    )
    .map(|i| i.unwrap().value)
    .collect();
    assert_eq!(
        items,
        vec![
            R::StructureComment(st("RenderMan RIB")),
            R::WorldBegin,
            R::StructureComment(st("Include x.rib"))
        ]
    );
}

#[test]
fn spans_point_at_request_names() {
    let spans: Vec<(u32, u32, u64)> = Parser::new(
        "WorldBegin\n  Sphere 1\n -1 1 360\n\tWorldEnd".as_bytes(),
        "s.rib",
    )
    .map(|i| {
        let s = i.unwrap().span;
        assert_eq!(&*s.file, "s.rib");
        (s.line, s.col, s.offset)
    })
    .collect();
    assert_eq!(spans, vec![(1, 1, 0), (2, 3, 13), (4, 2, 33)]);
}

// ---- random round trips ------------------------------------------------------------------
//
// Random requests of every kind are made by taking each table row's canonical text and
// replacing every number and string with random ones of the same class (integers stay
// integers, so the signature still fits): any finite f32 including subnormals and -0, any
// i32, strings with quotes, backslashes, control characters and non-ASCII text. Random
// parameter lists of every value type are added through `Surface` and `Unknown`.

struct SplitMix(u64);
impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn float(&mut self) -> f32 {
        loop {
            let f = match self.below(4) {
                0 => f32::from_bits(self.next() as u32),
                1 => (self.next() % 20001) as f32 / 100.0 - 100.0,
                2 => -0.0,
                _ => (self.next() as u32 as f32) * 1e-12,
            };
            if f.is_finite() {
                return f;
            }
        }
    }
    fn int(&mut self) -> i32 {
        match self.below(3) {
            0 => self.next() as i32,
            _ => (self.below(2001) as i32) - 1000,
        }
    }
    fn string(&mut self) -> String {
        const PIECES: [&str; 12] = [
            "a", "Z", " ", "\"", "\\", "\n", "\t", "é", "漢", "\u{1}", "#", "[",
        ];
        (0..self.below(8))
            .map(|_| PIECES[self.below(PIECES.len() as u64) as usize])
            .collect()
    }
    fn value(&mut self) -> Value {
        let n = self.below(6) as usize;
        match self.below(3) {
            _ if n == 0 => Value::Floats(vec![]), // the reader's type for `[]`
            0 => Value::Ints((0..n).map(|_| self.int()).collect()),
            1 => Value::Floats((0..n).map(|_| self.float()).collect()),
            _ => Value::Strings((0..n).map(|_| self.string()).collect()),
        }
    }
}

/// Replaces the numbers and strings of canonical RIB text with random ones of the same class.
fn mutate(text: &str, rng: &mut SplitMix) -> String {
    let mut out = String::new();
    let chars: Vec<char> = text.chars().collect();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        if c == '"' {
            let mut j = k + 1;
            while chars[j] != '"' {
                j += if chars[j] == '\\' { 2 } else { 1 };
            }
            // Request-shaping strings (basis names) may become any string: still a string.
            out.push_str(
                &illume_rib::to_ascii(&R::ErrorHandler(rng.string()))["ErrorHandler ".len()..],
            );
            k = j + 1;
        } else if c.is_ascii_digit() || c == '-' || c == '+' || c == '.' {
            let mut j = k;
            while j < chars.len() && (chars[j].is_ascii_alphanumeric() || "+-.".contains(chars[j]))
            {
                j += 1;
            }
            let word: String = chars[k..j].iter().collect();
            if word.contains(['.', 'e']) {
                out.push_str(&format!("{:?}", rng.float()));
            } else {
                // Integer slots: keep counts and codes small and non-negative so the request
                // stays well-formed (`Format` sizes, `nleaf`); the sign is exercised elsewhere.
                out.push_str(&(rng.below(100) as i32).to_string());
            }
            k = j;
        } else {
            out.push(c);
            k += 1;
        }
    }
    out
}

fn random_request(rows: &[(String, R)], pick: usize, seed: u64) -> R {
    let mut rng = SplitMix(seed);
    let k = pick % (rows.len() + 2);
    if let Some((_, template)) = rows.get(k) {
        if let R::StructureComment(_) = template {
            return template.clone(); // `##` text is not a quoted string; keep it
        }
        return parse_one(&mutate(&illume_rib::to_ascii(template), &mut rng));
    }
    let params: Vec<Param> = (0..rng.below(4))
        .map(|_| Param {
            name: rng.string(),
            value: rng.value(),
        })
        .collect();
    if k == rows.len() {
        R::Surface {
            name: rng.string(),
            params,
        }
    } else {
        R::Unknown {
            name: "MyThing".into(),
            args: params.into_iter().map(|p| p.value).collect(),
        }
    }
}

fn random_stream(picks: &[(usize, u64)]) -> Vec<R> {
    let rows = table();
    picks
        .iter()
        .map(|&(pick, seed)| random_request(&rows, pick, seed))
        .collect()
}

/// Every request of the stream; warnings (for `Unknown`) are expected and skipped.
fn parse_all(bytes: &[u8]) -> Vec<R> {
    Parser::new(bytes, "p.rib")
        .filter_map(|i| match i {
            Ok(r) => Some(r.value),
            Err(d) if d.severity == illume_rib::Severity::Warning => None,
            Err(d) => panic!("{d}"),
        })
        .collect()
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

    #[test]
    fn random_request_streams_survive_ascii(picks in proptest::collection::vec((0usize..200, proptest::prelude::any::<u64>()), 1..30)) {
        let stream = random_stream(&picks);
        let mut text = Vec::new();
        for r in &stream {
            illume_rib::write_ascii(r, &mut text).unwrap();
        }
        let back = parse_all(&text);
        proptest::prop_assert_eq!(&back, &stream);
        // Bit-exact floats: compare the printouts too (PartialEq says 0.0 == -0.0).
        let mut again = Vec::new();
        for r in &back {
            illume_rib::write_ascii(r, &mut again).unwrap();
        }
        proptest::prop_assert_eq!(String::from_utf8(again).unwrap(), String::from_utf8(text).unwrap());
    }

    #[test]
    fn random_request_streams_survive_binary(picks in proptest::collection::vec((0usize..200, proptest::prelude::any::<u64>()), 1..30)) {
        let stream = random_stream(&picks);
        let mut w = illume_rib::BinaryWriter::new(Vec::new());
        for r in &stream {
            w.write(r).unwrap();
        }
        let back = parse_all(&w.into_inner());
        proptest::prop_assert_eq!(&back, &stream);
        let print = |rs: &[R]| rs.iter().map(illume_rib::to_ascii).collect::<Vec<_>>();
        proptest::prop_assert_eq!(print(&back), print(&stream));
    }
}
