//! RIB tokens, read in chunks from any `Read`: ASCII (RI Spec 3.2 chapter "RIB") and the binary
//! encoding of Appendix C, freely mixed in one stream (a byte ≥ 0x80 outside a string starts a
//! binary token).
//!
//! Memory stays bounded by the token in hand: the buffer holds one chunk plus the unfinished
//! token, and variable-length binary tokens (strings, float arrays) are read incrementally, so a
//! corrupt length field of 2^31 costs nothing until that many bytes actually arrive.
use nom::bytes::complete::take_while1;
use nom::IResult;
use std::collections::HashMap;
use std::io::{self, Read};
use std::sync::Arc;

/// Bytes requested from the reader per refill, at most.
const CHUNK: usize = 256 * 1024;
/// Bytes requested by the first refill; each refill doubles it up to [`CHUNK`]. Zeroing and
/// mapping a 256 KiB buffer for a 100-byte archive (or fuzz input) cost more than parsing it.
const FIRST_CHUNK: usize = 4096;
/// Longest number or name token; anything longer is corrupt input, not a RIB token.
const MAX_WORD: usize = 4096;
/// Longest string: beyond this an unterminated string would swallow the whole file.
pub(crate) const MAX_STRING: usize = 16 << 20;
/// Longest `##` comment kept; the rest of the line is skipped.
const MAX_COMMENT: usize = 4096;
/// How much of a line before the current token the buffer keeps for diagnostics.
const KEEP_LINE: usize = 512;

#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Token {
    /// A request name: an ASCII identifier or a binary-encoded request (0246).
    Name(Arc<str>),
    Int(i32),
    Float(f32),
    Str(String),
    /// A binary IEEE float array (0310–0313): an array by itself, no brackets.
    FloatArray(Vec<f32>),
    Open,
    Close,
    /// `##` comment text, after the `##`.
    Structure(String),
    Eof,
}

impl Token {
    /// How the token is named in messages ("expected a number, found a string").
    pub(crate) fn describe(&self) -> String {
        match self {
            Token::Name(n) => format!("request name `{n}`"),
            Token::Int(i) => format!("number {i}"),
            Token::Float(f) => format!("number {f}"),
            Token::Str(s) => format!("string \"{}\"", s.escape_debug()),
            Token::FloatArray(_) => "binary float array".into(),
            Token::Open => "`[`".into(),
            Token::Close => "`]`".into(),
            Token::Structure(_) => "`##` comment".into(),
            Token::Eof => "end of file".into(),
        }
    }
}

/// A position in the decompressed stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Pos {
    pub line: u32,
    pub col: u32,
    pub offset: u64,
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LexError {
    pub pos: Pos,
    pub message: String,
    /// The line the error is on, as far as the buffer still holds it.
    pub source_line: String,
}

pub(crate) struct Lexer<R> {
    reader: R,
    buf: Vec<u8>,
    pos: usize,
    /// Stream offset of `buf[0]`.
    base: u64,
    eof: bool,
    line: u32,
    /// Stream offset where the current line starts.
    line_start: u64,
    /// Skipping the rest of an over-long comment line.
    in_comment: bool,
    /// Every comment record (`##` structural: true), when asked for (`RiReadArchive` callbacks).
    pub(crate) comments: Option<Vec<(bool, String)>>,
    pub(crate) io_error: Option<io::Error>,
    /// Errors leave out the source line: the parser is skipping to the next request and drops
    /// them, and copying the line for every garbage byte cost half the parse of a corrupt file.
    pub(crate) quiet: bool,
    /// Binary request definitions (0314): code → request name.
    requests: HashMap<u8, Arc<str>>,
    /// Binary string definitions (0315/0316): token → string.
    strings: HashMap<u16, String>,
    /// Bytes the next refill asks for: [`FIRST_CHUNK`], doubling up to [`CHUNK`].
    chunk: usize,
}

/// Byte classes for the word scanners, as a table: the hot loop of the whole parser.
const DIGIT: u8 = 1;
const NUMBER_PUNCT: u8 = 2;
const NAME: u8 = 4;
static CLASS: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut b = 0;
    while b < 256 {
        let c = b as u8;
        let mut k = 0;
        if c.is_ascii_digit() {
            k |= DIGIT;
        }
        if matches!(c, b'+' | b'-' | b'.' | b'e' | b'E') {
            k |= NUMBER_PUNCT;
        }
        if c.is_ascii_alphanumeric() || c == b'_' {
            k |= NAME;
        }
        t[b] = k;
        b += 1;
    }
    t
};

fn is_name_byte(b: u8) -> bool {
    CLASS[usize::from(b)] & NAME != 0
}

/// A maximal run of bytes that can belong to a word (name or number), for the nom recognisers.
fn word(input: &[u8], number: bool) -> IResult<&[u8], &[u8]> {
    if number {
        // Letters are included so that `1.0f` is reported as one bad number, not `1.0` then `f`.
        take_while1(|b| CLASS[usize::from(b)] != 0)(input)
    } else {
        take_while1(is_name_byte)(input)
    }
}

/// Classifies a number token: integer literals become `Int` (ASCII cannot tell `1` from `1.0`
/// by type, so the parser keeps the distinction it can see), everything else `Float`.
pub(crate) fn parse_number(text: &[u8]) -> Result<Token, String> {
    let (neg, digits) = match text.first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    if !digits.is_empty()
        && digits.len() <= 10
        && digits.iter().all(|&b| CLASS[usize::from(b)] & DIGIT != 0)
    {
        let v = digits
            .iter()
            .fold(0i64, |v, &d| v * 10 + i64::from(d - b'0'));
        if let Ok(i) = i32::try_from(if neg { -v } else { v }) {
            return Ok(Token::Int(i));
        }
    }
    // fast-float2 reads every RIB number form (`-.5`, `1.e-3`, `1E+4`, `+2`); it also reads
    // `inf` and `nan`, which RIB does not have: the finiteness check rejects them.
    match fast_float2::parse::<f32, _>(text) {
        Ok(f) if f.is_finite() => Ok(Token::Float(f)),
        Ok(_)
            if !text
                .iter()
                .any(|b| b.is_ascii_alphabetic() && !matches!(b, b'e' | b'E')) =>
        {
            Err(format!(
                "number `{}` is out of range for a float",
                String::from_utf8_lossy(text)
            ))
        }
        _ => Err(format!("bad number `{}`", String::from_utf8_lossy(text))),
    }
}

/// A comment's text as the printer can write it back: invalid UTF-8 becomes U+FFFD, which
/// takes three bytes where the bad byte took one, so the text is cut again (at a character
/// boundary) to what fits a `##` line of [`MAX_COMMENT`] bytes; without that cut, a printed
/// comment would be read back shorter than it was printed (a fuzzing finding). A trailing
/// `\r` (a CRLF line end) is dropped.
fn comment_text(raw: &[u8]) -> String {
    let mut text = String::from_utf8_lossy(raw).into_owned();
    let mut end = text.len().min(MAX_COMMENT - 2);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    text.truncate(end);
    let kept = text.trim_end_matches('\r').len();
    text.truncate(kept);
    text
}

/// The UTF-8 encoding of U+FEFF.
const UTF8_BOM: &[u8] = &[0xef, 0xbb, 0xbf];

impl<R: Read> Lexer<R> {
    pub(crate) fn new(reader: R) -> Self {
        Lexer {
            reader,
            buf: Vec::new(),
            pos: 0,
            base: 0,
            eof: false,
            line: 1,
            line_start: 0,
            in_comment: false,
            comments: None,
            io_error: None,
            quiet: false,
            requests: HashMap::new(),
            strings: HashMap::new(),
            chunk: FIRST_CHUNK,
        }
    }

    fn abs(&self) -> u64 {
        self.base + self.pos as u64
    }

    pub(crate) fn here(&self) -> Pos {
        let offset = self.abs();
        let col = offset.saturating_sub(self.line_start) + 1;
        Pos {
            line: self.line,
            col: u32::try_from(col).unwrap_or(u32::MAX),
            offset,
        }
    }

    /// The current line as far as the buffer holds it (at most 200 characters shown).
    pub(crate) fn current_line(&self) -> String {
        let start = self.line_start.saturating_sub(self.base) as usize;
        if self.line_start < self.base || start > self.buf.len() {
            return String::new();
        }
        let rest = &self.buf[start..];
        // At most 200 bytes are shown: a newline further on changes nothing.
        let rest = &rest[..rest.len().min(200)];
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        let text = &rest[..end];
        let control = |b: u8| (b < 0x20 && b != b'\t' && b != b'\r') || b == 0x7f;
        if text.iter().any(|&b| control(b)) || std::str::from_utf8(text).is_err() {
            // Binary RIB or garbage: a caret under it would not help.
            return String::new();
        }
        String::from_utf8_lossy(text)
            .trim_end_matches('\r')
            .to_string()
    }

    fn error(&self, pos: Pos, message: impl Into<String>) -> LexError {
        LexError {
            pos,
            message: message.into(),
            source_line: if self.quiet {
                String::new()
            } else {
                self.current_line()
            },
        }
    }

    /// Reads one more chunk; `false` at end of input (or after a read error, kept in
    /// `io_error`). Bytes before `pos` are dropped except a little of the current line.
    fn fill(&mut self) -> bool {
        if self.eof {
            return false;
        }
        let line_start = self.line_start.saturating_sub(self.base) as usize;
        let keep_from = if self.line_start >= self.base && self.pos - line_start <= KEEP_LINE {
            line_start
        } else {
            self.pos
        };
        if keep_from > 0 {
            self.buf.drain(..keep_from);
            self.base += keep_from as u64;
            self.pos -= keep_from;
        }
        let old = self.buf.len();
        self.buf.resize(old + self.chunk, 0);
        self.chunk = (2 * self.chunk).min(CHUNK);
        loop {
            match self.reader.read(&mut self.buf[old..]) {
                Ok(0) => {
                    self.buf.truncate(old);
                    self.eof = true;
                    return false;
                }
                Ok(n) => {
                    self.buf.truncate(old + n);
                    return true;
                }
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => {
                    self.buf.truncate(old);
                    self.io_error = Some(e);
                    self.eof = true;
                    return false;
                }
            }
        }
    }

    /// Makes at least `n` bytes available after `pos`; `false` if the stream ends first.
    fn ensure(&mut self, n: usize) -> bool {
        while self.buf.len() - self.pos < n {
            if !self.fill() {
                return false;
            }
        }
        true
    }

    /// A UTF-8 byte-order mark at the very start of the stream.
    fn at_utf8_bom(&mut self) -> bool {
        self.abs() == 0 && self.ensure(UTF8_BOM.len()) && self.buf[self.pos..].starts_with(UTF8_BOM)
    }

    fn newline(&mut self) {
        self.line += 1;
        self.line_start = self.abs();
    }

    /// The next token and where it starts. Errors consume the offending bytes, so calling again
    /// always makes progress.
    pub(crate) fn next_token(&mut self) -> Result<(Token, Pos), LexError> {
        loop {
            if self.pos == self.buf.len() && !self.fill() {
                return Ok((Token::Eof, self.here()));
            }
            if self.in_comment {
                self.skip_comment_rest();
                continue;
            }
            let b = self.buf[self.pos];
            match b {
                b' ' | b'\t' | b'\r' | 0x0b | 0x0c => {
                    self.skip_blanks();
                }
                b'\n' => {
                    self.pos += 1;
                    self.newline();
                }
                b'#' => {
                    if let Some(t) = self.comment() {
                        return Ok(t);
                    }
                }
                b'"' => return self.string().map(|(s, p)| (Token::Str(s), p)),
                b'[' => {
                    let p = self.here();
                    self.pos += 1;
                    return Ok((Token::Open, p));
                }
                b']' => {
                    let p = self.here();
                    self.pos += 1;
                    return Ok((Token::Close, p));
                }
                b'0'..=b'9' | b'+' | b'-' | b'.' => return self.word(true),
                b'a'..=b'z' | b'A'..=b'Z' | b'_' => return self.word(false),
                0xef if self.at_utf8_bom() => {
                    // Editors on Windows save RIB as UTF-8 with a byte-order mark: invisible text,
                    // not the binary encoding that other bytes >= 0x80 start.
                    self.pos += UTF8_BOM.len();
                    self.line_start = self.abs();
                }
                0x80..=0xff => {
                    if let Some(t) = self.binary()? {
                        return Ok(t);
                    }
                }
                0 => {
                    let p = self.here();
                    self.pos += 1;
                    return Err(self.error(p, "NUL byte in the stream (is this a RIB file?)"));
                }
                _ => {
                    let p = self.here();
                    self.pos += 1;
                    let shown = if b.is_ascii_graphic() {
                        format!("`{}`", b as char)
                    } else {
                        format!("byte 0x{b:02x}")
                    };
                    return Err(self.error(p, format!("unexpected {shown}")));
                }
            }
        }
    }

    fn skip_blanks(&mut self) {
        let rest = &self.buf[self.pos..];
        let n = rest
            .iter()
            .position(|b| !matches!(b, b' ' | b'\t' | b'\r' | 0x0b | 0x0c))
            .unwrap_or(rest.len());
        self.pos += n;
    }

    fn skip_comment_rest(&mut self) {
        let rest = &self.buf[self.pos..];
        match rest.iter().position(|&b| b == b'\n') {
            Some(n) => {
                self.pos += n;
                self.in_comment = false;
            }
            None => self.pos = self.buf.len(),
        }
    }

    /// `#` to end of line; `##` comments are structural and become a token.
    fn comment(&mut self) -> Option<(Token, Pos)> {
        let p = self.here();
        // Find the end of the line, refilling for long comments up to MAX_COMMENT.
        loop {
            let rest = &self.buf[self.pos..];
            let end = rest.iter().position(|&b| b == b'\n');
            let complete = end.is_some() || self.eof || rest.len() > MAX_COMMENT;
            if complete {
                let len = end.unwrap_or(rest.len()).min(MAX_COMMENT);
                let structural = rest.get(1) == Some(&b'#');
                let skip = if structural { 2 } else { 1 };
                let body = comment_text(&rest[skip.min(len)..len]);
                if let Some(c) = &mut self.comments {
                    c.push((structural, body.clone()));
                }
                let text = structural.then_some(body);
                self.pos += len;
                if end.is_none_or(|e| e > len) {
                    self.in_comment = true;
                }
                return text.map(|t| (Token::Structure(t), p));
            }
            if !self.fill() {
                continue; // eof now set: the next pass completes
            }
        }
    }

    /// A name or number; the whole word must be in the buffer, so refill while it touches the end.
    fn word(&mut self, number: bool) -> Result<(Token, Pos), LexError> {
        let p = self.here();
        let len = loop {
            let rest = &self.buf[self.pos..];
            let len = word(rest, number).map(|(_, w)| w.len()).unwrap_or(0);
            if len == rest.len() && !self.eof && len <= MAX_WORD {
                self.fill();
                continue;
            }
            break len;
        };
        let text = &self.buf[self.pos..self.pos + len];
        self.pos += len;
        if len > MAX_WORD {
            return Err(self.error(p, format!("token longer than {MAX_WORD} bytes")));
        }
        if number {
            match parse_number(text) {
                Ok(t) => Ok((t, p)),
                Err(m) => Err(self.error(p, m)),
            }
        } else {
            // Names are ASCII by construction.
            let name = std::str::from_utf8(text).unwrap_or_default();
            Ok((Token::Name(Arc::from(name)), p))
        }
    }

    /// A quoted string with C escapes (`\n \t \r \b \f \\ \" \ooo`, backslash-newline
    /// continues the line), read incrementally.
    fn string(&mut self) -> Result<(String, Pos), LexError> {
        let p = self.here();
        self.pos += 1;
        let mut out: Vec<u8> = Vec::new();
        let mut nul = false;
        loop {
            if self.pos == self.buf.len() && !self.fill() {
                return Err(self.error(p, "unterminated string"));
            }
            if out.len() > MAX_STRING {
                return Err(self.error(p, "string longer than 16 MiB (unterminated string?)"));
            }
            let rest = &self.buf[self.pos..];
            // Copy the plain run in one go: strings are mostly plain bytes.
            let run = rest
                .iter()
                .position(|&b| matches!(b, b'"' | b'\\' | b'\n' | 0))
                .unwrap_or(rest.len());
            out.extend_from_slice(&rest[..run]);
            self.pos += run;
            if self.pos == self.buf.len() {
                continue;
            }
            match self.buf[self.pos] {
                b'"' => {
                    self.pos += 1;
                    break;
                }
                b'\n' => {
                    out.push(b'\n');
                    self.pos += 1;
                    self.newline();
                }
                0 => {
                    nul = true;
                    self.pos += 1;
                }
                _ => self.escape(&mut out),
            }
        }
        if nul {
            return Err(self.error(p, "NUL byte in string"));
        }
        match String::from_utf8(out) {
            Ok(s) => Ok((s, p)),
            Err(_) => Err(self.error(p, "string is not valid UTF-8")),
        }
    }

    /// One backslash escape at `pos`.
    fn escape(&mut self, out: &mut Vec<u8>) {
        self.ensure(4);
        let rest = &self.buf[self.pos + 1..];
        let Some(&c) = rest.first() else {
            self.pos += 1; // a lone backslash at end of file; the caller reports the string
            return;
        };
        let mut used = 2;
        match c {
            b'n' => out.push(b'\n'),
            b't' => out.push(b'\t'),
            b'r' => out.push(b'\r'),
            b'b' => out.push(8),
            b'f' => out.push(12),
            b'\n' => {
                self.pos += used;
                self.newline();
                return;
            }
            b'\r' if rest.get(1) == Some(&b'\n') => {
                self.pos += 3;
                self.newline();
                return;
            }
            b'0'..=b'7' => {
                let digits = rest
                    .iter()
                    .take(3)
                    .take_while(|d| (b'0'..=b'7').contains(d))
                    .count();
                let v = rest[..digits]
                    .iter()
                    .fold(0u32, |v, d| v * 8 + u32::from(d - b'0'));
                out.push((v & 0xff) as u8);
                used = 1 + digits;
            }
            other => out.push(other),
        }
        self.pos += used;
    }

    fn take(&mut self, n: usize, p: Pos, what: &str) -> Result<&[u8], LexError> {
        if !self.ensure(n) {
            self.pos = self.buf.len();
            return Err(self.error(p, format!("binary RIB truncated in {what}")));
        }
        let s = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    /// Big-endian unsigned integer of `n` ≤ 4 bytes.
    fn take_unsigned(&mut self, n: usize, p: Pos, what: &str) -> Result<u32, LexError> {
        Ok(self
            .take(n, p, what)?
            .iter()
            .fold(0u32, |v, &b| (v << 8) | u32::from(b)))
    }

    /// A binary token (Appendix C). Definitions return `None`: they produce no token.
    fn binary(&mut self) -> Result<Option<(Token, Pos)>, LexError> {
        let p = self.here();
        let code = self.buf[self.pos];
        self.pos += 1;
        let token = match code {
            // 0200 + 4d + l: (l+1)-byte signed integer with d bytes of fraction.
            0x80..=0x8f => {
                let l = usize::from(code & 3) + 1;
                let d = i32::from((code >> 2) & 3);
                let raw = self.take_unsigned(l, p, "an encoded number")?;
                let shift = 32 - 8 * l as u32;
                let v = ((raw << shift) as i32) >> shift;
                if d == 0 {
                    Token::Int(v)
                } else {
                    Token::Float((f64::from(v) / 256f64.powi(d)) as f32)
                }
            }
            0x90..=0x9f => Token::Str(self.binary_string(usize::from(code & 0xf), p)?),
            0xa0..=0xa3 => {
                let len = self.take_unsigned(usize::from(code & 3) + 1, p, "a string length")?;
                Token::Str(self.binary_string(len as usize, p)?)
            }
            0xa4 => {
                let b = self.take(4, p, "a float")?;
                Token::Float(f32::from_be_bytes([b[0], b[1], b[2], b[3]]))
            }
            0xa5 => {
                let b = self.take(8, p, "a double")?;
                let mut a = [0u8; 8];
                a.copy_from_slice(b);
                Token::Float(f64::from_be_bytes(a) as f32)
            }
            0xa6 => {
                let c = self.take(1, p, "a request code")?[0];
                match self.requests.get(&c) {
                    Some(name) => Token::Name(name.clone()),
                    None => return Err(self.error(p, format!("undefined binary request code {c}"))),
                }
            }
            0xc8..=0xcb => {
                let n = self.take_unsigned(usize::from(code & 3) + 1, p, "an array length")?;
                Token::FloatArray(self.binary_floats(n as usize, p)?)
            }
            0xcc => {
                let c = self.take(1, p, "a request definition")?[0];
                let name = self.definition_string(p)?;
                let starts_alpha = name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_');
                if !starts_alpha || !name.bytes().all(is_name_byte) {
                    return Err(self.error(p, format!("bad binary request name {name:?}")));
                }
                self.requests.insert(c, Arc::from(name.as_str()));
                return Ok(None);
            }
            0xcd | 0xce => {
                let id = self.take_unsigned(usize::from(code - 0xcd) + 1, p, "a string token")?;
                let s = self.definition_string(p)?;
                self.strings.insert(id as u16, s);
                return Ok(None);
            }
            0xcf | 0xd0 => {
                let id = self.take_unsigned(usize::from(code - 0xcf) + 1, p, "a string token")?;
                match self.strings.get(&(id as u16)) {
                    Some(s) => Token::Str(s.clone()),
                    None => return Err(self.error(p, format!("undefined binary string {id}"))),
                }
            }
            _ => {
                return Err(self.error(
                    p,
                    format!("reserved binary RIB code 0x{code:02x} (octal {code:o})"),
                ))
            }
        };
        let finite = match &token {
            Token::Float(f) => f.is_finite(),
            Token::FloatArray(v) => v.iter().all(|f| f.is_finite()),
            _ => true,
        };
        if !finite {
            // As in ASCII RIB, where `inf` and `nan` do not lex: no request takes them.
            return Err(self.error(p, "binary float is infinite or NaN"));
        }
        Ok(Some((token, p)))
    }

    /// The string operand of a definition: any string encoding, ASCII or binary.
    fn definition_string(&mut self, p: Pos) -> Result<String, LexError> {
        match self.next_token()? {
            (Token::Str(s), _) => Ok(s),
            (other, _) => Err(self.error(
                p,
                format!(
                    "binary definition expects a string, found {}",
                    other.describe()
                ),
            )),
        }
    }

    /// `len` bytes of string, read as they arrive (no allocation from the length field).
    fn binary_string(&mut self, len: usize, p: Pos) -> Result<String, LexError> {
        if len > MAX_STRING {
            return Err(self.error(p, format!("binary string length {len} exceeds 16 MiB")));
        }
        let mut out = Vec::with_capacity(len.min(4096));
        while out.len() < len {
            if self.pos == self.buf.len() && !self.fill() {
                return Err(self.error(p, "binary RIB truncated in a string"));
            }
            let n = (len - out.len()).min(self.buf.len() - self.pos);
            out.extend_from_slice(&self.buf[self.pos..self.pos + n]);
            self.pos += n;
        }
        String::from_utf8(out).map_err(|_| self.error(p, "string is not valid UTF-8"))
    }

    /// `n` big-endian IEEE floats, read as they arrive.
    fn binary_floats(&mut self, n: usize, p: Pos) -> Result<Vec<f32>, LexError> {
        let mut out = Vec::with_capacity(n.min(4096));
        while out.len() < n {
            if !self.ensure(4) {
                self.pos = self.buf.len();
                return Err(self.error(
                    p,
                    format!(
                        "binary RIB truncated in a float array ({} of {n} floats)",
                        out.len()
                    ),
                ));
            }
            let avail = (self.buf.len() - self.pos) / 4;
            let k = avail.min(n - out.len());
            let bytes = &self.buf[self.pos..self.pos + 4 * k];
            out.extend(
                bytes
                    .chunks_exact(4)
                    .map(|c| f32::from_be_bytes([c[0], c[1], c[2], c[3]])),
            );
            self.pos += 4 * k;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests;
