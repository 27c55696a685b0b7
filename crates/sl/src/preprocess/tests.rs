//! Preprocessor unit tests: macros of Listing 9.7, stringize and paste, conditionals,
//! includes, and the limits that stop hostile input.

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
