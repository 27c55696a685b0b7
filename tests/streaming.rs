//! Streaming output (issue 21): `render_to_displays` writes each display while the frame
//! renders (TIFF strip by strip, the other kinds from one whole-frame buffer). Every file must
//! equal, byte for byte, the file `render` then `write_displays` writes from the whole image:
//! the streamed path may change when memory is used, never what is written.
use illume_render::{render, render_to_displays, write_displays, RenderSettings};
use std::path::Path;
mod support;

/// A lit scene with one display per kind and mode family, its files in `dir`.
fn scene(dir: &Path, extra: &str) -> String {
    let d = |name: &str| dir.join(name).display().to_string();
    format!(
        "Format 150 110 1\nPixelSamples 2 2\nOption \"limits\" \"bucketsize\" [16 8]\n\
         Display \"{}\" \"tiff\" \"rgba\"\nDisplay \"+{}\" \"tiff\" \"z\"\n\
         Display \"+{}\" \"tiff\" \"rgbaz\"\nDisplay \"+{}\" \"tiff\" \"Cs\"\n\
         Display \"+{}\" \"png\" \"rgba\"\nDisplay \"+{}\" \"openexr\" \"rgba,N\"\n\
         Display \"+{}\" \"zfile\" \"z\"\n{extra}\n\
         Projection \"perspective\" \"fov\" [40]\nWorldBegin\n\
         LightSource \"distantlight\" 1 \"from\" [0 1 -1] \"to\" [0 0 0]\n\
         Surface \"plastic\"\nColor [0.8 0.4 0.2]\nTranslate 0 0 5\nSphere 1 -1 1 360\n\
         Translate 0.8 0.3 1\nColor [0.2 0.5 0.9]\nSphere 0.8 -0.8 0.8 360\nWorldEnd\n",
        d("a.tif"),
        d("z.tif"),
        d("rgbaz.tif"),
        d("cs.tif"),
        d("a.png"),
        d("n.exr"),
        d("d.zfile"),
    )
}

/// `rib` with a displacement farther than its `displacementbound` on its surfaces: the hider
/// renders such a frame again (the displacement-bound loop).
fn overflowing(rib: String) -> String {
    rib.replace(
        "Surface \"plastic\"",
        "Surface \"plastic\"\nAttribute \"displacementbound\" \"sphere\" [0.01]\n\
         Displacement \"ripple\" \"Km\" [0] \"frequency\" [0] \"offset\" [0.3]",
    )
}

/// Fails unless the render went through the displacement-bound loop.
fn assert_overflows(r: &illume_render::Rendered) {
    assert!(
        r.warnings
            .iter()
            .any(|w| w.message.contains("re-rendering")),
        "the scene must overflow its bound: {:?}",
        r.warnings
    );
}

/// Writes `rib`'s frame both ways (into `dir/whole` and `dir/streamed`) and compares every file.
/// The streamed side runs on `threads` threads, which must not change a byte.
fn same_files_both_ways(
    dir: &Path,
    rib: impl Fn(&Path) -> String,
    crop: Option<[f32; 4]>,
    threads: usize,
) {
    let (whole, streamed) = (dir.join("whole"), dir.join("streamed"));
    for d in [&whole, &streamed] {
        std::fs::create_dir_all(d).unwrap();
    }
    let frame = &support::frames(&rib(&whole), crop)[0];
    let r = render(frame, &RenderSettings::default());
    for w in write_displays(frame, &r) {
        w.unwrap();
    }
    let frame = &support::frames(&rib(&streamed), crop)[0];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let (report, written) = pool.install(|| render_to_displays(frame, &RenderSettings::default()));
    assert_eq!(
        report.warnings.len(),
        r.warnings.len(),
        "{:?}",
        report.warnings
    );
    assert_eq!(written.len(), 7);
    for w in written {
        let w = w.unwrap();
        let name = w.path.file_name().unwrap().to_owned();
        let a = std::fs::read(whole.join(&name)).unwrap();
        let b = std::fs::read(&w.path).unwrap();
        assert!(
            a == b,
            "{name:?} differs ({} vs {} bytes)",
            a.len(),
            b.len()
        );
    }
    // Nothing left under a temporary name.
    for entry in std::fs::read_dir(&streamed).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.contains("illume-tmp"), "left behind: {name}");
    }
}

#[test]
fn streamed_displays_equal_the_whole_image_files_byte_for_byte() {
    let dir = std::env::temp_dir().join(format!("illume-stream-{}", std::process::id()));
    for threads in [1, 3] {
        let dir = dir.join(threads.to_string());
        same_files_both_ways(&dir.join("full"), |d| scene(d, ""), None, threads);
        // A crop window: rows start below the frame's top, dither is keyed on full-frame pixels.
        same_files_both_ways(
            &dir.join("crop"),
            |d| scene(d, "Exposure 1.5 2.2"),
            Some([0.13, 0.71, 0.21, 0.9]),
            threads,
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A frame so wide that a band of rows (8 rows here) is over the hider's budget for holding it
/// while the next band renders (1 MiB: 7000 × 8 pixels of RGBA and depth alone are 1.1 MB) is
/// written band by band as each is done: the same bytes as the overlapped small frames above.
#[test]
fn a_wide_frame_written_band_by_band_streams_the_same_files() {
    let dir = std::env::temp_dir().join(format!("illume-stream-wide-{}", std::process::id()));
    let rib = |d: &Path| scene(d, "").replace("Format 150 110 1", "Format 7000 16 1");
    same_files_both_ways(&dir, rib, None, 2);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A displacement larger than its bound makes the hider render the frame again; the streamed
/// files of the first pass are dropped and the second pass's rows written instead.
#[test]
fn a_pass_that_starts_over_streams_the_final_image() {
    let dir = std::env::temp_dir().join(format!("illume-stream-disp-{}", std::process::id()));
    let rib = |d: &Path| overflowing(scene(d, ""));
    let frame = &support::frames(&rib(&dir.join("probe")), None)[0];
    assert_overflows(&render(frame, &RenderSettings::default()));
    same_files_both_ways(&dir, rib, None, 3);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A frame so wide that the hider renders it in column blocks (1024 pixels wide, each refined
/// band after band without refining ahead: holding the next band's pieces would cost too much)
/// gives the pixels that a narrower crop window of it gives, rendered as one block whose bands
/// are refined ahead, with spheres on the block borders at x = 3072 and 4096 (their grids are
/// diced in both blocks): blocks and refining ahead change when pieces and grids are made,
/// never which or what they shade.
#[test]
fn column_blocks_and_refining_ahead_give_the_pixels_of_one_crop_window() {
    // Spheres at camera z = 5 whose centres project to raster x = 3072 and 4096 (and two
    // more at 1024 and 2048): x_cam = (x − 3500) / 24 · 5·tan 20°.
    let at = |x: f64| (x - 3500.0) / 24.0 * 5.0 * 20f64.to_radians().tan();
    let spheres: String = [1024.0, 2048.0, 3072.0, 4096.0]
        .iter()
        .map(|&x| {
            format!(
                "AttributeBegin\nTranslate {} 0.3 5\nSphere 0.9 -0.9 0.9 360\nAttributeEnd\n",
                at(x)
            )
        })
        .collect();
    let rib = format!(
        "Format 7000 48 1\nPixelSamples 2 2\nOption \"limits\" \"bucketsize\" [16 8]\n\
         Projection \"perspective\" \"fov\" [40]\nWorldBegin\n\
         LightSource \"distantlight\" 1 \"from\" [0 1 -1] \"to\" [0 0 0]\n\
         Surface \"plastic\"\nColor [0.8 0.4 0.2]\n{spheres}WorldEnd\n"
    );
    let render_crop = |crop| render(&support::frames(&rib, crop)[0], &RenderSettings::default());
    let wide = render_crop(None);
    let narrow = render_crop(Some([0.4, 0.65, 0.0, 1.0]));
    assert_eq!((wide.width, wide.height), (7000, 48));
    assert!(
        narrow.x0 < 3050 && narrow.x0 + narrow.width > 4120,
        "{}",
        narrow.x0
    );
    // One block: at most `illume_reyes::BLOCKS_ABOVE` (2048) pixels wide.
    assert!(narrow.width <= 2048, "{}", narrow.width);
    for border in [3072, 4096] {
        let x = (border - narrow.x0) as usize;
        let covered = (0..narrow.height as usize)
            .filter(|y| narrow.rgba[4 * (y * narrow.width as usize + x) + 3] > 0.0)
            .count();
        assert!(
            covered > 10,
            "only {covered} pixels covered at x = {border}"
        );
    }
    for y in 0..narrow.height as usize {
        for x in 0..narrow.width as usize {
            let n = y * narrow.width as usize + x;
            let w = (y + (narrow.y0 - wide.y0) as usize) * wide.width as usize
                + x
                + (narrow.x0 - wide.x0) as usize;
            let bits = |v: &[f32]| v.iter().map(|c| c.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(&narrow.rgba[4 * n..4 * n + 4]),
                bits(&wide.rgba[4 * w..4 * w + 4]),
                "pixel ({x}, {y}) of the crop"
            );
            assert_eq!(narrow.z[n].to_bits(), wide.z[w].to_bits());
        }
    }
}

/// A window rendered in column blocks whose displacement leaves its bound is rendered again in
/// full-width bands: the streamed tiled TIFF then takes whole rows of tiles, and reads back as
/// the file written from the whole image (the tiles in another order, the same pixels).
#[test]
fn a_wide_pass_that_starts_over_streams_the_same_pixels() {
    let dir = std::env::temp_dir().join(format!("illume-stream-wide-disp-{}", std::process::id()));
    let rib = |d: &Path| overflowing(scene(d, "").replace("Format 150 110 1", "Format 2200 40 1"));
    let (whole, streamed) = (dir.join("whole"), dir.join("streamed"));
    for d in [&whole, &streamed] {
        std::fs::create_dir_all(d).unwrap();
    }
    let frame = &support::frames(&rib(&whole), None)[0];
    let r = render(frame, &RenderSettings::default());
    assert_overflows(&r);
    for w in write_displays(frame, &r) {
        w.unwrap();
    }
    let frame = &support::frames(&rib(&streamed), None)[0];
    let (_, written) = render_to_displays(frame, &RenderSettings::default());
    for w in written {
        let w = w.unwrap();
        let name = w.path.file_name().unwrap().to_owned();
        if !name.to_string_lossy().ends_with(".tif") {
            continue;
        }
        let a = illume_imageio::read_image(&whole.join(&name)).unwrap();
        let b = illume_imageio::read_image(&w.path).unwrap();
        assert_eq!(
            (a.width, a.height, &a.channels),
            (b.width, b.height, &b.channels)
        );
        assert!(
            a.data
                .iter()
                .zip(&b.data)
                .all(|(x, y)| x.to_bits() == y.to_bits()),
            "{name:?} reads back differently"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
