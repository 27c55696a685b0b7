//! Reading Aqsis `jobs.cfg` files: the Python subset they use, parsed in Rust.
//!
//! A `jobs.cfg` is Python that `rendertester.py` executed, but every file of the suite is a list
//! of calls `RenderJob(workingdir, rib, shaders=[...], outimagename=None, ricalls=[AUTO],
//! description="""...""", known_issues=...)` plus comments and `include_cfg(...)`. Parsing that
//! subset here (strings in all four quote styles, lists, `None`, bare names, numbers, keyword
//! arguments) keeps the runner free of a Python dependency just to list the jobs, makes the job
//! list deterministic, and lets a malformed file fail with `file:line:col` and what was
//! expected. Anything beyond the subset (expressions, variables) is an error, not a guess.
use std::fmt;
use std::path::Path;

/// One `RenderJob(...)` call as written (paths still relative to the file's directory).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderJobSpec {
    pub workingdir: String,
    pub rib: String,
    /// Shader sources to compile before rendering (relative to `workingdir`); empty strings,
    /// which some files write as `shaders=[""]`, are dropped.
    pub shaders: Vec<String>,
    /// Output image names; empty means "the RIB's name with `.tif`".
    pub outimagename: Vec<String>,
    pub description: String,
    pub known_issues: Option<String>,
    /// 1-based line of the call, for messages.
    pub line: usize,
}

/// A parse error with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct CfgError {
    pub file: String,
    pub line: usize,
    pub col: usize,
    pub message: String,
}

impl fmt::Display for CfgError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file, self.line, self.col, self.message
        )
    }
}

impl std::error::Error for CfgError {}

/// A Python literal value of the subset.
#[derive(Debug, Clone, PartialEq)]
enum Value {
    Str(String),
    List(Vec<Value>),
    None,
    /// A bare name such as `AUTO`, `True`.
    Name(String),
    Number(String),
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Name(String),
    Str(String),
    Number(String),
    Punct(char),
}

struct Token {
    tok: Tok,
    line: usize,
    col: usize,
}

/// Parses the text of one `jobs.cfg`; `file` names it in errors. Calls other than `RenderJob`
/// (`include_cfg`) are accepted and ignored: the suite walker finds every `jobs.cfg` anyway.
pub fn parse(text: &str, file: &Path) -> Result<Vec<RenderJobSpec>, CfgError> {
    let file = file.display().to_string();
    let tokens = tokenize(text, &file)?;
    let mut p = Parser {
        tokens,
        pos: 0,
        file,
    };
    let mut jobs = Vec::new();
    while p.pos < p.tokens.len() {
        let (name, line) = match p.next_tok() {
            Some((Tok::Name(n), line, _)) => (n, line),
            Some((t, line, col)) => {
                return Err(p.err_at(line, col, format!("expected a call, found {}", show(&t))))
            }
            None => break,
        };
        let (positional, keywords) = p.call_args(&name)?;
        if name == "RenderJob" {
            jobs.push(p.render_job(positional, keywords, line)?);
        }
    }
    Ok(jobs)
}

fn show(t: &Tok) -> String {
    match t {
        Tok::Name(n) => format!("name `{n}`"),
        Tok::Str(_) => "a string".to_string(),
        Tok::Number(n) => format!("number `{n}`"),
        Tok::Punct(c) => format!("`{c}`"),
    }
}

fn tokenize(text: &str, file: &str) -> Result<Vec<Token>, CfgError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line, mut line_start) = (0usize, 1usize, 0usize);
    let err = |line: usize, col: usize, message: String| CfgError {
        file: file.to_string(),
        line,
        col,
        message,
    };
    while i < chars.len() {
        let c = chars[i];
        let col = i - line_start + 1;
        if c == '\n' {
            i += 1;
            line += 1;
            line_start = i;
        } else if c.is_whitespace() || c == '\\' {
            i += 1;
        } else if c == '#' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let word: String = chars[start..i].iter().collect();
            // String prefixes (r"", u"", b""...) glue onto the following quote.
            let is_prefix = word.len() <= 2 && word.chars().all(|c| "rRuUbB".contains(c));
            if is_prefix && i < chars.len() && (chars[i] == '"' || chars[i] == '\'') {
                continue;
            }
            out.push(Token {
                tok: Tok::Name(word),
                line,
                col,
            });
        } else if c.is_ascii_digit()
            || (c == '-' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            let start = i;
            i += 1;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '.') {
                i += 1;
            }
            out.push(Token {
                tok: Tok::Number(chars[start..i].iter().collect()),
                line,
                col,
            });
        } else if c == '"' || c == '\'' {
            let raw = i > 0 && matches!(chars[i - 1], 'r' | 'R');
            let triple = chars.get(i + 1) == Some(&c) && chars.get(i + 2) == Some(&c);
            let (tok_line, tok_col) = (line, col);
            i += if triple { 3 } else { 1 };
            let mut s = String::new();
            loop {
                let Some(&d) = chars.get(i) else {
                    return Err(err(tok_line, tok_col, "unterminated string".to_string()));
                };
                if d == c
                    && (!triple || (chars.get(i + 1) == Some(&c) && chars.get(i + 2) == Some(&c)))
                {
                    i += if triple { 3 } else { 1 };
                    break;
                }
                if d == '\n' {
                    if !triple {
                        return Err(err(tok_line, tok_col, "unterminated string".to_string()));
                    }
                    line += 1;
                    line_start = i + 1;
                }
                if d == '\\' && !raw {
                    if let Some(&e) = chars.get(i + 1) {
                        match e {
                            'n' => s.push('\n'),
                            't' => s.push('\t'),
                            '\n' => {
                                line += 1;
                                line_start = i + 2;
                            }
                            _ => s.push(e),
                        }
                        i += 2;
                        continue;
                    }
                }
                s.push(d);
                i += 1;
            }
            out.push(Token {
                tok: Tok::Str(s),
                line: tok_line,
                col: tok_col,
            });
        } else if "()[],=".contains(c) {
            out.push(Token {
                tok: Tok::Punct(c),
                line,
                col,
            });
            i += 1;
        } else {
            return Err(err(line, col, format!("unexpected character `{c}`")));
        }
    }
    Ok(out)
}

struct Parser {
    tokens: Vec<Token>,
    pos: usize,
    file: String,
}

type Args = (Vec<Value>, Vec<(String, Value)>);

impl Parser {
    fn next_tok(&mut self) -> Option<(Tok, usize, usize)> {
        let t = self.tokens.get(self.pos)?;
        self.pos += 1;
        Some((t.tok.clone(), t.line, t.col))
    }

    fn peek(&self) -> Option<&Tok> {
        self.tokens.get(self.pos).map(|t| &t.tok)
    }

    fn err_at(&self, line: usize, col: usize, message: String) -> CfgError {
        CfgError {
            file: self.file.clone(),
            line,
            col,
            message,
        }
    }

    /// An error at the current token (or the end of the file).
    fn err_here(&self, expected: &str) -> CfgError {
        match self.tokens.get(self.pos) {
            Some(t) => self.err_at(
                t.line,
                t.col,
                format!("expected {expected}, found {}", show(&t.tok)),
            ),
            None => {
                let (line, col) = self.tokens.last().map_or((1, 1), |t| (t.line, t.col));
                self.err_at(
                    line,
                    col,
                    format!("expected {expected}, found the end of the file"),
                )
            }
        }
    }

    fn expect(&mut self, c: char) -> Result<(), CfgError> {
        if self.peek() == Some(&Tok::Punct(c)) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.err_here(&format!("`{c}`")))
        }
    }

    /// `( value, ..., name=value, ... )` after the call's name.
    fn call_args(&mut self, name: &str) -> Result<Args, CfgError> {
        self.expect('(')?;
        let (mut positional, mut keywords) = (Vec::new(), Vec::new());
        loop {
            if self.peek() == Some(&Tok::Punct(')')) {
                self.pos += 1;
                return Ok((positional, keywords));
            }
            let is_keyword = matches!(self.peek(), Some(Tok::Name(_)))
                && self.tokens.get(self.pos + 1).map(|t| &t.tok) == Some(&Tok::Punct('='));
            if is_keyword {
                let Some((Tok::Name(k), _, _)) = self.next_tok() else {
                    unreachable!("checked above")
                };
                self.pos += 1; // '='
                keywords.push((k, self.value()?));
            } else if keywords.is_empty() {
                positional.push(self.value()?);
            } else {
                return Err(self.err_here(&format!("a keyword argument of {name}(...)")));
            }
            if self.peek() == Some(&Tok::Punct(',')) {
                self.pos += 1;
            } else if self.peek() != Some(&Tok::Punct(')')) {
                return Err(self.err_here(&format!("`,` or `)` in {name}(...)")));
            }
        }
    }

    fn value(&mut self) -> Result<Value, CfgError> {
        let here = self.err_here("a string, list, number, None or name");
        let Some((tok, _, _)) = self.next_tok() else {
            return Err(here);
        };
        match tok {
            Tok::Str(mut s) => {
                // Adjacent literals concatenate, as in Python.
                while let Some(Tok::Str(more)) = self.peek() {
                    s.push_str(more);
                    self.pos += 1;
                }
                Ok(Value::Str(s))
            }
            Tok::Number(n) => Ok(Value::Number(n)),
            Tok::Name(n) if n == "None" => Ok(Value::None),
            Tok::Name(n) => Ok(Value::Name(n)),
            Tok::Punct('[') => {
                let mut items = Vec::new();
                loop {
                    if self.peek() == Some(&Tok::Punct(']')) {
                        self.pos += 1;
                        return Ok(Value::List(items));
                    }
                    items.push(self.value()?);
                    if self.peek() == Some(&Tok::Punct(',')) {
                        self.pos += 1;
                    } else if self.peek() != Some(&Tok::Punct(']')) {
                        return Err(self.err_here("`,` or `]` in a list"));
                    }
                }
            }
            _ => Err(here),
        }
    }

    fn render_job(
        &self,
        positional: Vec<Value>,
        keywords: Vec<(String, Value)>,
        line: usize,
    ) -> Result<RenderJobSpec, CfgError> {
        const ORDER: [&str; 7] = [
            "workingdir",
            "rib",
            "shaders",
            "outimagename",
            "ricalls",
            "description",
            "known_issues",
        ];
        let err = |message: String| self.err_at(line, 1, message);
        if positional.len() > ORDER.len() {
            return Err(err(format!(
                "RenderJob takes at most {} arguments, found {}",
                ORDER.len(),
                positional.len()
            )));
        }
        let mut args: Vec<(String, Value)> = ORDER
            .iter()
            .map(|s| s.to_string())
            .zip(positional)
            .collect();
        for (k, v) in keywords {
            if !ORDER.contains(&k.as_str()) {
                return Err(err(format!("RenderJob has no argument `{k}`")));
            }
            if args.iter().any(|(a, _)| *a == k) {
                return Err(err(format!("RenderJob argument `{k}` given twice")));
            }
            args.push((k, v));
        }
        let get = |k: &str| args.iter().find(|(a, _)| a == k).map(|(_, v)| v);
        let string = |k: &str| -> Result<Option<String>, CfgError> {
            match get(k) {
                None | Some(Value::None) => Ok(None),
                Some(Value::Str(s)) => Ok(Some(s.clone())),
                Some(v) => Err(err(format!(
                    "RenderJob `{k}` must be a string, found {v:?}"
                ))),
            }
        };
        let strings = |k: &str| -> Result<Vec<String>, CfgError> {
            match get(k) {
                None | Some(Value::None) => Ok(Vec::new()),
                Some(Value::Str(s)) => Ok(vec![s.clone()]),
                Some(Value::List(items)) => items
                    .iter()
                    .map(|v| match v {
                        Value::Str(s) => Ok(s.clone()),
                        v => Err(err(format!(
                            "RenderJob `{k}` must list strings, found {v:?}"
                        ))),
                    })
                    .collect(),
                Some(v) => Err(err(format!("RenderJob `{k}` must be a list, found {v:?}"))),
            }
        };
        let rib = string("rib")?.filter(|s| !s.is_empty());
        let Some(rib) = rib else {
            return Err(err("RenderJob needs a `rib`".to_string()));
        };
        Ok(RenderJobSpec {
            workingdir: string("workingdir")?.unwrap_or_default(),
            rib,
            shaders: strings("shaders")?
                .into_iter()
                .filter(|s| !s.trim().is_empty())
                .collect(),
            outimagename: strings("outimagename")?,
            description: string("description")?.unwrap_or_default(),
            known_issues: string("known_issues")?,
            line,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(s: &str) -> Result<Vec<RenderJobSpec>, CfgError> {
        parse(s, Path::new("jobs.cfg"))
    }

    #[test]
    fn positional_keyword_and_triple_quoted_arguments() {
        let jobs = parse_str(
            "# comment\ninclude_cfg(\"RIBs/jobs.cfg\", recursive=True)\n\
             RenderJob(\"\", \"a.rib\", shaders=[\"\", '../x.sl'], ricalls = [\"Skew\", AUTO],\n\
             description=\"\"\"two\nlines \"quoted\" \"\"\", known_issues='''k''')\n\
             RenderJob('d', 'gen.py', [], ['one.tif', \"two.tif\"])\n",
        )
        .unwrap();
        assert_eq!(jobs.len(), 2);
        assert_eq!(jobs[0].rib, "a.rib");
        assert_eq!(jobs[0].shaders, vec!["../x.sl".to_string()]);
        assert_eq!(jobs[0].description, "two\nlines \"quoted\" ");
        assert_eq!(jobs[0].known_issues.as_deref(), Some("k"));
        assert_eq!(jobs[0].line, 3);
        assert_eq!(jobs[1].workingdir, "d");
        assert_eq!(jobs[1].outimagename, vec!["one.tif", "two.tif"]);
        assert_eq!(jobs[1].line, 6);
    }

    #[test]
    fn errors_name_file_line_and_column() {
        let e = parse_str("RenderJob(\"\", \"a.rib\"\n  description=\"x\")").unwrap_err();
        assert_eq!((e.line, e.col), (2, 3), "{e}");
        assert!(
            e.to_string()
                .starts_with("jobs.cfg:2:3: expected `,` or `)`"),
            "{e}"
        );
        let e = parse_str("RenderJob(\"\", \"a.rib\", description=\"\"\"open").unwrap_err();
        assert_eq!((e.line, e.col), (1, 36), "{e}");
        let e = parse_str("RenderJob(\"\", shaders=[])").unwrap_err();
        assert!(e.message.contains("needs a `rib`"), "{e}");
        let e = parse_str("RenderJob(\"\", \"a.rib\", colour=1)").unwrap_err();
        assert!(e.message.contains("no argument `colour`"), "{e}");
        let e = parse_str("x = 1").unwrap_err();
        assert!(e.message.contains("expected `(`"), "{e}");
    }
}
