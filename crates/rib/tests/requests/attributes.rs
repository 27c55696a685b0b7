//! Table rows for attributes, shaders and transformations.
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// Attributes, shaders and transformations.
pub(super) fn rows() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
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
    ]
}
