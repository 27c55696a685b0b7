//! Reading's lowest layer: bounds-checked access to the file, its header and the first IFD's tags.

use super::*;
use crate::{format_error, ImageError};
use std::path::Path;

/// The whole file and its byte order; every read is bounds-checked.
pub(super) struct TiffBytes<'a> {
    pub(super) path: &'a Path,
    data: &'a [u8],
    pub(super) big_endian: bool,
}

impl TiffBytes<'_> {
    fn truncated(&self, what: &str, at: u64) -> ImageError {
        format_error(
            self.path,
            format!(
                "truncated TIFF: expected {what} at byte {at}, found end of file at {}",
                self.data.len()
            ),
        )
    }

    pub(super) fn bytes(&self, at: u64, len: u64, what: &str) -> Result<&[u8], ImageError> {
        let end = at.checked_add(len).filter(|&e| e <= self.data.len() as u64);
        match end {
            Some(end) => Ok(&self.data[at as usize..end as usize]),
            None => Err(self.truncated(what, at)),
        }
    }

    fn u16_at(&self, at: u64) -> Result<u16, ImageError> {
        let b = self.bytes(at, 2, "a 16-bit value")?;
        let b = [b[0], b[1]];
        Ok(if self.big_endian {
            u16::from_be_bytes(b)
        } else {
            u16::from_le_bytes(b)
        })
    }

    fn u32_at(&self, at: u64) -> Result<u32, ImageError> {
        let b = self.bytes(at, 4, "a 32-bit value")?;
        let b = [b[0], b[1], b[2], b[3]];
        Ok(if self.big_endian {
            u32::from_be_bytes(b)
        } else {
            u32::from_le_bytes(b)
        })
    }
}

/// One IFD entry as read: where its values live.
#[derive(Clone, Copy)]
pub(super) struct RawEntry {
    tag: u16,
    kind: u16,
    count: u32,
    /// Offset of the values (inline entries point into the IFD itself).
    at: u64,
}

fn type_size(kind: u16) -> u64 {
    match kind {
        1 | 2 | 6 | 7 => 1,
        3 | 8 => 2,
        4 | 9 | 11 | 13 => 4,
        5 | 10 | 12 | 16 | 17 | 18 => 8,
        _ => 0,
    }
}

pub(super) struct Ifd<'a> {
    file: &'a TiffBytes<'a>,
    entries: Vec<RawEntry>,
}

impl Ifd<'_> {
    pub(super) fn find(&self, tag: u16) -> Option<RawEntry> {
        self.entries.iter().copied().find(|e| e.tag == tag)
    }

    /// Unsigned integer values of `tag` (BYTE, SHORT, LONG), at most `limit` of them.
    pub(super) fn uints(&self, tag: u16, limit: u64) -> Result<Option<Vec<u64>>, ImageError> {
        let Some(e) = self.find(tag) else {
            return Ok(None);
        };
        let size = type_size(e.kind);
        if !matches!(e.kind, 1 | 3 | 4 | 16) {
            return Err(format_error(
                self.file.path,
                format!(
                    "TIFF tag {tag}: expected an unsigned integer type, found type {}",
                    e.kind
                ),
            ));
        }
        if e.count as u64 > limit {
            return Err(format_error(
                self.file.path,
                format!(
                    "TIFF tag {tag}: expected at most {limit} values, found {}",
                    e.count
                ),
            ));
        }
        let bytes = self.file.bytes(e.at, size * e.count as u64, "tag values")?;
        let mut out = Vec::with_capacity(e.count as usize);
        for c in bytes.chunks_exact(size as usize) {
            let v = match (size, self.file.big_endian) {
                (1, _) => c[0] as u64,
                (2, false) => u16::from_le_bytes([c[0], c[1]]) as u64,
                (2, true) => u16::from_be_bytes([c[0], c[1]]) as u64,
                (4, false) => u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as u64,
                (4, true) => u32::from_be_bytes([c[0], c[1], c[2], c[3]]) as u64,
                (_, false) => u64::from_le_bytes(c.try_into().unwrap_or([0; 8])),
                (_, true) => u64::from_be_bytes(c.try_into().unwrap_or([0; 8])),
            };
            out.push(v);
        }
        Ok(Some(out))
    }

    pub(super) fn uint(&self, tag: u16) -> Result<Option<u64>, ImageError> {
        Ok(self.uints(tag, 1 << 24)?.and_then(|v| v.first().copied()))
    }

    pub(super) fn required(&self, tag: u16, name: &str) -> Result<u64, ImageError> {
        self.uint(tag)?.ok_or_else(|| {
            format_error(
                self.file.path,
                format!("TIFF: expected the {name} tag ({tag}), found none"),
            )
        })
    }

    pub(super) fn ascii(&self, tag: u16) -> Option<String> {
        let e = self.find(tag)?;
        if e.kind != TYPE_ASCII {
            return None;
        }
        let b = self.file.bytes(e.at, e.count as u64, "text").ok()?;
        let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
        Some(String::from_utf8_lossy(&b[..end]).into_owned())
    }
}

impl<'a> TiffBytes<'a> {
    /// Checks the byte-order mark and the classic-TIFF version number.
    pub(super) fn parse(path: &'a Path, data: &'a [u8]) -> Result<Self, ImageError> {
        let big_endian = match data.get(..2) {
            Some(b"II") => false,
            Some(b"MM") => true,
            _ => {
                return Err(format_error(
                    path,
                    "expected a TIFF byte-order mark II or MM",
                ));
            }
        };
        let file = TiffBytes {
            path,
            data,
            big_endian,
        };
        let version = file.u16_at(2)?;
        if version != 42 {
            return Err(format_error(
                path,
                format!("expected classic TIFF (version 42), found version {version}"),
            ));
        }
        Ok(file)
    }

    /// The entries of the first IFD (only the first image is read).
    pub(super) fn first_ifd(&'a self) -> Result<Ifd<'a>, ImageError> {
        let file = self;
        let ifd_at = file.u32_at(4)? as u64;
        let count = file.u16_at(ifd_at)? as u64;
        let mut entries = Vec::with_capacity(count as usize);
        for i in 0..count {
            let e = ifd_at + 2 + 12 * i;
            let tag = file.u16_at(e)?;
            let kind = file.u16_at(e + 2)?;
            let n = file.u32_at(e + 4)?;
            let size = type_size(kind) * n as u64;
            let at = if size <= 4 {
                e + 8
            } else {
                file.u32_at(e + 8)? as u64
            };
            entries.push(RawEntry {
                tag,
                kind,
                count: n,
                at,
            });
        }
        Ok(Ifd { file, entries })
    }
}
