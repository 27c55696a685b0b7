//! The RIB-writing back end: canonical ASCII (`catrib`'s form), binary RIB (RI 3.2 Appendix C)
//! or either one gzip-compressed, chosen as PRMan does with `Option "rib" "string format"
//! ["ascii"|"binary"]` and `"string compression" ["gzip"|"none"]`.
//!
//! The encoder starts at the first request that is not a `rib` option, so options given right
//! after `RiBegin` decide the compression; the format may change at any point (binary and
//! ASCII mix freely in one stream). Defaults come from the file name (`.gz` means gzip) and the
//! environment (`ILLUME_RIBFORMAT`, `ILLUME_RIBCOMPRESSION`), so `ILLUME_RIBOUT` captures can be
//! binary or compressed without changing the program.
use crate::backend::Backend;
use crate::errors::{RiError, RIE_BADTOKEN, RIE_ILLSTATE, RIE_SEVERE, RIE_SYSTEM, RIE_WARNING};
use flate2::write::GzEncoder;
use illume_ri::{Frame, Ri};
use illume_rib::{BinaryWriter, Declaration, Param, Request, Value};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// How requests are encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RibFormat {
    Ascii,
    Binary,
}

/// The file, plain or gzip-compressed.
enum Output {
    Plain(BufWriter<File>),
    Gzip(GzEncoder<BufWriter<File>>),
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match self {
            Output::Plain(w) => w.write(buf),
            Output::Gzip(w) => w.write(buf),
        }
    }
    fn flush(&mut self) -> io::Result<()> {
        match self {
            Output::Plain(w) => w.flush(),
            Output::Gzip(w) => w.flush(),
        }
    }
}

impl Output {
    /// Writes the gzip trailer (if any) and flushes the file.
    fn finish(self) -> io::Result<()> {
        match self {
            Output::Plain(mut w) => w.flush(),
            Output::Gzip(w) => w.finish()?.flush(),
        }
    }
}

/// Writes a session's requests to a RIB file.
pub struct RibWriter {
    /// The opened file until the encoder starts.
    file: Option<File>,
    /// The encoder once the first request is written (it keeps the binary request codes).
    stream: Option<BinaryWriter<Output>>,
    path: PathBuf,
    format: RibFormat,
    gzip: bool,
}

impl RibWriter {
    /// Creates the file now (so a bad path is reported by `RiBegin`); nothing is written yet.
    pub fn create(path: &Path) -> io::Result<RibWriter> {
        let env = |k: &str| std::env::var(k).unwrap_or_default().to_ascii_lowercase();
        let gz_name = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
        Ok(RibWriter {
            file: Some(File::create(path)?),
            stream: None,
            path: path.to_path_buf(),
            format: match env("ILLUME_RIBFORMAT").as_str() {
                "binary" => RibFormat::Binary,
                _ => RibFormat::Ascii,
            },
            gzip: match env("ILLUME_RIBCOMPRESSION").as_str() {
                "gzip" => true,
                "none" => false,
                _ => gz_name,
            },
        })
    }

    fn io_error(&self, e: io::Error) -> RiError {
        RiError::new(
            RIE_SYSTEM,
            RIE_SEVERE,
            format!("{}: {e}", self.path.display()),
        )
    }

    /// The encoder, started on first use with the header comment.
    fn stream(&mut self) -> io::Result<&mut BinaryWriter<Output>> {
        if self.stream.is_none() {
            let file = BufWriter::new(self.file.take().expect("file kept until the stream starts"));
            let mut out = if self.gzip {
                Output::Gzip(GzEncoder::new(file, flate2::Compression::default()))
            } else {
                Output::Plain(file)
            };
            writeln!(out, "##RenderMan RIB")?;
            self.stream = Some(BinaryWriter::new(out));
        }
        Ok(self.stream.as_mut().expect("started above"))
    }

    /// `Option "rib" …`: the writer's own settings (never written to the file).
    fn set_option(&mut self, params: &[Param]) -> Vec<RiError> {
        let mut problems = Vec::new();
        for p in params {
            let name = Declaration::split_inline(&p.name).map_or(p.name.as_str(), |(_, n)| n);
            let value = match &p.value {
                Value::Strings(s) => s.first().map(|s| s.to_ascii_lowercase()),
                _ => None,
            };
            match (name, value.as_deref()) {
                ("format", Some("ascii")) => self.format = RibFormat::Ascii,
                ("format", Some("binary")) => self.format = RibFormat::Binary,
                ("compression", Some(c @ ("gzip" | "none"))) => {
                    let gzip = c == "gzip";
                    if self.stream.is_some() && gzip != self.gzip {
                        problems.push(RiError::new(
                            RIE_ILLSTATE,
                            RIE_WARNING,
                            format!(
                                "Option \"rib\" \"compression\": requests were already written \
                                 to {}; give it right after RiBegin (ignored)",
                                self.path.display()
                            ),
                        ));
                    } else {
                        self.gzip = gzip;
                    }
                }
                _ => problems.push(RiError::new(
                    RIE_BADTOKEN,
                    RIE_WARNING,
                    format!(
                        "Option \"rib\" \"{name}\": expected \"format\" [\"ascii\"|\"binary\"] \
                         or \"compression\" [\"gzip\"|\"none\"] (ignored)"
                    ),
                )),
            }
        }
        problems
    }
}

impl Backend for RibWriter {
    fn configure(&self, ri: &mut Ri) {
        // The RIB's reader makes the textures; the shadow state machine only validates.
        ri.set_texture_maker(Box::new(|_, _| Ok(())));
    }

    fn writes_rib(&self) -> bool {
        true
    }

    fn rib_option(&mut self, params: &[Param]) -> Vec<RiError> {
        self.set_option(params)
    }

    fn write(&mut self, req: &Request) -> Result<(), RiError> {
        let format = self.format;
        let result = self.stream().and_then(|s| match format {
            RibFormat::Ascii => illume_rib::write_ascii(req, s.get_mut()),
            RibFormat::Binary => s.write(req),
        });
        result.map_err(|e| self.io_error(e))
    }

    fn comment(&mut self, text: &str) -> Result<(), RiError> {
        let result = self.stream().and_then(|s| {
            text.lines()
                .try_for_each(|line| writeln!(s.get_mut(), "#{line}"))
        });
        result.map_err(|e| self.io_error(e))
    }

    fn frame(&mut self, _frame: Frame) -> Vec<RiError> {
        Vec::new()
    }

    fn finish(&mut self) -> Result<(), RiError> {
        let result = self.stream().map(|_| ()).and_then(|()| {
            let s = self.stream.take().expect("started above");
            s.into_inner().finish()
        });
        result.map_err(|e| self.io_error(e))
    }
}
