//! Texel access for one lookup: tiles fetched through the cache, with a tiny per-lookup memo so
//! the 4–64 texels of a filtered lookup cost a handful of cache probes, not one each.

use crate::cache::{Backing, TexFile, TextureCache, Tile};
use crate::wrapmode::WrapMode;
use crate::TextureError;
use std::sync::Arc;

/// (level, tile x, tile y) and the tile.
type Memo = ((u32, u32, u32), Arc<Tile>);

pub(crate) struct Sampler<'a> {
    pub cache: &'a TextureCache,
    pub file: &'a TexFile,
    memo: [Option<Memo>; 4],
    next: usize,
}

impl<'a> Sampler<'a> {
    pub fn new(cache: &'a TextureCache, file: &'a TexFile) -> Sampler<'a> {
        Sampler {
            cache,
            file,
            memo: [None, None, None, None],
            next: 0,
        }
    }

    /// Stored channel `ch` of texel `(x, y)` of level `level` (in range).
    pub fn texel(
        &mut self,
        level: usize,
        x: usize,
        y: usize,
        out: &mut [f32; 8],
    ) -> Result<(), TextureError> {
        let nch = self.file.nch.min(8);
        match &self.file.backing {
            Backing::Memory(levels) => {
                let t = levels[level].texel(x, y);
                out[..nch].copy_from_slice(&t[..nch]);
                Ok(())
            }
            Backing::Tiled(tx) => {
                let (tw, th) = tx.tile;
                let (bx, by) = (x / tw, y / th);
                let key = (level as u32, bx as u32, by as u32);
                let nc = self.file.nch;
                let read = |tile: &Tile, out: &mut [f32]| {
                    tile.data
                        .read(((y - by * th) * tile.w + (x - bx * tw)) * nc, out)
                };
                // A memo hit reads the tile where the memo holds it: cloning its `Arc` per
                // texel was two atomic operations on a count every thread's lookups share.
                if let Some((_, tile)) = self.memo.iter().flatten().find(|(k, _)| *k == key) {
                    read(tile, &mut out[..nch]);
                    return Ok(());
                }
                let tile = self.cache.tile(self.file, tx, level, bx, by)?;
                read(&tile, &mut out[..nch]);
                self.memo[self.next] = Some((key, tile));
                self.next = (self.next + 1) % self.memo.len();
                Ok(())
            }
        }
    }

    /// Bilinear filter of level `level` at continuous texel coordinates (centres at `i + 0.5`),
    /// with the file's wrap modes; accumulates `weight ×` the stored channels into `acc`.
    pub fn bilinear(
        &mut self,
        level: usize,
        x: f32,
        y: f32,
        wrap: [WrapMode; 2],
        weight: f32,
        acc: &mut [f32; 8],
    ) -> Result<(), TextureError> {
        let (w, h) = self.file.levels[level];
        let (fx, fy) = (x - 0.5, y - 0.5);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (ax, ay) = (fx - x0, fy - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let mut t = [0.0f32; 8];
        let nch = self.file.nch.min(8);
        for (dy, wy) in [(0i64, 1.0 - ay), (1, ay)] {
            if wy == 0.0 {
                continue;
            }
            let Some(yy) = wrap[1].texel(y0 + dy, h) else {
                continue;
            };
            for (dx, wx) in [(0i64, 1.0 - ax), (1, ax)] {
                if wx == 0.0 {
                    continue;
                }
                let Some(xx) = wrap[0].texel(x0 + dx, w) else {
                    continue;
                };
                self.texel(level, xx, yy, &mut t)?;
                let wt = weight * wx * wy;
                for c in 0..nch {
                    acc[c] += wt * t[c];
                }
            }
        }
        Ok(())
    }

    /// Trilinear: bilinear on the two levels around `lod` (clamped to the pyramid).
    #[allow(clippy::too_many_arguments)]
    pub fn trilinear(
        &mut self,
        s: f32,
        t: f32,
        lod: f32,
        max_level: usize,
        wrap: [WrapMode; 2],
        weight: f32,
        acc: &mut [f32; 8],
    ) -> Result<(), TextureError> {
        let lod = lod.clamp(0.0, max_level as f32);
        let l0 = lod.floor() as usize;
        let f = lod - l0 as f32;
        let (w, h) = self.file.levels[l0];
        self.bilinear(
            l0,
            s * w as f32,
            t * h as f32,
            wrap,
            weight * (1.0 - f),
            acc,
        )?;
        if f > 0.0 && l0 < max_level {
            let (w, h) = self.file.levels[l0 + 1];
            self.bilinear(l0 + 1, s * w as f32, t * h as f32, wrap, weight * f, acc)?;
        }
        Ok(())
    }

    /// Copies RenderMan channels `first..first+n` of a stored-order accumulator, `fill` beyond.
    pub fn select(&self, acc: &[f32; 8], first: usize, n: usize, fill: f32) -> [f32; 4] {
        let mut out = [0.0f32; 4];
        for (k, o) in out.iter_mut().enumerate().take(n.min(4)) {
            *o = match self.file.order.get(first + k) {
                Some(&i) if i < 8 => acc[i],
                _ => fill,
            };
        }
        out
    }
}
