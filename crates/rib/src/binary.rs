//! Binary RIB writing (RI Spec 3.2 Appendix C). Reading is in the lexer, since binary and ASCII
//! tokens mix freely in one stream.
//!
//! Encoding choices: request names are defined once (0314) and then sent as one-byte codes
//! (0246); integers use the fewest bytes of 0200–0203; positional floats are IEEE singles
//! (0244) and float arrays IEEE arrays (0310–0313), so every float is exact; integer and
//! string arrays are bracketed with ASCII `[` `]`, which the format allows.
use crate::request::Request;
use crate::signature::{emit, Sink};
use std::collections::HashMap;
use std::io::{self, Write};

/// A binary RIB encoder that remembers which request names it has already defined.
pub struct BinaryWriter<W: Write> {
    w: W,
    codes: HashMap<String, u8>,
}

impl<W: Write> BinaryWriter<W> {
    pub fn new(w: W) -> Self {
        BinaryWriter {
            w,
            codes: HashMap::new(),
        }
    }

    pub fn write(&mut self, req: &Request) -> io::Result<()> {
        emit(req, self)
    }

    pub fn into_inner(self) -> W {
        self.w
    }

    pub fn get_mut(&mut self) -> &mut W {
        &mut self.w
    }
}

/// Writes one request in binary RIB, self-contained (it defines its own request code).
pub fn write_binary(req: &Request, w: &mut impl Write) -> io::Result<()> {
    BinaryWriter::new(w).write(req)
}

/// The shortest big-endian two's-complement form of `v`: 1 to 4 bytes.
fn int_bytes(v: i32) -> (usize, [u8; 4]) {
    let n = (1..4)
        .find(|&n| {
            let shift = 32 - 8 * n;
            (v << shift) >> shift == v
        })
        .unwrap_or(4);
    (n, v.to_be_bytes())
}

/// A length field: 1 to 4 unsigned bytes after `base + (bytes - 1)`.
fn length(w: &mut impl Write, base: u8, len: usize) -> io::Result<()> {
    let len = u32::try_from(len)
        .map_err(|_| io::Error::new(io::ErrorKind::InvalidInput, "array too long for RIB"))?;
    let n = match len {
        0..=0xff => 1,
        0x100..=0xffff => 2,
        0x1_0000..=0xff_ffff => 3,
        _ => 4,
    };
    w.write_all(&[base + (n as u8 - 1)])?;
    w.write_all(&len.to_be_bytes()[4 - n..])
}

impl<W: Write> Sink for BinaryWriter<W> {
    fn name(&mut self, name: &str) -> io::Result<()> {
        if let Some(&c) = self.codes.get(name) {
            return self.w.write_all(&[0xa6, c]);
        }
        if self.codes.len() < 256 {
            let c = self.codes.len() as u8;
            self.codes.insert(name.to_string(), c);
            self.w.write_all(&[0xcc, c])?;
            self.string(name)?;
            return self.w.write_all(&[0xa6, c]);
        }
        // All 256 codes taken: spell the name in ASCII, ended by a newline.
        self.w.write_all(name.as_bytes())?;
        self.w.write_all(b"\n")
    }
    fn int(&mut self, v: i32) -> io::Result<()> {
        let (n, b) = int_bytes(v);
        self.w.write_all(&[0x80 + (n as u8 - 1)])?;
        self.w.write_all(&b[4 - n..])
    }
    fn float(&mut self, v: f32) -> io::Result<()> {
        self.w.write_all(&[0xa4])?;
        self.w.write_all(&v.to_be_bytes())
    }
    fn string(&mut self, s: &str) -> io::Result<()> {
        if s.len() < 16 {
            self.w.write_all(&[0x90 + s.len() as u8])?;
        } else {
            length(&mut self.w, 0xa0, s.len())?;
        }
        self.w.write_all(s.as_bytes())
    }
    fn ints(&mut self, v: &[i32]) -> io::Result<()> {
        self.w.write_all(b"[")?;
        v.iter().try_for_each(|&i| self.int(i))?;
        self.w.write_all(b"]")
    }
    fn floats(&mut self, v: &[f32]) -> io::Result<()> {
        length(&mut self.w, 0xc8, v.len())?;
        let mut bytes = Vec::with_capacity(4 * v.len());
        for f in v {
            bytes.extend_from_slice(&f.to_be_bytes());
        }
        self.w.write_all(&bytes)
    }
    fn strings(&mut self, v: &[String]) -> io::Result<()> {
        self.w.write_all(b"[")?;
        v.iter().try_for_each(|s| self.string(s))?;
        self.w.write_all(b"]")
    }
    fn structure(&mut self, text: &str) -> io::Result<()> {
        let one_line: String = text.chars().filter(|&c| c != '\n').collect();
        writeln!(self.w, "##{one_line}")
    }
    fn end(&mut self) -> io::Result<()> {
        Ok(())
    }
}
