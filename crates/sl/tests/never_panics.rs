//! The front end never panics, whatever the input: random bytes, random token soup, and
//! chapter-9-like sources with random edits.

use illume_sl::{compile_str, PpOptions};
use proptest::prelude::*;

/// Words and symbols the grammar cares about, so random sequences reach deep into the parser.
const PIECES: &[&str] = &[
    "surface",
    "light",
    "displacement",
    "volume",
    "imager",
    "float",
    "color",
    "point",
    "vector",
    "normal",
    "matrix",
    "string",
    "void",
    "uniform",
    "varying",
    "output",
    "extern",
    "if",
    "else",
    "while",
    "for",
    "break",
    "continue",
    "return",
    "illuminance",
    "illuminate",
    "solar",
    "texture",
    "environment",
    "shadow",
    "noise",
    "spline",
    "fresnel",
    "lightsource",
    "surface",
    "P",
    "N",
    "Ci",
    "Cl",
    "L",
    "x",
    "y",
    "PI",
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    ";",
    ",",
    ".",
    "?",
    ":",
    "+",
    "-",
    "*",
    "/",
    "^",
    "!",
    "=",
    "+=",
    "==",
    "<",
    ">=",
    "&&",
    "||",
    "1",
    "0.5",
    "2e3",
    "\"s\"",
    "\"hsv\"",
    "#define",
    "#if",
    "#else",
    "#endif",
    "#include",
    "#undef",
    "\n",
    "##",
    "#",
    "\\\n",
    "/*",
    "*/",
    "//",
];

fn soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(PIECES), 0..120).prop_map(|v| v.join(" "))
}

const PLASTIC: &str = "surface plastic (float Ka = 1, Kd = .5, Ks = .5, roughness = .1; color specularcolor = 1;)
{
    normal Nf = faceforward (normalize(N), I);
    vector V = -normalize(I);
    float k[3] = {1, 2, 3};
    illuminance (P, Nf, PI/2) { Ci += Cl * (Nf . normalize(L)); }
    Oi = Os; Ci = Os * (Cs * (Ka*ambient() + Kd*diffuse(Nf)) + specularcolor * Ks*specular(Nf,V,roughness)) * k[1];
}
";

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn random_text_never_panics(s in "\\PC{0,400}") {
        let _ = compile_str("r.sl", &s, &PpOptions::default());
    }

    #[test]
    fn random_token_soup_never_panics(s in soup()) {
        let _ = compile_str("r.sl", &s, &PpOptions::default());
    }

    #[test]
    fn edited_shader_never_panics(cut in 0usize..PLASTIC.len(), len in 0usize..40, insert in soup()) {
        let mut s = PLASTIC.to_string();
        let start = (0..=cut).rev().find(|&i| s.is_char_boundary(i)).unwrap_or(0);
        let end = (start + len).min(s.len());
        let end = (end..=s.len()).find(|&i| s.is_char_boundary(i)).unwrap_or(s.len());
        s.replace_range(start..end, &insert);
        let _ = compile_str("r.sl", &s, &PpOptions::default());
    }
}

#[test]
fn the_unedited_shader_compiles() {
    // Guards the mutation test above: its starting point must be valid.
    let out = compile_str("p.sl", PLASTIC, &PpOptions::default());
    assert!(!out.has_errors(), "{}", out.render_diagnostics());
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let src = format!(
        "surface s() {{ Ci = {}1{}; }}",
        "(".repeat(20000),
        ")".repeat(20000)
    );
    let out = compile_str("deep.sl", &src, &PpOptions::default());
    assert!(out
        .render_diagnostics()
        .contains("error: nesting deeper than 256 levels"));
    let src = format!("surface s() {} {}", "{".repeat(20000), "}".repeat(20000));
    let out = compile_str("deep.sl", &src, &PpOptions::default());
    assert!(out
        .render_diagnostics()
        .contains("error: nesting deeper than 256 levels"));
    let src = format!("surface s() {{ Ci = {}1; }}", "-".repeat(20000));
    let out = compile_str("deep.sl", &src, &PpOptions::default());
    assert!(out.has_errors());
}

#[test]
fn long_operator_chains_and_assignment_chains_are_bounded() {
    let src = format!(
        "surface s() {{ float a = 0; a = {}1; }}",
        "a + ".repeat(20000)
    );
    let out = compile_str("chain.sl", &src, &PpOptions::default());
    assert!(out
        .render_diagnostics()
        .contains("error: nesting deeper than 256 levels"));
    let src = format!("surface s() {{ float a = 0; {}1; }}", "a = ".repeat(20000));
    let out = compile_str("chain.sl", &src, &PpOptions::default());
    assert!(out
        .render_diagnostics()
        .contains("error: nesting deeper than 256 levels"));
    // Ordinary long sums still compile.
    let src = format!(
        "surface s() {{ float a = 0; a = {}1; }}",
        "a + ".repeat(100)
    );
    assert!(!compile_str("ok.sl", &src, &PpOptions::default()).has_errors());
}
