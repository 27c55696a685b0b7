//! The RI specification's standard shaders and a few feature-dense ones (in `tests/shaders/`,
//! written for these tests) compile, with the shapes the executor relies on.

use illume_sl::ast::*;
use illume_sl::types::{Detail, ShaderKind};
use illume_sl::{compile_file, Compiled, PpOptions};
use std::path::PathBuf;

fn shader_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/shaders")
}

fn compile(name: &str) -> Compiled {
    let out = compile_file(&shader_dir().join(name), &PpOptions::default());
    assert!(!out.has_errors(), "{name}:\n{}", out.render_diagnostics());
    out
}

#[test]
fn every_test_shader_compiles_cleanly() {
    let mut n = 0;
    for entry in std::fs::read_dir(shader_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "sl") {
            let out = compile_file(&path, &PpOptions::default());
            assert!(
                out.diagnostics.is_empty(),
                "{}:\n{}",
                path.display(),
                out.render_diagnostics()
            );
            n += 1;
        }
    }
    assert_eq!(n, 14);
}

#[test]
fn shader_kinds_and_lighting_forms() {
    let kind = |f: &str| compile(f).program.shaders[0].kind;
    assert_eq!(kind("fog.sl"), ShaderKind::Volume);
    assert_eq!(kind("bumpy.sl"), ShaderKind::Displacement);
    assert_eq!(kind("ambientlight.sl"), ShaderKind::Light);
    let p = compile("distantlight.sl").program;
    let StmtKind::Solar(so) = &p.shaders[0].body.stmts[0].kind else {
        panic!()
    };
    assert!(so.cone.is_some(), "solar (axis, angle) form");
    let p = compile("pointlight.sl").program;
    let StmtKind::Illuminate(il) = &p.shaders[0].body.stmts[0].kind else {
        panic!()
    };
    assert!(il.cone.is_none(), "illuminate (from) form: all directions");
}

#[test]
fn brickbump_macros_output_parameters_and_uniform_loops() {
    let out = compile("brickbump.sl");
    let p = &out.program;
    let f = &p.functions[0];
    assert_eq!(f.name, "brickcoords");
    assert_eq!(
        f.params.iter().map(|q| q.output).collect::<Vec<_>>(),
        [false, false, true, true]
    );
    let sh = &p.shaders[0];
    let v = |n: &str| sh.vars.iter().find(|v| v.name == n).unwrap();
    assert_eq!(
        v("sbrick").inferred,
        Detail::Varying,
        "written through an output parameter by a varying call"
    );
    assert_eq!(v("total").inferred, Detail::Uniform);
    assert_eq!(v("soft").inferred, Detail::Varying);
    // N = calculatenormal (P) resolved to the builtin.
    let StmtKind::Expr(e) = &sh.body.stmts.last().unwrap().kind else {
        panic!()
    };
    let ExprKind::Assign { target, value, .. } = &e.kind else {
        panic!()
    };
    assert_eq!(target.var, Some(VarRef::Global(Global::N)));
    let ExprKind::Call(c) = &value.kind else {
        panic!()
    };
    assert!(matches!(&c.callee, Some(Callee::Builtin(b)) if b.name == "calculatenormal"));
}

#[test]
fn uniform_work_is_found_in_a_feature_dense_shader() {
    let out = compile("colorspaces.sl");
    let sh = &out.program.shaders[0];
    let v = |n: &str| sh.vars.iter().find(|v| v.name == n).unwrap();
    for n in ["c", "d", "m", "w", "det", "msg", "r"] {
        assert_eq!(v(n).inferred, Detail::Uniform, "{n}");
    }
    for n in ["q", "dq", "a", "sp"] {
        assert_eq!(v(n).inferred, Detail::Varying, "{n}");
    }
    assert_eq!(
        v("msg").detail,
        Detail::Uniform,
        "strings are uniform by default"
    );
}

mod common;

#[test]
fn checked_programs_keep_the_ast_promises() {
    for entry in std::fs::read_dir(shader_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "sl") {
            let out = compile_file(&path, &PpOptions::default());
            let bad = common::invariant_violations(&out.program);
            assert!(bad.is_empty(), "{}: {bad:#?}", path.display());
        }
    }
}
