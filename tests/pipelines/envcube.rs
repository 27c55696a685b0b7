//! The cube-environment pipeline of `rib/pipelines/envcube/` (chapter 9 §9.2.2, Table 9.1,
//! Listing 9.5): six 90° face renders of a room from the chrome sphere's map centre,
//! `MakeCubeFaceEnvironment`/`txmake -envcube`, a beauty pass through `Environment()`.
use super::forms::{assert_same_image, copy_example, rib_in, run_both_forms, scratch};
use super::geometry::{environment_direction, hit_sphere, reflect, Camera};
use crate::support::run_rib;
use glam::DVec3;

/// The room (`room.rib`): walls at ±5 on every axis.
const HALF: f64 = 5.0;
/// `envrad` of the beauty pass.
const ENVRAD: f64 = 5.0;
/// The chrome sphere: radius 1, 1.15 to the left of the map centre (the origin).
const CHROME: DVec3 = DVec3::new(-0.8131728, 0.0, 0.8131728);

/// `room.rib`'s colours: wall (axis, positive side?) → full colour; the half of the wall on
/// the negative side of the next axis (x → y → z → x) is 0.45 of it.
fn wall_colour(axis: usize, positive: bool, bright_half: bool) -> DVec3 {
    let base = match (axis, positive) {
        (0, true) => DVec3::new(1.0, 0.2, 0.2),
        (0, false) => DVec3::new(0.2, 1.0, 0.2),
        (1, true) => DVec3::new(0.2, 0.2, 1.0),
        (1, false) => DVec3::new(1.0, 1.0, 0.2),
        (2, true) => DVec3::new(1.0, 0.2, 1.0),
        _ => DVec3::new(0.2, 1.0, 1.0),
    };
    if bright_half {
        base
    } else {
        base * 0.45
    }
}

/// A wall half: (axis, positive side, bright half).
type Patch = (usize, bool, bool);

/// The wall half containing point `q` on the room's surface, or `None` within `margin` of a wall
/// edge or of the line splitting the wall (where filtering mixes two colours).
fn patch_at(q: DVec3, margin: f64) -> Option<Patch> {
    let axis = (0..3).max_by(|&a, &b| q[a].abs().total_cmp(&q[b].abs()))?;
    let on_wall = q * (HALF / q[axis].abs());
    let others = [(axis + 1) % 3, (axis + 2) % 3];
    if others.iter().any(|&o| on_wall[o].abs() > HALF - margin) || on_wall[others[0]].abs() < margin
    {
        return None;
    }
    Some((axis, on_wall[axis] > 0.0, on_wall[others[0]] > 0.0))
}

/// Where the true reflected ray (p, r) meets the room.
fn room_hit(p: DVec3, r: DVec3) -> DVec3 {
    let t = (0..3)
        .map(|a| (HALF.copysign(r[a]) - p[a]) / r[a])
        .filter(|t| t.is_finite() && *t > 0.0)
        .fold(f64::INFINITY, f64::min);
    p + t * r
}

fn beauty_camera() -> Camera {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    Camera {
        eye: DVec3::new(-3.0, 0.0, -3.0),
        right: DVec3::new(s, 0.0, -s),
        up: DVec3::Y,
        view: DVec3::new(s, 0.0, s),
        width: 320.0,
        height: 160.0,
        fov_degrees: 40.0,
    }
}

/// The wall half the chrome sphere must show at raster point (x, y): the one the environment
/// map holds in Listing 9.5's lookup direction, provided it is also the wall the true mirror
/// ray hits (the map is only exact where both agree). `None` off the sphere or near an edge.
fn expected_patch(cam: &Camera, x: f64, y: f64) -> Option<Patch> {
    let d = cam.ray(x, y);
    let t = hit_sphere(cam.eye, d, CHROME, 1.0)?;
    let p = cam.eye + t * d;
    let n = (p - CHROME).normalize();
    let r = reflect(d, n);
    let lookup = patch_at(environment_direction(p, r, ENVRAD), 0.4)?;
    let truth = patch_at(room_hit(p, r), 0.4)?;
    (lookup == truth).then_some(lookup)
}

#[test]
fn each_wall_shows_in_the_chrome_sphere_where_the_mirror_direction_points() {
    let dir = scratch("envcube");
    copy_example("envcube", &dir);
    let frames = run_rib(&rib_in("envcube", "envcube_single.rib", &dir));
    assert_eq!(
        frames.len(),
        8,
        "six faces, the tested frame and Figure 9.6"
    );
    let beauty = &frames[6];
    let cam = beauty_camera();
    let (w, h) = (beauty.width as usize, beauty.height as usize);
    assert_eq!((w, h), (320, 160));
    // Every pixel whose whole filter footprint (gaussian 2×2: ±1 px, checked at ±1.5 px) sees
    // one wall half, in the map and in truth.
    let mut tested = std::collections::BTreeMap::<Patch, usize>::new();
    let mut worst = 0.0f64;
    for y in 0..h {
        for x in 0..w {
            let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
            let Some(patch) = expected_patch(&cam, cx, cy) else {
                continue;
            };
            let corners = [(-1.5, -1.5), (1.5, -1.5), (-1.5, 1.5), (1.5, 1.5)];
            if corners
                .iter()
                .any(|(dx, dy)| expected_patch(&cam, cx + dx, cy + dy) != Some(patch))
            {
                continue;
            }
            let px = &beauty.rgba[(y * w + x) * 4..][..4];
            let got = DVec3::new(px[0].into(), px[1].into(), px[2].into());
            let want = wall_colour(patch.0, patch.1, patch.2);
            let err = (got - want).abs().max_element();
            // 0.05: the map's half floats and filtering inside a constant patch err by ~1e-3;
            // any two of the twelve colours differ by at least 0.3, so a face that is wrongly
            // placed, rotated or mirrored fails by far more.
            assert!(
                err < 0.05,
                "pixel ({x}, {y}): expected wall {patch:?} {want:?}, rendered {got:?}"
            );
            worst = worst.max(err);
            *tested.entry(patch).or_default() += 1;
        }
    }
    eprintln!("envcube: pixels tested per wall half {tested:?}, largest error {worst:.4}");
    for axis in 0..3 {
        for positive in [true, false] {
            let n: usize = tested
                .iter()
                .filter(|((a, p, _), _)| *a == axis && *p == positive)
                .map(|(_, n)| n)
                .sum();
            assert!(
                n >= 4,
                "wall axis {axis} positive {positive}: only {n} pixels tested"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn envcube_sh_and_render_single_rib_write_identical_files() {
    let Some(images) = run_both_forms(
        "envcube",
        "envcube_single.rib",
        "envcube.sh",
        &[
            ["envcube_single.tif", "envcube_script.tif"],
            ["fig9_6_envcube_single.tif", "fig9_6_envcube_script.tif"],
        ],
    ) else {
        return;
    };
    let [single, script] = &images[0];
    assert_eq!((single.width, single.height), (320, 160));
    assert_same_image(single, script, "envcube_single.tif vs envcube_script.tif");
    // Worth comparing: the chrome sphere's reflection is in there (some saturated green, -x).
    let greens = single
        .data
        .chunks_exact(4)
        .filter(|p| p[1] > 0.8 && p[0] < 0.4 && p[2] < 0.4)
        .count();
    assert!(greens > 50, "{greens} green pixels");
    let [single, script] = &images[1];
    assert_same_image(single, script, "the two forms' Figure 9.6");
}
