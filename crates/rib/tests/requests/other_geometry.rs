//! Table rows for points, curves, subdivision meshes, blobbies, procedurals and `Geometry`.
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// Points, curves, subdivision meshes, blobbies, procedurals and `Geometry`.
pub(super) fn rows() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
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
    ]
}
