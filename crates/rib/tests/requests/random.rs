//! Random round trips (see the comment below) built from the table of the other modules.
use super::*;

// ---- random round trips ------------------------------------------------------------------
//
// Random requests of every kind are made by taking each table row's canonical text and
// replacing every number and string with random ones of the same class (integers stay
// integers, so the signature still fits): any finite f32 including subnormals and -0, any
// i32, strings with quotes, backslashes, control characters and non-ASCII text. Random
// parameter lists of every value type are added through `Surface` and `Unknown`.

struct SplitMix(u64);
impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e3779b97f4a7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58476d1ce4e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d049bb133111eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn float(&mut self) -> f32 {
        loop {
            let f = match self.below(4) {
                0 => f32::from_bits(self.next() as u32),
                1 => (self.next() % 20001) as f32 / 100.0 - 100.0,
                2 => -0.0,
                _ => (self.next() as u32 as f32) * 1e-12,
            };
            if f.is_finite() {
                return f;
            }
        }
    }
    fn int(&mut self) -> i32 {
        match self.below(3) {
            0 => self.next() as i32,
            _ => (self.below(2001) as i32) - 1000,
        }
    }
    fn string(&mut self) -> String {
        const PIECES: [&str; 12] = [
            "a", "Z", " ", "\"", "\\", "\n", "\t", "é", "漢", "\u{1}", "#", "[",
        ];
        (0..self.below(8))
            .map(|_| PIECES[self.below(PIECES.len() as u64) as usize])
            .collect()
    }
    fn value(&mut self) -> Value {
        let n = self.below(6) as usize;
        match self.below(3) {
            _ if n == 0 => Value::Floats(vec![]), // the reader's type for `[]`
            0 => Value::Ints((0..n).map(|_| self.int()).collect()),
            1 => Value::Floats((0..n).map(|_| self.float()).collect()),
            _ => Value::Strings((0..n).map(|_| self.string()).collect()),
        }
    }
}

/// Replaces the numbers and strings of canonical RIB text with random ones of the same class.
fn mutate(text: &str, rng: &mut SplitMix) -> String {
    let mut out = String::new();
    let chars: Vec<char> = text.chars().collect();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        if c == '"' {
            let mut j = k + 1;
            while chars[j] != '"' {
                j += if chars[j] == '\\' { 2 } else { 1 };
            }
            // Request-shaping strings (basis names) may become any string: still a string.
            out.push_str(
                &illume_rib::to_ascii(&R::ErrorHandler(rng.string()))["ErrorHandler ".len()..],
            );
            k = j + 1;
        } else if c.is_ascii_digit() || c == '-' || c == '+' || c == '.' {
            let mut j = k;
            while j < chars.len() && (chars[j].is_ascii_alphanumeric() || "+-.".contains(chars[j]))
            {
                j += 1;
            }
            let word: String = chars[k..j].iter().collect();
            if word.contains(['.', 'e']) {
                out.push_str(&format!("{:?}", rng.float()));
            } else {
                // Integer slots: keep counts and codes small and non-negative so the request
                // stays well-formed (`Format` sizes, `nleaf`); the sign is exercised elsewhere.
                out.push_str(&(rng.below(100) as i32).to_string());
            }
            k = j;
        } else {
            out.push(c);
            k += 1;
        }
    }
    out
}

fn random_request(rows: &[(String, R)], pick: usize, seed: u64) -> R {
    let mut rng = SplitMix(seed);
    let k = pick % (rows.len() + 2);
    if let Some((_, template)) = rows.get(k) {
        if let R::StructureComment(_) = template {
            return template.clone(); // `##` text is not a quoted string; keep it
        }
        return parse_one(&mutate(&illume_rib::to_ascii(template), &mut rng));
    }
    let params: Vec<Param> = (0..rng.below(4))
        .map(|_| Param {
            name: rng.string(),
            value: rng.value(),
        })
        .collect();
    if k == rows.len() {
        R::Surface {
            name: rng.string(),
            params,
        }
    } else {
        R::Unknown {
            name: "MyThing".into(),
            args: params.into_iter().map(|p| p.value).collect(),
        }
    }
}

fn random_stream(picks: &[(usize, u64)]) -> Vec<R> {
    let rows = table();
    picks
        .iter()
        .map(|&(pick, seed)| random_request(&rows, pick, seed))
        .collect()
}

/// Every request of the stream; warnings (for `Unknown`) are expected and skipped.
fn parse_all(bytes: &[u8]) -> Vec<R> {
    Parser::new(bytes, "p.rib")
        .filter_map(|i| match i {
            Ok(r) => Some(r.value),
            Err(d) if d.severity == illume_rib::Severity::Warning => None,
            Err(d) => panic!("{d}"),
        })
        .collect()
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]

    #[test]
    fn random_request_streams_survive_ascii(picks in proptest::collection::vec((0usize..200, proptest::prelude::any::<u64>()), 1..30)) {
        let stream = random_stream(&picks);
        let mut text = Vec::new();
        for r in &stream {
            illume_rib::write_ascii(r, &mut text).unwrap();
        }
        let back = parse_all(&text);
        proptest::prop_assert_eq!(&back, &stream);
        // Bit-exact floats: compare the printouts too (PartialEq says 0.0 == -0.0).
        let mut again = Vec::new();
        for r in &back {
            illume_rib::write_ascii(r, &mut again).unwrap();
        }
        proptest::prop_assert_eq!(String::from_utf8(again).unwrap(), String::from_utf8(text).unwrap());
    }

    #[test]
    fn random_request_streams_survive_binary(picks in proptest::collection::vec((0usize..200, proptest::prelude::any::<u64>()), 1..30)) {
        let stream = random_stream(&picks);
        let mut w = illume_rib::BinaryWriter::new(Vec::new());
        for r in &stream {
            w.write(r).unwrap();
        }
        let back = parse_all(&w.into_inner());
        proptest::prop_assert_eq!(&back, &stream);
        let print = |rs: &[R]| rs.iter().map(illume_rib::to_ascii).collect::<Vec<_>>();
        proptest::prop_assert_eq!(print(&back), print(&stream));
    }
}
