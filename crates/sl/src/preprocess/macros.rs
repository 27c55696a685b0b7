//! Macros: `#define` (object- and function-like), expansion with self-reference blocked and
//! bounded depth and size, argument substitution with `#` stringizing and `##` pasting.

use super::{Macro, Pp, MAX_EXPANSION_DEPTH, MAX_EXPANSION_TOKENS};
use crate::lexer::{lex, Punct, TokKind, Token};
use crate::span::Loc;

impl Pp<'_> {
    pub(super) fn define(&mut self, at: &Token, rest: &[Token]) {
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

    /// Macro-expands `toks` into `out`. `active` holds the macros being expanded (a macro is
    /// not expanded inside its own expansion, the C rule that makes `#define X X` safe).
    pub(super) fn expand(
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
    pub(super) fn substitute(&mut self, mac: &Macro, args: &[Vec<Token>], site: Loc) -> Vec<Token> {
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
pub(super) fn spell(toks: &[Token]) -> String {
    let mut s = String::new();
    for (k, t) in toks.iter().enumerate() {
        if k > 0 && t.space_before {
            s.push(' ');
        }
        s.push_str(&t.text);
    }
    s
}
