//! Column blocks (issue 21: memory that does not grow with the frame). Bands of buckets that
//! span a wide frame hold a band's worth of grids, pieces and float rows, all growing with the
//! width: a grid is diced by the first bucket that samples it and kept until the last one does,
//! and most of a 16-row band's grids reach the band below (5120×3840 `rib/bench/spotlight.rib`:
//! 10 MB of heap against 3 MB at 640×480). A crop window wider than [`BLOCKS_ABOVE`] pixels is
//! therefore rendered as vertical blocks [`BLOCK_WIDTH`] pixels wide, each top to bottom in
//! bands, as its own crop window; what is held is then one block's band. The image is the same
//! bits (every stage depends on full-frame positions only, never on the crop), at the price of
//! the grids on a block's border being diced and shaded in both blocks. A `tiff` display takes
//! the blocks as columns of tiles ([`illume_imageio`]'s tiled `TiffRows`).

/// Crop windows wider than this (pixels) are rendered in column blocks.
pub const BLOCKS_ABOVE: u32 = 2048;

/// The width of a column block (pixels; a multiple of 16, the tiles' width).
pub const BLOCK_WIDTH: u32 = 1024;

/// The block width a crop window `crop_width` pixels wide is rendered in (`None`: one block).
pub fn column_block_width(crop_width: u32) -> Option<u32> {
    (crop_width > BLOCKS_ABOVE).then_some(BLOCK_WIDTH)
}

/// The column blocks of crop window `[x0, x1, y0, y1]`, left to right (the window itself when
/// it is narrow enough).
pub(crate) fn column_blocks(crop: [u32; 4]) -> Vec<[u32; 4]> {
    let [x0, x1, y0, y1] = crop;
    match column_block_width(x1.saturating_sub(x0)) {
        None => vec![crop],
        Some(w) => (x0..x1)
            .step_by(w as usize)
            .map(|bx| [bx, (bx + w).min(x1), y0, y1])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_tile_a_wide_window_and_leave_a_narrow_one_whole() {
        assert_eq!(column_blocks([3, 2051, 0, 9]), vec![[3, 2051, 0, 9]]);
        let blocks = column_blocks([10, 5130, 4, 40]);
        assert_eq!(blocks.len(), 5);
        assert_eq!(blocks[0], [10, 1034, 4, 40]);
        assert_eq!(blocks[4], [4106, 5130, 4, 40]);
        assert!(blocks.windows(2).all(|w| w[0][1] == w[1][0]));
        let odd = column_blocks([0, 2100, 0, 1]);
        assert_eq!(odd.last(), Some(&[2048, 2100, 0, 1]));
    }
}
