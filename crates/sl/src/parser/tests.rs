//! Parser unit tests: precedence, casts, construct forms, nesting, error recovery.

use super::*;
use crate::preprocess::{preprocess_str, PpOptions};
use crate::span::SourceMap;
use crate::types::ArrayLen;

fn parse_src(src: &str) -> (Program, Vec<String>) {
    let mut map = SourceMap::new();
    let mut d = Vec::new();
    let toks = preprocess_str(&mut map, "t.sl", src, &PpOptions::default(), &mut d);
    let prog = parse(&toks, &mut d);
    let msgs = d.iter().map(|d| d.render(&map).to_string()).collect();
    (prog, msgs)
}

fn body_expr(p: &Program) -> &Expr {
    match &p.shaders[0].body.stmts[0].kind {
        StmtKind::Expr(e) => e,
        other => panic!("expected an expression statement, got {other:?}"),
    }
}

#[test]
fn dot_binds_tighter_than_times_and_cross_looser() {
    let (p, e) = parse_src("surface s() { x = a * b . c ^ d + e; }");
    assert!(e.is_empty(), "{e:?}");
    let ExprKind::Assign { value, .. } = &body_expr(&p).kind else {
        panic!()
    };
    // ((a * (b . c)) ^ d) + e
    let ExprKind::Binary {
        op: BinaryOp::Add,
        lhs,
        ..
    } = &value.kind
    else {
        panic!("{value:?}")
    };
    let ExprKind::Binary {
        op: BinaryOp::Cross,
        lhs,
        ..
    } = &lhs.kind
    else {
        panic!()
    };
    let ExprKind::Binary {
        op: BinaryOp::Mul,
        rhs,
        ..
    } = &lhs.kind
    else {
        panic!()
    };
    assert!(matches!(
        rhs.kind,
        ExprKind::Binary {
            op: BinaryOp::Dot,
            ..
        }
    ));
}

#[test]
fn casts_with_spaces_tuples_and_texture_channels() {
    let (p, e) = parse_src(
        "surface s(point from = point \"shader\" (0,0,0);) { a = float texture (m[3], s, t, \"blur\", 0.1); }",
    );
    assert!(e.is_empty(), "{e:?}");
    let d = p.shaders[0].params[0].default.as_ref().unwrap();
    let ExprKind::Cast {
        to: BaseType::Point,
        space: Some(_),
        expr,
    } = &d.kind
    else {
        panic!()
    };
    assert!(matches!(&expr.kind, ExprKind::Tuple(v) if v.len() == 3));
    let ExprKind::Assign { value, .. } = &body_expr(&p).kind else {
        panic!()
    };
    let ExprKind::Cast {
        to: BaseType::Float,
        expr,
        ..
    } = &value.kind
    else {
        panic!()
    };
    let ExprKind::Texture(tc) = &expr.kind else {
        panic!()
    };
    assert_eq!(tc.kind, TextureKind::Texture);
    assert!(tc.channel.is_some());
    assert_eq!(tc.coords.len(), 2);
    assert_eq!(tc.params.len(), 1);
}

#[test]
fn lighting_construct_forms_are_identified_by_argument_count() {
    let (p, e) = parse_src(
        "surface s() { illuminance (P) {} illuminance (\"spec\", P) {} illuminance (P, N, 1) {} illuminance (\"c\", P, N, 1) ; }
         light l() { illuminate (P) {} illuminate (P, N, 1) {} solar () {} solar (N, 0) {} }",
    );
    assert!(e.is_empty(), "{e:?}");
    let forms: Vec<(bool, bool)> = p.shaders[0]
        .body
        .stmts
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Illuminance(i) => (i.category.is_some(), i.cone.is_some()),
            _ => panic!(),
        })
        .collect();
    assert_eq!(
        forms,
        vec![(false, false), (true, false), (false, true), (true, true)]
    );
    let light: Vec<bool> = p.shaders[1]
        .body
        .stmts
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Illuminate(i) => i.cone.is_some(),
            StmtKind::Solar(s) => s.cone.is_some(),
            _ => panic!(),
        })
        .collect();
    assert_eq!(light, vec![false, true, false, true]);
}

#[test]
fn nested_functions_record_their_parent() {
    let (p, e) = parse_src(
        "color f (normal N; float a, b;) { float sqr (float x) { return x*x; } return sqr(a); }",
    );
    assert!(e.is_empty(), "{e:?}");
    assert_eq!(p.functions.len(), 2);
    assert_eq!(p.functions[0].name, "f");
    assert_eq!(p.functions[0].params.len(), 3);
    assert_eq!(p.functions[1].parent, Some(Owner::Function(FuncId(0))));
    assert!(matches!(
        p.functions[0].body.stmts[0].kind,
        StmtKind::Function(FuncId(1))
    ));
}

#[test]
fn break_and_continue_levels_and_array_declarations() {
    let (p, e) = parse_src(
        "surface s() { float a[3] = {1, 2, 3}; for (i = 0; i < 3; i += 1) { while (1) { break 2; } continue; } }",
    );
    assert!(e.is_empty(), "{e:?}");
    let StmtKind::Decl(d) = &p.shaders[0].body.stmts[0].kind else {
        panic!()
    };
    assert_eq!(d.vars[0].array, Some(ArrayLen::Fixed(3)));
    assert!(
        matches!(d.vars[0].init.as_ref().unwrap().kind, ExprKind::ArrayInit(ref v) if v.len() == 3)
    );
}

#[test]
fn errors_name_what_was_expected_and_recover_at_semicolons() {
    let (_, e) =
        parse_src("surface s() {\n  float a = ;\n  b = 1 +* 2;\n  c = (1, 2;\n  d = 3;\n}\n");
    assert_eq!(
        e,
        vec![
            "t.sl:2:13: error: expected an expression, found ';'",
            "t.sl:3:10: error: expected an expression, found '*'",
            "t.sl:4:12: error: expected ')', found ';'",
        ]
    );
}

#[test]
fn errors_at_file_scope_skip_the_broken_definition() {
    let (p, e) = parse_src("surface (x) { }\nsurface ok() { Ci = 1; }\n42\n");
    assert_eq!(
        e,
        vec![
            "t.sl:1:9: error: expected a shader name, found '('",
            "t.sl:3:1: error: expected a shader or function definition, found number 42",
        ]
    );
    assert!(p.shaders.iter().any(|s| s.name == "ok"));
}

#[test]
fn assignment_to_a_non_variable_is_an_error() {
    let (_, e) = parse_src("surface s() { 1 = 2; }");
    assert_eq!(
        e,
        vec![
            "t.sl:1:17: error: expected a variable or array element on the left of the assignment"
        ]
    );
}
