//! Small seeds for each target, made in-process (no corpus in the repository): the repository's
//! small RIBs (ASCII, binary and gzip) and shaders, and pictures and textures written by our own
//! writers at a few bytes' size, so mutations reach every reader's header, tables and data.
use illume_imageio::{write_display, DepthMatrices, Image, Quantize};
use illume_texture::{make_latlong_environment, make_shadow, make_texture, MakeOptions};
use illume_texture::{PixelFormat, WrapMode};
use std::path::{Path, PathBuf};

/// A named input.
pub type Seed = (String, Vec<u8>);

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Files under `dir` (recursively) with extension `ext` and at most `max` bytes, sorted.
fn files(dir: &Path, ext: &str, max: u64) -> Vec<Seed> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display())) {
            let path = entry.expect("directory entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == ext)
                && path.metadata().is_ok_and(|m| m.len() <= max)
            {
                let name = path.strip_prefix(repo()).unwrap_or(&path);
                let bytes = std::fs::read(&path).expect("readable seed");
                out.push((name.to_string_lossy().into_owned(), bytes));
            }
        }
    }
    out.sort();
    out
}

/// The repository's RIBs of at most `max` bytes (rib/ and the golden scenes).
pub fn ribs(max: u64) -> Vec<Seed> {
    let mut out = files(&repo().join("rib"), "rib", max);
    out.extend(files(&repo().join("tests/golden"), "rib", max));
    assert!(out.len() >= 5, "expected the repository's small RIBs");
    out
}

/// `rib` re-encoded as binary RIB (Appendix C), through the parser and the binary writer.
pub fn binary_rib(rib: &[u8]) -> Vec<u8> {
    let mut w = illume_rib::BinaryWriter::new(Vec::new());
    for r in illume_rib::Parser::new(rib, "seed.rib").flatten() {
        w.write(&r.value).expect("in memory");
    }
    w.into_inner()
}

/// CRC-32 (IEEE, reflected), as gzip's trailer needs it.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = (crc >> 1) ^ (0xEDB8_8320 & (crc & 1).wrapping_neg());
        }
    }
    !crc
}

/// `data` as a gzip member of stored (uncompressed) deflate blocks: RFC 1951/1952 by hand, so
/// the gzip path has seeds without a compressor.
pub fn gzip_stored(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x1f, 0x8b, 8, 0, 0, 0, 0, 0, 0, 0xff];
    let mut chunks = data.chunks(0xffff).peekable();
    if chunks.peek().is_none() {
        out.extend([1, 0, 0, 0xff, 0xff]);
    }
    while let Some(chunk) = chunks.next() {
        let len = chunk.len() as u16;
        out.push(u8::from(chunks.peek().is_none()));
        out.extend(len.to_le_bytes());
        out.extend((!len).to_le_bytes());
        out.extend(chunk);
    }
    out.extend(crc32(data).to_le_bytes());
    out.extend((data.len() as u32).to_le_bytes());
    out
}

/// The SL test shaders of at most `max` bytes.
pub fn shaders(max: u64) -> Vec<Seed> {
    let out = files(&repo().join("crates/sl/tests/shaders"), "sl", max);
    assert!(out.len() >= 5, "expected the SL test shaders");
    out
}

/// A small picture with distinct values in every sample.
fn picture(width: u32, height: u32, mode: &str) -> Image {
    let mut img = Image::new(width, height, mode);
    let n = img.data.len() as f32;
    for (i, v) in img.data.iter_mut().enumerate() {
        *v = i as f32 / n;
    }
    img
}

fn depth_matrices() -> DepthMatrices {
    let mut m = [0.0; 16];
    for i in 0..4 {
        m[i * 5] = 1.0;
    }
    DepthMatrices {
        world_to_screen: m,
        world_to_camera: m,
    }
}

/// Files our writers produce, in a scratch directory.
pub struct Pictures {
    dir: PathBuf,
}

impl Pictures {
    pub fn new(tag: &str) -> Self {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join("fuzz_smoke")
            .join(tag);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("scratch dir");
        Pictures { dir }
    }

    fn display(&self, name: &str, kind: &str, img: &Image, q: Quantize) -> Seed {
        let path = self.dir.join(name);
        let depth = depth_matrices();
        write_display(&path, kind, img, q, Some(&depth))
            .unwrap_or_else(|e| panic!("writing seed {name}: {e}"));
        (
            name.to_string(),
            std::fs::read(&path).expect("seed written"),
        )
    }

    /// TIFF seeds: 8-bit, 16-bit and float from our writer, and the repository's textures.
    pub fn tiffs(&self) -> Vec<Seed> {
        let sixteen = Quantize {
            one: 65535,
            min: 0,
            max: 65535,
            dither: 0.0,
        };
        let mut out = vec![
            self.display(
                "rgba8.tif",
                "tiff",
                &picture(5, 3, "rgba"),
                Quantize::default(),
            ),
            self.display("rgb16.tif", "tiff", &picture(3, 4, "rgb"), sixteen),
            self.display("float.tif", "tiff", &picture(4, 2, "rgba"), Quantize::FLOAT),
        ];
        out.extend(files(&repo().join("textures"), "tif", 16 << 10));
        out
    }

    pub fn pngs(&self) -> Vec<Seed> {
        let sixteen = Quantize {
            one: 65535,
            min: 0,
            max: 65535,
            dither: 0.0,
        };
        vec![
            self.display(
                "rgba8.png",
                "png",
                &picture(5, 3, "rgba"),
                Quantize::default(),
            ),
            self.display("rgb16.png", "png", &picture(3, 4, "rgb"), sixteen),
        ]
    }

    pub fn exrs(&self) -> Vec<Seed> {
        vec![
            self.display(
                "rgba.exr",
                "openexr",
                &picture(5, 3, "rgba"),
                Quantize::FLOAT,
            ),
            self.display(
                "rgbaz.exr",
                "openexr",
                &picture(2, 3, "rgbaz"),
                Quantize::FLOAT,
            ),
        ]
    }

    pub fn zfiles(&self) -> Vec<Seed> {
        vec![self.display("depth.z", "zfile", &picture(4, 3, "z"), Quantize::FLOAT)]
    }

    /// `.tx` (half and float), latlong environment and `.sm` files from the texture builders.
    pub fn textures(&self) -> Vec<Seed> {
        let img = picture(6, 4, "rgb");
        let float = MakeOptions {
            format: PixelFormat::Float,
            wrap: [WrapMode::Periodic, WrapMode::Clamp],
            ..MakeOptions::default()
        };
        let build = |name: &str, made: Result<(), illume_texture::TextureError>| -> Seed {
            made.unwrap_or_else(|e| panic!("building seed {name}: {e}"));
            let bytes = std::fs::read(self.dir.join(name)).expect("seed written");
            (name.to_string(), bytes)
        };
        let opts = MakeOptions::default();
        let at = |name: &str| self.dir.join(name);
        let depth = picture(4, 4, "z");
        vec![
            build("half.tx", make_texture(&img, &at("half.tx"), &opts)),
            build("float.tx", make_texture(&img, &at("float.tx"), &float)),
            build(
                "env.tx",
                make_latlong_environment(&img, &at("env.tx"), &opts),
            ),
            build(
                "shadow.sm",
                make_shadow(&depth, &depth_matrices(), &at("shadow.sm"), &opts),
            ),
        ]
    }
}
