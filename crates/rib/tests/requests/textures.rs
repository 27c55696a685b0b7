//! Table rows for texture-making requests.
//!
//! Each row: the RIB text as users write it and the typed request it must produce.
use super::*;

/// Texture-making requests.
pub(super) fn rows() -> Vec<(String, R)> {
    let t = |x: &str| x.to_string();
    vec![
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
