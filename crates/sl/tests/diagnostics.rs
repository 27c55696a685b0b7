//! Each error the front end reports: its exact `file:line:col` and message.

use illume_sl::{compile_str, PpOptions};

/// The rendered diagnostics of compiling `src` as `e.sl`.
fn diags(src: &str) -> Vec<String> {
    let out = compile_str("e.sl", src, &PpOptions::default());
    out.render_diagnostics()
        .lines()
        .map(str::to_string)
        .collect()
}

fn one(src: &str) -> String {
    let d = diags(src);
    assert_eq!(d.len(), 1, "expected exactly one diagnostic, got {d:#?}");
    d[0].clone()
}

#[test]
fn undeclared_variable() {
    assert_eq!(
        one("surface s() {\n  Ci = Kd;\n}\n"),
        "e.sl:2:8: error: undeclared variable 'Kd'"
    );
}

#[test]
fn type_mismatch_in_assignment() {
    assert_eq!(
        one("surface s() {\n  float f = 0;\n  f = Cs;\n}\n"),
        "e.sl:3:7: error: assignment to 'f': expected float, found color"
    );
}

#[test]
fn colour_and_point_do_not_mix() {
    assert_eq!(
        one("surface s() {\n  Ci = Cs + P;\n}\n"),
        "e.sl:2:11: error: operator '+' cannot combine color and point"
    );
}

#[test]
fn unknown_function_and_bad_overload() {
    assert_eq!(
        one("surface s() { Ci = glow(N); }"),
        "e.sl:1:20: warning: unknown function 'glow' (another renderer's extension?): calling it at run time is an error"
    );
    assert_eq!(
        one("surface s() { float f = sin(P); }"),
        "e.sl:1:25: error: no overload of 'sin' takes (point)"
    );
}

#[test]
fn output_argument_must_be_a_variable() {
    assert_eq!(
        one("surface s() { float kr, kt; fresnel(I, N, 1.5, kr + 1, kt); }"),
        "e.sl:1:29: error: no overload of 'fresnel' takes (vector, normal, float, float, float) (an output argument must be a variable)"
    );
}

#[test]
fn globals_follow_the_shader_kind() {
    assert_eq!(
        one("light l() { Ci = 1; }"),
        "e.sl:1:13: error: global 'Ci' is not available in a light shader"
    );
    assert_eq!(
        one("displacement d() { Ng = N; }"),
        "e.sl:1:20: error: cannot assign: global 'Ng' is read-only in a displacement shader"
    );
    assert_eq!(
        one("surface s() { Ci = Cl; }"),
        "e.sl:1:20: error: 'Cl' is only defined inside an illuminance loop"
    );
    assert_eq!(
        one("surface s() { Ci = length(Ps); }"),
        "e.sl:1:27: warning: global 'Ps' is not defined in a surface shader: using P"
    );
    assert_eq!(
        one("displacement d() { P = Ps; }"),
        "e.sl:1:24: error: global 'Ps' is not available in a displacement shader"
    );
}

#[test]
fn lighting_constructs_belong_to_their_shader_kinds() {
    assert_eq!(
        one("surface s() { illuminate (P) { } }"),
        "e.sl:1:15: error: 'illuminate' is only allowed in light shaders, not in a surface shader"
    );
    assert_eq!(
        one("light l() { illuminance (P) { } }"),
        "e.sl:1:13: error: 'illuminance' is only allowed in surface and volume shaders, not in a light shader"
    );
    assert_eq!(
        one("surface s() { float x; lightsource(\"a\", x); }"),
        "e.sl:1:24: error: 'lightsource' may only be called inside an illuminance loop"
    );
}

/// Issue 18: peer compilers accept a uniform variable given a varying value (liquidspot,
/// terran.sl rely on it): a warning, and the variable becomes varying.
#[test]
fn uniform_variables_given_varying_values_warn_and_become_varying() {
    assert_eq!(
        one("surface s() {\n  uniform float u0 = 0;\n  u0 = s;\n}\n"),
        "e.sl:3:3: warning: uniform variable 'u0' is given a varying value; it becomes varying"
    );
    assert_eq!(
        one("surface s(float Kd = 1;) {\n  if (t > 0.5)\n    Kd = 2;\n}\n"),
        "e.sl:3:5: warning: uniform variable 'Kd' is assigned under varying control flow (a varying condition, loop or lighting construct); it becomes varying"
    );
    // Warned once per variable, at the first such assignment.
    assert_eq!(
        diags("surface s() {\n  uniform float u0 = 0;\n  u0 = s;\n  u0 = t;\n}\n").len(),
        1
    );
}

#[test]
fn function_rules() {
    assert_eq!(
        one("float f(float x) { x = 1; return x; }"),
        "e.sl:1:20: error: cannot assign: function parameter 'x' is read-only (declare it 'output' to write it)"
    );
    assert_eq!(
        one("float f(float x) { return; }"),
        "e.sl:1:20: error: expected a return value of type float"
    );
    assert_eq!(
        one("float f(float x) { return f(x); }"),
        "e.sl:1:27: error: 'f' calls itself: the Shading Language has no recursion"
    );
    assert_eq!(
        one("surface s() { Ci = later(); }\ncolor later() { return 1; }"),
        "e.sl:1:20: error: unknown function 'later'"
    );
}

#[test]
fn nested_functions_need_extern_for_outer_variables() {
    assert_eq!(
        one("color f() {\n  float k = 2;\n  float g() { return k; }\n  return g();\n}\n"),
        "e.sl:3:22: error: 'k' belongs to an enclosing function: declare it 'extern' to use it here"
    );
}

#[test]
fn break_outside_loops_and_shader_params_without_defaults() {
    assert_eq!(
        one("surface s() { while (1) { break 2; } }"),
        "e.sl:1:27: error: 'break 2' needs 2 enclosing loop(s), found 1"
    );
    assert_eq!(
        one("surface s(float Kd;) { }"),
        "e.sl:1:17: error: shader parameter 'Kd' needs a default value"
    );
}

#[test]
fn redeclaration_and_texture_arity() {
    assert_eq!(
        one("surface s() { float a; color a; }"),
        "e.sl:1:30: error: 'a' is already declared in this scope"
    );
    assert_eq!(
        one("surface s() { Ci = texture(\"m\", s); }"),
        "e.sl:1:20: error: texture takes 0 or 2 or 8 coordinate argument(s) after the name, found 1"
    );
}

#[test]
fn errors_inside_macros_name_the_body_and_the_expansion() {
    assert_eq!(
        one("#define BAD(x) (x + Cs + P)\nsurface s() {\n  Ci = BAD(1);\n}\n"),
        "e.sl:1:24: error: operator '+' cannot combine color and point (in macro expanded at e.sl:3:8)"
    );
}

#[test]
fn several_syntax_errors_are_reported_in_one_run() {
    let d = diags("surface s() {\n  float a = 1\n  Ci = ;\n  Oi = Os;\n}\nlight l( { }\n");
    assert_eq!(
        d,
        vec![
            "e.sl:3:3: error: expected ';', found 'Ci'",
            "e.sl:6:10: error: expected a parameter type, found '{'",
        ]
    );
}

#[test]
fn into_program_turns_errors_into_the_crate_error() {
    let err = compile_str(
        "e.sl",
        "surface s() { Ci = a; Oi = b; }",
        &PpOptions::default(),
    )
    .into_program()
    .unwrap_err();
    assert_eq!(
        err.to_string(),
        "2 error(s) compiling e.sl:\ne.sl:1:20: error: undeclared variable 'a'\ne.sl:1:28: error: undeclared variable 'b'\n"
    );
    let ok = compile_str("e.sl", "surface s() { Ci = Cs; }", &PpOptions::default()).into_program();
    assert_eq!(ok.unwrap().shaders[0].name, "s");
}

#[test]
fn varying_argument_for_a_uniform_parameter() {
    assert_eq!(
        one("float f(uniform float k) { return k; }\nsurface s() { Ci = f(1) + f(s); }"),
        "e.sl:2:29: error: argument 1 of 'f' must be uniform (the parameter is declared uniform), found a varying value"
    );
}

#[test]
fn duplicate_function_definitions_but_overloads_are_fine() {
    assert_eq!(
        one("float f(float x) { return x; }\nfloat f(float y) { return y; }\n"),
        "e.sl:2:7: error: function 'f' is already defined with these parameter types"
    );
    assert!(diags("float f(float x) { return x; }\ncolor f(color y) { return y; }\nsurface s() { Ci = f(Cs) * f(1); }\n").is_empty());
}
