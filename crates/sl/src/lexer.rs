//! Lexer: Shading Language (and preprocessor) source text to tokens.
//!
//! The lexer runs *before* the preprocessor, once per file, so every token carries the span of
//! the text it was read from; macro expansion then moves tokens around without losing their
//! original file:line:col (see `preprocess.rs`). Comments become whitespace and `\`-newline
//! joins lines, as in C translation phases 2–3, and each token records whether it starts a
//! logical line (to find `#` directives) and whether whitespace preceded it (to tell a
//! function-like `#define F(x)` from an object-like `#define F (x)`).

use crate::diagnostic::Diagnostic;
use crate::span::{FileId, Span};

/// Punctuators of the Shading Language, plus the few only `#if` expressions use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Punct {
    /// `(`
    LParen,
    /// `)`
    RParen,
    /// `{`
    LBrace,
    /// `}`
    RBrace,
    /// `[`
    LBracket,
    /// `]`
    RBracket,
    /// `;`
    Semi,
    /// `,`
    Comma,
    /// `.` (dot product)
    Dot,
    /// `?`
    Question,
    /// `:`
    Colon,
    /// `+`
    Plus,
    /// `-`
    Minus,
    /// `*`
    Star,
    /// `/`
    Slash,
    /// `^` (cross product)
    Caret,
    /// `!`
    Bang,
    /// `=`
    Assign,
    /// `<`
    Lt,
    /// `>`
    Gt,
    /// `+=`
    PlusEq,
    /// `-=`
    MinusEq,
    /// `*=`
    StarEq,
    /// `/=`
    SlashEq,
    /// `==`
    EqEq,
    /// `!=`
    Ne,
    /// `<=`
    Le,
    /// `>=`
    Ge,
    /// `&&`
    AndAnd,
    /// `||`
    OrOr,
    /// `%` (`#if` only)
    Percent,
    /// `&` (`#if` only)
    Amp,
    /// `|` (`#if` only)
    Pipe,
    /// `~` (`#if` only)
    Tilde,
    /// `#` (directives, stringizing)
    Hash,
    /// `##` (token pasting)
    HashHash,
}

impl Punct {
    /// The punctuator as written.
    pub fn text(self) -> &'static str {
        use Punct::*;
        match self {
            LParen => "(",
            RParen => ")",
            LBrace => "{",
            RBrace => "}",
            LBracket => "[",
            RBracket => "]",
            Semi => ";",
            Comma => ",",
            Dot => ".",
            Question => "?",
            Colon => ":",
            Plus => "+",
            Minus => "-",
            Star => "*",
            Slash => "/",
            Caret => "^",
            Bang => "!",
            Assign => "=",
            Lt => "<",
            Gt => ">",
            PlusEq => "+=",
            MinusEq => "-=",
            StarEq => "*=",
            SlashEq => "/=",
            EqEq => "==",
            Ne => "!=",
            Le => "<=",
            Ge => ">=",
            AndAnd => "&&",
            OrOr => "||",
            Percent => "%",
            Amp => "&",
            Pipe => "|",
            Tilde => "~",
            Hash => "#",
            HashHash => "##",
        }
    }
}

/// What a token is.
#[derive(Debug, Clone, PartialEq)]
pub enum TokKind {
    /// Identifier or keyword (keywords are recognised by the parser, so macros can use them).
    Ident(String),
    /// Numeric literal.
    Number(f64),
    /// String literal with escapes decoded.
    Str(String),
    /// Punctuator.
    Punct(Punct),
    /// A character that starts no token (reported once by the lexer; kept so the parser's error
    /// names it).
    Unknown(char),
    /// End of input (the parser's sentinel; the lexer never emits it).
    Eof,
}

/// One token with its original location.
#[derive(Debug, Clone, PartialEq)]
pub struct Token {
    /// What it is.
    pub kind: TokKind,
    /// Where it was written.
    pub span: Span,
    /// Its spelling in the source (for `#` stringizing, `##` pasting and messages).
    pub text: String,
    /// First token of a logical line (after `\`-newline joining).
    pub line_start: bool,
    /// Whitespace or a comment came directly before it.
    pub space_before: bool,
}

impl Token {
    /// True when this token is the punctuator `p`.
    pub fn is(&self, p: Punct) -> bool {
        self.kind == TokKind::Punct(p)
    }

    /// The identifier's name, if this is an identifier.
    pub fn ident(&self) -> Option<&str> {
        match &self.kind {
            TokKind::Ident(s) => Some(s),
            _ => None,
        }
    }

    /// How the token reads in an error message: `'foo'`, `number 1.5`, `end of file`.
    pub fn describe(&self) -> String {
        match &self.kind {
            TokKind::Ident(s) => format!("'{s}'"),
            TokKind::Number(_) => format!("number {}", self.text),
            TokKind::Str(_) => format!("string {}", self.text),
            TokKind::Punct(p) => format!("'{}'", p.text()),
            TokKind::Unknown(c) => format!("'{c}'"),
            TokKind::Eof => "end of file".to_string(),
        }
    }
}

/// Character cursor tracking line and column (1-based, columns in characters).
struct Cursor<'a> {
    chars: std::iter::Peekable<std::str::Chars<'a>>,
    line: u32,
    col: u32,
}

impl Cursor<'_> {
    fn peek(&mut self) -> Option<char> {
        self.chars.peek().copied()
    }

    fn peek2(&self) -> Option<char> {
        let mut it = self.chars.clone();
        it.next();
        it.next()
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.chars.next()?;
        if c == '\n' {
            self.line += 1;
            self.col = 1;
        } else {
            self.col += 1;
        }
        Some(c)
    }
}

/// Splits one file's text into tokens, reporting unterminated comments and strings and stray
/// characters. Never panics, whatever the input.
pub fn lex(file: FileId, text: &str, diags: &mut Vec<Diagnostic>) -> Vec<Token> {
    let mut cur = Cursor {
        chars: text.chars().peekable(),
        line: 1,
        col: 1,
    };
    let mut out = Vec::new();
    let mut line_start = true;
    let mut space_before = false;
    while let Some(c) = cur.peek() {
        // Whitespace, line continuations and comments.
        if c == '\n' {
            cur.bump();
            line_start = true;
            space_before = true;
            continue;
        }
        if c.is_whitespace() {
            cur.bump();
            space_before = true;
            continue;
        }
        if c == '\\' && matches!(cur.peek2(), Some('\n') | Some('\r')) {
            cur.bump();
            if cur.peek() == Some('\r') {
                cur.bump();
            }
            if cur.peek() == Some('\n') {
                cur.bump();
            }
            space_before = true;
            continue;
        }
        let span = Span::at(file, cur.line, cur.col);
        if c == '/' && cur.peek2() == Some('/') {
            while let Some(c) = cur.peek() {
                if c == '\n' {
                    break;
                }
                cur.bump();
            }
            space_before = true;
            continue;
        }
        if c == '/' && cur.peek2() == Some('*') {
            cur.bump();
            cur.bump();
            let mut closed = false;
            while let Some(c) = cur.bump() {
                if c == '*' && cur.peek() == Some('/') {
                    cur.bump();
                    closed = true;
                    break;
                }
            }
            if !closed {
                diags.push(Diagnostic::error(span, "unterminated comment"));
            }
            space_before = true;
            continue;
        }
        let (kind, spelling) = if c.is_ascii_alphabetic() || c == '_' {
            let mut s = String::new();
            while let Some(c) = cur.peek() {
                if c.is_ascii_alphanumeric() || c == '_' {
                    s.push(c);
                    cur.bump();
                } else {
                    break;
                }
            }
            (TokKind::Ident(s.clone()), s)
        } else if c.is_ascii_digit()
            || (c == '.' && cur.peek2().is_some_and(|d| d.is_ascii_digit()))
        {
            lex_number(&mut cur)
        } else if c == '"' {
            lex_string(&mut cur, span, diags)
        } else if let Some(p) = lex_punct(&mut cur) {
            (TokKind::Punct(p), p.text().to_string())
        } else {
            cur.bump();
            diags.push(Diagnostic::error(
                span,
                format!("unexpected character '{c}'"),
            ));
            (TokKind::Unknown(c), c.to_string())
        };
        out.push(Token {
            kind,
            span,
            text: spelling,
            line_start,
            space_before,
        });
        line_start = false;
        space_before = false;
    }
    out
}

/// `12`, `1.5`, `.5`, `1.`, `1e-4`, `2.5E+3`. A trailing `f`/`F` (C habit) is accepted.
fn lex_number(cur: &mut Cursor<'_>) -> (TokKind, String) {
    let mut s = String::new();
    while let Some(c) = cur.peek() {
        if c.is_ascii_digit() || c == '.' {
            s.push(c);
            cur.bump();
        } else {
            break;
        }
    }
    if matches!(cur.peek(), Some('e') | Some('E')) {
        let next = cur.peek2();
        let signed_digit = {
            let mut it = cur.chars.clone();
            it.next();
            it.next();
            it.next()
        };
        let exp_ok = next.is_some_and(|d| d.is_ascii_digit())
            || (matches!(next, Some('+') | Some('-'))
                && signed_digit.is_some_and(|d| d.is_ascii_digit()));
        if exp_ok {
            s.push(cur.bump().unwrap_or('e'));
            if matches!(cur.peek(), Some('+') | Some('-')) {
                s.push(cur.bump().unwrap_or('+'));
            }
            while let Some(c) = cur.peek() {
                if c.is_ascii_digit() {
                    s.push(c);
                    cur.bump();
                } else {
                    break;
                }
            }
        }
    }
    let mut spelling = s.clone();
    if matches!(cur.peek(), Some('f') | Some('F')) {
        spelling.push(cur.bump().unwrap_or('f'));
    }
    // "1.2.3" is not a number; parse the longest valid prefix rather than panic or reject.
    let value = s
        .parse::<f64>()
        .ok()
        .or_else(|| {
            let end = s
                .match_indices('.')
                .nth(1)
                .map(|(i, _)| i)
                .unwrap_or(s.len());
            s[..end].parse::<f64>().ok()
        })
        .unwrap_or(0.0);
    (TokKind::Number(value), spelling)
}

/// `"…"` with C escapes (`\n \t \" \\` and others kept literally).
fn lex_string(cur: &mut Cursor<'_>, span: Span, diags: &mut Vec<Diagnostic>) -> (TokKind, String) {
    let mut spelling = String::from('"');
    let mut value = String::new();
    cur.bump();
    loop {
        match cur.peek() {
            None | Some('\n') => {
                diags.push(Diagnostic::error(span, "unterminated string"));
                break;
            }
            Some('"') => {
                cur.bump();
                spelling.push('"');
                break;
            }
            Some('\\') => {
                cur.bump();
                spelling.push('\\');
                let Some(e) = cur.peek() else { continue };
                if e == '\n' {
                    continue; // reported as unterminated on the next turn
                }
                cur.bump();
                spelling.push(e);
                value.push(match e {
                    'n' => '\n',
                    't' => '\t',
                    'r' => '\r',
                    '0' => '\0',
                    other => other,
                });
            }
            Some(c) => {
                cur.bump();
                spelling.push(c);
                value.push(c);
            }
        }
    }
    (TokKind::Str(value), spelling)
}

/// The longest punctuator at the cursor, consumed.
fn lex_punct(cur: &mut Cursor<'_>) -> Option<Punct> {
    use Punct::*;
    let c = cur.peek()?;
    let n = cur.peek2();
    let two = match (c, n) {
        ('+', Some('=')) => Some(PlusEq),
        ('-', Some('=')) => Some(MinusEq),
        ('*', Some('=')) => Some(StarEq),
        ('/', Some('=')) => Some(SlashEq),
        ('=', Some('=')) => Some(EqEq),
        ('!', Some('=')) => Some(Ne),
        ('<', Some('=')) => Some(Le),
        ('>', Some('=')) => Some(Ge),
        ('&', Some('&')) => Some(AndAnd),
        ('|', Some('|')) => Some(OrOr),
        ('#', Some('#')) => Some(HashHash),
        _ => None,
    };
    if let Some(p) = two {
        cur.bump();
        cur.bump();
        return Some(p);
    }
    let one = match c {
        '(' => LParen,
        ')' => RParen,
        '{' => LBrace,
        '}' => RBrace,
        '[' => LBracket,
        ']' => RBracket,
        ';' => Semi,
        ',' => Comma,
        '.' => Dot,
        '?' => Question,
        ':' => Colon,
        '+' => Plus,
        '-' => Minus,
        '*' => Star,
        '/' => Slash,
        '^' => Caret,
        '!' => Bang,
        '=' => Assign,
        '<' => Lt,
        '>' => Gt,
        '%' => Percent,
        '&' => Amp,
        '|' => Pipe,
        '~' => Tilde,
        '#' => Hash,
        _ => return None,
    };
    cur.bump();
    Some(one)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<TokKind> {
        let mut d = Vec::new();
        lex(FileId(0), src, &mut d)
            .into_iter()
            .map(|t| t.kind)
            .collect()
    }

    #[test]
    fn numbers_in_every_spelling() {
        let k = kinds("1 1.5 .5 1. 1e-4 2.5E+3 3f");
        let v: Vec<f64> = k
            .iter()
            .map(|k| match k {
                TokKind::Number(x) => *x,
                _ => f64::NAN,
            })
            .collect();
        assert_eq!(v, vec![1.0, 1.5, 0.5, 1.0, 1e-4, 2.5e3, 3.0]);
    }

    #[test]
    fn dot_between_identifiers_is_the_dot_operator() {
        let k = kinds("N.V");
        assert_eq!(
            k,
            vec![
                TokKind::Ident("N".into()),
                TokKind::Punct(Punct::Dot),
                TokKind::Ident("V".into())
            ]
        );
    }

    #[test]
    fn columns_and_lines_are_one_based_and_skip_comments() {
        let mut d = Vec::new();
        let t = lex(FileId(0), "w /* a\n b */ x\n  // c\n\ty", &mut d);
        assert!(d.is_empty());
        assert_eq!((t[1].span.loc.line, t[1].span.loc.col), (2, 7));
        assert_eq!((t[2].span.loc.line, t[2].span.loc.col), (4, 2));
        assert!(
            !t[1].line_start,
            "a block comment does not end the logical line"
        );
        assert!(t[2].line_start);
    }

    #[test]
    fn backslash_newline_continues_the_logical_line() {
        let mut d = Vec::new();
        let t = lex(FileId(0), "#define A \\\n  1\nB", &mut d);
        let starts: Vec<bool> = t.iter().map(|t| t.line_start).collect();
        assert_eq!(starts, vec![true, false, false, false, true]);
        assert_eq!(t[3].span.loc.line, 2);
    }

    #[test]
    fn strings_decode_escapes_and_report_unterminated() {
        let mut d = Vec::new();
        let t = lex(FileId(0), r#""a\"b\n" "open"#, &mut d);
        assert_eq!(t[0].kind, TokKind::Str("a\"b\n".into()));
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].message, "unterminated string");
        assert_eq!(d[0].span.loc.col, 10);
    }

    #[test]
    fn two_character_operators_win_over_one() {
        let k = kinds("+= == != <= >= && || ## ^");
        let p: Vec<Punct> = k
            .into_iter()
            .filter_map(|k| match k {
                TokKind::Punct(p) => Some(p),
                _ => None,
            })
            .collect();
        use Punct::*;
        assert_eq!(
            p,
            vec![PlusEq, EqEq, Ne, Le, Ge, AndAnd, OrOr, HashHash, Caret]
        );
    }
}
