//! A tiny deterministic mutator for the smoke pass: xorshift64* picks one to four edits of a
//! seed (bit flips, boundary bytes, byte inserts and deletes, range deletes and copies,
//! truncation), the mutations libFuzzer starts from, without its coverage feedback. The same
//! seed and index always give the same bytes, so a failure names a reproducible input.

/// xorshift64* (Vigna 2016): small, fast, and good enough to choose edits.
pub struct XorShift(u64);

impl XorShift {
    pub fn new(seed: u64) -> Self {
        // Zero is the generator's fixed point.
        XorShift(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A value in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Bytes that sit on the boundaries readers check (signs, lengths, counts).
const BOUNDARY: [u8; 8] = [0x00, 0x01, 0x7f, 0x80, 0xff, b'0', b'9', b'"'];

/// Mutation `index` of `seed`: one to four edits chosen by a generator seeded with `index`.
pub fn mutate(seed: &[u8], index: u64) -> Vec<u8> {
    let mut rng = XorShift::new(index);
    let mut out = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        edit(&mut out, &mut rng);
    }
    out
}

fn edit(out: &mut Vec<u8>, rng: &mut XorShift) {
    if out.is_empty() {
        out.push(rng.next() as u8);
        return;
    }
    let at = rng.below(out.len());
    match rng.below(7) {
        0 => out[at] ^= 1 << rng.below(8),
        1 => out[at] = BOUNDARY[rng.below(BOUNDARY.len())],
        2 => out.insert(at, rng.next() as u8),
        3 => {
            out.remove(at);
        }
        4 => {
            let end = (at + 1 + rng.below(16)).min(out.len());
            out.drain(at..end);
        }
        5 => {
            // Copy a short run elsewhere: repeats tokens and chunks.
            let len = (1 + rng.below(16)).min(out.len() - at);
            let run = out[at..at + len].to_vec();
            let to = rng.below(out.len() + 1);
            out.splice(to..to, run);
        }
        _ => out.truncate(at),
    }
}
