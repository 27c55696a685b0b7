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
//!
//! Files: this one reads files and directives and handles `#include`; `macros.rs` defines and
//! expands macros; `condition.rs` evaluates `#if` expressions.

mod condition;
mod macros;
#[cfg(test)]
mod tests;

use crate::diagnostic::Diagnostic;
use crate::lexer::{lex, Punct, TokKind, Token};
use crate::span::{FileId, SourceMap, Span};
use macros::spell;
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
}

/// Index just past the directive line starting at `from` (the next token starting a line).
fn line_end(toks: &[Token], from: usize) -> usize {
    let mut i = from;
    while i < toks.len() && !toks[i].line_start {
        i += 1;
    }
    i
}
