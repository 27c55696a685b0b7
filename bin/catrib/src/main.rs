//! `catrib`: reads RIB files (ASCII, gzip or binary, `-` for stdin) and writes the request stream
//! as canonical ASCII RIB (one request per line), binary RIB, or either gzipped.
//!
//! Exit codes: 0 clean (warnings allowed), 1 errors found (the good requests are still
//! written), 2 usage or output failure.
#![forbid(unsafe_code)]
use clap::Parser as _;
use illume_rib::{BinaryWriter, Request};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Parser)]
#[command(
    name = "catrib",
    version,
    about = "Print RIB as canonical ASCII or binary RIB"
)]
struct Cli {
    /// Write to this file instead of stdout (written to a temporary name, then renamed).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Write binary RIB (RI Spec 3.2 Appendix C).
    #[arg(long)]
    binary: bool,
    /// Compress the output with gzip.
    #[arg(long)]
    gzip: bool,
    /// Input RIB files; `-` reads stdin.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
}

/// The chosen encoding over the chosen byte sink.
enum Encoder<W: Write> {
    Ascii(W),
    Binary(BinaryWriter<W>),
}

impl<W: Write> Encoder<W> {
    fn write(&mut self, req: &Request) -> io::Result<()> {
        match self {
            Encoder::Ascii(w) => illume_rib::write_ascii(req, w),
            Encoder::Binary(b) => b.write(req),
        }
    }

    fn finish(self) -> io::Result<W> {
        match self {
            Encoder::Ascii(w) => Ok(w),
            Encoder::Binary(b) => Ok(b.into_inner()),
        }
    }
}

/// Copies every input to `out`; returns whether any error diagnostic was printed.
fn copy<W: Write>(inputs: &[PathBuf], out: &mut Encoder<W>) -> io::Result<bool> {
    let mut errors = false;
    let stderr = io::stderr();
    for input in inputs {
        let parser = match illume_rib::open(input) {
            Ok(p) => p,
            Err(e) => {
                writeln!(stderr.lock(), "catrib: {}: {e}", input.display())?;
                errors = true;
                continue;
            }
        };
        for item in parser {
            match item {
                Ok(req) => out.write(&req.value)?,
                Err(d) => {
                    errors |= d.is_error();
                    writeln!(stderr.lock(), "{d}")?;
                }
            }
        }
    }
    Ok(errors)
}

fn run(cli: &Cli, sink: Box<dyn Write>) -> io::Result<bool> {
    let sink: Box<dyn Write> = if cli.gzip {
        Box::new(flate2::write::GzEncoder::new(
            sink,
            flate2::Compression::default(),
        ))
    } else {
        sink
    };
    let mut enc = if cli.binary {
        Encoder::Binary(BinaryWriter::new(sink))
    } else {
        Encoder::Ascii(sink)
    };
    let errors = copy(&cli.inputs, &mut enc)?;
    enc.finish()?.flush()?;
    Ok(errors)
}

fn temp_name(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".catrib-{}.tmp", std::process::id()));
    path.with_file_name(name)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.output {
        None => {
            let stdout = BufWriter::with_capacity(1 << 16, io::stdout().lock());
            run(&cli, Box::new(stdout))
        }
        Some(path) => {
            let tmp = temp_name(path);
            let done = File::create(&tmp)
                .and_then(|f| run(&cli, Box::new(BufWriter::with_capacity(1 << 16, f))));
            match done {
                Ok(errors) => std::fs::rename(&tmp, path).map(|()| errors),
                Err(e) => {
                    let _ = std::fs::remove_file(&tmp);
                    Err(e)
                }
            }
        }
    };
    match result {
        Ok(false) => ExitCode::SUCCESS,
        Ok(true) => ExitCode::from(1),
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("catrib: {e}");
            ExitCode::from(2)
        }
    }
}
