//! `slc`: compile RenderMan Shading Language files and report diagnostics without rendering.
//!
//! Exit codes: 0 every file compiled cleanly (warnings allowed), 1 some file has errors,
//! 2 usage error (bad arguments; clap reports those).
#![forbid(unsafe_code)]

use clap::{Parser, ValueEnum};
use illume_sl::ast::{Program, VarKind};
use illume_sl::{compile_file, PpOptions};
use std::path::PathBuf;
use std::process::ExitCode;

/// What to print after a successful compile.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Emit {
    /// Nothing (diagnostics only).
    None,
    /// One line per shader and function with its parameters, types and details.
    Summary,
    /// The whole checked syntax tree (Rust debug form), for debugging the compiler.
    Ast,
}

/// Compile Shading Language sources; print `file:line:col: error: …` for every problem.
#[derive(Debug, Parser)]
#[command(name = "slc", version)]
struct Args {
    /// Directory searched by `#include` (after the including file's own directory); repeatable.
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
    /// Preprocessor definition `NAME` or `NAME=VALUE`; repeatable.
    #[arg(short = 'D', value_name = "NAME[=VALUE]")]
    define: Vec<String>,
    /// What to print for each compiled file.
    #[arg(long, value_enum, default_value = "none")]
    emit: Emit,
    /// Shader source files.
    #[arg(required = true, value_name = "FILE.sl")]
    files: Vec<PathBuf>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    let opts = PpOptions {
        include_dirs: args.include.clone(),
        defines: args
            .define
            .iter()
            .map(|d| match d.split_once('=') {
                Some((n, v)) => (n.to_string(), v.to_string()),
                None => (d.clone(), "1".to_string()),
            })
            .collect(),
    };
    let mut failed = false;
    for file in &args.files {
        let out = compile_file(file, &opts);
        eprint!("{}", out.render_diagnostics());
        if out.has_errors() {
            failed = true;
            continue;
        }
        match args.emit {
            Emit::None => {}
            Emit::Summary => print!("{}", summary(&out.program)),
            Emit::Ast => println!("{:#?}", out.program),
        }
    }
    if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// `surface plastic (uniform float Ka = …; …)`-style lines for every definition.
fn summary(p: &Program) -> String {
    let mut s = String::new();
    for sh in &p.shaders {
        s.push_str(&format!("{} {}\n", sh.kind, sh.name));
        for v in &sh.vars {
            let role = match v.kind {
                VarKind::ShaderParam { output: true } => "output param",
                VarKind::ShaderParam { output: false } => "param",
                VarKind::FunctionParam { .. } => "param",
                VarKind::Local => "local",
            };
            s.push_str(&format!(
                "  {role} {} {} {} (inferred {})\n",
                v.detail, v.ty, v.name, v.inferred
            ));
        }
    }
    for f in &p.functions {
        let params: Vec<String> = f
            .params
            .iter()
            .map(|q| {
                format!(
                    "{}{} {}",
                    if q.output { "output " } else { "" },
                    q.ty,
                    q.name
                )
            })
            .collect();
        s.push_str(&format!(
            "function {} {}({}){}\n",
            f.ret,
            f.name,
            params.join("; "),
            if f.reads_varying {
                " reads varying"
            } else {
                ""
            }
        ));
        for v in f.vars.iter().filter(|v| v.kind == VarKind::Local) {
            s.push_str(&format!(
                "  local {} {} {} (inferred {})\n",
                v.detail, v.ty, v.name, v.inferred
            ));
        }
    }
    s
}
