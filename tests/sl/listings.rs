//! The chapter 9 listings, read from the reference text at test time.
//!
//! A listing starts at a line `Listing 9.N …` whose next non-blank line opens a ``` block. The
//! next block (after blank lines only) continues it when the code so far is unfinished — inside
//! a comment or an open brace — as Listing 9.5 is, split by a page break inside a comment
//! (ERRATA.md); a finished listing followed by a block is not joined (after Listing 9.14 comes
//! the prose's `solar (…) { statements; }` template). Prose that merely mentions a listing has
//! no block after it.
use std::collections::BTreeMap;

/// Listing number → code, or `None` when `../shared/reference/…` (beside the checkout, or under
/// `$ILLUME_SHARED`) is absent: skipped loudly, a failure under `CI=true`.
pub fn chapter9() -> Option<BTreeMap<u32, String>> {
    let path = illume_testenv::shared_file(
        "reference/advanced-renderman-ch9-illumination-and-lights.txt",
    )?;
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let is_fence = |k: usize| lines[k].trim_start().starts_with("```");
    let next_non_blank = |from: usize| (from..lines.len()).find(|&k| !lines[k].trim().is_empty());
    let mut out = BTreeMap::new();
    let mut i = 0;
    while i < lines.len() {
        let number = lines[i]
            .strip_prefix("Listing 9.")
            .map(|r| {
                r.chars()
                    .take_while(char::is_ascii_digit)
                    .collect::<String>()
            })
            .and_then(|d| d.parse::<u32>().ok());
        let (Some(n), Some(mut open)) = (number, next_non_blank(i + 1).filter(|&k| is_fence(k)))
        else {
            i += 1;
            continue;
        };
        let mut code = String::new();
        loop {
            let close = (open + 1..lines.len())
                .find(|&k| is_fence(k))
                .unwrap_or(lines.len());
            for l in &lines[open + 1..close] {
                code.push_str(l);
                code.push('\n');
            }
            match next_non_blank(close + 1) {
                Some(k) if is_fence(k) && unfinished(&code) => open = k,
                _ => {
                    i = close + 1;
                    break;
                }
            }
        }
        out.insert(n, code);
    }
    Some(out)
}

/// ERRATA.md fixes where the printed listing is wrong: `C1`/`C!` are `Cl` (Listings 9.11–9.13,
/// 9.17), and Listing 9.9's `fresnel` call lost its `fkt` argument.
pub fn errata(n: u32, code: &str) -> String {
    let chars: Vec<char> = code.chars().collect();
    let ident = |c: Option<&char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_');
    let mut out = String::with_capacity(code.len());
    let mut i = 0;
    while i < chars.len() {
        let misread = chars[i] == 'C'
            && matches!(chars.get(i + 1), Some('1' | '!'))
            && !(i > 0 && ident(chars.get(i - 1)))
            && !ident(chars.get(i + 2))
            // `C!=` would be a comparison, not a misread name.
            && chars.get(i + 2) != Some(&'=');
        if misread {
            out.push_str("Cl");
            i += 2;
        } else {
            out.push(chars[i]);
            i += 1;
        }
    }
    if n == 9 {
        out = out.replace(
            "fresnel (IN, Nf, 1/ior, fkr, R, T)",
            "fresnel (IN, Nf, 1/ior, fkr, fkt, R, T)",
        );
    }
    out
}

/// Whether `code` ends inside a `/* */` comment or with unbalanced braces.
fn unfinished(code: &str) -> bool {
    let b = code.as_bytes();
    let (mut depth, mut in_comment, mut i) = (0i32, false, 0);
    while i < b.len() {
        if in_comment {
            if b[i..].starts_with(b"*/") {
                in_comment = false;
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            in_comment = true;
            i += 1;
        } else if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i] == b'{' {
            depth += 1;
        } else if b[i] == b'}' {
            depth -= 1;
        }
        i += 1;
    }
    in_comment || depth != 0
}
