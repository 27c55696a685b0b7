//! Writes the analytic lat-long environment of `rib/pipelines/latlong/`: every texel's colour is
//! `(d + 1) / 2` for the unit direction `d` at its centre, in RenderMan's lat-long orientation
//! (+z at the top row, `t = θ/π` from +z, `s = ½ + φ/2π` with `φ = atan2(y, x)`), so any
//! lookup's expected colour is known in closed form.
//!
//! ```sh
//! cargo run -p illume-texture --example latlong_sky -- rib/pipelines/latlong/sky.exr [width]
//! ```
//! (width defaults to 128; the height is half of it). Float RGB OpenEXR.
use illume_imageio::{write_display, Image, Quantize};
use std::f64::consts::PI;
use std::path::PathBuf;
use std::process::ExitCode;

/// `(d + 1) / 2` at the centre of texel (i, j) of a `w × h` lat-long image.
fn sky(i: u32, j: u32, w: u32, h: u32) -> [f32; 3] {
    let s = (f64::from(i) + 0.5) / f64::from(w);
    let t = (f64::from(j) + 0.5) / f64::from(h);
    let (phi, theta) = ((s - 0.5) * 2.0 * PI, t * PI);
    let d = [
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    ];
    d.map(|c| ((c + 1.0) / 2.0) as f32)
}

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let Some(out) = args.next().map(PathBuf::from) else {
        eprintln!("usage: latlong_sky OUT.exr [width]");
        return ExitCode::from(2);
    };
    let w: u32 = match args.next().map(|a| a.parse()) {
        None => 128,
        Some(Ok(w)) if w >= 2 && w % 2 == 0 => w,
        Some(_) => {
            eprintln!("latlong_sky: width must be an even number >= 2");
            return ExitCode::from(2);
        }
    };
    let h = w / 2;
    let mut img = Image::new(w, h, "rgb");
    for j in 0..h {
        for i in 0..w {
            let k = (j as usize * w as usize + i as usize) * 3;
            img.data[k..k + 3].copy_from_slice(&sky(i, j, w, h));
        }
    }
    let float = Quantize {
        one: 0,
        min: 0,
        max: 0,
        dither: 0.0,
    };
    match write_display(&out, "exr", &img, float, None) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("latlong_sky: {e}");
            ExitCode::from(1)
        }
    }
}
