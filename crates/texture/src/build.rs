//! Texture building: `MakeTexture`, `MakeCubeFaceEnvironment`, `MakeLatLongEnvironment`,
//! `MakeShadow` and `txmake`.
//!
//! Every builder writes the `.tx` container of [`crate::txfile`] with the attributes DESIGN.md
//! lists: `textureformat`, `wrapmodes`, `filter`, `source` (and `envmap` for environments,
//! `worldToCamera`/`worldToNDC` for shadows).

use crate::cubeface::{face_coords, face_direction, input_face_pixel, texel_to_coord, CubeFace};
use crate::filter::FilterKind;
use crate::mipmap::{build_pyramid, level_size, resample, Level, Resampler};
use crate::shadowmap::build_minmax;
use crate::txfile::{parse_compression, write_tx, PixelFormat};
use crate::wrapmode::{format_wrapmodes, WrapMode};
use crate::TextureError;
use exr::meta::attribute::{AttributeValue, EnvironmentMap, Text};
use glam::Vec3;
use illume_imageio::{DepthMatrices, Image};
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::Path;

/// `-resize`: how a non-power-of-two image is rescaled before mip-mapping.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resize {
    /// Keep the size (levels round down, OpenEXR style).
    None,
    /// Next power of two up.
    Up,
    /// Next power of two down.
    Down,
    /// Nearest power of two.
    Round,
}

impl Resize {
    /// Parses `up|down|round|none` and the `-` variants (`up-`, …), which differ in PRMan only in
    /// how non-square textures map s,t; here s,t always span the whole image, so both agree.
    pub fn parse(word: &str) -> Option<Resize> {
        Some(match word.trim_end_matches('-') {
            "none" => Resize::None,
            "up" => Resize::Up,
            "down" => Resize::Down,
            "round" => Resize::Round,
            _ => return None,
        })
    }

    fn apply(self, n: usize) -> usize {
        let up = n.next_power_of_two();
        let down = if up == n { n } else { up / 2 };
        match self {
            Resize::None => n,
            Resize::Up => up,
            Resize::Down => down.max(1),
            Resize::Round => {
                if n - down <= up - n {
                    down.max(1)
                } else {
                    up
                }
            }
        }
    }
}

/// Options shared by every builder (the `txmake` flags and the RIB Make* parameters).
#[derive(Clone, Debug, PartialEq)]
pub struct MakeOptions {
    /// s and t wrap modes (`-smode/-tmode`).
    pub wrap: [WrapMode; 2],
    pub resize: Resize,
    pub filter: FilterKind,
    /// Filter widths in destination pixels; `None` means the filter's default width.
    pub swidth: Option<f32>,
    pub twidth: Option<f32>,
    pub format: PixelFormat,
    /// OpenEXR compression name (`zip`, `piz`, `none`, …).
    pub compression: String,
    /// Cube face field of view in degrees (`-fov`, `MakeCubeFaceEnvironment … fov`).
    pub fov: f32,
    /// Recorded in the `source` attribute.
    pub source: String,
}

impl Default for MakeOptions {
    fn default() -> Self {
        MakeOptions {
            wrap: [WrapMode::Black; 2],
            resize: Resize::Up,
            filter: FilterKind::Box,
            swidth: None,
            twidth: None,
            format: PixelFormat::Half,
            compression: "zip".into(),
            fov: 90.0,
            source: String::new(),
        }
    }
}

impl MakeOptions {
    fn resampler(&self, wrap: [WrapMode; 2]) -> Resampler {
        Resampler {
            filter: self.filter,
            swidth: self.swidth.unwrap_or(self.filter.default_width()),
            twidth: self.twidth.unwrap_or(self.filter.default_width()),
            wrap,
        }
    }

    fn compression(&self, out: &Path) -> Result<exr::prelude::Compression, TextureError> {
        parse_compression(&self.compression).ok_or_else(|| TextureError::Format {
            path: out.display().to_string(),
            message: format!(
                "unknown compression `{}` (expected none, rle, zips, zip, piz, pxr24, b44, b44a)",
                self.compression
            ),
        })
    }

    fn base_attributes(
        &self,
        format: &str,
        wrap: [WrapMode; 2],
    ) -> Vec<(&'static str, AttributeValue)> {
        let r = self.resampler(wrap);
        vec![
            ("textureformat", AttributeValue::Text(Text::from(format))),
            (
                "wrapmodes",
                AttributeValue::Text(Text::from(format_wrapmodes(wrap).as_str())),
            ),
            (
                "filter",
                AttributeValue::Text(Text::from(
                    format!("{} {} {}", self.filter.name(), r.swidth, r.twidth).as_str(),
                )),
            ),
            (
                "source",
                AttributeValue::Text(Text::from(self.source.as_str())),
            ),
        ]
    }
}

/// Converts an imageio image into a level plus OpenEXR channel names (`R`,`G`,`B`,`A`,`Z`, or `Y`
/// for a single grey channel).
pub(crate) fn image_to_level(
    image: &Image,
    what: &Path,
) -> Result<(Level, Vec<String>), TextureError> {
    let nch = image.channels.len();
    let (w, h) = (image.width as usize, image.height as usize);
    if nch == 0 || w == 0 || h == 0 || image.data.len() != w * h * nch {
        return Err(TextureError::Format {
            path: what.display().to_string(),
            message: format!(
                "image {}x{} with channels {:?} has {} values, expected {}",
                w,
                h,
                image.channels,
                image.data.len(),
                w * h * nch
            ),
        });
    }
    let names = if nch == 1 && image.channels[0] != "z" {
        vec!["Y".to_string()]
    } else {
        image
            .channels
            .iter()
            .map(|c| c.to_ascii_uppercase())
            .collect()
    };
    Ok((
        Level {
            width: w,
            height: h,
            channels: nch,
            data: image.data.clone(),
        },
        names,
    ))
}

/// Level 0 resized as `-resize` says, then the filtered pyramid, all with `wrap` at the edges;
/// shared by the plain and lat-long builders (cube faces are filtered face by face instead).
fn resized_pyramid(
    input: &Image,
    out: &Path,
    opts: &MakeOptions,
    wrap: [WrapMode; 2],
) -> Result<(Vec<Level>, Vec<String>), TextureError> {
    let (mut level0, names) = image_to_level(input, out)?;
    let r = opts.resampler(wrap);
    let (w, h) = (
        opts.resize.apply(level0.width),
        opts.resize.apply(level0.height),
    );
    if (w, h) != (level0.width, level0.height) {
        level0 = resample(&level0, w, h, &r);
    }
    Ok((build_pyramid(level0, &r), names))
}

/// Builds a plain mip-mapped texture (`MakeTexture`, `txmake in out`).
pub fn make_texture(input: &Image, out: &Path, opts: &MakeOptions) -> Result<(), TextureError> {
    let (levels, names) = resized_pyramid(input, out, opts, opts.wrap)?;
    write_tx(
        out,
        &names,
        &levels,
        opts.format,
        opts.compression(out)?,
        opts.base_attributes("Plain Texture", opts.wrap),
    )
}

/// Builds a lat-long environment (`MakeLatLongEnvironment`, `txmake -envlatl`): periodic in s,
/// clamped in t; pixels stay in RenderMan orientation (see [`crate::latlong`]).
pub fn make_latlong_environment(
    input: &Image,
    out: &Path,
    opts: &MakeOptions,
) -> Result<(), TextureError> {
    let wrap = [WrapMode::Periodic, WrapMode::Clamp];
    let (levels, names) = resized_pyramid(input, out, opts, wrap)?;
    let mut attrs = opts.base_attributes("LatLong Environment", wrap);
    attrs.push((
        "envmap",
        AttributeValue::EnvironmentMap(EnvironmentMap::LatitudeLongitude),
    ));
    write_tx(
        out,
        &names,
        &levels,
        opts.format,
        opts.compression(out)?,
        attrs,
    )
}

/// Six faces of one cube level, each `n×n`, in OpenEXR face order.
pub(crate) struct CubeLevel {
    pub n: usize,
    pub channels: usize,
    pub faces: Vec<Level>,
}

impl CubeLevel {
    /// Bilinear sample of face `face` at face coordinates `(col,row)`, clamped to the face.
    pub fn bilinear(&self, face: CubeFace, col: f32, row: f32, out: &mut [f32]) {
        let f = &self.faces[face as usize];
        let n = self.n;
        let x = crate::cubeface::coord_to_texel(col, n).clamp(0.0, (n - 1) as f32);
        let y = crate::cubeface::coord_to_texel(row, n).clamp(0.0, (n - 1) as f32);
        let (x0, y0) = (x.floor() as usize, y.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(n - 1), (y0 + 1).min(n - 1));
        let (fx, fy) = (x - x0 as f32, y - y0 as f32);
        for (c, o) in out.iter_mut().enumerate().take(self.channels) {
            let a = f.texel(x0, y0)[c] * (1.0 - fx) + f.texel(x1, y0)[c] * fx;
            let b = f.texel(x0, y1)[c] * (1.0 - fx) + f.texel(x1, y1)[c] * fx;
            *o = a * (1.0 - fy) + b * fy;
        }
    }

    /// Bilinear sample of the direction `d`, on whichever face it hits.
    pub fn sample_dir(&self, d: Vec3, out: &mut [f32]) {
        let (face, col, row) = face_coords(d);
        self.bilinear(face, col, row, out);
    }

    /// Border texels of adjacent faces describe the same direction: make them bit-identical
    /// (their mean), so lookups are continuous across every edge and corner.
    fn weld_edges(&mut self) {
        let n = self.n;
        if n < 2 {
            return;
        }
        let c = self.channels;
        let mut groups: HashMap<[i64; 3], Vec<(usize, usize, usize)>> = HashMap::new();
        for face in CubeFace::ALL {
            for y in 0..n {
                for x in 0..n {
                    if x != 0 && y != 0 && x != n - 1 && y != n - 1 {
                        continue;
                    }
                    let d = face_direction(
                        face,
                        texel_to_coord(x as f32, n),
                        texel_to_coord(y as f32, n),
                    );
                    let key =
                        [d.x, d.y, d.z].map(|v| ((v + 1.0) * 0.5 * (n - 1) as f32).round() as i64);
                    groups.entry(key).or_default().push((face as usize, x, y));
                }
            }
        }
        for members in groups.values() {
            if members.len() < 2 {
                continue;
            }
            let mut sum = vec![0.0f64; c];
            for &(f, x, y) in members {
                for (s, v) in sum.iter_mut().zip(self.faces[f].texel(x, y)) {
                    *s += *v as f64;
                }
            }
            for &(f, x, y) in members {
                let i = (y * n + x) * c;
                for (k, s) in sum.iter().enumerate() {
                    self.faces[f].data[i + k] = (*s / members.len() as f64) as f32;
                }
            }
        }
    }

    /// The next coarser level: each texel filters the finer level around its own direction,
    /// reading across face edges, so no face's pyramid bleeds across an edge it doesn't share.
    fn reduce(&self, r: &Resampler) -> CubeLevel {
        let n = (self.n / 2).max(1);
        let c = self.channels;
        let s_src = 2.0 / (self.n.max(2) - 1) as f32;
        let s_dst = 2.0 / (n.max(2) - 1) as f32;
        let ratio = s_dst / s_src;
        let kx = (0.5 * r.swidth * ratio).ceil().max(1.0) as i32;
        let ky = (0.5 * r.twidth * ratio).ceil().max(1.0) as i32;
        let faces: Vec<Level> = CubeFace::ALL
            .par_iter()
            .map(|&face| {
                let mut out = Level::new(n, n, c);
                let mut tmp = vec![0.0f32; c];
                for y in 0..n {
                    for x in 0..n {
                        let (cu, cv) = (texel_to_coord(x as f32, n), texel_to_coord(y as f32, n));
                        let mut acc = vec![0.0f32; c];
                        let mut wsum = 0.0f32;
                        for j in -ky..ky {
                            let oy = (j as f32 + 0.5) * s_src;
                            let wy = r.filter.eval(oy / s_dst, r.twidth);
                            if wy == 0.0 {
                                continue;
                            }
                            for i in -kx..kx {
                                let ox = (i as f32 + 0.5) * s_src;
                                let wx = r.filter.eval(ox / s_dst, r.swidth);
                                if wx == 0.0 {
                                    continue;
                                }
                                let d = face_direction(face, cu + ox, cv + oy);
                                self.sample_dir(d, &mut tmp);
                                let wt = wx * wy;
                                for (a, t) in acc.iter_mut().zip(&tmp) {
                                    *a += wt * t;
                                }
                                wsum += wt;
                            }
                        }
                        let i0 = (y * n + x) * c;
                        for (o, a) in out.data[i0..i0 + c].iter_mut().zip(&acc) {
                            *o = if wsum != 0.0 { a / wsum } else { 0.0 };
                        }
                    }
                }
                out
            })
            .collect();
        let mut level = CubeLevel {
            n,
            channels: c,
            faces,
        };
        level.weld_edges();
        level
    }

    /// Stacks the faces vertically, OpenEXR order.
    fn stacked(&self) -> Level {
        let mut data = Vec::with_capacity(6 * self.n * self.n * self.channels);
        for f in &self.faces {
            data.extend_from_slice(&f.data);
        }
        Level {
            width: self.n,
            height: 6 * self.n,
            channels: self.channels,
            data,
        }
    }
}

/// Bilinear sample of an input face at continuous pixel coordinates (centres at `i+0.5`), clamped.
fn sample_input(l: &Level, x: f32, y: f32, out: &mut [f32]) {
    let x = (x - 0.5).clamp(0.0, (l.width - 1) as f32);
    let y = (y - 0.5).clamp(0.0, (l.height - 1) as f32);
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(l.width - 1), (y0 + 1).min(l.height - 1));
    let (fx, fy) = (x - x0 as f32, y - y0 as f32);
    for (c, o) in out.iter_mut().enumerate() {
        let a = l.texel(x0, y0)[c] * (1.0 - fx) + l.texel(x1, y0)[c] * fx;
        let b = l.texel(x0, y1)[c] * (1.0 - fx) + l.texel(x1, y1)[c] * fx;
        *o = a * (1.0 - fy) + b * fy;
    }
}

/// Builds the in-memory cube pyramid from Table 9.1 faces (used by the builder and by tests).
pub(crate) fn cube_pyramid(
    faces: [&Image; 6],
    out: &Path,
    opts: &MakeOptions,
) -> Result<(Vec<CubeLevel>, Vec<String>), TextureError> {
    let mut inputs = Vec::with_capacity(6);
    let mut names: Option<Vec<String>> = None;
    for (k, img) in faces.iter().enumerate() {
        let (l, n) = image_to_level(img, out)?;
        if let Some(prev) = &names {
            if *prev != n {
                return Err(TextureError::Format {
                    path: out.display().to_string(),
                    message: format!("cube face {k} has channels {n:?}, face 0 has {prev:?}"),
                });
            }
        }
        names = Some(n);
        inputs.push(l);
    }
    let names = names.unwrap_or_default();
    let c = inputs[0].channels;
    if !(opts.fov > 1.0 && opts.fov < 179.0) {
        return Err(TextureError::Format {
            path: out.display().to_string(),
            message: format!("cube face field of view {} is outside (1°, 179°)", opts.fov),
        });
    }
    // Face resolution: the part of the input covering exactly 90°, rounded to a power of two so
    // every face level has an integer size (OpenEXR's stacked round-down levels stay 6:1).
    let w_in = inputs
        .iter()
        .map(|l| l.width.max(l.height))
        .max()
        .unwrap_or(1);
    let covered = w_in as f32 / (0.5 * opts.fov.to_radians()).tan();
    let n = match opts.resize {
        Resize::Down => Resize::Down.apply(covered.round().max(2.0) as usize),
        Resize::Round => Resize::Round.apply(covered.round().max(2.0) as usize),
        _ => Resize::Up.apply(covered.round().max(2.0) as usize),
    }
    .max(2);
    let fov = opts.fov;
    let level0_faces: Vec<Level> = CubeFace::ALL
        .par_iter()
        .map(|&face| {
            let mut l = Level::new(n, n, c);
            let mut tmp = vec![0.0f32; c];
            for y in 0..n {
                for x in 0..n {
                    let d = face_direction(
                        face,
                        texel_to_coord(x as f32, n),
                        texel_to_coord(y as f32, n),
                    );
                    // The input face whose view axis is the major axis of d (same tie rule as lookups).
                    let k = match CubeFace::of(d) {
                        CubeFace::PosX => 0,
                        CubeFace::NegX => 1,
                        CubeFace::PosY => 2,
                        CubeFace::NegY => 3,
                        CubeFace::PosZ => 4,
                        CubeFace::NegZ => 5,
                    };
                    let src = &inputs[k];
                    if let Some((px, py)) = input_face_pixel(k, d, fov, src.width, src.height) {
                        sample_input(src, px, py, &mut tmp);
                    } else {
                        tmp.iter_mut().for_each(|v| *v = 0.0);
                    }
                    let i = (y * n + x) * c;
                    l.data[i..i + c].copy_from_slice(&tmp);
                }
            }
            l
        })
        .collect();
    let mut level = CubeLevel {
        n,
        channels: c,
        faces: level0_faces,
    };
    level.weld_edges();
    let r = opts.resampler([WrapMode::Clamp; 2]);
    let mut levels = vec![level];
    while levels.last().map(|l| l.n).unwrap_or(1) > 1 {
        let next = levels.last().map(|l| l.reduce(&r));
        if let Some(next) = next {
            levels.push(next);
        }
    }
    Ok((levels, names))
}

/// Builds a cube-face environment (`MakeCubeFaceEnvironment px nx py ny pz nz`, `txmake -envcube`)
/// from faces in Table 9.1's orientation, rendered with field of view `opts.fov` (≥ 90°; the
/// margin beyond 90° is used, not cropped away, so edge texels are interpolated, not clamped).
pub fn make_cube_face_environment(
    faces: [&Image; 6],
    out: &Path,
    opts: &MakeOptions,
) -> Result<(), TextureError> {
    let (cube, names) = cube_pyramid(faces, out, opts)?;
    let n0 = cube[0].n;
    let mut levels: Vec<Level> = cube.iter().map(|l| l.stacked()).collect();
    // OpenEXR's round-down levels of an n×6n image go two levels past the 1×1 faces (1×3, 1×1).
    let total = crate::mipmap::level_count(n0, 6 * n0);
    let r = opts.resampler([WrapMode::Clamp; 2]);
    while levels.len() < total {
        let l = levels.len();
        let prev = levels
            .last()
            .cloned()
            .unwrap_or_else(|| Level::new(1, 1, 1));
        levels.push(resample(
            &prev,
            level_size(n0, l),
            level_size(6 * n0, l),
            &r,
        ));
    }
    let mut attrs = opts.base_attributes("CubeFace Environment", [WrapMode::Clamp; 2]);
    attrs.push((
        "envmap",
        AttributeValue::EnvironmentMap(EnvironmentMap::Cube),
    ));
    write_tx(
        out,
        &names,
        &levels,
        opts.format,
        opts.compression(out)?,
        attrs,
    )
}

/// Converts the zfile's world→screen matrix to OpenEXR's worldToNDC: see
/// [`illume_core::spaces::world_to_ndc_from_np`], the one home of the conversion.
pub use illume_core::spaces::world_to_ndc_from_np as screen_to_ndc;

/// Builds a shadow map (`MakeShadow`, `txmake -shadow`): one float channel `Z` of light-camera
/// depths; coarser levels of `Z` hold the *minimum* depth under each texel and channel `Zmax`
/// the maximum, so wide lookups decide fully lit/fully shadowed regions without sampling.
pub fn make_shadow(
    depth: &Image,
    matrices: &DepthMatrices,
    out: &Path,
    opts: &MakeOptions,
) -> Result<(), TextureError> {
    let (level0, _) = image_to_level(depth, out)?;
    let zc = depth
        .channels
        .iter()
        .position(|c| c == "z")
        .unwrap_or(depth.channels.len() - 1);
    let mut z = Level::new(level0.width, level0.height, 1);
    for (i, v) in z.data.iter_mut().enumerate() {
        *v = level0.data[i * level0.channels + zc];
    }
    let levels = build_minmax(z);
    let mut attrs = opts.base_attributes("Shadow", [WrapMode::Clamp; 2]);
    attrs.push((
        "worldToCamera",
        AttributeValue::Matrix4x4(matrices.world_to_camera),
    ));
    attrs.push((
        "worldToNDC",
        AttributeValue::Matrix4x4(screen_to_ndc(&matrices.world_to_screen)),
    ));
    write_tx(
        out,
        &["Z".to_string(), "Zmax".to_string()],
        &levels,
        PixelFormat::Float,
        opts.compression(out)?,
        attrs,
    )
}
