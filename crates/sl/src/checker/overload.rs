//! Overload resolution: which table overload of a built-in, or which user function of a name,
//! a call's arguments select. Each candidate gets a conversion cost (exact 0, float → triple
//! or matrix 1, among point/vector/normal 2); the cheapest applicable one wins, the first in
//! table or scope order on a tie.

use super::unknown;
use crate::ast::{FuncId, FunctionDef, SigParam, Signature};
use crate::builtins::{self, BuiltinId, Overload, Slot};
use crate::types::{ArrayLen, BaseType, Type};

/// What an argument offers to overload resolution.
pub(super) struct ArgInfo {
    pub(super) ty: Type,
    pub(super) assignable: bool,
    pub(super) is_str_literal: bool,
}

/// Cost of converting a value of `from` to `to` (`None` when impossible): exact 0, float →
/// triple 1, among point/vector/normal 2.
pub(super) fn conversion_cost(from: Type, to: Type) -> Option<u32> {
    if from.base == BaseType::Unknown || to.base == BaseType::Unknown {
        return Some(0);
    }
    match (from.array, to.array) {
        (None, None) => {}
        (Some(_), Some(ArrayLen::Open)) => return (from.base == to.base).then_some(0),
        (Some(a), Some(b)) => return (from.base == to.base && a == b).then_some(0),
        _ => return None,
    }
    if from.base == to.base {
        Some(0)
    } else if from.base == BaseType::Float && (to.base.is_triple() || to.base == BaseType::Matrix) {
        Some(1)
    } else if from.base.is_geometric() && to.base.is_geometric() {
        Some(2)
    } else {
        None
    }
}

/// The cheapest table overload of `id` that `args` fit: its concrete signature and the index of
/// the first optional `"name", value` pair. `expected` is the type the context wants, which
/// chooses the return type of `noise`-like built-ins.
pub(super) fn resolve_builtin(
    id: BuiltinId,
    args: &[ArgInfo],
    expected: Option<BaseType>,
) -> Option<(Signature, Option<usize>)> {
    let mut best: Option<(u32, Signature, Option<usize>)> = None;
    for ov in builtins::overloads_of(id) {
        if let Some(m) = match_builtin(ov, args, expected) {
            if best.as_ref().is_none_or(|b| m.0 < b.0) {
                best = Some(m);
            }
        }
    }
    best.map(|(_, sig, optional_from)| (sig, optional_from))
}

/// The cheapest of the visible user functions `users` (innermost scope first) that `args` fit.
/// An `output` parameter needs an assignable argument of exactly its type (any length for an
/// open array).
pub(super) fn best_user(
    functions: &[FunctionDef],
    users: &[FuncId],
    args: &[ArgInfo],
) -> Option<FuncId> {
    let mut best: Option<(u32, FuncId)> = None;
    for &id in users {
        let f = &functions[id.0 as usize];
        if f.params.len() != args.len() {
            continue;
        }
        let mut cost = 0;
        let mut ok = true;
        for (p, a) in f.params.iter().zip(args) {
            if p.output {
                ok &= a.assignable
                    && (a.ty == p.ty
                        || unknown(a.ty)
                        || (p.ty.array == Some(ArrayLen::Open) && a.ty.base == p.ty.base));
            } else {
                match conversion_cost(a.ty, p.ty) {
                    Some(c) => cost += c,
                    None => ok = false,
                }
            }
        }
        if ok && best.is_none_or(|b| cost < b.0) {
            best = Some((cost, id));
        }
    }
    best.map(|(_, id)| id)
}

/// The concrete signature of a call to user function `f`: its parameter types, except that an
/// open-array parameter takes the argument's length.
pub(super) fn user_signature(f: &FunctionDef, args: &[ArgInfo]) -> Signature {
    Signature {
        ret: f.ret,
        params: f
            .params
            .iter()
            .zip(args)
            .map(|(p, a)| SigParam {
                ty: if p.ty.array == Some(ArrayLen::Open) {
                    a.ty
                } else {
                    p.ty
                },
                output: p.output,
            })
            .collect(),
    }
}

/// A hint for "no overload" errors whose cause is a non-assignable output argument.
pub(super) fn output_hint(id: BuiltinId, args: &[ArgInfo]) -> String {
    let needs_output = builtins::overloads_of(id).any(|o| {
        o.params.len() == args.len()
            && o.params
                .iter()
                .zip(args)
                .any(|(p, a)| p.output && !a.assignable)
    });
    if needs_output {
        " (an output argument must be a variable)".to_string()
    } else {
        String::new()
    }
}

/// Matches a table overload against the arguments: `(cost, concrete signature,
/// optional_from)`, or `None` if it does not apply.
fn match_builtin(
    ov: &Overload,
    args: &[ArgInfo],
    expected: Option<BaseType>,
) -> Option<(u32, Signature, Option<usize>)> {
    // How many arguments are positional: with pairs allowed, positional ones end at the
    // first string literal at or after the fixed parameters.
    let fixed = ov.params.len();
    let repeat = ov.params.last().is_some_and(|p| p.repeat);
    let positional = if ov.pairs {
        let split = (fixed.saturating_sub(usize::from(repeat))..args.len())
            .find(|&i| args[i].is_str_literal)
            .unwrap_or(args.len());
        if split < fixed.saturating_sub(usize::from(repeat)) || (args.len() - split) % 2 != 0 {
            return None;
        }
        split
    } else {
        args.len()
    };
    // A repeating last parameter may appear zero or more times.
    let min = if repeat { fixed - 1 } else { fixed };
    if positional < min || (!repeat && positional > fixed) {
        return None;
    }
    let spec_at = |i: usize| &ov.params[i.min(fixed - 1)];
    // Bind T: the first triple among T arguments, else float. G: the first geometric.
    let mut t = None;
    let mut g = None;
    for (i, a) in args[..positional].iter().enumerate() {
        let s = spec_at(i);
        match s.slot {
            Slot::Generic if a.ty.base.is_triple() && t.is_none() => t = Some(a.ty.base),
            Slot::Geometric if a.ty.base.is_geometric() && g.is_none() => g = Some(a.ty.base),
            _ => {}
        }
    }
    let t = t.unwrap_or(if ov.ret == Slot::Generic {
        expected
            .filter(|b| *b == BaseType::Float)
            .unwrap_or(BaseType::Float)
    } else {
        BaseType::Float
    });
    let g = g.unwrap_or(BaseType::Vector);
    let r = match expected {
        Some(b @ (BaseType::Float | BaseType::Color | BaseType::Point | BaseType::Vector)) => b,
        _ => BaseType::Float,
    };
    let mut cost = 0;
    let mut params = Vec::with_capacity(args.len());
    for (i, a) in args.iter().enumerate() {
        if i >= positional {
            // "name", value pairs: names are strings, values any type.
            let ty = if (i - positional) % 2 == 0 {
                Type::STRING
            } else {
                a.ty
            };
            if (i - positional) % 2 == 0 && a.ty.base != BaseType::String {
                return None;
            }
            params.push(SigParam { ty, output: false });
            continue;
        }
        let s = spec_at(i);
        let base = match s.slot {
            Slot::Fixed(b) => b,
            Slot::Generic => t,
            Slot::Geometric => g,
            Slot::ContextReturn => r,
            Slot::Any => a.ty.base,
        };
        let ty = if s.array {
            if !a.ty.is_array() {
                return None;
            }
            Type {
                base,
                array: a.ty.array,
            }
        } else if s.slot == Slot::Any {
            a.ty
        } else {
            Type::scalar(base)
        };
        if s.output {
            if !a.assignable || (a.ty != ty && !unknown(a.ty)) {
                return None;
            }
        } else {
            cost += conversion_cost(a.ty, ty)?;
        }
        params.push(SigParam {
            ty,
            output: s.output,
        });
    }
    let ret = match ov.ret {
        Slot::Fixed(b) => b,
        Slot::Generic => t,
        Slot::Geometric => g,
        Slot::ContextReturn => r,
        Slot::Any => BaseType::Float,
    };
    let optional_from = (ov.pairs && positional < args.len()).then_some(positional);
    Some((
        cost,
        Signature {
            ret: Type::scalar(ret),
            params,
        },
        optional_from,
    ))
}
