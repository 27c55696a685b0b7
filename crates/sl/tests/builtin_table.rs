//! Every overload of the built-in table is reachable: a call written with arguments of exactly
//! that overload's parameter types resolves to a signature with those types and return type.
//! This pins down both the table and overload resolution (a shadowing or mis-ranked overload
//! fails here), independently of any hand-picked example.

use illume_sl::ast::{Callee, ExprKind, StmtKind};
use illume_sl::builtins::{all, Overload, Slot};
use illume_sl::types::{BaseType, Type};
use illume_sl::{compile_str, PpOptions};

/// A variable of each type declared at the top of the test shader.
fn var_of(b: BaseType, array: bool) -> &'static str {
    match (b, array) {
        (BaseType::Float, false) => "vf",
        (BaseType::Color, false) => "vc",
        (BaseType::Point, false) => "vp",
        (BaseType::Vector, false) => "vv",
        (BaseType::Normal, false) => "vn",
        (BaseType::Matrix, false) => "vm",
        (BaseType::String, false) => "vs",
        (BaseType::Float, true) => "af",
        (BaseType::Color, true) => "ac",
        _ => panic!("no test variable for {b:?} array={array}"),
    }
}

const DECLS: &str = "float vf = 0.5; color vc = 1; point vp = 0; vector vv = 1; normal vn = 1;
    matrix vm = 1; string vs = \"s\"; float af[4] = {1, 2, 3, 4}; color ac[4] = {1, 1, 1, 1};";

/// Concrete types for an overload's slots: T as color (exercising the generic path where a
/// float overload also exists), G as normal, R as color, A as float.
fn bind(slot: Slot) -> BaseType {
    match slot {
        Slot::Fixed(b) => b,
        Slot::Generic => BaseType::Color,
        Slot::Geometric => BaseType::Normal,
        Slot::ContextReturn => BaseType::Color,
        Slot::Any => BaseType::Float,
    }
}

/// `name(args)` for an overload, with each repeating parameter written once.
fn call_text(ov: &Overload) -> (String, Vec<Type>) {
    let mut args = Vec::new();
    let mut types = Vec::new();
    for p in &ov.params {
        let b = bind(p.slot);
        args.push(var_of(b, p.array).to_string());
        types.push(if p.array {
            Type::array(b, 4)
        } else {
            Type::scalar(b)
        });
    }
    (format!("{}({})", ov.name, args.join(", ")), types)
}

#[test]
fn every_overload_resolves_to_itself() {
    let mut failures = Vec::new();
    let mut checked = 0;
    for ov in all() {
        let (call, want_params) = call_text(ov);
        let ret = bind(ov.ret);
        // Only surface shaders may call lightsource() (inside illuminance) and the lighting
        // functions; everything is called there.
        let stmt = if ret == BaseType::Void {
            format!("{call};")
        } else {
            format!("{} r = {call};", ret.keyword())
        };
        let src = format!("surface s() {{ {DECLS} illuminance (P) {{ {stmt} }} }}");
        let out = compile_str("b.sl", &src, &PpOptions::default());
        if out.has_errors() {
            failures.push(format!("{call}: {}", out.render_diagnostics()));
            continue;
        }
        let sh = &out.program.shaders[0];
        let StmtKind::Illuminance(il) = &sh.body.stmts.last().unwrap().kind else {
            panic!()
        };
        let StmtKind::Block(b) = &il.body.kind else {
            panic!()
        };
        let e = match &b.stmts[0].kind {
            StmtKind::Expr(e) => e,
            StmtKind::Decl(d) => d.vars[0].init.as_ref().unwrap(),
            _ => panic!(),
        };
        let ExprKind::Call(c) = &e.kind else {
            failures.push(format!("{call}: not a call: {:?}", e.kind));
            continue;
        };
        let Some(Callee::Builtin(bc)) = &c.callee else {
            failures.push(format!("{call}: not resolved to a builtin"));
            continue;
        };
        let got: Vec<Type> = bc.sig.params.iter().map(|p| p.ty).collect();
        if got != want_params || bc.sig.ret != Type::scalar(ret) {
            failures.push(format!(
                "{call}: resolved to ({}) -> {}, wanted ({}) -> {}",
                got.iter()
                    .map(|t| t.to_string())
                    .collect::<Vec<_>>()
                    .join(", "),
                bc.sig.ret,
                want_params
                    .iter()
                    .map(|t| t.to_string())
                    .collect::<Vec<_>>()
                    .join(", "),
                ret
            ));
        }
        let outputs: Vec<bool> = bc.sig.params.iter().map(|p| p.output).collect();
        let want_out: Vec<bool> = ov.params.iter().map(|p| p.output).collect();
        if outputs != want_out {
            failures.push(format!(
                "{call}: output flags {outputs:?}, wanted {want_out:?}"
            ));
        }
        checked += 1;
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(checked, all().len());
    assert!(checked > 120, "the table shrank to {checked} overloads");
}

#[test]
fn the_table_covers_the_ri_3_2_function_list() {
    // RI 3.2 chapter 15, by section (texture/environment/shadow/bump are parsed specially).
    let names = [
        // 15.1 mathematical
        "radians",
        "degrees",
        "sin",
        "asin",
        "cos",
        "acos",
        "tan",
        "atan",
        "pow",
        "exp",
        "sqrt",
        "inversesqrt",
        "log",
        "mod",
        "abs",
        "sign",
        "floor",
        "ceil",
        "round",
        "min",
        "max",
        "clamp",
        "mix",
        "step",
        "smoothstep",
        "filterstep",
        "spline",
        "Du",
        "Dv",
        "Deriv",
        "random",
        "noise",
        "pnoise",
        "cellnoise",
        // 15.2 geometric
        "xcomp",
        "ycomp",
        "zcomp",
        "setxcomp",
        "setycomp",
        "setzcomp",
        "length",
        "normalize",
        "distance",
        "ptlined",
        "rotate",
        "area",
        "faceforward",
        "reflect",
        "refract",
        "fresnel",
        "transform",
        "vtransform",
        "ntransform",
        "depth",
        "calculatenormal",
        // 15.3 colour, 15.4 matrix, 15.5 string
        "comp",
        "setcomp",
        "ctransform",
        "determinant",
        "translate",
        "scale",
        "concat",
        "printf",
        "format",
        "match",
        // 15.6 shading and lighting
        "ambient",
        "diffuse",
        "specular",
        "specularbrdf",
        "phong",
        "trace",
        // 15.7 texture information, 15.8 message passing and information
        "textureinfo",
        "atmosphere",
        "displacement",
        "incident",
        "lightsource",
        "opposite",
        "surface",
        "attribute",
        "option",
        "rendererinfo",
    ];
    for n in names {
        assert!(
            illume_sl::builtins::is_builtin(n),
            "{n} missing from the built-in table"
        );
    }
    for n in ["texture", "environment", "shadow", "bump"] {
        assert!(illume_sl::builtins::is_builtin(n));
    }
}
