//! Fuzzes the RIB parser on arbitrary bytes (ASCII, binary and gzip paths): it must never
//! panic, must terminate, and whatever parses must print and re-parse to the same requests.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut requests = Vec::new();
    let reader = illume_rib::decompress(std::io::Cursor::new(data.to_vec())).expect("in memory");
    for (n, item) in illume_rib::Parser::new(reader, "fuzz.rib").enumerate() {
        // Each item consumes at least one byte of the decompressed stream or ends it; gzip
        // may expand, so the bound is generous.
        assert!(n < 1 << 24, "parser does not terminate");
        if let Ok(r) = item {
            requests.push(r.value);
        }
    }
    let mut text = Vec::new();
    for r in &requests {
        illume_rib::write_ascii(r, &mut text).unwrap();
    }
    let back: Vec<_> = illume_rib::Parser::new(&text[..], "printed")
        .filter_map(Result::ok)
        .map(|r| r.value)
        .collect();
    // Compare printouts: NaN-free by construction (the lexer rejects non-finite numbers), and
    // bit-exact where PartialEq would equate 0.0 and -0.0.
    let mut again = Vec::new();
    for r in &back {
        illume_rib::write_ascii(r, &mut again).unwrap();
    }
    assert_eq!(String::from_utf8_lossy(&again), String::from_utf8_lossy(&text));
});
