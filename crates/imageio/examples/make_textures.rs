//! Writes the project's own source images in `textures/` (README there says what each is for):
//!
//! * `checker.tif`: 256×256 RGB, four quadrants labelled with where they sit in RenderMan's
//!   texture coordinates: `s0t0` (s < ½, t < ½: the image's top-left, red), `s1t0` (top-right,
//!   green), `s0t1` (bottom-left, blue), `s1t1` (bottom-right, yellow); each an 8×8 checker of
//!   its colour and a darker shade, the label black on white. The letters are not symmetric, so
//!   a flipped or rotated lookup shows.
//! * `brick.tif`: 256×256 RGB running-bond bricks (64×32, 4-pixel mortar), periodic in s and t.
//! * `sky.exr`: 256×128 float RGB lat-long sky (RenderMan's orientation: +z at the top row,
//!   `t = θ/π`, `s = ½ + φ/2π`): a blue gradient above the horizon, brown ground below, and a
//!   sun of radiance 40 (HDR) at 35° elevation, φ = 60°.
//! * `bump.tif`: 256×256 grayscale heights: a 4×4 grid of smooth round domes (cos²), 0 between
//!   them and 1 at their tops, periodic, for `bumpy`.
//!
//! Every value is a closed form of the texel centre, so the files are rerunnable bit for bit
//! (8-bit files are written without dither).
//!
//! ```sh
//! cargo run -p illume-imageio --example make_textures -- textures
//! ```
use illume_imageio::{write_display, Image, Quantize};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// 8-bit, no dither: the written bytes are `round(255 v)`.
pub const EIGHT_BIT: Quantize = Quantize {
    one: 255,
    min: 0,
    max: 255,
    dither: 0.0,
};
pub const FLOAT: Quantize = Quantize {
    one: 0,
    min: 0,
    max: 0,
    dither: 0.0,
};

/// One image to write: file name, display type, pixels, quantization.
pub struct SourceImage {
    pub name: &'static str,
    pub kind: &'static str,
    pub image: Image,
    pub quantize: Quantize,
}

/// 5×7 glyphs (rows top to bottom, `#` set) for the quadrant labels.
fn glyph(c: char) -> [&'static str; 7] {
    match c {
        's' => [
            ".....", ".....", ".####", "#....", ".###.", "....#", "####.",
        ],
        't' => [
            ".#...", ".#...", "####.", ".#...", ".#...", ".#..#", "..##.",
        ],
        '0' => [
            ".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###.",
        ],
        _ => [
            "..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###.",
        ],
    }
}

fn image(w: u32, h: u32, mode: &str, f: impl Fn(u32, u32) -> Vec<f32>) -> Image {
    let mut img = Image::new(w, h, mode);
    let nc = mode.len();
    for y in 0..h {
        for x in 0..w {
            let k = (y as usize * w as usize + x as usize) * nc;
            img.data[k..k + nc].copy_from_slice(&f(x, y));
        }
    }
    img
}

/// Label pixel test: is (x, y), relative to a label's top-left, inside a glyph stroke?
fn label_ink(text: &str, scale: u32, x: u32, y: u32) -> bool {
    let (col, row) = (x / scale, y / scale);
    let (k, gx) = ((col / 6) as usize, col % 6);
    let Some(c) = text.chars().nth(k) else {
        return false;
    };
    row < 7 && gx < 5 && glyph(c)[row as usize].as_bytes()[gx as usize] == b'#'
}

pub fn checker() -> Image {
    const N: u32 = 256;
    const SCALE: u32 = 4;
    let colours = [
        ("s0t0", [0.85, 0.15, 0.1]),
        ("s1t0", [0.15, 0.7, 0.2]),
        ("s0t1", [0.15, 0.3, 0.9]),
        ("s1t1", [0.95, 0.85, 0.15]),
    ];
    // Label box: 4 glyphs of 6 columns (last gap dropped) by 7 rows, plus a 2-glyph-pixel margin.
    let (lw, lh) = ((4 * 6 - 1) * SCALE, 7 * SCALE);
    let margin = 2 * SCALE;
    image(N, N, "rgb", |x, y| {
        let half = N / 2;
        let q = (usize::from(y >= half) << 1) | usize::from(x >= half);
        let (text, c) = colours[q];
        let (qx, qy) = (x % half, y % half);
        let (x0, y0) = ((half - lw) / 2, (half - lh) / 2);
        let in_box = qx + margin >= x0
            && qx < x0 + lw + margin
            && qy + margin >= y0
            && qy < y0 + lh + margin;
        if in_box {
            let ink = qx >= x0 && qy >= y0 && label_ink(text, SCALE, qx - x0, qy - y0);
            return vec![if ink { 0.0 } else { 1.0 }; 3];
        }
        let dark = ((qx / 16) + (qy / 16)) % 2 == 1;
        c.iter()
            .map(|&v: &f32| if dark { v * 0.45 } else { v })
            .collect()
    })
}

/// Integer hash of a brick's row and column: its colour variation, fixed forever.
fn brick_shade(col: u32, row: u32) -> f32 {
    let h = (col.wrapping_mul(73_856_093) ^ row.wrapping_mul(19_349_663)) % 1000;
    0.85 + 0.3 * h as f32 / 1000.0
}

pub fn brick() -> Image {
    const N: u32 = 256;
    const BW: u32 = 64;
    const BH: u32 = 32;
    const MORTAR: u32 = 4;
    image(N, N, "rgb", |x, y| {
        let row = y / BH;
        let xs = (x + if row % 2 == 1 { BW / 2 } else { 0 }) % N;
        let (col, bx, by) = (xs / BW, xs % BW, y % BH);
        if bx < MORTAR || by < MORTAR {
            return vec![0.78, 0.76, 0.72];
        }
        let k = brick_shade(col, row);
        vec![0.62 * k, 0.25 * k, 0.16 * k]
    })
}

/// The sky's radiance in direction `d` (unit, +z up).
fn sky_radiance(d: [f64; 3]) -> [f64; 3] {
    let (elevation, azimuth) = (35f64.to_radians(), 60f64.to_radians());
    let sun = [
        elevation.cos() * azimuth.cos(),
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
    ];
    let cos_sun = d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2];
    // Sun disk of 4° radius (large enough to show at 256×128).
    if cos_sun > 4f64.to_radians().cos() {
        return [40.0, 38.0, 34.0];
    }
    if d[2] < 0.0 {
        return [0.25, 0.2, 0.15];
    }
    let up = d[2];
    let glow = 0.6 * cos_sun.max(0.0).powi(8);
    [
        0.85 - 0.6 * up + glow,
        0.9 - 0.45 * up + glow,
        1.0 - 0.1 * up + 0.8 * glow,
    ]
}

pub fn sky() -> Image {
    let (w, h) = (256u32, 128u32);
    image(w, h, "rgb", |x, y| {
        let s = (f64::from(x) + 0.5) / f64::from(w);
        let t = (f64::from(y) + 0.5) / f64::from(h);
        let (phi, theta) = ((s - 0.5) * 2.0 * PI, t * PI);
        let d = [
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ];
        sky_radiance(d).iter().map(|&v| v as f32).collect()
    })
}

pub fn bump() -> Image {
    const N: u32 = 256;
    const CELL: f64 = 64.0;
    image(N, N, "r", |x, y| {
        let cx = (f64::from(x % 64) + 0.5) / CELL - 0.5;
        let cy = (f64::from(y % 64) + 0.5) / CELL - 0.5;
        let r = (cx * cx + cy * cy).sqrt() / 0.4;
        let height = if r < 1.0 {
            (r * PI / 2.0).cos().powi(2)
        } else {
            0.0
        };
        vec![height as f32]
    })
}

pub fn all() -> Vec<SourceImage> {
    vec![
        SourceImage {
            name: "checker.tif",
            kind: "tiff",
            image: checker(),
            quantize: EIGHT_BIT,
        },
        SourceImage {
            name: "brick.tif",
            kind: "tiff",
            image: brick(),
            quantize: EIGHT_BIT,
        },
        SourceImage {
            name: "sky.exr",
            kind: "exr",
            image: sky(),
            quantize: FLOAT,
        },
        SourceImage {
            name: "bump.tif",
            kind: "tiff",
            image: bump(),
            quantize: EIGHT_BIT,
        },
    ]
}

pub fn write_all(dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for s in all() {
        write_display(&dir.join(s.name), s.kind, &s.image, s.quantize, None)
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}

#[allow(dead_code)]
fn main() -> ExitCode {
    let Some(dir) = std::env::args().nth(1).map(PathBuf::from) else {
        eprintln!("usage: make_textures DIR   (the repository's textures/)");
        return ExitCode::from(2);
    };
    match write_all(&dir) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("make_textures: {e}");
            ExitCode::from(1)
        }
    }
}
