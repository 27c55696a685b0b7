//! The request stream: tokens from the [`Lexer`](crate::lexer) grouped into requests (a
//! request's arguments are every token up to the next request name, as in every RIB reader
//! since PRMan's), checked against their [signature](crate::signature) and yielded one at a
//! time with their source span.
//!
//! After an error the parser drops the request in hand and resynchronises at the next request
//! name, so one typo costs one request, not the file.
use crate::diagnostic::{Diagnostic, Severity};
use crate::lexer::{LexError, Lexer, Pos, Token};
use crate::request::{Request, Value};
use crate::signature::{build, Arg, SignatureError};
use crate::span::{Span, Spanned};
use std::collections::VecDeque;
use std::fs::File;
use std::io::{self, BufReader, Read};
use std::path::Path;
use std::sync::Arc;

/// One item of the stream: a request, or a problem found on the way.
pub type Item = Result<Spanned<Request>, Diagnostic>;

/// Streaming RIB parser over any reader (ASCII and binary RIB, mixed). Wrap gzip streams in a
/// decoder first, or use [`open`], which detects them.
pub struct Parser<R> {
    lexer: Lexer<R>,
    file: Arc<str>,
    /// The token that ended the previous request (its successor's name, a `##`, or the end).
    pending: Option<(Token, Pos)>,
    /// Items ready to hand out (an unknown request's warning comes before the request).
    queue: VecDeque<Item>,
    finished: bool,
}

impl<R: Read> Parser<R> {
    /// `file_name` is what diagnostics and spans call the stream (`-` for stdin).
    pub fn new(reader: R, file_name: &str) -> Self {
        Parser {
            lexer: Lexer::new(reader),
            file: Arc::from(file_name),
            pending: None,
            queue: VecDeque::new(),
            finished: false,
        }
    }

    /// Also keeps every comment record (`#` and `##`, text after the `#`s) for
    /// [`Parser::take_comments`]: `RiReadArchive`'s callback sees them.
    pub fn keep_comments(mut self) -> Self {
        self.lexer.comments = Some(Vec::new());
        self
    }

    /// Comment records read so far, in order, as (structural, text); empty unless
    /// [`Parser::keep_comments`].
    pub fn take_comments(&mut self) -> Vec<(bool, String)> {
        self.lexer
            .comments
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }

    /// The name spans use for this stream.
    pub fn file_name(&self) -> &Arc<str> {
        &self.file
    }

    fn span(&self, p: Pos) -> Span {
        Span::new(self.file.clone(), p.line, p.col, p.offset)
    }

    fn diagnostic(
        &self,
        severity: Severity,
        p: Pos,
        request: Option<&str>,
        message: String,
        source_line: String,
    ) -> Diagnostic {
        Diagnostic {
            severity,
            span: self.span(p),
            request: request.map(str::to_string),
            message,
            source_line,
        }
    }

    fn lex_diagnostic(&self, e: LexError, request: Option<&str>) -> Diagnostic {
        self.diagnostic(Severity::Error, e.pos, request, e.message, e.source_line)
    }

    fn token(&mut self) -> Result<(Token, Pos), LexError> {
        match self.pending.take() {
            Some(t) => Ok(t),
            None => self.lexer.next_token(),
        }
    }

    /// Skips tokens up to the next request name (kept as pending), ignoring further errors.
    fn resynchronise(&mut self) {
        self.lexer.quiet = true;
        loop {
            match self.token() {
                Ok((t @ (Token::Name(_) | Token::Structure(_) | Token::Eof), p)) => {
                    self.pending = Some((t, p));
                    self.lexer.quiet = false;
                    return;
                }
                _ => continue,
            }
        }
    }

    /// Reads a bracketed array after its `[`.
    fn array(&mut self, open: Pos) -> Result<Value, LexError> {
        let mut ints: Vec<i32> = Vec::new();
        let mut floats: Vec<f32> = Vec::new();
        let mut strings: Vec<String> = Vec::new();
        let mut is_float = false;
        let mixed = |lexer: &Lexer<R>, p: Pos| LexError {
            pos: p,
            message: "array mixes numbers and strings".into(),
            source_line: lexer.current_line(),
        };
        loop {
            let (tok, p) = self.lexer.next_token()?;
            match tok {
                Token::Int(i) if strings.is_empty() => {
                    if is_float {
                        floats.push(i as f32)
                    } else {
                        ints.push(i)
                    }
                }
                Token::Float(f) if strings.is_empty() => {
                    if !is_float {
                        is_float = true;
                        floats.extend(ints.drain(..).map(|i| i as f32));
                    }
                    floats.push(f);
                }
                Token::FloatArray(v) if strings.is_empty() => {
                    if !is_float {
                        is_float = true;
                        floats.extend(ints.drain(..).map(|i| i as f32));
                    }
                    floats.extend(v);
                }
                Token::Str(s) if ints.is_empty() && floats.is_empty() => strings.push(s),
                Token::Int(_) | Token::Float(_) | Token::FloatArray(_) | Token::Str(_) => {
                    return Err(mixed(&self.lexer, p))
                }
                Token::Close => {
                    return Ok(if !strings.is_empty() {
                        Value::Strings(strings)
                    } else if is_float || ints.is_empty() {
                        // An empty array has no type; it is read as an empty float array.
                        Value::Floats(floats)
                    } else {
                        Value::Ints(ints)
                    });
                }
                Token::Open => {
                    return Err(LexError {
                        pos: p,
                        message: "`[` inside an array (arrays do not nest)".into(),
                        source_line: self.lexer.current_line(),
                    })
                }
                end @ (Token::Name(_) | Token::Structure(_) | Token::Eof) => {
                    let message = format!(
                        "unterminated array: `[` at {}:{} has no `]` before {}",
                        open.line,
                        open.col,
                        end.describe()
                    );
                    self.pending = Some((end, p));
                    return Err(LexError {
                        pos: open,
                        message,
                        source_line: String::new(),
                    });
                }
            }
        }
    }

    /// Collects the arguments after a request name up to the next name (left pending).
    fn arguments(&mut self) -> Result<Vec<Arg>, LexError> {
        let mut args = Vec::new();
        loop {
            let (tok, p) = self.lexer.next_token()?;
            let arg = match tok {
                end @ (Token::Name(_) | Token::Structure(_) | Token::Eof) => {
                    self.pending = Some((end, p));
                    return Ok(args);
                }
                Token::Int(i) => Arg::Int(i),
                Token::Float(f) => Arg::Float(f),
                Token::Str(s) => Arg::Str(s),
                Token::FloatArray(v) => Arg::Array(Value::Floats(v)),
                Token::Open => Arg::Array(self.array(p)?),
                Token::Close => {
                    return Err(LexError {
                        pos: p,
                        message: "`]` without `[`".into(),
                        source_line: self.lexer.current_line(),
                    })
                }
            };
            args.push(arg);
        }
    }

    fn request(&mut self, name: Arc<str>, p: Pos) -> Item {
        let source_line = self.lexer.current_line();
        let args = match self.arguments() {
            Ok(a) => a,
            Err(e) => {
                self.resynchronise();
                return Err(self.lex_diagnostic(e, Some(&name)));
            }
        };
        match build(&name, args) {
            Ok(value) => Ok(Spanned {
                span: self.span(p),
                value,
            }),
            Err(SignatureError::Bad(message)) => {
                Err(self.diagnostic(Severity::Error, p, Some(&name), message, source_line))
            }
            Err(SignatureError::Unknown(args)) => {
                let request = Request::Unknown {
                    name: name.to_string(),
                    args: args.into_iter().map(Arg::into_value).collect(),
                };
                self.queue.push_back(Ok(Spanned {
                    span: self.span(p),
                    value: request,
                }));
                Err(self.diagnostic(
                    Severity::Warning,
                    p,
                    Some(&name),
                    "unknown request, its arguments are skipped".into(),
                    source_line,
                ))
            }
        }
    }
}

impl<R: Read> Iterator for Parser<R> {
    type Item = Item;

    fn next(&mut self) -> Option<Item> {
        if let Some(item) = self.queue.pop_front() {
            return Some(item);
        }
        if self.finished {
            return None;
        }
        let (tok, p) = match self.token() {
            Ok(t) => t,
            Err(e) => return Some(Err(self.lex_diagnostic(e, None))),
        };
        match tok {
            Token::Eof => {
                self.finished = true;
                let e = self.lexer.io_error.take()?;
                let message = match e.kind() {
                    io::ErrorKind::InvalidInput | io::ErrorKind::InvalidData => {
                        format!("read error: {e} (truncated or corrupt gzip?)")
                    }
                    _ => format!("read error: {e}"),
                };
                Some(Err(self.diagnostic(
                    Severity::Error,
                    p,
                    None,
                    message,
                    String::new(),
                )))
            }
            Token::Structure(text) => Some(Ok(Spanned {
                span: self.span(p),
                value: Request::StructureComment(text),
            })),
            Token::Name(name) => Some(self.request(name, p)),
            stray => {
                let message = format!("{} outside any request", stray.describe());
                let line = self.lexer.current_line();
                self.resynchronise();
                Some(Err(self.diagnostic(
                    Severity::Error,
                    p,
                    None,
                    message,
                    line,
                )))
            }
        }
    }
}

/// Opens a RIB file for parsing: `-` is stdin; gzip (magic `1f 8b`) is decompressed on the fly.
pub fn open(path: &Path) -> io::Result<Parser<Box<dyn Read + Send>>> {
    let name = path.to_string_lossy();
    let raw: Box<dyn Read + Send> = if path == Path::new("-") {
        Box::new(io::stdin())
    } else {
        Box::new(File::open(path)?)
    };
    Ok(Parser::new(decompress(raw)?, &name))
}

/// Wraps `reader` in a gzip decoder if it starts with the gzip magic `1f 8b`.
pub fn decompress(mut reader: impl Read + Send + 'static) -> io::Result<Box<dyn Read + Send>> {
    let mut magic = [0u8; 2];
    let mut n = 0;
    // A pipe may deliver one byte at a time: read until two are seen or the input ends.
    while n < 2 {
        match reader.read(&mut magic[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        }
    }
    let whole = io::Cursor::new(magic[..n].to_vec()).chain(reader);
    if n == 2 && magic == [0x1f, 0x8b] {
        Ok(Box::new(flate2::read::MultiGzDecoder::new(BufReader::new(
            whole,
        ))))
    } else {
        Ok(Box::new(whole))
    }
}
