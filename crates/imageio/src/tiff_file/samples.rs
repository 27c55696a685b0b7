//! Sample encodings: unsigned, signed and float samples of any supported width, normalised to f32.

/// How one sample is stored.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(super) enum SampleKind {
    Unsigned,
    Signed,
    Float,
}

/// The first `n` samples of a decoded row, normalised, into `out` (cleared first). The common
/// 8/16/32-bit cases are tight loops; the rest go through [`sample`].
pub(super) fn row_to_f32(
    row: &[u8],
    n: usize,
    bits: usize,
    kind: SampleKind,
    be: bool,
    max: f64,
    out: &mut Vec<f32>,
) {
    out.clear();
    match (bits, kind) {
        (8, SampleKind::Unsigned) => out.extend(row[..n].iter().map(|&b| b as f32 / 255.0)),
        (16, SampleKind::Unsigned) => out.extend(row[..2 * n].chunks_exact(2).map(|c| {
            let v = if be {
                u16::from_be_bytes([c[0], c[1]])
            } else {
                u16::from_le_bytes([c[0], c[1]])
            };
            v as f32 / 65535.0
        })),
        (32, SampleKind::Float) => out.extend(row[..4 * n].chunks_exact(4).map(|c| {
            let b = [c[0], c[1], c[2], c[3]];
            if be {
                f32::from_be_bytes(b)
            } else {
                f32::from_le_bytes(b)
            }
        })),
        _ => out.extend((0..n).map(|i| sample(row, i, bits, kind, be, max))),
    }
}

/// Sample `index` of a decoded row, normalised: integers to [0, 1] (signed to [-1, 1]).
fn sample(row: &[u8], index: usize, bits: usize, kind: SampleKind, be: bool, max: f64) -> f32 {
    if bits < 8 {
        let bit = index * bits;
        let byte = row[bit / 8];
        let shift = 8 - bits - bit % 8;
        let v = (byte >> shift) & ((1u8 << bits) - 1);
        return (v as f64 / max) as f32;
    }
    let b = &row[index * bits / 8..(index + 1) * bits / 8];
    let uint = |b: &[u8]| -> u64 {
        let mut v = 0u64;
        if be {
            for &x in b {
                v = (v << 8) | x as u64;
            }
        } else {
            for &x in b.iter().rev() {
                v = (v << 8) | x as u64;
            }
        }
        v
    };
    let u = uint(b);
    match kind {
        SampleKind::Unsigned => (u as f64 / max) as f32,
        SampleKind::Signed => {
            let shift = 64 - bits;
            let s = ((u << shift) as i64) >> shift;
            (s as f64 / max).max(-1.0) as f32
        }
        SampleKind::Float => match bits {
            16 => half::f16::from_bits(u as u16).to_f32(),
            32 => f32::from_bits(u as u32),
            _ => f64::from_bits(u) as f32,
        },
    }
}
