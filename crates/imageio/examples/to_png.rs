//! Converts rendered images (TIFF, OpenEXR, PNG, …) to 8-bit RGB PNGs for the README gallery
//! (`docs/make_gallery.sh`), so the gallery needs no outside image tool. Alpha is dropped, not
//! composited (the renders are premultiplied over black already); no dither and no metadata, so
//! converting an unchanged image gives a byte-identical PNG.
//!
//! ```sh
//! cargo run -p illume-imageio --example to_png -- in.tif out.png [in2.tif out2.png …]
//! ```
use illume_imageio::{read_image, write_display, Image, Quantize};
use std::path::Path;
use std::process::ExitCode;

fn rgb(img: &Image) -> Result<Image, String> {
    let nc = img.channels.len();
    let index = |name: &str| img.channel_index(name);
    let channels = match (index("r"), index("g"), index("b"), index("y")) {
        (Some(r), Some(g), Some(b), _) => [r, g, b],
        (_, _, _, Some(y)) => [y; 3],
        _ if nc >= 1 => [0; 3],
        _ => return Err("image has no channels".into()),
    };
    let mut out = Image::new(img.width, img.height, "rgb");
    for (px, dst) in img.data.chunks_exact(nc).zip(out.data.chunks_exact_mut(3)) {
        for (d, &c) in dst.iter_mut().zip(&channels) {
            *d = px[c];
        }
    }
    Ok(out)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.is_empty() || args.len() % 2 != 0 {
        eprintln!("usage: to_png IN OUT.png [IN OUT.png …]");
        return ExitCode::from(2);
    }
    let eight_bit = Quantize {
        dither: 0.0,
        ..Quantize::RGBA_DEFAULT
    };
    let mut failed = false;
    for pair in args.chunks_exact(2) {
        let result = read_image(Path::new(&pair[0]))
            .map_err(|e| e.to_string())
            .and_then(|img| rgb(&img))
            .and_then(|img| {
                write_display(Path::new(&pair[1]), "png", &img, eight_bit, None)
                    .map_err(|e| e.to_string())
            });
        if let Err(e) = result {
            eprintln!("to_png: {}: {e}", pair[0]);
            failed = true;
        }
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
