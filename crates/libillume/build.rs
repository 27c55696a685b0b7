//! Compiles the C half of the binding (varargs collection, tokens, filters) into the library.
fn main() {
    println!("cargo:rerun-if-changed=csrc");
    println!("cargo:rerun-if-changed=../../include/ri.h");
    cc::Build::new()
        .file("csrc/ri.c")
        .file("csrc/geometry.c")
        .file("csrc/tokens.c")
        .include("../../include")
        .warnings(true)
        .compile("illume_c");
}
