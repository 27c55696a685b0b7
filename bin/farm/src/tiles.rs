//! Tile windows: a frame's crop region cut into `nx × ny` rectangles of whole pixels, each
//! given to `render --crop` as NDC numbers that land back on exactly those pixels.
//!
//! `render` turns an NDC crop edge `v` into pixel `ceil(res · v)` in f32 (RI spec's
//! `CropWindow` rule, `Options::crop_pixels`). Neighbouring tiles share an edge value, so the
//! tiles always partition the frame; choosing each edge as an f32 that maps to the intended
//! pixel (`p / res` when it maps back) keeps tiles equal-sized to within one pixel. The
//! pixel-filter margin around each tile is rendered by the hider itself (it refines and
//! samples a margin of filter radius + 1 pixels outside the crop), which is why pasted tiles
//! equal a full render.

/// One tile of one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct TileWindow {
    pub col: u32,
    pub row: u32,
    /// Pixels x0, x1, y0, y1 (ends exclusive), in the full frame.
    pub pixels: [u32; 4],
    /// The same window as `render --crop` arguments (NDC xmin xmax ymin ymax).
    pub ndc: [f32; 4],
}

impl TileWindow {
    /// `x1y3`: column and row, used in tile file names.
    pub fn name(&self) -> String {
        format!("x{}y{}", self.col, self.row)
    }
}

/// `Options::crop_pixels` for one edge.
pub fn pixel_of_edge(v: f32, res: u32) -> u32 {
    ((res as f32 * v).ceil().max(0.0) as u32).min(res)
}

/// An f32 `v` with `pixel_of_edge(v, res) == p` (`p ≤ res`): `p / res` itself whenever it maps
/// back (so scripts read `0.25`), else the nearest f32 that does.
pub fn edge_of_pixel(p: u32, res: u32) -> f32 {
    if p == 0 || res == 0 {
        return 0.0;
    }
    let mut v = (f64::from(p) / f64::from(res)) as f32;
    // At most a few ulps off either way.
    while pixel_of_edge(v, res) < p {
        v = f32::from_bits(v.to_bits() + 1);
    }
    while v > 0.0 && pixel_of_edge(v, res) > p {
        v = f32::from_bits(v.to_bits() - 1);
    }
    v
}

/// Edges `start + round-down(i · len / n)`, `i = 0..=n`.
fn split(start: u32, end: u32, n: u32) -> Vec<u32> {
    let len = u64::from(end - start);
    (0..=n)
        .map(|i| start + (u64::from(i) * len / u64::from(n)) as u32)
        .collect()
}

/// The non-empty tiles of `crop` (pixels x0, x1, y0, y1) in an `nx × ny` grid, row by row.
pub fn tile_windows(xres: u32, yres: u32, crop: [u32; 4], nx: u32, ny: u32) -> Vec<TileWindow> {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let [cx0, cx1, cy0, cy1] = crop;
    let (cx1, cy1) = (cx1.max(cx0), cy1.max(cy0));
    let xs = split(cx0, cx1, nx);
    let ys = split(cy0, cy1, ny);
    let mut out = Vec::new();
    for row in 0..ny as usize {
        for col in 0..nx as usize {
            let pixels = [xs[col], xs[col + 1], ys[row], ys[row + 1]];
            if pixels[0] == pixels[1] || pixels[2] == pixels[3] {
                continue;
            }
            out.push(TileWindow {
                col: col as u32,
                row: row as u32,
                pixels,
                ndc: [
                    edge_of_pixel(pixels[0], xres),
                    edge_of_pixel(pixels[1], xres),
                    edge_of_pixel(pixels[2], yres),
                    edge_of_pixel(pixels[3], yres),
                ],
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pixel_edge_has_an_ndc_value_that_maps_back_to_it() {
        for res in 1..=2100u32 {
            for p in 0..=res {
                let v = edge_of_pixel(p, res);
                assert_eq!(pixel_of_edge(v, res), p, "res {res} pixel {p} via {v}");
                assert!((0.0..=1.0).contains(&v));
            }
        }
    }

    #[test]
    fn tiles_cover_the_crop_once_and_skip_empty_ones() {
        for (xres, yres, crop, nx, ny) in [
            (320, 240, [0, 320, 0, 240], 4, 4),
            (97, 61, [0, 97, 0, 61], 3, 5),
            (64, 32, [10, 40, 3, 29], 4, 4),
            (3, 2, [0, 3, 0, 2], 4, 4),
        ] {
            let tiles = tile_windows(xres, yres, crop, nx, ny);
            let mut count = vec![0u32; (xres * yres) as usize];
            for t in &tiles {
                let [x0, x1, y0, y1] = t.pixels;
                assert!(x0 < x1 && y0 < y1);
                // The NDC numbers `render --crop` gets select exactly these pixels.
                assert_eq!(
                    [
                        pixel_of_edge(t.ndc[0], xres),
                        pixel_of_edge(t.ndc[1], xres),
                        pixel_of_edge(t.ndc[2], yres),
                        pixel_of_edge(t.ndc[3], yres)
                    ],
                    t.pixels
                );
                for y in y0..y1 {
                    for x in x0..x1 {
                        count[(y * xres + x) as usize] += 1;
                    }
                }
            }
            for y in 0..yres {
                for x in 0..xres {
                    let inside = (crop[0]..crop[1]).contains(&x) && (crop[2]..crop[3]).contains(&y);
                    assert_eq!(
                        count[(y * xres + x) as usize],
                        u32::from(inside),
                        "pixel {x},{y}"
                    );
                }
            }
        }
        assert_eq!(tile_windows(3, 2, [0, 3, 0, 2], 4, 4).len(), 6);
    }
}
