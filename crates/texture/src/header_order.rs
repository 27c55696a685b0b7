//! One attribute order for the OpenEXR headers we write, so the same input gives the same bytes.
//!
//! The `exr` crate keeps custom attributes (`textureformat`, `filter`, `source`, …) in a
//! `HashMap` with a per-process random hasher and writes them in its iteration order: five runs
//! of `txmake -shadow` gave three different files (issue 24), which breaks caches, `-newer`
//! dependency checks and content hashes. OpenEXR's own library writes a header's attributes
//! sorted by name (its `Header` is a `std::map`); [`sort_header_attributes`] does the same to a
//! file the crate wrote. Reordering keeps the header's length, so the offset table and the
//! chunks after it (absolute file positions) stay valid.
//!
//! Layout (OpenEXR file layout document): magic `76 2f 31 01`, a 4-byte version field, then
//! one header (a multi-part file: several, closed by an empty one); a header is a list of
//! attributes `name\0 type\0 size:i32le value[size]` closed by a `\0`.

/// Flag of the version field: the file has several parts, so several headers.
const MULTIPART: u32 = 0x1000;

/// Sorts every header's attributes by name, in place. `Err` names what is malformed; the
/// bytes are left as they were then.
pub(crate) fn sort_header_attributes(file: &mut [u8]) -> Result<(), String> {
    if file.len() < 8 || file[..4] != [0x76, 0x2f, 0x31, 0x01] {
        return Err("not an OpenEXR file (bad magic number)".into());
    }
    let version = u32::from_le_bytes([file[4], file[5], file[6], file[7]]);
    let mut pos = 8;
    loop {
        let (attributes, end) = read_header(file, pos)?;
        if attributes.is_empty() {
            break; // the empty header closing a multi-part list
        }
        let mut sorted = attributes.clone();
        sorted.sort_by(|a, b| a.name.cmp(&b.name));
        let mut bytes = Vec::with_capacity(end - pos);
        for a in &sorted {
            bytes.extend_from_slice(&file[a.start..a.end]);
        }
        file[pos..pos + bytes.len()].copy_from_slice(&bytes);
        pos = end + 1; // past the header's closing 0
        if version & MULTIPART == 0 {
            break;
        }
    }
    Ok(())
}

/// One attribute's name and its byte range in the file.
#[derive(Clone)]
struct Attribute {
    name: Vec<u8>,
    start: usize,
    end: usize,
}

/// The attributes of the header starting at `pos`, and the position of its closing 0.
fn read_header(file: &[u8], mut pos: usize) -> Result<(Vec<Attribute>, usize), String> {
    let mut out = Vec::new();
    loop {
        match file.get(pos) {
            None => {
                return Err(format!(
                    "header runs past the end of the file at byte {pos}"
                ))
            }
            Some(0) => return Ok((out, pos)),
            Some(_) => {}
        }
        let start = pos;
        let name = c_string(file, &mut pos)?.to_vec();
        c_string(file, &mut pos)?; // type name
        let size = file
            .get(pos..pos + 4)
            .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .ok_or_else(|| format!("attribute size runs past the end of the file at byte {pos}"))?;
        let size = usize::try_from(size).map_err(|_| format!("negative attribute size {size}"))?;
        pos += 4 + size;
        if pos > file.len() {
            return Err(format!(
                "attribute value runs past the end of the file at byte {pos}"
            ));
        }
        out.push(Attribute {
            name,
            start,
            end: pos,
        });
    }
}

/// The bytes before the next 0 at `*pos`, moving `*pos` past that 0.
fn c_string<'a>(file: &'a [u8], pos: &mut usize) -> Result<&'a [u8], String> {
    let rest = file.get(*pos..).unwrap_or_default();
    let len = rest
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| format!("unterminated name at byte {}", *pos))?;
    *pos += len + 1;
    Ok(&rest[..len])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn attr(name: &str, ty: &str, value: &[u8]) -> Vec<u8> {
        let mut v = Vec::new();
        v.extend_from_slice(name.as_bytes());
        v.push(0);
        v.extend_from_slice(ty.as_bytes());
        v.push(0);
        v.extend_from_slice(&(value.len() as i32).to_le_bytes());
        v.extend_from_slice(value);
        v
    }

    fn file(version: u32, headers: &[&[Vec<u8>]], tail: &[u8]) -> Vec<u8> {
        let mut f = vec![0x76, 0x2f, 0x31, 0x01];
        f.extend_from_slice(&version.to_le_bytes());
        for h in headers {
            for a in *h {
                f.extend_from_slice(a);
            }
            f.push(0);
        }
        f.extend_from_slice(tail);
        f
    }

    #[test]
    fn a_single_part_header_is_sorted_and_the_rest_is_untouched() {
        let (z, a, m) = (
            attr("zeta", "string", b"last"),
            attr("alpha", "int", &7i32.to_le_bytes()),
            attr("middle", "string", b""),
        );
        let tail = b"offsets and chunks, with a 0 byte: \0 and more";
        let mut f = file(2 | 0x200, &[&[z.clone(), a.clone(), m.clone()]], tail);
        sort_header_attributes(&mut f).unwrap();
        assert_eq!(f, file(2 | 0x200, &[&[a, m, z]], tail));
    }

    #[test]
    fn every_header_of_a_multipart_file_is_sorted() {
        let (b, a, d, c) = (
            attr("b", "int", &[1, 0, 0, 0]),
            attr("a", "int", &[2, 0, 0, 0]),
            attr("d", "int", &[3, 0, 0, 0]),
            attr("c", "int", &[4, 0, 0, 0]),
        );
        let mut f = file(
            2 | MULTIPART,
            &[&[b.clone(), a.clone()], &[d.clone(), c.clone()], &[]],
            b"x",
        );
        sort_header_attributes(&mut f).unwrap();
        assert_eq!(f, file(2 | MULTIPART, &[&[a, b], &[c, d], &[]], b"x"));
    }

    #[test]
    fn malformed_headers_are_errors_not_panics() {
        assert!(sort_header_attributes(&mut [1, 2, 3]).is_err());
        let good = file(2, &[&[attr("name", "string", b"value")]], b"");
        // Every truncation of a valid header, and a negative size.
        for cut in 8..good.len() {
            let mut f = good[..cut].to_vec();
            assert!(sort_header_attributes(&mut f).is_err(), "cut at {cut}");
        }
        let mut neg = file(2, &[&[attr("n", "int", &[0; 4])]], b"");
        neg[8 + 2 + 4..8 + 2 + 4 + 4].copy_from_slice(&(-5i32).to_le_bytes());
        assert!(sort_header_attributes(&mut neg).is_err());
    }
}
