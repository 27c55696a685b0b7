//! The lexer's buffer bounds on endless and unterminated input, and the spec's number classes.

use super::*;

/// An endless (or `limit`-byte) stream repeating `pattern`, generated as it is read.
struct Repeat {
    pattern: &'static [u8],
    at: usize,
    left: usize,
}

impl Read for Repeat {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let k = buf.len().min(self.left);
        for b in &mut buf[..k] {
            *b = self.pattern[self.at % self.pattern.len()];
            self.at += 1;
        }
        self.left -= k;
        Ok(k)
    }
}

fn drain(lexer: &mut Lexer<Repeat>) -> (usize, usize) {
    let (mut tokens, mut errors) = (0, 0);
    loop {
        match lexer.next_token() {
            Ok((Token::Eof, _)) => return (tokens, errors),
            Ok(_) => tokens += 1,
            Err(_) => errors += 1,
        }
        assert!(lexer.buf.capacity() <= 2 * CHUNK + MAX_WORD, "buffer grew");
    }
}

#[test]
fn buffer_stays_bounded_over_a_long_stream() {
    let mut lexer = Lexer::new(Repeat {
        pattern: b"Translate 1 -2.5 3e2 # note\n",
        at: 0,
        left: 20 << 20,
    });
    let (tokens, errors) = drain(&mut lexer);
    assert_eq!(errors, 0);
    // 748982 whole lines of 28 bytes, then 24 bytes that still hold all four tokens.
    assert_eq!(tokens, (20 << 20) / 28 * 4 + 4);
}

#[test]
fn unterminated_string_is_capped_not_buffered_whole() {
    let mut lexer = Lexer::new(Repeat {
        pattern: b"\"xxxxxxxxxxxxxxxx",
        at: 1,
        left: 40 << 20,
    });
    let (_, errors) = drain(&mut lexer);
    assert!(errors >= 1);
}

#[test]
fn word_classes_follow_the_spec() {
    for (text, tok) in [
        ("1", Token::Int(1)),
        ("-.5", Token::Float(-0.5)),
        ("1.e-3", Token::Float(1e-3)),
        ("1E+4", Token::Float(1e4)),
        ("+2", Token::Int(2)),
        ("-2147483648", Token::Int(i32::MIN)),
        ("2147483648", Token::Float(2147483648.0)),
    ] {
        assert_eq!(parse_number(text.as_bytes()), Ok(tok), "{text}");
    }
    for bad in ["1.2.3", "-", "1e", "1.0f", "-inf", "+nan"] {
        assert!(parse_number(bad.as_bytes()).is_err(), "{bad}");
    }
}
