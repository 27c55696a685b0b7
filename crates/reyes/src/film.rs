//! The film: what happens to composited samples on their way to pixels. Each bucket's samples
//! are filtered into a [`PixelBlock`] (pixel filter for colour, depth filter for `z`); the
//! blocks are pasted into the crop window's image and exposed (RI Spec 3.2 `RiExposure`).
//! Quantization and dithering are the displays' business (`illume-imageio`, through the
//! driver): the film hands over premultiplied float RGBA and depth.
//!
//! Why a stage of its own: streaming output (finished buckets written while others render) and
//! arbitrary output variables both extend what a bucket hands over, not how it is rendered.
use crate::filter::PixelFilter;
use illume_ri::{DepthFilter, Options};

/// One sample after visible-point compositing.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Composited {
    /// Premultiplied colour and alpha.
    pub rgba: [f32; 4],
    /// Depth of the nearest visible point (`f32::MAX` for none).
    pub z: f32,
    /// Halfway between the nearest and the second-nearest visible point (`depthfilter
    /// "midpoint"`; the nearest when there is one).
    pub z_mid: f32,
}

/// The samples of a bucket as the film sees them: a rectangle of pixels (grown by the
/// filter's reach) with `per_pixel` samples each, pixel by pixel, rows first.
pub(crate) struct SampleRegion<'s> {
    /// First pixel (x, y) and size (pixels) of the region.
    pub origin: [i32; 2],
    pub size: [usize; 2],
    pub per_pixel: usize,
    /// Raster position of each sample.
    pub pos: &'s [(f32, f32)],
}

/// One bucket's finished pixels: the unit streaming output and AOVs extend.
#[derive(Clone, Debug, Default)]
pub struct PixelBlock {
    /// Pixel rectangle x0 x1 y0 y1 (exclusive ends) in the full frame.
    pub rect: [u32; 4],
    /// Filtered premultiplied RGBA per pixel, top row first.
    pub rgba: Vec<[f32; 4]>,
    /// Camera-space depth per pixel after the depth filter (`f32::MAX` where nothing was hit).
    pub z: Vec<f32>,
    /// Filtered AOV records per pixel (`stride` floats each; empty without AOVs).
    pub aov: Vec<f32>,
}

/// The frame's film settings.
pub(crate) struct Film {
    pub filter: PixelFilter,
    depth_filter: DepthFilter,
    /// `RiExposure` gain and gamma.
    exposure: (f32, f32),
}

impl Film {
    pub fn new(opts: &Options) -> Film {
        Film {
            filter: PixelFilter::new(&opts.filter.0, opts.filter.1, opts.filter.2)
                .with_table(opts.filter_table.clone()),
            depth_filter: opts.depth_filter,
            exposure: opts.exposure,
        }
    }

    /// Filters the samples of `region` into the pixels of `rect` (x0 x1 y0 y1): colour by the
    /// pixel filter over every sample within its reach, depth by the depth filter over the
    /// pixel's own samples. `aov` holds `stride` composited AOV floats per sample, filtered
    /// with the same weights as the colour.
    pub fn develop(
        &self,
        rect: [u32; 4],
        region: &SampleRegion,
        samples: &[Composited],
        (aov, stride): (&[f32], usize),
    ) -> PixelBlock {
        let [px0, px1, py0, py1] = rect;
        let (rx, ry) = self.filter.radius();
        let [sx0, sy0] = region.origin;
        let [sw, sh] = region.size;
        let (sx1, sy1) = (sx0 + sw as i32, sy0 + sh as i32);
        let n_per = region.per_pixel;
        let pos = region.pos;
        let bw = (px1 - px0) as usize;
        let bh = (py1 - py0) as usize;
        let mut color = Vec::with_capacity(bw * bh);
        let mut depth = Vec::with_capacity(bw * bh);
        let mut aov_px = vec![0.0f32; bw * bh * stride];
        let mut aov_acc = vec![0.0f32; stride];
        for y in py0..py1 {
            for x in px0..px1 {
                let (cxp, cyp) = (x as f32 + 0.5, y as f32 + 0.5);
                let mut acc = [0.0f32; 4];
                let mut wsum = 0.0f32;
                aov_acc.fill(0.0);
                let qx0 = ((cxp - rx).floor() as i32).max(sx0);
                let qx1 = ((cxp + rx).floor() as i32).min(sx1 - 1);
                let qy0 = ((cyp - ry).floor() as i32).max(sy0);
                let qy1 = ((cyp + ry).floor() as i32).min(sy1 - 1);
                for qy in qy0..=qy1 {
                    for qx in qx0..=qx1 {
                        let base = (((qy - sy0) as usize) * sw + (qx - sx0) as usize) * n_per;
                        for s in base..base + n_per {
                            let (sxp, syp) = pos[s];
                            let w = self.filter.weight(sxp - cxp, syp - cyp);
                            if w != 0.0 {
                                wsum += w;
                                for (a, v) in acc.iter_mut().zip(samples[s].rgba) {
                                    *a += w * v;
                                }
                                let rec = &aov[s * stride..(s + 1) * stride];
                                for (a, v) in aov_acc.iter_mut().zip(rec) {
                                    *a += w * v;
                                }
                            }
                        }
                    }
                }
                if wsum != 0.0 {
                    acc = acc.map(|v| v / wsum);
                    aov_acc.iter_mut().for_each(|v| *v /= wsum);
                }
                color.push(acc);
                let k = color.len() - 1;
                aov_px[k * stride..(k + 1) * stride].copy_from_slice(&aov_acc);
                let base = (((y as i32 - sy0) as usize) * sw + (x as i32 - sx0) as usize) * n_per;
                depth.push(self.depth(&samples[base..base + n_per]));
            }
        }
        PixelBlock {
            rect,
            rgba: color,
            z: depth,
            aov: aov_px,
        }
    }

    /// `RiDepthFilter` over one pixel's own samples.
    fn depth(&self, own: &[Composited]) -> f32 {
        let zs = own.iter().map(|c| {
            if self.depth_filter == DepthFilter::Midpoint {
                c.z_mid
            } else {
                c.z
            }
        });
        match self.depth_filter {
            DepthFilter::Min | DepthFilter::Midpoint => zs.fold(f32::MAX, f32::min),
            DepthFilter::Max => zs.fold(f32::MIN, f32::max),
            DepthFilter::Average => {
                let hits: Vec<f32> = zs.filter(|&z| z < f32::MAX).collect();
                if hits.is_empty() {
                    f32::MAX
                } else {
                    hits.iter().sum::<f32>() / hits.len() as f32
                }
            }
        }
    }

    /// Pastes the blocks into the crop window `crop` (x0 x1 y0 y1 in the full frame) and
    /// exposes the colour: premultiplied RGBA, depth and the AOV records (`stride` floats per
    /// pixel, not exposed), top row first.
    pub fn print(
        &self,
        crop: [u32; 4],
        blocks: Vec<PixelBlock>,
        stride: usize,
    ) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
        let [cx0, cx1, cy0, cy1] = crop;
        let (width, height) = (cx1 - cx0, cy1 - cy0);
        let mut rgba = vec![0.0f32; (width * height * 4) as usize];
        let mut z = vec![f32::MAX; (width * height) as usize];
        let mut aov = vec![0.0f32; (width * height) as usize * stride];
        for b in blocks {
            let [bx0, bx1, by0, _] = b.rect;
            let bwid = bx1 - bx0;
            for (k, (pc, pz)) in b.rgba.iter().zip(&b.z).enumerate() {
                let (x, y) = (bx0 - cx0 + k as u32 % bwid, by0 - cy0 + k as u32 / bwid);
                let o = (y * width + x) as usize;
                rgba[o * 4..o * 4 + 4].copy_from_slice(pc);
                z[o] = *pz;
                if let Some(rec) = b.aov.get(k * stride..(k + 1) * stride) {
                    aov[o * stride..(o + 1) * stride].copy_from_slice(rec);
                }
            }
        }
        self.expose(&mut rgba);
        (rgba, z, aov)
    }

    /// Exposure (RI Spec 3.2 `RiExposure`): c' = (gain·c)^(1/gamma) on colour, not alpha.
    fn expose(&self, rgba: &mut [f32]) {
        let (gain, gamma) = self.exposure;
        if gain != 1.0 || gamma != 1.0 {
            for px in rgba.chunks_exact_mut(4) {
                for c in &mut px[..3] {
                    *c = (*c * gain).max(0.0).powf(1.0 / gamma);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn options(filter: &str, depth: DepthFilter, exposure: (f32, f32)) -> Options {
        Options {
            filter: (filter.to_string(), 2.0, 2.0),
            depth_filter: depth,
            exposure,
            ..Options::default()
        }
    }

    /// A 4×4-pixel sample region at (−1, −1), 2 samples per pixel, with `f(s)` per sample.
    fn develop(film: &Film, f: impl Fn(usize) -> Composited) -> PixelBlock {
        let pos: Vec<(f32, f32)> = (0..32)
            .map(|s| {
                let (p, k) = (s / 2, s % 2);
                let (x, y) = ((p % 4) as f32 - 1.0, (p / 4) as f32 - 1.0);
                (x + 0.25 + 0.5 * k as f32, y + 0.25 + 0.5 * k as f32)
            })
            .collect();
        let samples: Vec<Composited> = (0..32).map(f).collect();
        let region = SampleRegion {
            origin: [-1, -1],
            size: [4, 4],
            per_pixel: 2,
            pos: &pos,
        };
        film.develop([0, 2, 0, 2], &region, &samples, (&[], 0))
    }

    #[test]
    fn a_flat_field_stays_flat_through_any_filter() {
        for name in ["box", "triangle", "gaussian", "catmull-rom", "sinc"] {
            let film = Film::new(&options(name, DepthFilter::Min, (1.0, 1.0)));
            let rgba = [0.25, 0.5, 0.75, 1.0];
            let block = develop(&film, |_| Composited {
                rgba,
                z: 1.0,
                z_mid: 1.0,
            });
            for px in &block.rgba {
                for (a, b) in px.iter().zip(rgba) {
                    assert!((a - b).abs() < 1e-6, "{name}: {px:?}");
                }
            }
        }
    }

    #[test]
    fn depth_filters_reduce_a_pixels_own_samples() {
        // Sample s has depth 10 + s, except sample 11, which hit nothing.
        let z = |s: usize| if s == 11 { f32::MAX } else { 10.0 + s as f32 };
        let sample = |s: usize| Composited {
            rgba: [0.0; 4],
            z: z(s),
            z_mid: z(s) + 0.5,
        };
        // Pixel (0, 0) is region pixel (1, 1) = index 5: samples 10 and 11.
        let depth = |f| develop(&Film::new(&options("box", f, (1.0, 1.0))), sample).z[0];
        assert_eq!(depth(DepthFilter::Min), 20.0);
        assert_eq!(depth(DepthFilter::Max), f32::MAX);
        assert_eq!(depth(DepthFilter::Average), 20.0);
        assert_eq!(depth(DepthFilter::Midpoint), 20.5);
    }

    #[test]
    fn exposure_is_gain_then_gamma_on_colour_only() {
        let film = Film::new(&options("box", DepthFilter::Min, (2.0, 2.0)));
        let block = PixelBlock {
            rect: [0, 1, 0, 1],
            rgba: vec![[0.125, 0.5, 0.0, 0.5]],
            z: vec![3.0],
            aov: Vec::new(),
        };
        let (rgba, z, _) = film.print([0, 1, 0, 1], vec![block], 0);
        for (a, b) in rgba.iter().zip([0.5, 1.0, 0.0, 0.5]) {
            assert!((a - b).abs() < 1e-6, "{rgba:?}");
        }
        assert_eq!(z, vec![3.0]);
    }
}
