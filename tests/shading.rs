//! Built-in shading through real RIB: chapter 9's closed forms per pixel (issue 5 item 7).
//!
//! Scene: an orthographic unit sphere, one `distantlight` shining along +z from the camera, so
//! at every point L = V = H = -z and N·L = N·H = cos θ = n_z. With jitter off the samples sit at
//! the stratum centres, and the box-filtered pixel is the mean of the closed form over exactly
//! those 16 positions: that mean, in f64, is the reference. Interior pixels only (object
//! radius < 0.9): near the silhouette a pixel is part background and the normal turns faster
//! than any finite ShadingRate follows. Threshold 1/255: one 8-bit code value.
use illume_render::{render, RenderSettings, Rendered};
mod support;

use support::frames;

const RES: u32 = 100;
const SPP: u32 = 4;

fn render_rib(rib: &str) -> Rendered {
    let frames = frames(rib, None);
    assert_eq!(frames.len(), 1);
    render(&frames[0], &RenderSettings::default())
}

fn sphere_scene(options: &str, surface: &str) -> String {
    format!(
        "Format {RES} {RES} 1\nScreenWindow -1.25 1.25 -1.25 1.25\nPixelSamples {SPP} {SPP}\n\
         PixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n{options}\n\
         WorldBegin\nLightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [0 0 0] \"to\" [0 0 1]\n\
         ShadingRate 0.25\nShadingInterpolation \"smooth\"\n{surface}\nTranslate 0 0 5\n\
         Sphere 1 -1 1 360\nWorldEnd\n"
    )
}

/// Largest |pixel − mean of `model(n_z)` over the pixel's samples| over interior pixels.
fn max_error(r: &Rendered, model: impl Fn(f64) -> f64) -> (f64, usize) {
    let scale = 2.5 / f64::from(RES); // object units per pixel
    let (mut worst, mut count) = (0.0f64, 0);
    for py in 0..RES {
        for px in 0..RES {
            let mut sum = 0.0;
            let mut interior = true;
            for j in 0..SPP {
                for i in 0..SPP {
                    let x = -1.25 + (f64::from(px) + (f64::from(i) + 0.5) / f64::from(SPP)) * scale;
                    let y = 1.25 - (f64::from(py) + (f64::from(j) + 0.5) / f64::from(SPP)) * scale;
                    let r2 = x * x + y * y;
                    interior &= r2 < 0.81;
                    sum += model((1.0 - r2).max(0.0).sqrt());
                }
            }
            if !interior {
                continue;
            }
            let expected = sum / f64::from(SPP * SPP);
            let got = f64::from(r.rgba[((py * RES + px) * 4) as usize]);
            worst = worst.max((got - expected).abs());
            count += 1;
        }
    }
    (worst, count)
}

#[test]
fn matte_sphere_equals_kd_cos_theta_per_pixel() {
    let r = render_rib(&sphere_scene(
        "",
        "Surface \"matte\" \"Ka\" [0] \"Kd\" [0.8]",
    ));
    let (err, n) = max_error(&r, |c| 0.8 * c);
    // π·0.9²·40² ≈ 4070 pixel centres lie inside; whole pixels inside are a little fewer.
    assert!(n > 3500, "only {n} interior pixels");
    eprintln!("matte: max error {err:.2e} over {n} interior pixels");
    assert!(err < 1.0 / 255.0, "max error {err}");
}

#[test]
fn plastic_sphere_equals_lambert_plus_blinn_under_both_specular_models() {
    // The default is PRMan's exponent 8/roughness (what BMRT, Aqsis and 3Delight use, and what
    // RIBs in the wild were tuned on); `"blinn"` selects the RI spec's 1/roughness.
    let plastic = "Surface \"plastic\" \"Ka\" [0] \"Kd\" [0.5] \"Ks\" [0.5] \"roughness\" [0.25]";
    let r = render_rib(&sphere_scene("", plastic));
    let (err, _) = max_error(&r, |c| 0.5 * c + 0.5 * c.powf(8.0 / 0.25));
    eprintln!("plastic (default = prman): max error {err:.2e}");
    assert!(err < 1.0 / 255.0, "default (prman): max error {err}");

    let blinn = "Option \"shading\" \"string specularmodel\" [\"blinn\"]";
    let r = render_rib(&sphere_scene(blinn, plastic));
    let (err, _) = max_error(&r, |c| 0.5 * c + 0.5 * c.powf(1.0 / 0.25));
    eprintln!("plastic (blinn): max error {err:.2e}");
    assert!(err < 1.0 / 255.0, "blinn: max error {err}");
    // The two models differ visibly, so the option really switched the exponent.
    let (diff, _) = max_error(&r, |c| 0.5 * c + 0.5 * c.powf(8.0 / 0.25));
    assert!(
        diff > 0.05,
        "blinn model indistinguishable from prman ({diff})"
    );
}

#[test]
fn oren_nayar_with_zero_roughness_equals_matte() {
    let r = render_rib(&sphere_scene(
        "",
        "Surface \"orennayar\" \"Ka\" [0] \"Kd\" [0.8] \"roughness\" [0]",
    ));
    let (err, _) = max_error(&r, |c| 0.8 * c);
    assert!(err < 1.0 / 255.0, "max error {err}");
}

#[test]
fn bumpy_with_a_constant_map_grows_the_sphere_by_km() {
    use illume_imageio::Image;
    use illume_texture::{make_texture, MakeOptions, TextureCache, WrapMode};
    let dir = std::env::temp_dir().join(format!("illume-bumpy-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let map = dir.join("one.tx");
    let one = Image {
        width: 8,
        height: 8,
        channels: vec!["y".into()],
        data: vec![1.0; 64],
    };
    // Periodic: a black border would fade the amplitude at the sphere's s and t seams.
    let opts = MakeOptions {
        wrap: [WrapMode::Periodic; 2],
        ..MakeOptions::default()
    };
    make_texture(&one, &map, &opts).unwrap();
    // Radius 1 displaced by Km·1 = 0.2 along N: an orthographic disc of radius 1.2.
    let rib = format!(
        "Format {RES} {RES} 1\nScreenWindow -1.5 1.5 -1.5 1.5\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\n\
         WorldBegin\nAttribute \"displacementbound\" \"sphere\" [0.25]\n\
         Displacement \"bumpy\" \"Km\" [0.2] \"texturename\" \"{}\"\nTranslate 0 0 5\n\
         Sphere 1 -1 1 360\nWorldEnd\n",
        map.display()
    );
    let frames = frames(&rib, None);
    let cache = TextureCache::new(1 << 22);
    let settings = RenderSettings {
        textures: Some(&cache),
        ..RenderSettings::default()
    };
    let r = render(&frames[0], &settings);
    let px_per_unit = f64::from(RES) / 3.0;
    let area: f64 =
        r.rgba.chunks_exact(4).map(|p| f64::from(p[3])).sum::<f64>() / (px_per_unit * px_per_unit);
    let expected = std::f64::consts::PI * 1.2 * 1.2;
    assert!(
        (area - expected).abs() / expected < 0.01,
        "area {area}, expected {expected}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
