//! The C-style preprocessor shaders are written for (`#include`, `#define`, `#if`…), working on
//! tokens rather than text.
//!
//! Shader sources lean on the preprocessor: chapter 9's `ENVPARAMS` /
//! `DECLARE_DEFAULTED_ENVPARAMS` macros (Listing 9.7) paste parameter lists into several
//! shaders, and libraries of `Material*`/`LocIllum*` functions are `#include`d. Working on the
//! lexer's tokens keeps the source map trivial: a token taken from a macro body keeps the
//! body's file:line:col and gains `expanded_at` (the invocation), an `#include`d token keeps its
//! header's location. No text is re-lexed except the result of `##`.
//!
//! Supported: `#include "f"` / `<f>` (the including file's directory first for quotes, then
//! each `-I` directory in order), object- and function-like `#define` with `#` and `##`,
//! `#undef`, `#if`/`#ifdef`/`#ifndef`/`#elif`/`#else`/`#endif` with C integer expressions and
//! `defined`, `#error`, `#warning`; `#pragma` and `#line` are accepted and ignored.

use crate::diagnostic::Diagnostic;
use crate::lexer::{lex, Punct, TokKind, Token};
use crate::span::{FileId, Loc, SourceMap, Span};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Nesting limit for `#include`, so a file including itself reports an error instead of
/// recursing until the stack overflows.
const MAX_INCLUDE_DEPTH: usize = 40;
/// Limit on macro-expansion depth (self-reference is already blocked; this bounds mutual
/// recursion through arguments).
const MAX_EXPANSION_DEPTH: usize = 200;
/// Limit on tokens one macro expansion may produce, against exponential macro bombs
/// (`#define A B B`, `#define B C C`, …).
const MAX_EXPANSION_TOKENS: usize = 1 << 18;

/// Preprocessor settings (what `slc -I dir -D NAME=value` sets).
#[derive(Debug, Clone, Default)]
pub struct PpOptions {
    /// `-I` directories searched for `#include`, in order, after the including file's directory.
    pub include_dirs: Vec<PathBuf>,
    /// `-D NAME[=value]` definitions (value `1` when absent).
    pub defines: Vec<(String, String)>,
}

/// A macro definition.
#[derive(Debug, Clone)]
struct Macro {
    /// Parameter names for a function-like macro; `None` for object-like.
    params: Option<Vec<String>>,
    /// Replacement list.
    body: Vec<Token>,
}

/// One level of `#if` nesting.
struct Cond {
    /// Text in the current branch is emitted.
    active: bool,
    /// Some branch of this `#if` chain has been taken already.
    taken: bool,
    /// The enclosing region was active (else nothing in this chain is).
    parent_active: bool,
    /// `#else` seen (a later `#elif`/`#else` is an error).
    seen_else: bool,
    /// The `#if` itself, for "unterminated #if".
    span: Span,
}

/// Preprocessor state for one compilation.
struct Pp<'a> {
    map: &'a mut SourceMap,
    opts: &'a PpOptions,
    diags: &'a mut Vec<Diagnostic>,
    macros: HashMap<String, Macro>,
    out: Vec<Token>,
}

/// Preprocesses `file` (already registered in `map`) and everything it includes, returning the
/// token stream for the parser. Problems are pushed to `diags`; the result is always usable
/// (a missing include is skipped after an error).
pub fn preprocess(
    map: &mut SourceMap,
    file: FileId,
    opts: &PpOptions,
    diags: &mut Vec<Diagnostic>,
) -> Vec<Token> {
    let mut pp = Pp {
        map,
        opts,
        diags,
        macros: HashMap::new(),
        out: Vec::new(),
    };
    for (name, value) in &opts.defines {
        let mut scratch = Vec::new();
        let cmdline = pp.map.add("<command line>", value.clone());
        let body = lex(cmdline, value, &mut scratch);
        pp.macros.insert(name.clone(), Macro { params: None, body });
    }
    pp.run_file(file, 0);
    pp.out
}

/// Convenience: registers `text` as a file named `name` and preprocesses it.
pub fn preprocess_str(
    map: &mut SourceMap,
    name: &str,
    text: &str,
    opts: &PpOptions,
    diags: &mut Vec<Diagnostic>,
) -> Vec<Token> {
    let id = map.add(name, text);
    preprocess(map, id, opts, diags)
}

impl Pp<'_> {
    fn run_file(&mut self, file: FileId, depth: usize) {
        let text = self.map.files[file.0 as usize].text.clone();
        let toks = lex(file, &text, self.diags);
        let mut conds: Vec<Cond> = Vec::new();
        let mut run: Vec<Token> = Vec::new();
        let mut i = 0;
        while i < toks.len() {
            let active = conds.last().is_none_or(|c| c.active);
            if toks[i].line_start && toks[i].is(Punct::Hash) {
                let end = line_end(&toks, i + 1);
                if !run.is_empty() {
                    let r = std::mem::take(&mut run);
                    self.expand_into_out(&r);
                }
                self.directive(&toks[i], &toks[i + 1..end], &mut conds, active, file, depth);
                i = end;
                continue;
            }
            if active {
                run.push(toks[i].clone());
            }
            i += 1;
        }
        if !run.is_empty() {
            self.expand_into_out(&run);
        }
        for c in conds {
            self.diags.push(Diagnostic::error(
                c.span,
                "unterminated #if (missing #endif)",
            ));
        }
    }

    fn expand_into_out(&mut self, toks: &[Token]) {
        let mut active = Vec::new();
        let mut out = Vec::new();
        self.expand(toks, &mut active, &mut out, 0);
        self.out.extend(out);
    }

    fn directive(
        &mut self,
        hash: &Token,
        line: &[Token],
        conds: &mut Vec<Cond>,
        active: bool,
        file: FileId,
        depth: usize,
    ) {
        let Some(first) = line.first() else {
            return; // the null directive `#`
        };
        let name = first.ident().unwrap_or("");
        let rest = &line[1..];
        match name {
            "if" | "ifdef" | "ifndef" => {
                let value = if !active {
                    false
                } else if name == "if" {
                    self.eval_if(first, rest)
                } else {
                    match rest.first().and_then(|t| t.ident()) {
                        Some(m) => self.macros.contains_key(m) == (name == "ifdef"),
                        None => {
                            self.err(first.span, format!("expected a macro name after #{name}"));
                            false
                        }
                    }
                };
                conds.push(Cond {
                    active: value,
                    taken: value,
                    parent_active: active,
                    seen_else: false,
                    span: hash.span,
                });
            }
            "elif" | "else" => {
                let Some(mut c) = conds.pop() else {
                    self.err(first.span, format!("#{name} without #if"));
                    return;
                };
                if c.seen_else {
                    self.err(first.span, format!("#{name} after #else"));
                }
                let take =
                    c.parent_active && !c.taken && (name == "else" || self.eval_if(first, rest));
                c.active = take;
                c.taken |= take;
                c.seen_else |= name == "else";
                conds.push(c);
            }
            "endif" => {
                if conds.pop().is_none() {
                    self.err(first.span, "#endif without #if");
                }
            }
            _ if !active => {}
            "define" => self.define(first, rest),
            "undef" => match rest.first().and_then(|t| t.ident()) {
                Some(m) => {
                    self.macros.remove(m);
                }
                None => self.err(first.span, "expected a macro name after #undef"),
            },
            "include" => self.include(first, rest, file, depth),
            "error" => self.err(first.span, format!("#error {}", spell(rest))),
            "warning" => self.diags.push(Diagnostic::warning(
                first.span,
                format!("#warning {}", spell(rest)),
            )),
            "pragma" | "line" => {}
            _ => self.err(
                first.span,
                format!("unknown preprocessor directive '#{}'", first.text),
            ),
        }
    }

    fn err(&mut self, span: Span, msg: impl Into<String>) {
        self.diags.push(Diagnostic::error(span, msg));
    }

    fn define(&mut self, at: &Token, rest: &[Token]) {
        let Some(name_tok) = rest.first() else {
            self.err(at.span, "expected a macro name after #define");
            return;
        };
        let Some(name) = name_tok.ident() else {
            self.err(
                name_tok.span,
                format!("expected a macro name, found {}", name_tok.describe()),
            );
            return;
        };
        let mut i = 1;
        let mut params = None;
        if rest
            .get(1)
            .is_some_and(|t| t.is(Punct::LParen) && !t.space_before)
        {
            let mut names = Vec::new();
            i = 2;
            loop {
                match rest.get(i) {
                    Some(t) if t.is(Punct::RParen) && names.is_empty() => {
                        i += 1;
                        break;
                    }
                    Some(t) if t.ident().is_some() => {
                        names.push(t.text.clone());
                        i += 1;
                        match rest.get(i) {
                            Some(t) if t.is(Punct::Comma) => i += 1,
                            Some(t) if t.is(Punct::RParen) => {
                                i += 1;
                                break;
                            }
                            other => {
                                let span = other.map_or(name_tok.span, |t| t.span);
                                self.err(span, "expected ',' or ')' in macro parameter list");
                                return;
                            }
                        }
                    }
                    other => {
                        let span = other.map_or(name_tok.span, |t| t.span);
                        self.err(span, "expected a macro parameter name");
                        return;
                    }
                }
            }
            params = Some(names);
        }
        let body = rest[i.min(rest.len())..].to_vec();
        self.macros.insert(name.to_string(), Macro { params, body });
    }

    fn include(&mut self, at: &Token, rest: &[Token], file: FileId, depth: usize) {
        let (name, quoted) = match rest.first().map(|t| &t.kind) {
            Some(TokKind::Str(s)) => (s.clone(), true),
            Some(TokKind::Punct(Punct::Lt)) => {
                let close = rest.iter().position(|t| t.is(Punct::Gt));
                match close {
                    Some(c) => (rest[1..c].iter().map(|t| t.text.as_str()).collect(), false),
                    None => {
                        self.err(at.span, "expected '>' to close #include <…>");
                        return;
                    }
                }
            }
            _ => {
                self.err(at.span, "expected \"file\" or <file> after #include");
                return;
            }
        };
        if depth >= MAX_INCLUDE_DEPTH {
            self.err(
                at.span,
                format!("#include nested more than {MAX_INCLUDE_DEPTH} deep (recursive include?)"),
            );
            return;
        }
        let including_dir = self
            .map
            .path(file)
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let mut candidates = Vec::new();
        if quoted {
            candidates.push(including_dir.join(&name));
        }
        candidates.extend(self.opts.include_dirs.iter().map(|d| d.join(&name)));
        for path in candidates {
            if let Ok(text) = std::fs::read(&path).map(|b| String::from_utf8_lossy(&b).into_owned())
            {
                let id = self.map.add(path, text);
                self.run_file(id, depth + 1);
                return;
            }
        }
        self.err(
            rest[0].span,
            format!("cannot find include file '{name}' (searched the including file's directory and -I directories)"),
        );
    }

    /// Evaluates an `#if`/`#elif` condition: `defined` first, then macro expansion, then C
    /// integer arithmetic with unknown identifiers as 0.
    fn eval_if(&mut self, at: &Token, rest: &[Token]) -> bool {
        let mut resolved = Vec::new();
        let mut i = 0;
        while i < rest.len() {
            if rest[i].ident() == Some("defined") {
                let (name, next) = if rest.get(i + 1).is_some_and(|t| t.is(Punct::LParen)) {
                    let ok = rest.get(i + 3).is_some_and(|t| t.is(Punct::RParen));
                    (
                        rest.get(i + 2).and_then(|t| t.ident()).filter(|_| ok),
                        i + 4,
                    )
                } else {
                    (rest.get(i + 1).and_then(|t| t.ident()), i + 2)
                };
                let Some(name) = name else {
                    self.err(rest[i].span, "expected a macro name after 'defined'");
                    return false;
                };
                let v = self.macros.contains_key(name);
                resolved.push(number_token(if v { 1.0 } else { 0.0 }, rest[i].span));
                i = next;
            } else {
                resolved.push(rest[i].clone());
                i += 1;
            }
        }
        let mut expanded = Vec::new();
        self.expand(&resolved, &mut Vec::new(), &mut expanded, 0);
        if expanded.is_empty() {
            self.err(at.span, "expected an expression after #if");
            return false;
        }
        let mut ev = IfEval {
            toks: &expanded,
            pos: 0,
        };
        match ev.ternary() {
            Ok(v) if ev.pos == expanded.len() => v != 0,
            Ok(_) => {
                let t = &expanded[ev.pos];
                self.err(
                    t.span,
                    format!("expected end of #if expression, found {}", t.describe()),
                );
                false
            }
            Err(e) => {
                let span = expanded.get(e).map_or(at.span, |t| t.span);
                let found = expanded
                    .get(e)
                    .map_or("end of line".into(), |t| t.describe());
                self.err(
                    span,
                    format!("expected an integer expression in #if, found {found}"),
                );
                false
            }
        }
    }

    /// Macro-expands `toks` into `out`. `active` holds the macros being expanded (a macro is
    /// not expanded inside its own expansion, the C rule that makes `#define X X` safe).
    fn expand(
        &mut self,
        toks: &[Token],
        active: &mut Vec<String>,
        out: &mut Vec<Token>,
        depth: usize,
    ) {
        let mut i = 0;
        while i < toks.len() {
            let t = &toks[i];
            let Some(name) = t.ident() else {
                out.push(t.clone());
                i += 1;
                continue;
            };
            let Some(mac) = self
                .macros
                .get(name)
                .filter(|_| !active.iter().any(|a| a == name))
            else {
                out.push(t.clone());
                i += 1;
                continue;
            };
            if depth > MAX_EXPANSION_DEPTH || out.len() > MAX_EXPANSION_TOKENS {
                self.err(
                    t.span,
                    format!("macro '{name}' expands too deeply or too far"),
                );
                return;
            }
            let mac = mac.clone();
            let site = t.span.expanded_at.unwrap_or(t.span.loc);
            let replaced = match &mac.params {
                None => {
                    i += 1;
                    self.substitute(&mac, &[], site)
                }
                Some(params) => {
                    if !toks.get(i + 1).is_some_and(|t| t.is(Punct::LParen)) {
                        // A function-like macro name without arguments is just a name.
                        out.push(t.clone());
                        i += 1;
                        continue;
                    }
                    let Some((args, next)) = collect_args(toks, i + 2) else {
                        self.err(
                            t.span,
                            format!("unterminated argument list of macro '{name}'"),
                        );
                        return;
                    };
                    let nargs = if params.is_empty() && args.len() == 1 && args[0].is_empty() {
                        0
                    } else {
                        args.len()
                    };
                    if nargs != params.len() {
                        self.err(
                            t.span,
                            format!(
                                "macro '{name}' expects {} argument(s), found {nargs}",
                                params.len()
                            ),
                        );
                        i = next;
                        continue;
                    }
                    i = next;
                    let args = if params.is_empty() { Vec::new() } else { args };
                    self.substitute(&mac, &args, site)
                }
            };
            active.push(name.to_string());
            self.expand(&replaced, active, out, depth + 1);
            active.pop();
        }
    }

    /// The replacement list with parameters replaced by their (expanded) arguments, `#p`
    /// stringized and `a ## b` pasted. Body tokens are marked as expanded at `site`.
    fn substitute(&mut self, mac: &Macro, args: &[Vec<Token>], site: Loc) -> Vec<Token> {
        let params = mac.params.as_deref().unwrap_or(&[]);
        let param_index = |t: &Token| t.ident().and_then(|n| params.iter().position(|p| p == n));
        let mut result: Vec<Token> = Vec::new();
        let body = &mac.body;
        let mut i = 0;
        while i < body.len() {
            let t = &body[i];
            // `# param`: the argument's spelling as a string.
            if t.is(Punct::Hash) && mac.params.is_some() {
                if let Some(k) = body.get(i + 1).and_then(param_index) {
                    let text = spell(&args[k]);
                    let mut s = t.clone();
                    s.kind = TokKind::Str(text.clone());
                    s.text = format!("\"{text}\"");
                    s.span.expanded_at = Some(site);
                    result.push(s);
                    i += 2;
                    continue;
                }
            }
            let pasting = body.get(i + 1).is_some_and(|n| n.is(Punct::HashHash))
                || (i > 0 && body[i - 1].is(Punct::HashHash));
            if t.is(Punct::HashHash) {
                i += 1;
                continue;
            }
            let piece: Vec<Token> = match param_index(t) {
                Some(k) if pasting => args[k].clone(),
                Some(k) => {
                    let mut e = Vec::new();
                    self.expand(&args[k], &mut Vec::new(), &mut e, 1);
                    e
                }
                None => {
                    let mut b = t.clone();
                    b.span.expanded_at = Some(site);
                    vec![b]
                }
            };
            let joins_previous = i > 0 && body[i - 1].is(Punct::HashHash) && !result.is_empty();
            if joins_previous && !piece.is_empty() {
                let left = result.pop().unwrap_or_else(|| piece[0].clone());
                let glued = format!("{}{}", left.text, piece[0].text);
                let mut scratch = Vec::new();
                let relexed = lex(left.span.loc.file, &glued, &mut scratch);
                if relexed.len() == 1 && scratch.is_empty() {
                    let mut g = relexed[0].clone();
                    g.span = left.span;
                    g.space_before = left.space_before;
                    g.line_start = false;
                    result.push(g);
                } else {
                    self.err(
                        left.span,
                        format!(
                            "pasting '{}' and '{}' does not give a valid token",
                            left.text, piece[0].text
                        ),
                    );
                    result.push(left);
                    result.push(piece[0].clone());
                }
                result.extend_from_slice(&piece[1..]);
            } else {
                result.extend(piece);
            }
            i += 1;
        }
        result
    }
}

/// Index just past the directive line starting at `from` (the next token starting a line).
fn line_end(toks: &[Token], from: usize) -> usize {
    let mut i = from;
    while i < toks.len() && !toks[i].line_start {
        i += 1;
    }
    i
}

/// Splits a macro invocation's arguments at top-level commas, starting just after `(`.
/// Returns the arguments and the index after the closing `)`.
fn collect_args(toks: &[Token], from: usize) -> Option<(Vec<Vec<Token>>, usize)> {
    let mut args = vec![Vec::new()];
    let mut depth = 0usize;
    let mut i = from;
    while i < toks.len() {
        let t = &toks[i];
        if t.is(Punct::LParen) {
            depth += 1;
        } else if t.is(Punct::RParen) {
            if depth == 0 {
                return Some((args, i + 1));
            }
            depth -= 1;
        } else if t.is(Punct::Comma) && depth == 0 {
            args.push(Vec::new());
            i += 1;
            continue;
        }
        args.last_mut()?.push(t.clone());
        i += 1;
    }
    None
}

/// Tokens' spellings joined the way `#` stringizes them (single spaces where there was any).
fn spell(toks: &[Token]) -> String {
    let mut s = String::new();
    for (k, t) in toks.iter().enumerate() {
        if k > 0 && t.space_before {
            s.push(' ');
        }
        s.push_str(&t.text);
    }
    s
}

fn number_token(v: f64, span: Span) -> Token {
    Token {
        kind: TokKind::Number(v),
        span,
        text: format!("{v}"),
        line_start: false,
        space_before: true,
    }
}

/// C integer expression evaluator for `#if` (precedence climbing over the expanded tokens).
/// Errors carry the index of the offending token.
struct IfEval<'a> {
    toks: &'a [Token],
    pos: usize,
}

impl IfEval<'_> {
    fn peek(&self) -> Option<&Token> {
        self.toks.get(self.pos)
    }

    fn eat(&mut self, p: Punct) -> bool {
        if self.peek().is_some_and(|t| t.is(p)) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    fn ternary(&mut self) -> Result<i64, usize> {
        let c = self.binary(0)?;
        if self.eat(Punct::Question) {
            let a = self.ternary()?;
            if !self.eat(Punct::Colon) {
                return Err(self.pos);
            }
            let b = self.ternary()?;
            return Ok(if c != 0 { a } else { b });
        }
        Ok(c)
    }

    fn binary(&mut self, min_prec: u8) -> Result<i64, usize> {
        let mut lhs = self.unary()?;
        while let Some(TokKind::Punct(p)) = self.peek().map(|t| &t.kind) {
            let p = *p;
            let prec = match p {
                Punct::OrOr => 1,
                Punct::AndAnd => 2,
                Punct::Pipe => 3,
                Punct::Caret => 4,
                Punct::Amp => 5,
                Punct::EqEq | Punct::Ne => 6,
                Punct::Lt | Punct::Gt | Punct::Le | Punct::Ge => 7,
                Punct::Plus | Punct::Minus => 8,
                Punct::Star | Punct::Slash | Punct::Percent => 9,
                _ => break,
            };
            if prec < min_prec {
                break;
            }
            let at = self.pos;
            self.pos += 1;
            let rhs = self.binary(prec + 1)?;
            lhs = match p {
                Punct::OrOr => ((lhs != 0) || (rhs != 0)) as i64,
                Punct::AndAnd => ((lhs != 0) && (rhs != 0)) as i64,
                Punct::Pipe => lhs | rhs,
                Punct::Caret => lhs ^ rhs,
                Punct::Amp => lhs & rhs,
                Punct::EqEq => (lhs == rhs) as i64,
                Punct::Ne => (lhs != rhs) as i64,
                Punct::Lt => (lhs < rhs) as i64,
                Punct::Gt => (lhs > rhs) as i64,
                Punct::Le => (lhs <= rhs) as i64,
                Punct::Ge => (lhs >= rhs) as i64,
                Punct::Plus => lhs.wrapping_add(rhs),
                Punct::Minus => lhs.wrapping_sub(rhs),
                Punct::Star => lhs.wrapping_mul(rhs),
                Punct::Slash | Punct::Percent if rhs == 0 => return Err(at),
                Punct::Slash => lhs.wrapping_div(rhs),
                _ => lhs.wrapping_rem(rhs),
            };
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<i64, usize> {
        let Some(t) = self.peek() else {
            return Err(self.pos);
        };
        let kind = t.kind.clone();
        self.pos += 1;
        match kind {
            TokKind::Number(v) => Ok(v as i64),
            TokKind::Ident(_) => Ok(0),
            TokKind::Punct(Punct::Minus) => Ok(self.unary()?.wrapping_neg()),
            TokKind::Punct(Punct::Plus) => self.unary(),
            TokKind::Punct(Punct::Bang) => Ok((self.unary()? == 0) as i64),
            TokKind::Punct(Punct::Tilde) => Ok(!self.unary()?),
            TokKind::Punct(Punct::LParen) => {
                let v = self.ternary()?;
                if self.eat(Punct::RParen) {
                    Ok(v)
                } else {
                    Err(self.pos)
                }
            }
            _ => Err(self.pos - 1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pp(src: &str) -> (Vec<Token>, Vec<Diagnostic>, SourceMap) {
        let mut map = SourceMap::new();
        let mut d = Vec::new();
        let t = preprocess_str(&mut map, "t.sl", src, &PpOptions::default(), &mut d);
        (t, d, map)
    }

    fn text(t: &[Token]) -> String {
        t.iter()
            .map(|t| t.text.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    }

    #[test]
    fn envparams_macros_of_listing_9_7_expand_with_their_locations() {
        let src = "#define ENVPARAMS      envname, envspace, envrad\n\
                   #define DECLARE_ENVPARAMS \\\n    string envname, envspace; uniform float envrad\n\
                   f (DECLARE_ENVPARAMS;) { g(ENVPARAMS); }\n";
        let (t, d, _) = pp(src);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(
            text(&t),
            "f ( string envname , envspace ; uniform float envrad ; ) { g ( envname , envspace , envrad ) ; }"
        );
        // `string` comes from line 3 (the continued body of DECLARE_ENVPARAMS), expanded on line 4.
        let s = &t[2];
        assert_eq!((s.span.loc.line, s.span.loc.col), (3, 5));
        let at = s
            .span
            .expanded_at
            .expect("macro token marks its expansion site");
        assert_eq!((at.line, at.col), (4, 4));
    }

    #[test]
    fn function_like_macros_substitute_stringize_and_paste() {
        let (t, d, _) = pp("#define SQR(x) ((x)*(x))\n#define CAT(a,b) a##b\n#define STR(a) #a\nSQR(y+1) CAT(foo,2) STR(a  +b)\n");
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(text(&t), "( ( y + 1 ) * ( y + 1 ) ) foo2 \"a +b\"");
    }

    #[test]
    fn object_like_macro_with_parenthesis_after_a_space_is_not_function_like() {
        let (t, _, _) = pp("#define F (x)\nF\n");
        assert_eq!(text(&t), "( x )");
    }

    #[test]
    fn self_referential_macro_stops() {
        let (t, d, _) = pp("#define X X+1\nX\n");
        assert!(d.is_empty());
        assert_eq!(text(&t), "X + 1");
    }

    #[test]
    fn conditionals_with_defined_and_arithmetic() {
        let src = "#define A 2\n#if defined(A) && A*3 == 6\nyes\n#elif 1\nno1\n#else\nno2\n#endif\n\
                   #ifdef B\nno3\n#endif\n#ifndef B\nyes2\n#endif\n#if 0\n#if 1\nno4\n#endif\n#else\nyes3\n#endif\n";
        let (t, d, _) = pp(src);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(text(&t), "yes yes2 yes3");
    }

    #[test]
    fn undef_and_wrong_argument_counts() {
        let (t, d, map) = pp("#define A 1\n#undef A\nA\n#define F(a,b) a\nF(1)\n");
        assert_eq!(text(&t), "A");
        assert_eq!(d.len(), 1);
        assert_eq!(
            d[0].render(&map).to_string(),
            "t.sl:5:1: error: macro 'F' expects 2 argument(s), found 1"
        );
    }

    #[test]
    fn unterminated_if_and_stray_endif_are_reported() {
        let (_, d, map) = pp("#endif\n#if 1\nx\n");
        let msgs: Vec<String> = d.iter().map(|d| d.render(&map).to_string()).collect();
        assert_eq!(
            msgs,
            vec![
                "t.sl:1:2: error: #endif without #if",
                "t.sl:2:1: error: unterminated #if (missing #endif)"
            ]
        );
    }

    #[test]
    fn nested_includes_search_own_dir_then_include_dirs() {
        let root = std::env::temp_dir().join(format!("illume-sl-pp-{}", std::process::id()));
        let inc = root.join("inc");
        let sub = root.join("sub");
        std::fs::create_dir_all(&inc).unwrap();
        std::fs::create_dir_all(&sub).unwrap();
        std::fs::write(inc.join("outer.h"), "#include \"inner.h\"\nouter INNER\n").unwrap();
        std::fs::write(inc.join("inner.h"), "#define INNER inner\n  bad$\n").unwrap();
        std::fs::write(sub.join("main.sl"), "#include <outer.h>\nmain\n").unwrap();
        let mut map = SourceMap::new();
        let main = sub.join("main.sl");
        let id = map.add(&main, std::fs::read_to_string(&main).unwrap());
        let opts = PpOptions {
            include_dirs: vec![inc.clone()],
            defines: vec![],
        };
        let mut d = Vec::new();
        let t = preprocess(&mut map, id, &opts, &mut d);
        assert_eq!(text(&t), "bad $ outer inner main");
        // The stray `$` is reported in inner.h at its own line and column.
        assert_eq!(d.len(), 1);
        assert_eq!(
            d[0].render(&map).to_string(),
            format!(
                "{}:2:6: error: unexpected character '$'",
                inc.join("inner.h").display()
            )
        );
        std::fs::remove_dir_all(&root).ok();
    }

    #[test]
    fn missing_and_recursive_includes_are_errors_not_crashes() {
        let (_, d, map) = pp("#include \"no-such-file.h\"\n");
        assert_eq!(d.len(), 1);
        assert!(d[0]
            .render(&map)
            .to_string()
            .starts_with("t.sl:1:10: error: cannot find include file 'no-such-file.h'"));
        let dir = std::env::temp_dir().join(format!("illume-sl-rec-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("self.h"), "#include \"self.h\"\n").unwrap();
        let mut map = SourceMap::new();
        let id = map.add(dir.join("self.h"), "#include \"self.h\"\n");
        let mut d = Vec::new();
        preprocess(&mut map, id, &PpOptions::default(), &mut d);
        assert!(
            d.iter().any(|d| d.message.contains("nested more than")),
            "{d:?}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn exponential_macros_stop_with_an_error() {
        let mut src = String::new();
        for i in 0..40 {
            src.push_str(&format!("#define M{i} M{} M{}\n", i + 1, i + 1));
        }
        src.push_str("M0\n");
        let (t, d, _) = pp(&src);
        assert!(t.len() <= 4 * MAX_EXPANSION_TOKENS);
        assert!(
            d.iter()
                .any(|d| d.message.contains("expands too deeply or too far")),
            "{d:?}"
        );
    }

    #[test]
    fn command_line_defines_are_visible() {
        let mut map = SourceMap::new();
        let mut d = Vec::new();
        let opts = PpOptions {
            include_dirs: vec![],
            defines: vec![("N_LIGHTS".into(), "4".into())],
        };
        let t = preprocess_str(
            &mut map,
            "t.sl",
            "#if N_LIGHTS > 3\nmany\n#endif\n",
            &opts,
            &mut d,
        );
        assert_eq!(text(&t), "many");
    }
}
