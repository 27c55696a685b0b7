//! Parse throughput on a generated number-heavy RIB (PatchMesh and PointsPolygons), as ASCII,
//! gzip and binary. Run with
//! `cargo run --release -p illume-rib --example parse_throughput [megabytes]` (default 64).
//!
//! Throughput is MB of *decompressed ASCII-equivalent input per second* for ASCII and gzip,
//! and MB of binary input per second for binary (also given as ASCII-equivalent).
use illume_rib::{BinaryWriter, Parser};
use std::io::Write;
use std::time::Instant;

/// Deterministic pseudo-random floats with 3–6 significant digits, like exporter output.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let v = ((self.0 >> 33) % 2_000_000) as f32 / 1000.0 - 1000.0;
        (v * 1000.0).round() / 1000.0
    }
}

fn generate(bytes: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes + (1 << 20));
    let mut rng = Lcg(7);
    writeln!(out, "##RenderMan RIB\nversion 3.03\nWorldBegin").unwrap();
    let mut k = 0;
    while out.len() < bytes {
        if k % 2 == 0 {
            // A 16x16 bicubic patch mesh: 768 point coordinates.
            write!(
                out,
                "PatchMesh \"bicubic\" 16 \"nonperiodic\" 16 \"nonperiodic\" \"P\" ["
            )
            .unwrap();
            for i in 0..16 * 16 * 3 {
                if i % 12 == 0 {
                    out.push(b'\n');
                }
                write!(out, "{} ", rng.next()).unwrap();
            }
            writeln!(out, "]").unwrap();
        } else {
            // 200 quads over 400 points, with normals.
            write!(out, "PointsPolygons [").unwrap();
            for _ in 0..200 {
                write!(out, "4 ").unwrap();
            }
            write!(out, "] [").unwrap();
            for i in 0..800 {
                write!(out, "{} ", (i * 7) % 400).unwrap();
            }
            write!(out, "] \"P\" [").unwrap();
            for _ in 0..1200 {
                write!(out, "{} ", rng.next()).unwrap();
            }
            write!(out, "] \"N\" [").unwrap();
            for _ in 0..1200 {
                write!(out, "{} ", rng.next() / 1000.0).unwrap();
            }
            writeln!(out, "]").unwrap();
        }
        k += 1;
    }
    writeln!(out, "WorldEnd").unwrap();
    out
}

/// CPU time of this thread (Linux), so figures on a shared, loaded machine stay meaningful.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns as f64 / 1e9)
}

/// Parses `data` and returns (wall seconds, CPU seconds, requests); panics on any diagnostic.
fn time_parse(data: &[u8], gz: bool) -> (f64, f64, usize) {
    let start = Instant::now();
    let cpu0 = cpu_seconds();
    let reader: Box<dyn std::io::Read> = if gz {
        Box::new(flate2::read::MultiGzDecoder::new(data))
    } else {
        Box::new(data)
    };
    let mut n = 0;
    for item in Parser::new(reader, "bench.rib") {
        item.expect("generated RIB parses cleanly");
        n += 1;
    }
    let wall = start.elapsed().as_secs_f64();
    let cpu = match (cpu0, cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => wall,
    };
    (wall, cpu, n)
}

/// Best of `runs` by CPU time.
fn best_of(runs: usize, data: &[u8], gz: bool) -> (f64, f64, usize) {
    (0..runs)
        .map(|_| time_parse(data, gz))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap()
}

fn main() {
    let mb: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(64);
    let ascii = generate(mb << 20);
    let megabytes = ascii.len() as f64 / 1e6;

    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(&ascii).unwrap();
    let gz = gz.finish().unwrap();

    let mut bin = BinaryWriter::new(Vec::new());
    for item in Parser::new(&ascii[..], "bench.rib") {
        bin.write(&item.unwrap().value).unwrap();
    }
    let bin = bin.into_inner();

    let (wall, cpu, n) = best_of(3, &ascii, false);
    println!(
        "ascii : {megabytes:7.1} MB, {n} requests: {:6.1} MB/s CPU time ({:6.1} MB/s wall)",
        megabytes / cpu,
        megabytes / wall
    );
    let (wall, cpu, _) = best_of(3, &gz, true);
    println!(
        "gzip  : {megabytes:7.1} MB of RIB ({:.1} MB compressed): {:6.1} MB/s CPU time ({:6.1} MB/s wall)",
        gz.len() as f64 / 1e6,
        megabytes / cpu,
        megabytes / wall
    );
    let binary = bin.len() as f64 / 1e6;
    let (wall, cpu, _) = best_of(3, &bin, false);
    println!(
        "binary: {binary:7.1} MB: {:6.1} MB/s CPU time ({:6.1} MB/s wall; {:6.1} MB/s of ASCII-equivalent RIB)",
        binary / cpu,
        binary / wall,
        megabytes / cpu
    );
}
