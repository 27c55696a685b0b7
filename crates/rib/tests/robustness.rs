//! Hostile input never panics, always ends, and is always reported: random bytes, random
//! mutations of good RIB (ASCII and binary), and every truncation of a small file.
use illume_rib::{BinaryWriter, Parser};
use proptest::prelude::*;

const GOOD: &[u8] = b"##RenderMan RIB\nversion 3.03\nDeclare \"Kd\" \"uniform float\"\n\
Format 64 48 1\nWorldBegin\nAttributeBegin\n Color [1 .5 0] # orange\n\
 Surface \"plastic\" \"Kd\" .5 \"string texturename\" \"a\\tb\\101.tx\"\n\
 PointsPolygons [3 3] [0 1 2 2 1 3] \"P\" [0 0 0 1 0 0 0 1 0 1 1 -1.e-3]\n\
 Basis \"bezier\" 3 [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 3\n\
 Sphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n";

/// Parses to the end; returns (requests, diagnostics). The bound on items proves termination.
fn drain(bytes: &[u8]) -> (usize, usize) {
    let mut ok = 0;
    let mut bad = 0;
    for (n, item) in Parser::new(bytes, "fuzz.rib").enumerate() {
        assert!(n <= 2 * bytes.len() + 2, "parser does not terminate");
        match item {
            Ok(_) => ok += 1,
            Err(d) => {
                assert!(!d.message.is_empty());
                bad += 1;
            }
        }
    }
    (ok, bad)
}

fn good_binary() -> Vec<u8> {
    let mut w = BinaryWriter::new(Vec::new());
    for item in Parser::new(GOOD, "good.rib") {
        w.write(&item.unwrap().value).unwrap();
    }
    w.into_inner()
}

#[test]
fn good_input_is_clean_in_ascii_and_binary() {
    assert_eq!(drain(GOOD), (13, 0));
    assert_eq!(drain(&good_binary()), (13, 0));
}

#[test]
fn every_truncation_ends_cleanly() {
    for bytes in [GOOD.to_vec(), good_binary()] {
        for cut in 0..bytes.len() {
            drain(&bytes[..cut]);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn arbitrary_bytes_never_panic_and_print_to_a_fixed_point(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        drain(&bytes);
        let first = print(&bytes);
        proptest::prop_assert_eq!(print(&first), first);
    }

    #[test]
    fn mutated_rib_never_panics_and_prints_to_a_fixed_point(edits in proptest::collection::vec((any::<usize>(), any::<u8>()), 1..8), binary in any::<bool>()) {
        let mut bytes = if binary { good_binary() } else { GOOD.to_vec() };
        for (at, b) in edits {
            let k = at % bytes.len();
            bytes[k] = b;
        }
        drain(&bytes);
        // Whatever survives prints to a fixed point (what `catrib x | catrib -` relies on).
        let first = print(&bytes);
        proptest::prop_assert_eq!(print(&first), first);
    }
}

/// The canonical ASCII of every request that parses, diagnostics dropped.
fn print(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    for r in Parser::new(bytes, "p.rib").flatten() {
        illume_rib::write_ascii(&r.value, &mut out).unwrap();
    }
    out
}

/// A reader that hands out at most `n` bytes per call, so tokens straddle every refill.
struct Trickle<'a> {
    data: &'a [u8],
    n: usize,
}

impl std::io::Read for Trickle<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let k = self.n.min(buf.len()).min(self.data.len());
        buf[..k].copy_from_slice(&self.data[..k]);
        self.data = &self.data[k..];
        Ok(k)
    }
}

fn items(reader: impl std::io::Read) -> Vec<String> {
    Parser::new(reader, "t.rib")
        .map(|i| match i {
            Ok(r) => format!("{:?} @{}", r.value, r.span),
            Err(d) => d.to_string(),
        })
        .collect()
}

#[test]
fn tokens_split_across_reads_parse_as_whole() {
    let with_errors = [
        GOOD,
        b"Sphere 1 2 \"unterminated\nColor [1 2\nWorldEnd 1.2.3\n",
    ]
    .concat();
    for bytes in [GOOD.to_vec(), good_binary(), with_errors] {
        let whole = items(&bytes[..]);
        for n in [1, 2, 3, 7] {
            assert_eq!(items(Trickle { data: &bytes, n }), whole, "{n}-byte reads");
        }
    }
}
