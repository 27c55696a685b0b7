//! Display write and read throughput on a 1920×1080 RGBA frame (plus its depth for zfile).
//! Run: `cargo run -p illume-imageio --example display_speed --profile test` (or `--release`).

use illume_imageio::*;
use std::time::Instant;

fn main() -> Result<(), ImageError> {
    let (w, h) = (1920u32, 1080u32);
    let mut image = Image::new(w, h, "rgba");
    for (i, v) in image.data.iter_mut().enumerate() {
        *v = ((i * 2654435761) % 1000) as f32 / 999.0 * 0.5 + (i % 4096) as f32 / 8192.0;
    }
    let mut depth_image = Image::new(w, h, "z");
    for (i, v) in depth_image.data.iter_mut().enumerate() {
        *v = 1.0 + (i % 1920) as f32 * 0.01;
    }
    let depth = DepthMatrices {
        world_to_screen: std::array::from_fn(|i| if i % 5 == 0 { 1.0 } else { 0.0 }),
        world_to_camera: std::array::from_fn(|i| if i % 5 == 0 { 1.0 } else { 0.0 }),
    };
    let dir = std::env::temp_dir().join(format!("illume-display-speed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| ImageError::Io {
        path: dir.display().to_string(),
        source: e,
    })?;
    let q16 = Quantize {
        one: 65535,
        min: 0,
        max: 65535,
        dither: 0.5,
    };
    let cases: [(&str, &str, Quantize, &Image); 7] = [
        ("tiff 8-bit", "tiff", Quantize::RGBA_DEFAULT, &image),
        ("tiff 16-bit", "tiff", q16, &image),
        ("tiff float", "tiff", Quantize::FLOAT, &image),
        ("png 8-bit", "png", Quantize::RGBA_DEFAULT, &image),
        ("exr half", "exr", Quantize::RGBA_DEFAULT, &image),
        ("exr float", "exr", Quantize::FLOAT, &image),
        ("zfile", "zfile", Quantize::FLOAT, &depth_image),
    ];
    let mpix = (w * h) as f64 / 1e6;
    println!(
        "{:<12} {:>10} {:>10} {:>10} {:>10}",
        "display", "write ms", "Mpix/s", "read ms", "MiB"
    );
    for (i, (name, kind, q, img)) in cases.iter().enumerate() {
        let path = dir.join(format!("frame{i}"));
        let t = Instant::now();
        write_display(&path, kind, img, *q, Some(&depth))?;
        let write = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let back = read_image(&path)?;
        let read = t.elapsed().as_secs_f64();
        assert_eq!(back.width, w);
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0) as f64 / 1048576.0;
        println!(
            "{:<12} {:>10.1} {:>10.1} {:>10.1} {:>10.2}",
            name,
            write * 1e3,
            mpix / write,
            read * 1e3,
            size
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
