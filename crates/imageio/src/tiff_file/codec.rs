//! Compression and predictors: what turns a stored strip or tile back into raw sample bytes.

use crate::{format_error, ImageError};
use std::path::Path;

pub(super) fn decompress(
    path: &Path,
    compression: u64,
    raw: &[u8],
    expected: usize,
) -> Result<Vec<u8>, ImageError> {
    match compression {
        1 => Ok(raw.to_vec()),
        5 => lzw_decode(raw, expected).map_err(|m| format_error(path, format!("TIFF LZW: {m}"))),
        8 | 32946 => {
            use std::io::Read;
            let mut out = Vec::with_capacity(expected);
            flate2::read::ZlibDecoder::new(raw)
                .take(expected as u64)
                .read_to_end(&mut out)
                .map_err(|e| format_error(path, format!("TIFF Deflate: {e}")))?;
            Ok(out)
        }
        _ => Ok(packbits_decode(raw, expected)),
    }
}

/// TIFF LZW (MSB-first codes, 9 to 12 bits, "early change"), stopping at `expected` bytes.
pub(super) fn lzw_decode(input: &[u8], expected: usize) -> Result<Vec<u8>, String> {
    const CLEAR: usize = 256;
    const EOI: usize = 257;
    if input.len() >= 2 && input[0] == 0 && input[1] & 1 == 1 {
        return Err("old-style (LSB-first) LZW is not supported".into());
    }
    // Each table entry: (prefix code, last byte, length).
    let mut table: Vec<(u16, u8, u32)> = Vec::with_capacity(4096);
    let reset = |t: &mut Vec<(u16, u8, u32)>| {
        t.clear();
        for b in 0..256u16 {
            t.push((u16::MAX, b as u8, 1));
        }
        t.push((u16::MAX, 0, 0));
        t.push((u16::MAX, 0, 0));
    };
    reset(&mut table);
    let mut out = Vec::with_capacity(expected);
    let mut bitpos = 0usize;
    let mut width = 9usize;
    let mut prev: Option<usize> = None;
    let mut scratch = Vec::new();
    let emit = |code: usize, table: &[(u16, u8, u32)], scratch: &mut Vec<u8>| {
        scratch.clear();
        let mut c = code;
        loop {
            let (p, b, _) = table[c];
            scratch.push(b);
            if p == u16::MAX {
                break;
            }
            c = p as usize;
        }
        scratch.reverse();
    };
    while out.len() < expected {
        if bitpos + width > input.len() * 8 {
            break; // ran out of codes: the caller reports the short chunk
        }
        let mut code = 0usize;
        for i in 0..width {
            let bit = bitpos + i;
            code = (code << 1) | ((input[bit / 8] >> (7 - bit % 8)) & 1) as usize;
        }
        bitpos += width;
        if code == CLEAR {
            reset(&mut table);
            width = 9;
            prev = None;
            continue;
        }
        if code == EOI {
            break;
        }
        match prev {
            None => {
                if code >= 256 {
                    return Err(format!(
                        "expected a literal after a clear code, found {code}"
                    ));
                }
                out.push(code as u8);
            }
            Some(p) => {
                if code < table.len() {
                    emit(code, &table, &mut scratch);
                    if table.len() < 4096 {
                        table.push((p as u16, scratch[0], table[p].2 + 1));
                    }
                } else if code == table.len() {
                    emit(p, &table, &mut scratch);
                    let first = scratch[0];
                    scratch.push(first);
                    if table.len() < 4096 {
                        table.push((p as u16, first, table[p].2 + 1));
                    }
                } else {
                    return Err(format!(
                        "expected a code up to {}, found {code}",
                        table.len()
                    ));
                }
                out.extend_from_slice(&scratch);
            }
        }
        prev = Some(code);
        // Early change: widen one code before the table fills the current width.
        if table.len() + 1 >= (1 << width) && width < 12 {
            width += 1;
        }
    }
    out.truncate(expected);
    Ok(out)
}

/// PackBits run-length decoding (TIFF 6.0 §9), stopping at `expected` bytes.
pub(super) fn packbits_decode(input: &[u8], expected: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(expected);
    let mut i = 0;
    while i < input.len() && out.len() < expected {
        let n = input[i] as i8;
        i += 1;
        if n >= 0 {
            let len = n as usize + 1;
            let end = (i + len).min(input.len());
            out.extend_from_slice(&input[i..end]);
            i = end;
        } else if n != -128 {
            if let Some(&b) = input.get(i) {
                out.extend(std::iter::repeat_n(b, (1 - n as isize) as usize));
            }
            i += 1;
        }
    }
    out.truncate(expected);
    out
}

/// Undoes the horizontal (2) or floating-point (3) predictor on each row of a chunk.
pub(super) fn undo_predictor(
    bytes: &mut [u8],
    predictor: u64,
    row_bytes: usize,
    bps: usize,
    spp: usize,
    be: bool,
) {
    match predictor {
        2 => {
            for row in bytes.chunks_exact_mut(row_bytes) {
                match bps {
                    1 => {
                        for i in spp..row.len() {
                            row[i] = row[i].wrapping_add(row[i - spp]);
                        }
                    }
                    2 | 4 | 8 => {
                        let n = row.len() / bps;
                        let get = |r: &[u8], i: usize| -> u64 {
                            let b = &r[i * bps..(i + 1) * bps];
                            let mut v = 0u64;
                            if be {
                                b.iter().for_each(|&x| v = (v << 8) | x as u64);
                            } else {
                                b.iter().rev().for_each(|&x| v = (v << 8) | x as u64);
                            }
                            v
                        };
                        for i in spp..n {
                            let v = get(row, i).wrapping_add(get(row, i - spp));
                            let dst = &mut row[i * bps..(i + 1) * bps];
                            for (k, d) in dst.iter_mut().enumerate() {
                                let shift = if be { 8 * (bps - 1 - k) } else { 8 * k };
                                *d = (v >> shift) as u8;
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        3 => {
            // Bytes are differenced across the row, then stored as byte planes, most
            // significant first (Adobe Photoshop TIFF technical note 3).
            for row in bytes.chunks_exact_mut(row_bytes) {
                for i in spp..row.len() {
                    row[i] = row[i].wrapping_add(row[i - spp]);
                }
                let n = row.len() / bps;
                let planes = row.to_vec();
                for i in 0..n {
                    for k in 0..bps {
                        let b = planes[k * n + i];
                        let dst = if be { k } else { bps - 1 - k };
                        row[i * bps + dst] = b;
                    }
                }
            }
        }
        _ => {}
    }
}
