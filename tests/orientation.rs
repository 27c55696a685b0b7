//! Orientation relative to the current handedness (RI Spec 3.2 `Orientation`): "outside" and
//! "inside" are relative to the handedness of the object's coordinate system, resolved per
//! primitive against the sign of its object-to-camera determinant, so a mirroring camera or
//! world transform keeps an "outside" surface's normals pointing out (as PRMan and Aqsis do).
//! The flip applies to `Ng` and the default `N`, never to a user-supplied `N`.
//!
//! Closed forms: seen from outside, the outward normal of a sphere faces the eye everywhere
//! (`N·I < 0`); a flat patch whose object-space `dPdu × dPdv` is +z has camera-space
//! `Ng = M⁻ᵀ(+z)` times −1 for "inside", whatever the sign of `det M`; a user `N` is `M⁻ᵀN`.
use illume_render::{render, RenderSettings, Rendered};
mod support;

use std::path::PathBuf;
use std::sync::OnceLock;
use support::frames;

/// Red where the probed normal faces the eye (`n·I < 0`), green where it faces away.
const PROBE: &str = r#"surface orient_probe(float use_Ng = 0) {
    normal n = N;
    if (use_Ng != 0) { n = Ng; }
    float d = normalize(n) . normalize(I);
    Ci = color(d < 0 ? 1 : 0, d > 0 ? 1 : 0, 0);
    Oi = 1;
}"#;

/// The folder holding `orient_probe.sl`, written once: the tests run in parallel, and one
/// rewriting the file while another compiles it would hand that one a truncated shader.
fn shader_dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("illume-orientation-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("orient_probe.sl"), PROBE).unwrap();
        d
    })
}

/// 64×64 perspective render; `camera` goes before `WorldBegin` (after `Projection`), `body`
/// inside the world, 5 units in front of the eye.
fn render_scene(camera: &str, body: &str) -> Rendered {
    let dir = shader_dir();
    let rib = format!(
        "Option \"searchpath\" \"shader\" [\"{}:&\"]\nFormat 64 64 1\nPixelSamples 2 2\n\
         Projection \"perspective\" \"fov\" [40]\n{camera}\nWorldBegin\nTranslate 0 0 5\n\
         {body}\nWorldEnd\n",
        dir.display()
    );
    let f = frames(&rib, None);
    assert_eq!(f.len(), 1);
    render(&f[0], &RenderSettings::default())
}

/// (pixels facing the eye, pixels facing away) among the fully covered pixels; panics when a
/// covered pixel is neither pure red nor pure green (the probe shader did not run).
fn facing(r: &Rendered) -> (usize, usize) {
    let (mut toward, mut away) = (0, 0);
    for px in r.rgba.chunks_exact(4) {
        if px[3] < 0.999 {
            continue;
        }
        match (px[0] > 0.999, px[1] > 0.999) {
            (true, false) => toward += 1,
            (false, true) => away += 1,
            _ => {
                // A pixel straddling a sign change (the patch's user N is uniform: none).
                assert!(px[0] + px[1] > 0.999, "probe shader did not run: {px:?}");
            }
        }
    }
    (toward, away)
}

const SPHERE: &str = "Surface \"orient_probe\"\nSphere 1 -1 1 360";

/// Is every covered pixel facing the eye (`Some(true)`), every one away (`Some(false)`)?
fn all_facing(r: &Rendered) -> Option<bool> {
    let (toward, away) = facing(r);
    assert!(toward + away > 500, "only {} covered pixels", toward + away);
    match (toward, away) {
        (_, 0) => Some(true),
        (0, _) => Some(false),
        _ => None,
    }
}

#[test]
fn a_sphere_seen_from_outside_faces_the_eye_under_a_mirroring_camera() {
    // The last camera turns around and mirrors through the origin (det −1): the sphere at
    // world z = 5 is at camera z = 5 again.
    for camera in [
        "",
        "Scale -1 1 1",
        "Scale 1 -1 1",
        "Scale -1 -1 -1 Translate 0 0 -10",
    ] {
        let body = SPHERE;
        assert_eq!(
            all_facing(&render_scene(camera, body)),
            Some(true),
            "camera `{camera}`: the outside faces the eye"
        );
        assert_eq!(
            all_facing(&render_scene(
                camera,
                &format!("Orientation \"inside\"\n{body}")
            )),
            Some(false),
            "camera `{camera}`: \"inside\" turns the normals in"
        );
        assert_eq!(
            all_facing(&render_scene(
                camera,
                &format!("ReverseOrientation\n{body}")
            )),
            Some(false),
            "camera `{camera}`: ReverseOrientation turns the normals in"
        );
    }
}

#[test]
fn a_mirroring_world_transform_keeps_the_outside_out() {
    // Scale after the orientation call: "outside" still means outside.
    for body in [
        "Orientation \"outside\" Scale -1 1 1",
        "Scale 1 1 -1",
        "Scale -1 1 1 Orientation \"outside\"",
    ] {
        assert_eq!(
            all_facing(&render_scene("", &format!("{body}\n{SPHERE}"))),
            Some(true),
            "{body}"
        );
    }
    // "lh"/"rh" fix the orientation against the handedness when called; a later mirror
    // carries it along (as Aqsis flips the orientation with every mirroring transform): "lh" in
    // the left-handed world is "outside" there, and stays outside after the mirror, while
    // "rh" there is "inside".
    assert_eq!(
        all_facing(&render_scene(
            "",
            &format!("Orientation \"lh\" Scale -1 1 1\n{SPHERE}")
        )),
        Some(true)
    );
    assert_eq!(
        all_facing(&render_scene(
            "",
            &format!("Orientation \"rh\" Scale -1 1 1\n{SPHERE}")
        )),
        Some(false)
    );
    // "rh" called under a mirroring camera: the world is right-handed, so that is "outside".
    assert_eq!(
        all_facing(&render_scene(
            "Scale -1 1 1",
            &format!("Orientation \"rh\"\n{SPHERE}")
        )),
        Some(true)
    );
}

/// A flat patch at the origin with object-space `dPdu × dPdv = +z` (away from the eye), a
/// user `N` given as `n` at every vertex when `Some`.
fn patch(use_ng: bool, n: Option<[f32; 3]>) -> String {
    let normals = n.map_or(String::new(), |n| {
        let one = format!("{} {} {} ", n[0], n[1], n[2]);
        format!(" \"N\" [{}]", one.repeat(4))
    });
    format!(
        "Surface \"orient_probe\" \"use_Ng\" [{}]\n\
         Patch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]{normals}",
        u8::from(use_ng)
    )
}

#[test]
fn ng_follows_the_orientation_and_a_user_n_never_flips() {
    for camera in ["", "Scale -1 1 1"] {
        for (orientation, inside) in [("", false), ("Orientation \"inside\"", true)] {
            // Ng = M⁻ᵀ(+z)·(−1 if inside): +z (away from the eye) for "outside" in both
            // handednesses, since the mirror's reversed cross product is compensated.
            let r = render_scene(camera, &format!("{orientation}\n{}", patch(true, None)));
            assert_eq!(
                all_facing(&r),
                Some(inside),
                "camera `{camera}` {orientation}: Ng"
            );
            // The default N is Ng.
            let r = render_scene(camera, &format!("{orientation}\n{}", patch(false, None)));
            assert_eq!(
                all_facing(&r),
                Some(inside),
                "camera `{camera}` {orientation}: N"
            );
            // A user N toward the eye (object −z, which the mirror in x leaves alone) stays so.
            let r = render_scene(
                camera,
                &format!("{orientation}\n{}", patch(false, Some([0.0, 0.0, -1.0]))),
            );
            assert_eq!(
                all_facing(&r),
                Some(true),
                "camera `{camera}` {orientation}: user N"
            );
            let r = render_scene(
                camera,
                &format!("{orientation}\n{}", patch(false, Some([0.0, 0.0, 1.0]))),
            );
            assert_eq!(
                all_facing(&r),
                Some(false),
                "camera `{camera}` {orientation}: user N away"
            );
        }
    }
}
