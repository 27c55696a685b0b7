//! The lat-long pipeline of `rib/pipelines/latlong/`: an analytic environment (colour
//! `(d + 1)/2` for direction `d`) through `MakeLatLongEnvironment`/`txmake -envlatl` onto a
//! chrome sphere.
use super::forms::{assert_same_image, example_dir, rib_in, run_both_forms, scratch};
use super::geometry::{environment_direction, hit_sphere, reflect, Camera};
use crate::support::run_rib;
use glam::DVec3;
use std::f64::consts::PI;

const RES: usize = 128;

/// The direction at lat-long (s, t) in RenderMan's orientation: +z at t = 0 (θ = πt from +z),
/// φ = 2π(s − ½) from +x toward +y.
fn latlong_direction(s: f64, t: f64) -> DVec3 {
    let (phi, theta) = ((s - 0.5) * 2.0 * PI, t * PI);
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

fn sky(d: DVec3) -> DVec3 {
    (d.normalize() + DVec3::ONE) / 2.0
}

/// The analytic sky as a float RGB image, texel centres at ((i + ½)/w, (j + ½)/h).
fn sky_image(w: u32, h: u32) -> illume_imageio::Image {
    let mut img = illume_imageio::Image::new(w, h, "rgb");
    for j in 0..h {
        for i in 0..w {
            let s = (f64::from(i) + 0.5) / f64::from(w);
            let t = (f64::from(j) + 0.5) / f64::from(h);
            let c = sky(latlong_direction(s, t));
            let k = (j * w + i) as usize * 3;
            img.data[k..k + 3].copy_from_slice(&[c.x as f32, c.y as f32, c.z as f32]);
        }
    }
    img
}

fn camera() -> Camera {
    // `Transform [-1 0 0 0  0 0 1 0  0 1 0 0  0 0 4 1]`: eye (0, −4, 0), right −x, up +z, view +y.
    Camera {
        eye: DVec3::new(0.0, -4.0, 0.0),
        right: DVec3::NEG_X,
        up: DVec3::Z,
        view: DVec3::Y,
        width: RES as f64,
        height: RES as f64,
        fov_degrees: 35.0,
    }
}

#[test]
fn the_committed_sky_exr_is_the_analytic_environment() {
    let got = illume_imageio::read_image(&example_dir("latlong").join("sky.exr")).unwrap();
    let want = sky_image(got.width, got.height);
    assert_eq!(
        (got.width, got.height, &got.channels),
        (128, 64, &want.channels)
    );
    let worst = got
        .data
        .iter()
        .zip(&want.data)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    // Float pixels: only f32 rounding of the same formula.
    assert!(worst < 1e-6, "sky.exr differs from (d + 1)/2 by {worst}");
}

#[test]
fn the_chrome_sphere_looks_up_the_analytic_colour_in_the_mirror_direction() {
    let dir = scratch("latlong");
    // The test's own analytic map (not the committed file), written where the RIB reads it.
    let float = illume_imageio::Quantize {
        one: 0,
        min: 0,
        max: 0,
        dither: 0.0,
    };
    illume_imageio::write_display(
        &dir.join("sky.exr"),
        "exr",
        &sky_image(128, 64),
        float,
        None,
    )
    .unwrap();
    let frames = run_rib(&rib_in("latlong", "latlong_single.rib", &dir));
    assert_eq!(frames.len(), 1);
    let img = &frames[0];
    let cam = camera();
    let mut checked = 0;
    let mut worst = 0.0f64;
    // A 5×5 grid of pixels over the sphere's image (radius ≈ 52 px about the centre; the grid
    // reaches 40 px), each expected to show the analytic colour in its mirror direction through
    // Listing 9.5's envrad 100 sphere, averaged over the pixel filter (`gaussian 2 2`: weight
    // exp(−2(x² + y²)) over ±1 px, 9×9 points), since the direction sweeps fast near the rim.
    for gy in -2..=2 {
        for gx in -2..=2 {
            let (x, y) = ((RES / 2) as i64 + 14 * gx, (RES / 2) as i64 + 14 * gy);
            let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
            let mut sum = DVec3::ZERO;
            let mut weights = 0.0;
            let mut r_centre = DVec3::ZERO;
            for j in -4..=4 {
                for i in -4..=4 {
                    let (dx, dy) = (f64::from(i) / 4.0, f64::from(j) / 4.0);
                    let d = cam.ray(cx + dx, cy + dy);
                    let t = hit_sphere(cam.eye, d, DVec3::ZERO, 1.0)
                        .expect("grid pixels lie inside the sphere's image");
                    let p = cam.eye + t * d;
                    let r = reflect(d, p.normalize());
                    if (i, j) == (0, 0) {
                        r_centre = r;
                    }
                    let w = (-2.0 * (dx * dx + dy * dy)).exp();
                    sum += w * sky(environment_direction(p, r, 100.0));
                    weights += w;
                }
            }
            let (want, r) = (sum / weights, r_centre);
            let px = &img.rgba[(y as usize * RES + x as usize) * 4..][..4];
            let got = DVec3::new(px[0].into(), px[1].into(), px[2].into());
            let err = (got - want).abs().max_element();
            // 0.005: the map is a smooth function of direction; bilinear texel interpolation
            // errs by ~h²/8·|f''| ≈ 3e-4 (h = 2π/128), half-float texels by ≤ 5e-4, and the
            // lookup's own filter footprint blurs a nearly linear variation (second order). A
            // flipped or rotated map is wrong by tenths.
            assert!(
                err < 0.005,
                "pixel ({x}, {y}): mirror direction {r:?} expects {want:?}, rendered {got:?}"
            );
            worst = worst.max(err);
            checked += 1;
        }
    }
    eprintln!("latlong: {checked} pixels checked, largest error {worst:.5}");
    assert_eq!(checked, 25);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn latlong_sh_and_render_single_rib_write_identical_files() {
    let Some(images) = run_both_forms(
        "latlong",
        "latlong_single.rib",
        "latlong.sh",
        &[["latlong_single.tif", "latlong_script.tif"]],
    ) else {
        return;
    };
    let [single, script] = &images[0];
    assert_eq!((single.width, single.height), (128, 128));
    assert_same_image(single, script, "latlong_single.tif vs latlong_script.tif");
}
