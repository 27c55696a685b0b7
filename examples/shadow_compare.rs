//! Ray-traced vs shadow-map shadows on one scene with a closed-form answer (issue 9 item 4):
//! a sphere on a plane under a distant light (the scene of `tests/raytrace.rs`). For each
//! setting it prints the render time and the error against the analytic ellipse: pixels
//! whose shadow/lit class differs from the f64 closed form, all of them and those farther
//! than 1 px from the analytic boundary.
//!
//! `cargo run --release --example shadow_compare` (a few seconds; times include the depth
//! pass for maps).
use glam::{DMat4, DVec3};
use illume_render::{render, write_displays, RenderSettings, Rendered};
use illume_ri::{from_rib_diagnostic, Ri};
use std::time::Instant;

const RES: u32 = 200;
const PX: f64 = 50.0;
const SPHERE_R: f64 = 0.8;
const HEIGHT: f64 = 1.5;
const D: [f64; 3] = [0.5, 0.3, 1.0];

fn run_rib(rib: &str) -> Vec<Rendered> {
    let mut ri = Ri::new();
    ri.set_texture_maker(Box::new(|req, _| {
        illume_texture::make_from_request(req)
            .map(|_| ())
            .map_err(|e| e.to_string())
    }));
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "x.rib");
    let mut out = Vec::new();
    let go = |ri: &mut Ri, out: &mut Vec<Rendered>| {
        for d in ri.drain_diagnostics() {
            eprintln!("{d}");
        }
        for frame in ri.take_frames() {
            let cache =
                illume_texture::TextureCache::new(frame.options.texture_memory as usize * 1024);
            let r = render(
                &frame,
                &RenderSettings {
                    progress: None,
                    textures: Some(&cache),
                },
            );
            for w in write_displays(&frame, &r) {
                w.expect("display");
            }
            out.push(r);
        }
    };
    for item in parser {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
        go(&mut ri, &mut out);
    }
    ri.finish();
    go(&mut ri, &mut out);
    out
}

fn world() -> String {
    format!(
        "Translate 0 0 10\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\nPolygon \"P\" [-2.2 -2.2 0  2.2 -2.2 0  2.2 2.2 0  -2.2 2.2 0]\n\
         AttributeBegin\nTranslate 0 0 {}\nSphere {SPHERE_R} -{SPHERE_R} {SPHERE_R} 360\nAttributeEnd\n",
        -HEIGHT
    )
}

fn beauty(light: &str) -> String {
    format!(
        "FrameBegin 2\nFormat {RES} {RES} 1\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n\
         PixelSamples 1 1\nPixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         WorldBegin\nAttributeBegin\n{light}\nAttributeEnd\nIlluminate 1 1\n\
         ShadingRate 0.25\n{}WorldEnd\nFrameEnd\n",
        world()
    )
}

/// The chapter's depth pass from the light (orthographic for a distant light), `n`² pixels.
fn depth_pass(n: u32, map: &str) -> String {
    let dir = DVec3::from(D).normalize();
    // The scenes' world space is the beauty camera's: the objects sit 10 units along +z.
    let centre = DVec3::new(0.0, 0.0, 10.0 - HEIGHT);
    // Left-handed light camera: +z along the light, +y up, +x right.
    let eye = centre - dir * 6.0;
    let x = DVec3::Y.cross(dir).normalize();
    let y = dir.cross(x);
    let camera_from_world = DMat4::from_cols(
        glam::DVec4::new(x.x, y.x, dir.x, 0.0),
        glam::DVec4::new(x.y, y.y, dir.y, 0.0),
        glam::DVec4::new(x.z, y.z, dir.z, 0.0),
        glam::DVec4::new(-x.dot(eye), -y.dot(eye), -dir.dot(eye), 1.0),
    );
    let m: Vec<String> = camera_from_world
        .to_cols_array()
        .iter()
        .map(|v| format!("{v}"))
        .collect();
    format!(
        "FrameBegin 1\nFormat {n} {n} 1\nPixelSamples 1 1\nPixelFilter \"box\" 1 1\n\
         Hider \"hidden\" \"jitter\" [0]\nDisplay \"{map}\" \"shadow\" \"z\"\nShadingRate 4\n\
         Projection \"orthographic\"\nScreenWindow -3.2 3.2 -3.2 3.2\nTransform [{}]\n\
         WorldBegin\nSurface \"null\"\n{}WorldEnd\nFrameEnd\n",
        m.join(" "),
        world().replace("Surface \"matte\" \"Ka\" [0] \"Kd\" [1]\n", "")
    )
}

fn in_shadow(x: f64, y: f64) -> bool {
    let (gx, gy) = (x / PX - 2.0, 2.0 - y / PX);
    let d = -DVec3::from(D).normalize();
    let oc = DVec3::new(-gx, -gy, -HEIGHT);
    let t = oc.dot(d);
    t > 0.0 && oc.length_squared() - t * t < SPHERE_R * SPHERE_R
}

fn errors(r: &Rendered) -> (usize, usize) {
    let lit = D[2] / DVec3::from(D).length();
    let (mut all, mut far) = (0, 0);
    for y in 0..RES {
        for x in 0..RES {
            let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            let (gx, gy) = (cx / PX - 2.0, 2.0 - cy / PX);
            if (gx * gx + gy * gy).sqrt() < SPHERE_R + 1.5 / PX {
                continue;
            }
            let got = f64::from(r.rgba[((y * RES + x) * 4) as usize]) < 0.5 * lit;
            let want = in_shadow(cx, cy);
            if got != want {
                all += 1;
                let near = (0..16).any(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 16.0;
                    in_shadow(cx + a.cos(), cy + a.sin()) != want
                });
                far += usize::from(!near);
            }
        }
    }
    (all, far)
}

fn main() {
    let dir = std::env::temp_dir().join(format!("illume_shadow_compare_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    let [dx, dy, dz] = D;
    println!("| shadows | setting | time (s) | mismatched px | beyond 1 px |");
    println!("|---|---|---|---|---|");
    for (samples, blur) in [(1, 0.0), (16, 0.002)] {
        let light = format!(
            "LightSource \"shadowdistant\" 1 \"from\" [0 0 0] \"to\" [{dx} {dy} {dz}] \
             \"shadowname\" [\"raytrace\"] \"samples\" [{samples}] \"blur\" [{blur}]"
        );
        let t = Instant::now();
        let r = run_rib(&beauty(&light));
        let secs = t.elapsed().as_secs_f64();
        let (all, far) = errors(&r[0]);
        println!("| ray traced | samples {samples}, blur {blur} | {secs:.3} | {all} | {far} |");
    }
    for n in [256u32, 512, 1024, 2048] {
        for (samples, bias) in [(16, 0.02), (16, 0.005)] {
            let map = dir.join(format!("d{n}.sm"));
            let map = map.to_string_lossy();
            let light = format!(
                "LightSource \"shadowdistant\" 1 \"from\" [0 0 0] \"to\" [{dx} {dy} {dz}] \
                 \"shadowname\" [\"{map}\"] \"samples\" [{samples}] \"blur\" [0] \"bias\" [{bias}]"
            );
            let t = Instant::now();
            let r = run_rib(&(depth_pass(n, &map) + &beauty(&light)));
            let secs = t.elapsed().as_secs_f64();
            for w in &r[1].warnings {
                eprintln!("{w}");
            }
            let (all, far) = errors(&r[1]);
            println!(
                "| shadow map | {n}², samples {samples}, bias {bias} | {secs:.3} | {all} | {far} |"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
