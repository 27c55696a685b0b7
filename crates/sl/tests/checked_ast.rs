//! The checker's annotations: types chosen from context, explicit promotions and casts,
//! resolved variables and callees, and uniform/varying inference.

use illume_sl::ast::*;
use illume_sl::types::{BaseType, Detail, Type};
use illume_sl::{compile_str, PpOptions};

mod common;
use common::all_exprs;

fn compile(src: &str) -> Program {
    let out = compile_str("t.sl", src, &PpOptions::default());
    assert!(!out.has_errors(), "{}", out.render_diagnostics());
    out.program
}

/// The calls named `name`, in order.
fn calls<'a>(p: &'a Program, name: &str) -> Vec<(&'a Expr, &'a Call)> {
    all_exprs(p)
        .into_iter()
        .filter_map(|e| match &e.kind {
            ExprKind::Call(c) if c.name == name => Some((e, c)),
            _ => None,
        })
        .collect()
}

fn builtin(c: &Call) -> &BuiltinCall {
    match &c.callee {
        Some(Callee::Builtin(b)) => b,
        other => panic!("expected a builtin callee, got {other:?}"),
    }
}

fn var<'a>(p: &'a Program, owner: Owner, name: &str) -> &'a VarInfo {
    p.vars(owner)
        .iter()
        .find(|v| v.name == name)
        .unwrap_or_else(|| panic!("no variable {name}"))
}

const S0: Owner = Owner::Shader(ShaderId(0));

#[test]
fn noise_return_type_comes_from_the_assignment_context() {
    let p = compile(
        "surface s() { float f = noise(P); color c = noise(P); point q = noise(P); vector v = noise(s, t); Ci = Cs * noise(P); f = float noise(P*2); }",
    );
    let rets: Vec<BaseType> = calls(&p, "noise")
        .iter()
        .map(|(e, c)| {
            assert_eq!(
                e.ty,
                builtin(c).sig.ret,
                "expression type and chosen signature agree"
            );
            e.ty.base
        })
        .collect();
    use BaseType::*;
    assert_eq!(rets, vec![Float, Color, Point, Vector, Color, Float]);
    let (_, c) = calls(&p, "noise")[3];
    assert_eq!(
        builtin(c)
            .sig
            .params
            .iter()
            .map(|q| q.ty)
            .collect::<Vec<_>>(),
        vec![Type::FLOAT, Type::FLOAT]
    );
}

#[test]
fn float_to_triple_promotions_are_explicit() {
    let p = compile("surface s() { color c = 1; Ci = Cs * 0.5; c = mix(Cs, 1, 0.25); }");
    let promotes: Vec<&Expr> = all_exprs(&p)
        .into_iter()
        .filter(|e| matches!(e.kind, ExprKind::Promote(_)))
        .collect();
    assert_eq!(promotes.len(), 3);
    for e in &promotes {
        assert_eq!(e.ty, Type::COLOR);
        let ExprKind::Promote(inner) = &e.kind else {
            unreachable!()
        };
        assert_eq!(inner.ty, Type::FLOAT);
    }
    let (_, mix) = calls(&p, "mix")[0];
    let sig: Vec<Type> = builtin(mix).sig.params.iter().map(|q| q.ty).collect();
    assert_eq!(sig, vec![Type::COLOR, Type::COLOR, Type::FLOAT]);
    assert_eq!(
        mix.args[1].ty,
        Type::COLOR,
        "the argument was promoted to the parameter type"
    );
}

#[test]
fn point_arithmetic_follows_the_spec() {
    let p = compile(
        "surface s() { vector d = P - E; point q = P + d; normal n2 = N + N; vector c = d ^ vector N; float k = d . N; }",
    );
    let bin: Vec<(BinaryOp, BaseType)> = all_exprs(&p)
        .into_iter()
        .filter_map(|e| match &e.kind {
            ExprKind::Binary { op, .. } => Some((*op, e.ty.base)),
            _ => None,
        })
        .collect();
    use BaseType::*;
    assert_eq!(
        bin,
        vec![
            (BinaryOp::Sub, Vector),
            (BinaryOp::Add, Point),
            (BinaryOp::Add, Normal),
            (BinaryOp::Cross, Vector),
            (BinaryOp::Dot, Float)
        ]
    );
}

#[test]
fn implicit_conversions_between_geometric_types_become_casts() {
    let p = compile("surface s() { normal Nf = faceforward(normalize(N), I); vector v = N; }");
    let (e, ff) = calls(&p, "faceforward")[0];
    assert_eq!(
        e.ty,
        Type::NORMAL,
        "faceforward returns its first argument's type"
    );
    assert_eq!(builtin(ff).sig.params[1].ty, Type::VECTOR);
    let casts: Vec<&Expr> = all_exprs(&p)
        .into_iter()
        .filter(|e| matches!(e.kind, ExprKind::Cast { space: None, .. }))
        .collect();
    assert_eq!(casts.len(), 1, "only `vector v = N` converts");
    assert_eq!(casts[0].ty, Type::VECTOR);
}

#[test]
fn space_casts_and_matrix_literals() {
    let p = compile(
        "surface s() { color c = color \"hsv\" (0.5, 1, 1); point o = point \"world\" (0, 0, 0);
           matrix m = matrix \"shader\" (1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1); matrix i = 1; }",
    );
    let casts: Vec<(BaseType, String, Type)> = all_exprs(&p)
        .into_iter()
        .filter_map(|e| match &e.kind {
            ExprKind::Cast {
                to,
                space: Some(sp),
                expr,
            } => match &sp.kind {
                ExprKind::Str(s) => Some((*to, s.clone(), expr.ty)),
                _ => None,
            },
            _ => None,
        })
        .collect();
    assert_eq!(
        casts,
        vec![
            (BaseType::Color, "hsv".into(), Type::COLOR),
            (BaseType::Point, "world".into(), Type::POINT),
            (BaseType::Matrix, "shader".into(), Type::MATRIX)
        ]
    );
    assert!(all_exprs(&p)
        .iter()
        .any(|e| matches!(e.kind, ExprKind::Promote(_)) && e.ty == Type::MATRIX));
}

#[test]
fn pi_is_a_constant_unless_shadowed() {
    let p = compile("surface s() { float a = PI/2; } float f(float PI) { return PI; }");
    assert!(all_exprs(&p)
        .iter()
        .any(|e| matches!(e.kind, ExprKind::Float(v) if v == std::f64::consts::PI)));
    let f = &p.functions[0];
    let StmtKind::Return(Some(r)) = &f.body.stmts[0].kind else {
        panic!()
    };
    assert!(matches!(&r.kind, ExprKind::Var(v) if v.var == Some(VarRef::Slot(VarId(0)))));
}

#[test]
fn extern_resolves_globals_and_enclosing_variables() {
    let p = compile(
        "color f() { extern point P; float k = 2; float g() { extern float k; return k * xcomp(P); } return g(); }",
    );
    let f0 = &p.functions[0];
    let StmtKind::Decl(d) = &f0.body.stmts[0].kind else {
        panic!()
    };
    assert_eq!(d.vars[0].var, Some(VarRef::Global(Global::P)));
    let g = &p.functions[1];
    assert_eq!(g.parent, Some(Owner::Function(FuncId(0))));
    let StmtKind::Decl(d) = &g.body.stmts[0].kind else {
        panic!()
    };
    let k = var(&p, Owner::Function(FuncId(0)), "k");
    assert_eq!(k.kind, VarKind::Local);
    assert_eq!(
        d.vars[0].var,
        Some(VarRef::Outer {
            owner: Owner::Function(FuncId(0)),
            var: VarId(0)
        })
    );
    assert_eq!(
        k.inferred,
        Detail::Varying,
        "an extern target keeps its default detail"
    );
    assert!(g.reads_varying);
}

#[test]
fn spline_forms_and_array_arguments() {
    let p = compile(
        "surface s() { float k[4] = {1, 2, 3, 4}; float a = spline(t, 1, 2, 3, 4, 5);
           color c = spline(\"catmull-rom\", t, Cs, Cs, Cs, Cs); float b = spline(t, k); }",
    );
    let sigs: Vec<Vec<Type>> = calls(&p, "spline")
        .iter()
        .map(|(_, c)| builtin(c).sig.params.iter().map(|q| q.ty).collect())
        .collect();
    let f = Type::FLOAT;
    let c = Type::COLOR;
    assert_eq!(sigs[0], vec![f; 6]);
    assert_eq!(sigs[1], vec![Type::STRING, f, c, c, c, c]);
    assert_eq!(sigs[2], vec![f, Type::array(BaseType::Float, 4)]);
}

#[test]
fn texture_calls_split_channel_coordinates_and_parameters() {
    let p = compile(
        "surface s(string m = \"\";) { color c = color texture(m, s, t, \"blur\", 0.1, \"width\", 2);
           float a = float texture(m[3], s, t); float sh = shadow(m, P, \"bias\", 0.01); }",
    );
    let tex: Vec<&Expr> = all_exprs(&p)
        .into_iter()
        .filter(|e| matches!(e.kind, ExprKind::Texture(_)))
        .collect();
    assert_eq!(tex.len(), 3);
    let ExprKind::Texture(t0) = &tex[0].kind else {
        unreachable!()
    };
    assert_eq!(tex[0].ty, Type::COLOR);
    assert_eq!(
        (t0.coords.len(), t0.params.len(), t0.channel.is_some()),
        (2, 2, false)
    );
    let ExprKind::Texture(t1) = &tex[1].kind else {
        unreachable!()
    };
    assert_eq!(tex[1].ty, Type::FLOAT);
    assert!(t1.channel.is_some());
    let ExprKind::Texture(t2) = &tex[2].kind else {
        unreachable!()
    };
    assert_eq!(t2.kind, TextureKind::Shadow);
    assert_eq!(t2.coords[0].ty, Type::POINT);
    assert!(tex.iter().all(|e| e.detail == Detail::Varying));
}

#[test]
fn message_passing_and_printf_take_any_type() {
    let p = compile(
        "surface s() { color lc = 0; float ok = surface(\"Kd\", lc); illuminance (P) { float nd = 0; lightsource(\"__nondiffuse\", nd); }
           printf(\"%f %c\\n\", s, Cs); }",
    );
    let (_, c) = calls(&p, "surface")[0];
    let b = builtin(c);
    assert_eq!(
        b.sig.params[1],
        SigParam {
            ty: Type::COLOR,
            output: true
        }
    );
    let (_, ls) = calls(&p, "lightsource")[0];
    assert_eq!(
        builtin(ls).sig.params[1],
        SigParam {
            ty: Type::FLOAT,
            output: true
        }
    );
    let (pe, pf) = calls(&p, "printf")[0];
    assert_eq!(pe.ty, Type::VOID);
    let types: Vec<Type> = builtin(pf).sig.params.iter().map(|q| q.ty).collect();
    assert_eq!(types, vec![Type::STRING, Type::FLOAT, Type::COLOR]);
}

#[test]
fn filterstep_optional_pairs_are_marked() {
    let p = compile("surface s() { float f = filterstep(0.5, s, \"width\", 2); float g = filterstep(0.5, s, t); }");
    let fs = calls(&p, "filterstep");
    assert_eq!(builtin(fs[0].1).optional_from, Some(2));
    assert_eq!(builtin(fs[1].1).optional_from, None);
    assert_eq!(builtin(fs[1].1).sig.params.len(), 3);
}

#[test]
fn uniform_inference_refines_locals_fed_only_by_uniform_values() {
    let p = compile(
        "surface s(float Kd = 1;) {
            float k = Kd * 2;          /* uniform: only uniform inputs */
            float n = 0;               /* uniform: a loop with a uniform condition */
            float i;
            for (i = 0; i < 4; i += 1) n += i;
            float a = 1;               /* varying: assigned under a varying if */
            if (s > 0.5) a = 2;
            float b = 0;               /* varying: fed by a, which is varying */
            b = a * k;
            float w = 0;               /* varying: loop left by a varying break */
            float j;
            for (j = 0; j < 4; j += 1) { if (t > 0.5) break; w += 1; }
            uniform float u = 3;
            varying float v = 3;       /* declared varying stays varying */
            Ci = k * n * a * b * w * u * v;
        }",
    );
    let inferred = |n: &str| var(&p, S0, n).inferred;
    use Detail::*;
    assert_eq!(
        ["k", "n", "i", "a", "b", "w", "j", "u", "v"].map(inferred),
        [Uniform, Uniform, Uniform, Varying, Varying, Varying, Varying, Uniform, Varying]
    );
    assert_eq!(
        var(&p, S0, "k").detail,
        Varying,
        "the spec default for an unqualified local"
    );
    assert_eq!(var(&p, S0, "k").declared, None);
    assert_eq!(var(&p, S0, "u").declared, Some(Uniform));
    // The expression reading only uniform values is uniform.
    let StmtKind::Decl(d) = &p.shaders[0].body.stmts[0].kind else {
        panic!()
    };
    assert_eq!(d.vars[0].init.as_ref().unwrap().detail, Uniform);
}

#[test]
fn calls_of_pure_functions_with_uniform_arguments_are_uniform() {
    let p = compile(
        "float sq(float x) { return x*x; }
         float lit(float x) { extern point P; return x * xcomp(P); }
         surface s(float Kd = 1;) { float a = sq(Kd); float b = lit(Kd); float c = sq(s); Ci = a + b + c; }",
    );
    assert!(!p.functions[0].reads_varying);
    assert!(p.functions[1].reads_varying);
    use Detail::*;
    assert_eq!(
        ["a", "b", "c"].map(|n| var(&p, S0, n).inferred),
        [Uniform, Varying, Varying]
    );
}

#[test]
fn output_arguments_take_the_calls_detail() {
    let p = compile(
        "surface s() { float kr, kt; vector R, T; fresnel(normalize(I), normalize(N), 0.66, kr, kt, R, T);
           float u1 = 0, u2 = 0; vector r2, t2; fresnel(vector (0,0,1), normal (0,0,1), 0.66, u1, u2, r2, t2); Ci = kr + u1; }",
    );
    use Detail::*;
    assert_eq!(
        ["kr", "kt", "R", "T", "u1", "u2", "r2", "t2"].map(|n| var(&p, S0, n).inferred),
        [Varying, Varying, Varying, Varying, Uniform, Uniform, Uniform, Uniform]
    );
}

#[test]
fn lighting_bodies_are_varying_control() {
    let p = compile(
        "light l(float intensity = 1;) { float k = 0; illuminate (point \"shader\" (0,0,0)) { k = 1; Cl = intensity * k; } }
         surface s() { float c = 0; illuminance (P, N, PI/2) { c += 1; } Ci = c; }",
    );
    assert_eq!(
        var(&p, Owner::Shader(ShaderId(0)), "k").inferred,
        Detail::Varying
    );
    assert_eq!(
        var(&p, Owner::Shader(ShaderId(1)), "c").inferred,
        Detail::Varying
    );
    // Cl inside the illuminance loop resolves to the global.
    let p = compile("surface s() { color C = 0; illuminance (P) { C += Cl; } Ci = C; }");
    assert!(all_exprs(&p)
        .iter()
        .any(|e| matches!(&e.kind, ExprKind::Var(v) if v.var == Some(VarRef::Global(Global::Cl)))));
}

#[test]
fn user_functions_shadow_builtins_of_the_same_name() {
    // Listing 9.10 redefines diffuse(): later calls use it.
    let p = compile(
        "color diffuse (normal Nn) { extern point P; color C = 0; illuminance (P, Nn, PI/2) { C += Cl * (Nn . normalize(L)); } return C; }
         surface s() { Ci = diffuse(normalize(N)); }",
    );
    let (_, c) = calls(&p, "diffuse")[0];
    assert_eq!(c.callee, Some(Callee::User(FuncId(0))));
}

#[test]
fn transform_keeps_the_geometric_type_of_its_argument() {
    let p = compile(
        "surface s() { point a = transform(\"world\", P); normal b = transform(\"world\", N); vector c = transform(\"object\", \"world\", I); }",
    );
    let rets: Vec<Type> = calls(&p, "transform").iter().map(|(e, _)| e.ty).collect();
    assert_eq!(rets, vec![Type::POINT, Type::NORMAL, Type::VECTOR]);
    assert!(
        !all_exprs(&p)
            .iter()
            .any(|e| matches!(e.kind, ExprKind::Cast { .. })),
        "no conversion was needed"
    );
}

#[test]
fn inference_reaches_a_fixpoint_through_long_backward_chains() {
    // a0 = a1; a1 = a2; …; a29 = s: each walk makes one more link varying.
    let mut body = String::new();
    for k in 0..30 {
        body.push_str(&format!("float a{k} = 0; "));
    }
    for k in 0..29 {
        body.push_str(&format!("a{k} = a{}; ", k + 1));
    }
    body.push_str(
        "a29 = s; float untouched = a0 * 0; uniform float kept = 1; Ci = a0 + untouched + kept;",
    );
    let p = compile(&format!("surface s() {{ {body} }}"));
    for k in 0..30 {
        assert_eq!(
            var(&p, S0, &format!("a{k}")).inferred,
            Detail::Varying,
            "a{k}"
        );
    }
    assert_eq!(
        var(&p, S0, "untouched").inferred,
        Detail::Varying,
        "reads a varying value"
    );
    assert_eq!(var(&p, S0, "kept").inferred, Detail::Uniform);
}

#[test]
fn open_array_parameters_take_any_length() {
    let p = compile(
        "float sum(float a[]) { float t = 0, i; for (i = 0; i < arraylength(a); i += 1) t += a[i]; return t; }
         surface s() { float k[3] = {1, 2, 3}; float j[5] = {1, 2, 3, 4, 5}; Ci = sum(k) + sum(j); }",
    );
    let sums = calls(&p, "sum");
    assert_eq!(sums.len(), 2);
    assert!(sums
        .iter()
        .all(|(_, c)| c.callee == Some(Callee::User(FuncId(0)))));
    let (_, al) = calls(&p, "arraylength")[0];
    assert_eq!(
        builtin(al).sig.params[0].ty.array,
        Some(illume_sl::types::ArrayLen::Open)
    );
}

#[test]
fn a_varying_return_makes_only_later_statements_varying_control() {
    let p = compile(
        "float f(float x) {
            uniform float before = 1;   /* fine: assigned before any point returned */
            float early = 2;
            if (x > 0) return before;
            float late = 3;             /* assigned only for the points still running */
            return early + late;
        }",
    );
    let o = Owner::Function(FuncId(0));
    assert_eq!(var(&p, o, "early").inferred, Detail::Uniform);
    assert_eq!(var(&p, o, "late").inferred, Detail::Varying);
    // A declared-uniform assignment after the varying return is a warning (issue 18
    // leniency) and makes the variable varying.
    let out = compile_str(
        "r.sl",
        "float f(float x) { uniform float u = 0; if (x > 0) return 1; u = 2; return u; }",
        &PpOptions::default(),
    );
    assert_eq!(
        out.render_diagnostics(),
        "r.sl:1:62: warning: uniform variable 'u' is assigned under varying control flow (a varying condition, loop or lighting construct); it becomes varying\n"
    );
    assert_eq!(var(&out.program, o, "u").inferred, Detail::Varying);
    assert_eq!(var(&out.program, o, "u").declared, Some(Detail::Uniform));
}

/// Issue 18 leniencies that real shaders need (Liquid's liquidspot/liquidpoint, Advanced
/// RenderMan's terran.sl, vendor extensions such as `bake`).
#[test]
fn leniencies_of_peer_compilers() {
    // A uniform local given a varying value becomes varying, and so does what reads it.
    let p = compile("surface s() { uniform float k = 1; k = k * t; float m = k; Ci = m; }");
    assert_eq!(var(&p, S0, "k").inferred, Detail::Varying);
    assert_eq!(var(&p, S0, "m").inferred, Detail::Varying);
    // A nested function (and a top-level one) with a qualified return type.
    let p = compile(
        "uniform float half(float x) { return x / 2; }
         surface s() { uniform float urand() { return 0.25; } Ci = half(urand()); }",
    );
    assert_eq!(p.functions.len(), 2);
    assert_eq!(p.functions[1].name, "urand");
    assert_eq!(p.functions[1].ret, Type::FLOAT);
    // s and t are readable in imagers.
    let p = compile("imager i() { Ci = color (s, t, 0); }");
    assert_eq!(p.shaders[0].kind, illume_sl::types::ShaderKind::Imager);
    // An unknown function is a warning; the call stays unresolved, typed from context.
    let out = compile_str(
        "b.sl",
        "surface s() { color c = bake(\"map.ptc\", s, t, Ci); float f = bake(1); Ci = c; }",
        &PpOptions::default(),
    );
    assert!(!out.has_errors(), "{}", out.render_diagnostics());
    assert_eq!(out.diagnostics.len(), 2);
    let bakes = calls(&out.program, "bake");
    assert_eq!(bakes.len(), 2);
    assert!(bakes.iter().all(|(_, c)| c.callee.is_none()));
    assert_eq!(bakes[0].0.ty, Type::COLOR);
    assert_eq!(bakes[1].0.ty, Type::FLOAT);
    // But a function defined after its use is still an error.
    let out = compile_str(
        "l.sl",
        "surface s() { Ci = later(); }\ncolor later() { return 1; }",
        &PpOptions::default(),
    );
    assert!(out.has_errors());
}

#[test]
fn functions_nested_in_a_shader_reach_its_parameters_through_extern() {
    let p = compile(
        "surface s(float Kd = 0.5;) { color shade(normal n) { extern float Kd; return Kd * diffuse(n); } Ci = shade(normalize(N)); }",
    );
    let f = &p.functions[0];
    assert_eq!(f.parent, Some(S0));
    let StmtKind::Decl(d) = &f.body.stmts[0].kind else {
        panic!()
    };
    assert_eq!(
        d.vars[0].var,
        Some(VarRef::Outer {
            owner: S0,
            var: VarId(0)
        })
    );
    assert_eq!(
        var(&p, S0, "Kd").kind,
        VarKind::ShaderParam { output: false }
    );
}
