//! `texture(name[channel], s, t | s1,t1 … s4,t4)`: area-filtered plain texture lookups.
//!
//! The four corners (grid order: (u,v), (u+du,v), (u,v+dv), (u+du,v+dv)) give two footprint
//! axes; with the `width`s and `blur` they form an ellipse whose minor axis picks the mip level
//! and whose major axis is covered by up to `max_anisotropy` trilinear probes (multi-probe
//! anisotropic filtering). Zero derivatives select level 0 (bilinear magnification); huge ones
//! clamp to the coarsest level, splitting the footprint into several coarse probes.

use crate::lookup::{footprint, probe_grid, LookupOptions};
use crate::sampler::Sampler;
use crate::{TextureCache, TextureError};

impl TextureCache {
    /// Filtered lookup of `nchannels` (≤ 4) channels starting at `first_channel` over the
    /// quadrilateral `st` (see the module doc for corner order). Missing channels get `fill`.
    pub fn texture(
        &self,
        name: &str,
        first_channel: usize,
        nchannels: usize,
        st: [[f32; 2]; 4],
        opts: &LookupOptions,
    ) -> Result<[f32; 4], TextureError> {
        let f = self.file(name)?;
        let mut s = Sampler::new(self, &f);
        let (w, h) = (f.levels[0].0 as f32, f.levels[0].1 as f32);
        let cs = 0.25 * (st[0][0] + st[1][0] + st[2][0] + st[3][0]);
        let ct = 0.25 * (st[0][1] + st[1][1] + st[2][1] + st[3][1]);
        let a = [
            0.5 * ((st[1][0] - st[0][0]) + (st[3][0] - st[2][0])) * opts.swidth * w,
            0.5 * ((st[1][1] - st[0][1]) + (st[3][1] - st[2][1])) * opts.twidth * h,
        ];
        let b = [
            0.5 * ((st[2][0] - st[0][0]) + (st[3][0] - st[1][0])) * opts.swidth * w,
            0.5 * ((st[2][1] - st[0][1]) + (st[3][1] - st[1][1])) * opts.twidth * h,
        ];
        let blur = [(opts.blur + opts.sblur) * w, (opts.blur + opts.tblur) * h];
        let fp = footprint(a, b, blur);
        let max_level = f.levels.len() - 1;
        let coarsest = (1u64 << max_level) as f32;
        let (mut nmaj, mut nmin, mut size) = probe_grid(&fp, opts.max_anisotropy, coarsest);
        // A lone trilinear probe filters with about twice its footprint (mip box plus bilinear
        // tent); splitting near-isotropic footprints into 2×2 probes one level finer keeps the
        // kernel close to the footprint at 4 probes' cost.
        if size > 2.0 && nmaj <= 2 && nmin == 1 {
            nmaj *= 2;
            nmin = 2;
            size *= 0.5;
        }
        let minor = fp.minor.max(fp.major / opts.max_anisotropy.max(1) as f32);
        let lod = if size > 1.0 { size.log2() } else { 0.0 };
        let perp = [-fp.dir[1], fp.dir[0]];
        let mut acc = [0.0f32; 8];
        let mut wsum = 0.0f32;
        for i in 0..nmaj {
            let u = (i as f32 + 0.5) / nmaj as f32 - 0.5;
            for j in 0..nmin {
                let v = (j as f32 + 0.5) / nmin as f32 - 0.5;
                let ox = u * fp.major * fp.dir[0] + v * minor * perp[0];
                let oy = u * fp.major * fp.dir[1] + v * minor * perp[1];
                let wt = opts.probe_weight(u, v);
                s.trilinear(
                    cs + ox / w,
                    ct + oy / h,
                    lod,
                    max_level,
                    f.wrap,
                    wt,
                    &mut acc,
                )?;
                wsum += wt;
            }
        }
        if wsum > 0.0 {
            acc.iter_mut().for_each(|v| *v /= wsum);
        }
        Ok(s.select(&acc, first_channel, nchannels, opts.fill))
    }
}
