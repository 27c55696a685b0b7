//! Table rows for version, declarations and the block structure (`WorldBegin`, `ObjectBegin`,
//! motion blocks, archives).
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// Version, declarations and the block structure.
pub(super) fn rows() -> Vec<(String, R)> {
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
    ]
}
