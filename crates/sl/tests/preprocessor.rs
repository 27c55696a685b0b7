//! The preprocessor as shader libraries use it, end to end through the checker.

use illume_sl::{compile_file, compile_str, PpOptions};

#[test]
fn envparams_style_macros_with_arguments_declare_and_pass_parameters() {
    let src = r#"
#define DECLARE_ENV(p) string p##name = "", p##space = "world"; uniform float p##rad = 100
#define ENV(p) p##name, p##space, p##rad
#define SQR(x) ((x)*(x))
color lookup (string name, space; uniform float rad; vector R;)
{
    color C = 0;
    if (name != "")
        C = color environment (name, vtransform (space, R)) * SQR(rad) / SQR(rad);
    return C;
}
surface envmetal (float Kr = 1; DECLARE_ENV(env); DECLARE_ENV(refl);)
{
    vector R = reflect (normalize(I), normalize(N));
    Ci = Kr * (lookup (R = R, ENV(env), R) + lookup (ENV(refl), R));
}
"#;
    let out = compile_str("env.sl", src, &PpOptions::default());
    // The first call has one argument too many (R = R, ...): exactly one error, at the call.
    assert_eq!(
        out.render_diagnostics(),
        "env.sl:15:16: error: no function 'lookup' takes (vector, string, string, float, vector)\n"
    );
    let fixed = src.replace("lookup (R = R, ENV(env), R)", "lookup (ENV(env), R)");
    let out = compile_str("env.sl", &fixed, &PpOptions::default());
    assert!(!out.has_errors(), "{}", out.render_diagnostics());
    let names: Vec<&str> = out.program.shaders[0]
        .params
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "Kr",
            "envname",
            "envspace",
            "envrad",
            "reflname",
            "reflspace",
            "reflrad"
        ]
    );
}

#[test]
fn conditional_compilation_selects_the_model() {
    let src = "#define MODEL 2\n#if MODEL == 1\nsurface s() { Ci = diffuse(N); }\n#elif MODEL == 2 && defined(MODEL)\nsurface s() { Ci = Cs; }\n#else\nsurface s() { Ci = bogus; }\n#endif\n";
    let out = compile_str("m.sl", src, &PpOptions::default());
    assert!(!out.has_errors(), "{}", out.render_diagnostics());
    assert_eq!(out.program.shaders.len(), 1);
    let opts = PpOptions {
        include_dirs: vec![],
        defines: vec![("MODEL".into(), "3".into())],
    };
    let out = compile_str("m.sl", &src.replace("#define MODEL 2\n", ""), &opts);
    assert_eq!(
        out.render_diagnostics(),
        "m.sl:6:20: error: undeclared variable 'bogus'\n"
    );
}

#[test]
fn errors_in_nested_includes_point_into_the_header() {
    let dir = std::env::temp_dir().join(format!("illume-sl-inc-{}", std::process::id()));
    let lib = dir.join("lib");
    std::fs::create_dir_all(&lib).unwrap();
    std::fs::write(
        lib.join("material.h"),
        "#include \"locillum.h\"\ncolor Mat (normal Nf;) { return Loc (Nf); }\n",
    )
    .unwrap();
    std::fs::write(
        lib.join("locillum.h"),
        "color Loc (normal Nf;)\n{\n    return Nf;\n}\n",
    )
    .unwrap();
    let main = dir.join("main.sl");
    std::fs::write(
        &main,
        "#include <material.h>\nsurface s() { Ci = Mat (normalize(N)); }\n",
    )
    .unwrap();
    let opts = PpOptions {
        include_dirs: vec![lib.clone()],
        defines: vec![],
    };
    let out = compile_file(&main, &opts);
    assert_eq!(
        out.render_diagnostics(),
        format!(
            "{}:3:12: error: return value: expected color, found normal\n",
            lib.join("locillum.h").display()
        )
    );
    std::fs::remove_dir_all(&dir).ok();
}
