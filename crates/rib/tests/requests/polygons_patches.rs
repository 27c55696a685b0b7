//! Table rows for polygons and patches (`Basis` included, as it only shapes patches).
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// Polygons and patches (`Basis` included, as it only shapes patches).
pub(super) fn rows() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
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
    ]
}
