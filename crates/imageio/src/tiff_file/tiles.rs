//! Tiled layout for [`super::TiffRows`]: a frame rendered in column blocks (issue 21, bounded
//! memory for wide frames) arrives a block of columns at a time, top to bottom, so its file
//! cannot be cut into full-width strips without holding the whole frame. Each block of columns
//! is a column of tiles `width` pixels wide and [`TILE_LENGTH`] rows tall; a tile is
//! compressed and written as soon as its rows are in. Edge tiles are padded with zeros (TIFF
//! 6.0 §15: every tile has the full size; readers crop).

/// Rows per tile (TIFF 6.0 §15 asks for a multiple of 16).
pub(super) const TILE_LENGTH: u32 = 16;

/// The tile grid and what each column of tiles has received.
pub(super) struct Tiles {
    /// Tile width in pixels (a multiple of 16).
    pub width: u32,
    /// Columns of tiles across the image; per column, quantized rows not yet in a tile and
    /// rows received so far.
    pub pending: Vec<Vec<u8>>,
    pub rows: Vec<u32>,
    /// Per tile, row of tiles by row of tiles: its file offset and compressed size (0 until
    /// written).
    pub offsets: Vec<u64>,
    pub counts: Vec<u32>,
}

impl Tiles {
    /// The tile grid of an image of `size` pixels in tiles `width` wide.
    pub fn new(size: [u32; 2], width: u32) -> Tiles {
        let across = size[0].div_ceil(width).max(1) as usize;
        let down = size[1].div_ceil(TILE_LENGTH).max(1) as usize;
        Tiles {
            width,
            pending: vec![Vec::new(); across],
            rows: vec![0; across],
            offsets: vec![0; across * down],
            counts: vec![0; across * down],
        }
    }

    /// The columns of tiles `[c0, c1)` a block `x .. x + w` of the image `image_width` wide
    /// covers exactly (`None` when it does not start and end on tile columns).
    pub fn columns(&self, x: u32, w: u32, image_width: u32) -> Option<(usize, usize)> {
        let tw = self.width;
        let end = x.checked_add(w)?;
        let ends_on_column = end % tw == 0 || end == image_width;
        (x % tw == 0 && w > 0 && ends_on_column && end <= image_width)
            .then(|| ((x / tw) as usize, end.div_ceil(tw) as usize))
    }

    /// Pixel width of tile column `c` inside an image `image_width` wide.
    pub fn column_width(&self, c: usize, image_width: u32) -> u32 {
        let x = c as u32 * self.width;
        self.width.min(image_width - x)
    }

    /// The tiles of column `c` whose rows are all in (or that end the image), each as
    /// (tile index, uncompressed tile bytes padded to the full tile), taken out of `pending`.
    pub fn complete(
        &mut self,
        c: usize,
        size: [u32; 2],
        pixel_bytes: usize,
    ) -> Vec<(usize, Vec<u8>)> {
        let across = self.pending.len();
        let row_bytes = self.column_width(c, size[0]) as usize * pixel_bytes;
        let tile_row_bytes = self.width as usize * pixel_bytes;
        let mut done = Vec::new();
        loop {
            let pending_rows = self.pending[c].len() / row_bytes.max(1);
            let first = self.rows[c] - pending_rows as u32;
            let n = (TILE_LENGTH as usize).min(pending_rows);
            let last = first + n as u32 == size[1];
            if n == 0 || (n < TILE_LENGTH as usize && !last) {
                return done;
            }
            let mut tile = vec![0u8; tile_row_bytes * TILE_LENGTH as usize];
            for (r, row) in self.pending[c][..n * row_bytes]
                .chunks_exact(row_bytes)
                .enumerate()
            {
                tile[r * tile_row_bytes..r * tile_row_bytes + row_bytes].copy_from_slice(row);
            }
            self.pending[c].drain(..n * row_bytes);
            done.push(((first / TILE_LENGTH) as usize * across + c, tile));
        }
    }
}
