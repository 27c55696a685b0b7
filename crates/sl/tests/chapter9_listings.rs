//! Every Shading Language listing of *Advanced RenderMan* chapter 9, extracted from the
//! reference text at test time, compiles without errors.
//!
//! The text is `../shared/reference/advanced-renderman-ch9-illumination-and-lights.txt`
//! relative to the repository root (or under `$ILLUME_SHARED`). A listing is a line starting
//! `Listing 9.N` whose next non-blank line opens a ``` code block; a block that follows the
//! first one with only blank lines between belongs to the same listing (ERRATA.md: Listing 9.5
//! is split across a page break). Only the errata that say the printed listing is wrong are
//! applied: `C1`/`C!` read for `Cl` (Listings 9.11–9.13, 9.17) and the lost `fkt` argument of
//! Listing 9.9's `fresnel` call.

use illume_sl::ast::{Callee, ExprKind, StmtKind};
use illume_sl::types::{BaseType, Detail, ShaderKind};
use illume_sl::{compile_str, Compiled, PpOptions};
use std::collections::BTreeMap;

/// The reference text, or `None` (skipped loudly; a failure under `CI=true`).
fn reference_text() -> Option<String> {
    let path = illume_testenv::shared_file(
        "reference/advanced-renderman-ch9-illumination-and-lights.txt",
    )?;
    Some(std::fs::read_to_string(path).unwrap())
}

/// Listing number (the `N` of `9.N`) → its code, blocks joined.
fn extract_listings(text: &str) -> BTreeMap<u32, String> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = BTreeMap::new();
    let mut i = 0;
    while i < lines.len() {
        let Some(rest) = lines[i].strip_prefix("Listing 9.") else {
            i += 1;
            continue;
        };
        let num: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
        let Ok(n) = num.parse::<u32>() else {
            i += 1;
            continue;
        };
        let next_non_blank =
            |from: usize| (from..lines.len()).find(|&k| !lines[k].trim().is_empty());
        let mut k = match next_non_blank(i + 1) {
            Some(k) if lines[k].trim_start().starts_with("```") => k,
            _ => {
                i += 1;
                continue; // a prose mention such as "Listing 9.12 lists the function …"
            }
        };
        let mut code = String::new();
        loop {
            let start = k + 1;
            let end = (start..lines.len())
                .find(|&e| lines[e].trim_start().starts_with("```"))
                .unwrap_or(lines.len());
            for l in &lines[start..end] {
                code.push_str(l);
                code.push('\n');
            }
            match next_non_blank(end + 1) {
                Some(nk) if lines[nk].trim_start().starts_with("```") && unfinished(&code) => {
                    k = nk
                }
                _ => {
                    i = end + 1;
                    break;
                }
            }
        }
        out.insert(n, code);
    }
    out
}

/// Whether `code` stops mid-definition (an open brace or comment): only then does the next
/// code block continue it (Listing 9.5 across its page break). A finished listing followed by
/// a block is prose's own example (after Listing 9.14, the `solar (…) { statements; }` form).
fn unfinished(code: &str) -> bool {
    let (mut depth, mut comment) = (0i32, false);
    let b = code.as_bytes();
    let mut i = 0;
    while i < b.len() {
        match (comment, b[i], b.get(i + 1)) {
            (false, b'/', Some(b'*')) => (comment, i) = (true, i + 1),
            (true, b'*', Some(b'/')) => (comment, i) = (false, i + 1),
            (false, b'/', Some(b'/')) => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            (false, b'{', _) => depth += 1,
            (false, b'}', _) => depth -= 1,
            _ => {}
        }
        i += 1;
    }
    comment || depth > 0
}

/// The errata that correct the printed listings (see the module documentation).
fn apply_errata(n: u32, code: &str) -> String {
    let mut fixed = String::with_capacity(code.len());
    let chars: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let prev_is_ident = i > 0 && (chars[i - 1].is_ascii_alphanumeric() || chars[i - 1] == '_');
        let next = chars.get(i + 2).copied().unwrap_or(' ');
        let next_is_ident = next.is_ascii_alphanumeric() || next == '_';
        if chars[i] == 'C'
            && matches!(chars.get(i + 1), Some('1') | Some('!'))
            && !prev_is_ident
            && !next_is_ident
            && chars.get(i + 2) != Some(&'=')
        {
            fixed.push_str("Cl");
            i += 2;
            continue;
        }
        fixed.push(chars[i]);
        i += 1;
    }
    if n == 9 {
        fixed = fixed.replace(
            "fresnel (IN, Nf, 1/ior, fkr, R, T)",
            "fresnel (IN, Nf, 1/ior, fkr, fkt, R, T)",
        );
    }
    fixed
}

/// Listings that use functions or macros of earlier listings.
fn prerequisites(n: u32) -> &'static [u32] {
    match n {
        7 => &[5, 6],
        8 | 9 => &[5, 6, 7],
        _ => &[],
    }
}

fn compile_listing(listings: &BTreeMap<u32, String>, n: u32, errata: bool) -> Compiled {
    let mut src = String::new();
    for p in prerequisites(n).iter().chain(std::iter::once(&n)) {
        let code = &listings[p];
        src.push_str(&if errata {
            apply_errata(*p, code)
        } else {
            code.clone()
        });
    }
    compile_str(&format!("listing9.{n}.sl"), &src, &PpOptions::default())
}

#[test]
fn every_chapter_listing_is_found() {
    let Some(text) = reference_text() else { return };
    let listings = extract_listings(&text);
    let found: Vec<u32> = listings.keys().copied().collect();
    assert_eq!(found, (1..=19).collect::<Vec<u32>>());
    // Listing 9.5's two page-broken blocks were joined: raysphere and Environment.
    assert!(
        listings[&5].contains("raysphere (point E") && listings[&5].contains("color Environment")
    );
}

#[test]
fn every_chapter_listing_compiles() {
    let Some(text) = reference_text() else { return };
    let listings = extract_listings(&text);
    let mut failures = String::new();
    for &n in listings.keys() {
        let out = compile_listing(&listings, n, true);
        if out.has_errors() {
            failures.push_str(&format!("Listing 9.{n}:\n{}", out.render_diagnostics()));
        }
    }
    assert!(failures.is_empty(), "{failures}");
}

mod common;

#[test]
fn checked_listings_keep_the_ast_promises() {
    let Some(text) = reference_text() else { return };
    let listings = extract_listings(&text);
    for &n in listings.keys() {
        let out = compile_listing(&listings, n, true);
        let bad = common::invariant_violations(&out.program);
        assert!(bad.is_empty(), "Listing 9.{n}: {bad:#?}");
    }
}

#[test]
fn the_errata_are_needed_where_they_say() {
    let Some(text) = reference_text() else { return };
    let listings = extract_listings(&text);
    // As printed, Listing 9.9 passes five arguments to fresnel, which has no such form.
    let out = compile_listing(&listings, 9, false);
    assert!(
        out.render_diagnostics().contains(
            "error: no overload of 'fresnel' takes (vector, normal, float, float, vector, vector)"
        ),
        "{}",
        out.render_diagnostics()
    );
    // As printed, Listing 9.11 names `C1`, which is not a variable.
    let out = compile_listing(&listings, 11, false);
    assert!(
        out.render_diagnostics().contains(
            "extern 'C1' is neither a global variable nor a variable of an enclosing function"
        ),
        "{}",
        out.render_diagnostics()
    );
}

#[test]
fn shinymetal_resolves_macros_functions_and_globals() {
    let Some(text) = reference_text() else { return };
    let listings = extract_listings(&text);
    let out = compile_listing(&listings, 8, true);
    assert!(!out.has_errors(), "{}", out.render_diagnostics());
    let p = &out.program;
    let sh = p
        .shaders
        .iter()
        .find(|s| s.name == "shinymetal")
        .expect("shinymetal shader");
    assert_eq!(sh.kind, ShaderKind::Surface);
    // DECLARE_DEFAULTED_ENVPARAMS added envname, envspace, envrad.
    let names: Vec<&str> = sh.params.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "Ka",
            "Kd",
            "Ks",
            "roughness",
            "Kr",
            "blur",
            "envname",
            "envspace",
            "envrad"
        ]
    );
    assert_eq!(sh.params[8].detail, Some(Detail::Uniform));
    // `Ci = MaterialShinyMetal (…)` calls the user function, not a builtin.
    let StmtKind::Expr(e) = &sh.body.stmts[1].kind else {
        panic!()
    };
    let ExprKind::Assign { value, .. } = &e.kind else {
        panic!()
    };
    let ExprKind::Call(call) = &value.kind else {
        panic!("{value:?}")
    };
    let Some(Callee::User(id)) = call.callee else {
        panic!()
    };
    assert_eq!(p.function(id).name, "MaterialShinyMetal");
    assert_eq!(value.ty.base, BaseType::Color);
    assert_eq!(value.detail, Detail::Varying);
}

#[test]
fn light_listings_have_their_forms_and_uniform_setup() {
    let Some(text) = reference_text() else { return };
    let listings = extract_listings(&text);
    // 9.15 distantlight: solar (axis, angle); 9.16 pointlight: illuminate (from);
    // 9.17 spotlight: illuminate (from, axis, angle) with uniform set-up outside it.
    let first_stmt_forms = |n: u32| {
        let out = compile_listing(&listings, n, true);
        assert!(!out.has_errors(), "{}", out.render_diagnostics());
        let sh = &out.program.shaders[0];
        let form = sh
            .body
            .stmts
            .iter()
            .find_map(|s| match &s.kind {
                StmtKind::Solar(so) => Some(("solar", so.cone.is_some())),
                StmtKind::Illuminate(il) => Some(("illuminate", il.cone.is_some())),
                _ => None,
            })
            .expect("a lighting construct");
        (sh.kind, form, out)
    };
    let (k, form, _) = first_stmt_forms(15);
    assert_eq!((k, form), (ShaderKind::Light, ("solar", true)));
    let (_, form, _) = first_stmt_forms(16);
    assert_eq!(form, ("illuminate", false));
    let (_, form, out) = first_stmt_forms(17);
    assert_eq!(form, ("illuminate", true));
    let v = |n: &str| {
        out.program.shaders[0]
            .vars
            .iter()
            .find(|v| v.name == n)
            .unwrap()
            .inferred
    };
    assert_eq!(
        ["A", "cosoutside", "cosinside", "cosangle", "atten"].map(v),
        [
            Detail::Uniform,
            Detail::Uniform,
            Detail::Uniform,
            Detail::Varying,
            Detail::Varying
        ]
    );
}
