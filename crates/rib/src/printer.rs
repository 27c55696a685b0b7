//! Canonical ASCII RIB: one request per line, parameters as given, numbers that read back to
//! the same bits.
//!
//! Floats use Rust's shortest round-trip formatting. Inside arrays a float always shows a `.`
//! or an exponent (`1.0`, `1e-7`), because the reader types an all-integer array as integers
//! (see [`Value`](crate::Value)); positional numbers print integral values bare (`Sphere 1 -1 1
//! 360`), since positional slots have a fixed type.
use crate::request::Request;
use crate::signature::{emit, Sink};
use std::io::{self, Write};

/// Writes `req` as one line of ASCII RIB (with its newline).
pub fn write_ascii(req: &Request, w: &mut impl Write) -> io::Result<()> {
    emit(req, &mut AsciiSink { w })
}

/// The canonical ASCII text of one request, without the newline.
pub fn to_ascii(req: &Request) -> String {
    let mut out = Vec::new();
    write_ascii(req, &mut out).expect("writing to a Vec cannot fail");
    out.pop();
    String::from_utf8(out).expect("the printer writes UTF-8")
}

struct AsciiSink<'a, W> {
    w: &'a mut W,
}

/// A string literal with C escapes: what the lexer reads back byte for byte.
pub(crate) fn quote(s: &str, w: &mut impl Write) -> io::Result<()> {
    w.write_all(b"\"")?;
    let bytes = s.as_bytes();
    let mut start = 0;
    for (i, &b) in bytes.iter().enumerate() {
        let escape: Option<&[u8]> = match b {
            b'"' => Some(b"\\\""),
            b'\\' => Some(b"\\\\"),
            b'\n' => Some(b"\\n"),
            b'\t' => Some(b"\\t"),
            b'\r' => Some(b"\\r"),
            _ => None,
        };
        if escape.is_some() || b < 0x20 || b == 0x7f {
            w.write_all(&bytes[start..i])?;
            match escape {
                Some(e) => w.write_all(e)?,
                None => write!(w, "\\{b:03o}")?,
            }
            start = i + 1;
        }
    }
    w.write_all(&bytes[start..])?;
    w.write_all(b"\"")
}

fn positional(f: f32, w: &mut impl Write) -> io::Result<()> {
    if f.fract() == 0.0 && f.abs() < 1e9 && !(f == 0.0 && f.is_sign_negative()) {
        write!(w, "{}", f as i32)
    } else {
        write!(w, "{f:?}")
    }
}

impl<W: Write> Sink for AsciiSink<'_, W> {
    fn name(&mut self, name: &str) -> io::Result<()> {
        self.w.write_all(name.as_bytes())
    }
    fn int(&mut self, v: i32) -> io::Result<()> {
        write!(self.w, " {v}")
    }
    fn float(&mut self, v: f32) -> io::Result<()> {
        self.w.write_all(b" ")?;
        positional(v, self.w)
    }
    fn string(&mut self, s: &str) -> io::Result<()> {
        self.w.write_all(b" ")?;
        quote(s, self.w)
    }
    fn ints(&mut self, v: &[i32]) -> io::Result<()> {
        self.w.write_all(b" [")?;
        for (i, x) in v.iter().enumerate() {
            if i > 0 {
                self.w.write_all(b" ")?;
            }
            write!(self.w, "{x}")?;
        }
        self.w.write_all(b"]")
    }
    fn floats(&mut self, v: &[f32]) -> io::Result<()> {
        self.w.write_all(b" [")?;
        for (i, x) in v.iter().enumerate() {
            if i > 0 {
                self.w.write_all(b" ")?;
            }
            write!(self.w, "{x:?}")?;
        }
        self.w.write_all(b"]")
    }
    fn number_array(&mut self, v: &[f32]) -> io::Result<()> {
        self.w.write_all(b" [")?;
        for (i, &x) in v.iter().enumerate() {
            if i > 0 {
                self.w.write_all(b" ")?;
            }
            positional(x, self.w)?;
        }
        self.w.write_all(b"]")
    }
    fn strings(&mut self, v: &[String]) -> io::Result<()> {
        self.w.write_all(b" [")?;
        for (i, s) in v.iter().enumerate() {
            if i > 0 {
                self.w.write_all(b" ")?;
            }
            quote(s, self.w)?;
        }
        self.w.write_all(b"]")
    }
    fn structure(&mut self, text: &str) -> io::Result<()> {
        // A newline inside would end the comment early; `##` text comes from one line anyway.
        let one_line: String = text.chars().filter(|&c| c != '\n').collect();
        writeln!(self.w, "##{one_line}")
    }
    fn end(&mut self) -> io::Result<()> {
        self.w.write_all(b"\n")
    }
}
