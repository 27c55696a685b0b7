//! The shadow map's min/max depth pyramid.
//!
//! Level 0 holds the depth twice (`Z` = `Zmax`); each coarser texel holds the minimum (`Z`) and
//! maximum (`Zmax`) of *every* finer texel under it, including the odd last row/column that
//! round-down sizes fold into the last texel, so the bounds are conservative: a point nearer than
//! the minimum is fully lit, one beyond the maximum fully shadowed.

use crate::mipmap::{level_count, level_size, Level};

/// Builds the 2-channel (min, max) pyramid from one depth channel.
pub fn build_minmax(z: Level) -> Vec<Level> {
    let (w0, h0) = (z.width, z.height);
    let mut first = Level::new(w0, h0, 2);
    for (i, v) in z.data.iter().enumerate() {
        first.data[2 * i] = *v;
        first.data[2 * i + 1] = *v;
    }
    let n = level_count(w0, h0);
    let mut levels = vec![first];
    for l in 1..n {
        let prev = &levels[l - 1];
        let (w, h) = (level_size(w0, l), level_size(h0, l));
        let mut out = Level::new(w, h, 2);
        for y in 0..h {
            let y1 = if y == h - 1 { prev.height } else { 2 * y + 2 };
            for x in 0..w {
                let x1 = if x == w - 1 { prev.width } else { 2 * x + 2 };
                let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
                for py in (2 * y).min(prev.height - 1)
                    ..y1.min(prev.height).max((2 * y).min(prev.height - 1) + 1)
                {
                    for px in (2 * x).min(prev.width - 1)
                        ..x1.min(prev.width).max((2 * x).min(prev.width - 1) + 1)
                    {
                        let t = prev.texel(px, py);
                        lo = lo.min(t[0]);
                        hi = hi.max(t[1]);
                    }
                }
                let i = (y * w + x) * 2;
                out.data[i] = lo;
                out.data[i + 1] = hi;
            }
        }
        levels.push(out);
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minmax_pyramid_bounds_every_depth_under_each_texel() {
        let (w, h) = (13, 7);
        let mut z = Level::new(w, h, 1);
        for (i, v) in z.data.iter_mut().enumerate() {
            *v = ((i * 7919) % 101) as f32;
        }
        let src = z.clone();
        let levels = build_minmax(z);
        for (l, lv) in levels.iter().enumerate() {
            // Every level-0 texel maps to texel (x>>l, y>>l) clamped to the level's last texel.
            for y in 0..h {
                for x in 0..w {
                    let tx = (x >> l).min(lv.width - 1);
                    let ty = (y >> l).min(lv.height - 1);
                    let t = lv.texel(tx, ty);
                    let d = src.data[y * w + x];
                    assert!(t[0] <= d && d <= t[1], "level {l} texel ({tx},{ty})");
                }
            }
        }
        let top = levels.last().unwrap();
        assert_eq!(top.data, vec![0.0, 100.0]);
    }
}
