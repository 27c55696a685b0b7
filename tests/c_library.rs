//! The C library beyond the request table (tests/c_binding.rs): a program's own pixel filter
//! function, `RiReadArchive`'s comment callback, and the RI error code of each kind of bad
//! call, all from real C programs built with `cc` against libillume.
//!
//! Needs `cargo build -p libillume -p render -p catrib` (as .ci/run does) and a C compiler.
#[path = "support/c_programs.rs"]
mod c_programs;
use c_programs::{compile, run, scratch, tools};

/// Two frames of the same small scene, one filtered by `FILTER_A`, one by `FILTER_B`.
fn filter_program(a: &str, b: &str) -> String {
    format!(
        r#"#include <ri.h>
#include <stdio.h>
#include <math.h>
static int calls;
/* A box written by the program: the same weights as RiBoxFilter. */
static RtFloat mybox(RtFloat x, RtFloat y, RtFloat xw, RtFloat yw) {{
  (void)x; (void)y; (void)xw; (void)yw;
  calls++;
  return 1.0f;
}}
/* Weight only left of the pixel centre: no standard filter is like it. */
static RtFloat lefthalf(RtFloat x, RtFloat y, RtFloat xw, RtFloat yw) {{
  (void)y; (void)xw; (void)yw;
  calls++;
  return x < 0 ? 1.0f : 0.0f;
}}
static void frame(int n, const char *out, RtFilterFunc f) {{
  RtColor red = {{1, 0.2f, 0.1f}};
  RiFrameBegin(n);
  RiFormat(48, 32, 1);
  RiPixelSamples(3, 3);
  RiPixelFilter(f, 2, 2);
  RiDisplay((char *)out, RI_FILE, RI_RGBA, RI_NULL);
  RiProjection(RI_PERSPECTIVE, RI_NULL);
  RiTranslate(0, 0, 3);
  RiWorldBegin();
  RiColor(red);
  RiSurface("constant", RI_NULL);
  RiSphere(1, -1, 1, 360, RI_NULL);
  RiWorldEnd();
  RiFrameEnd();
}}
int main(void) {{
  (void)mybox;
  (void)lefthalf;
  RiBegin(RI_NULL);
  /* The same frame number: sample positions depend on it. */
  frame(1, "a.tif", {a});
  frame(1, "b.tif", {b});
  RiEnd();
  printf("%d\n", calls);
  return 0;
}}
"#
    )
}

#[test]
fn a_user_box_filter_renders_the_bits_of_ri_box_filter() {
    let Some(t) = tools() else { return };
    let dir = scratch("user_filter_box");
    let exe = compile(&t, &dir, &filter_program("RiBoxFilter", "mybox"));
    let out = run(&exe, &dir, &[]);
    // Tabulated once: 64×64 calls, not one per sample.
    assert_eq!(out.trim(), "4096", "calls of the program's filter");
    let (a, b) = (
        std::fs::read(dir.join("a.tif")).unwrap(),
        std::fs::read(dir.join("b.tif")).unwrap(),
    );
    assert!(a == b, "a user box filter must render RiBoxFilter's bits");
}

#[test]
fn a_user_filter_unlike_any_standard_one_is_used_as_written() {
    let Some(t) = tools() else { return };
    let dir = scratch("user_filter_lefthalf");
    // Frame 1: the nearest standard filter RIB would name (box); frame 2: the program's.
    let exe = compile(&t, &dir, &filter_program("RiBoxFilter", "lefthalf"));
    run(&exe, &dir, &[]);
    let read = |f: &str| illume_imageio::read_image(&dir.join(f)).unwrap();
    let (a, b) = (read("a.tif"), read("b.tif"));
    // Weight only on the left shifts the image by about half a pixel: the sphere's edges
    // move, the interior stays red.
    let differing = a
        .data
        .iter()
        .zip(&b.data)
        .filter(|(x, y)| (*x - *y).abs() > 0.02)
        .count();
    assert!(differing > 20, "only {differing} samples differ");
    let centre = (16 * 48 + 24) * a.channels.len();
    assert!(
        (b.data[centre] - 1.0).abs() < 1e-3,
        "interior red: {}",
        b.data[centre]
    );
}

#[test]
fn rib_output_of_a_user_filter_names_the_nearest_standard_filter_with_a_warning() {
    let Some(t) = tools() else { return };
    let dir = scratch("user_filter_rib");
    let prog = r#"#include <ri.h>
#include <stdio.h>
#include <math.h>
static RtFloat cone(RtFloat x, RtFloat y, RtFloat xw, RtFloat yw) {
  RtFloat u = 2 * fabsf(x) / xw, v = 2 * fabsf(y) / yw;
  return (1 - u) * (1 - v);
}
static void h(RtInt code, RtInt severity, char *msg) { printf("%d %d %s\n", code, severity, msg); }
int main(void) {
  RiErrorHandler(h);
  RiBegin("f.rib");
  RiPixelFilter(cone, 3, 2);
  RiEnd();
  return 0;
}
"#;
    let exe = compile(&t, &dir, prog);
    let out = run(&exe, &dir, &[]);
    // RIE_INCAPABLE (11), a warning (1), naming the filter written.
    assert!(
        out.starts_with("11 1 ") && out.contains("\"triangle\""),
        "{out}"
    );
    let rib = std::fs::read_to_string(dir.join("f.rib")).unwrap();
    assert!(rib.contains("PixelFilter \"triangle\" 3 2\n"), "{rib}");
}

#[test]
fn read_archive_calls_back_for_each_comment_record_in_order() {
    let Some(t) = tools() else { return };
    let dir = scratch("archive_callback");
    std::fs::write(
        dir.join("part.rib"),
        "##RenderMan RIB\n# made by hand\nAttributeBegin # trailing words\n  Sphere 1 -1 1 360\nAttributeEnd\n##Include nothing\n",
    )
    .unwrap();
    let prog = r#"#include <ri.h>
#include <stdio.h>
#include <stdarg.h>
static void cb(RtToken type, char *format, ...) {
  va_list ap;
  va_start(ap, format);
  printf("%s|", type);
  vprintf(format, ap);
  printf("|\n");
  va_end(ap);
}
int main(void) {
  RiBegin("out.rib");
  RiWorldBegin();
  RiReadArchive("part.rib", cb, RI_NULL);
  RiReadArchive("part.rib", NULL, RI_NULL);
  RiWorldEnd();
  RiEnd();
  return 0;
}
"#;
    let exe = compile(&t, &dir, prog);
    let out = run(&exe, &dir, &[]);
    assert_eq!(
        out,
        "structure|RenderMan RIB|\ncomment| made by hand|\ncomment| trailing words|\nstructure|Include nothing|\n"
    );
    // The archive is still read (by the RIB reader: the request is written once per call).
    let rib = std::fs::read_to_string(dir.join("out.rib")).unwrap();
    assert_eq!(rib.matches("ReadArchive \"part.rib\"").count(), 2, "{rib}");
}

/// (case, C statements, expected RIE code, expected severity): each case's first error.
/// Every call runs in an open in-process session with a world block unless the case says
/// otherwise (the statements manage their own blocks).
const ERROR_CASES: &[(&str, &str, i32, i32)] = &[
    ("end before begin", "RiEnd();", 23, 2),
    ("begin twice", "RiBegin(RI_NULL); RiBegin(RI_NULL); RiEnd();", 24, 2),
    ("begin unwritable", "RiBegin(\"/nonexistent-dir/x.rib\");", 3, 3),
    ("options in world", "RiBegin(RI_NULL); RiWorldBegin(); RiFormat(8, 8, 1); RiWorldEnd(); RiEnd();", 25, 2),
    ("geometry before world", "RiBegin(RI_NULL); RiSphere(1, -1, 1, 360, RI_NULL); RiEnd();", 27, 2),
    ("null token list", "RiBegin(\"x.rib\"); RiWorldBegin(); RiPolygonV(3, 2, NULL, NULL); RiWorldEnd(); RiEnd();", 46, 2),
    ("undeclared token", "RiBegin(\"x.rib\"); RiWorldBegin(); RiSphere(1, -1, 1, 360, \"nosuch\", f1, RI_NULL); RiWorldEnd(); RiEnd();", 41, 2),
    ("unknown light", "RiBegin(\"x.rib\"); RiWorldBegin(); RiIlluminate((RtLightHandle)42, RI_TRUE); RiWorldEnd(); RiEnd();", 44, 2),
    ("unknown object", "RiBegin(\"x.rib\"); RiWorldBegin(); RiObjectInstance((RtObjectHandle)42); RiWorldEnd(); RiEnd();", 44, 2),
    ("end without begin", "RiBegin(\"x.rib\"); RiAttributeEnd(); RiEnd();", 24, 2),
    ("unclosed block", "RiBegin(\"x.rib\"); RiAttributeBegin(); RiEnd();", 24, 2),
    ("decreasing motion times", "RiBegin(\"x.rib\"); RiWorldBegin(); RiMotionBegin(2, 1.0, 0.0); RiMotionEnd(); RiWorldEnd(); RiEnd();", 29, 2),
    ("nested motion", "RiBegin(\"x.rib\"); RiWorldBegin(); RiMotionBegin(1, 0.0); RiMotionBegin(1, 0.0); RiMotionEnd(); RiMotionEnd(); RiWorldEnd(); RiEnd();", 24, 2),
    ("too many motion times", "RiBegin(\"x.rib\"); RiMotionBegin(65, 0.0); RiEnd();", 13, 2),
    ("missing archive", "RiBegin(\"x.rib\"); RiWorldBegin(); RiReadArchive(\"nosuch.rib\", NULL, RI_NULL); RiWorldEnd(); RiEnd();", 3, 2),
    // The message contains "outside": the code comes from the kind, not the words.
    ("bad orientation", "RiBegin(\"x.rib\"); RiWorldBegin(); RiOrientation(\"sideways\"); RiWorldEnd(); RiEnd();", 43, 2),
    ("verbatim syntax error", "RiBegin(\"x.rib\"); RiArchiveRecord(RI_VERBATIM, \"Sphere 1 2\\n\"); RiEnd();", 47, 2),
    ("bad rib option", "RiBegin(\"x.rib\"); RiOption(\"rib\", \"string format\", s1, RI_NULL); RiEnd();", 41, 1),
    ("late compression", "RiBegin(\"x.rib\"); RiWorldBegin(); RiOption(\"rib\", \"string compression\", gz, RI_NULL); RiWorldEnd(); RiEnd();", 28, 1),
    ("null archive record", "RiBegin(\"x.rib\"); RiArchiveRecord(NULL, NULL); RiEnd();", 46, 2),
];

#[test]
fn each_kind_of_bad_call_reaches_the_handler_with_its_ri_code() {
    let Some(t) = tools() else { return };
    let dir = scratch("error_codes");
    let cases: String = ERROR_CASES
        .iter()
        .map(|(name, stmts, _, _)| format!("  printf(\"case {name}\\n\");\n  {stmts}\n"))
        .collect();
    let prog = format!(
        r#"#include <ri.h>
#include <stdio.h>
#include <stddef.h>
static void h(RtInt code, RtInt severity, char *msg) {{ printf("%d %d %s\n", code, severity, msg); }}
int main(void) {{
  RtFloat f1[1] = {{0.5f}};
  RtString s1[1] = {{"weird"}}, gz[1] = {{"gzip"}};
  RiErrorHandler(h);
{cases}  printf("case done\n");
  return 0;
}}
"#
    );
    let exe = compile(&t, &dir, &prog);
    let out = run(&exe, &dir, &[]);
    for (name, _, code, severity) in ERROR_CASES {
        let marker = format!("case {name}\n");
        let start = out.find(&marker).unwrap_or_else(|| panic!("{out}")) + marker.len();
        let first = out[start..].lines().next().unwrap_or("");
        let got: Vec<i32> = first
            .split_whitespace()
            .take(2)
            .filter_map(|w| w.parse().ok())
            .collect();
        assert_eq!(
            got,
            [*code, *severity],
            "{name}: first report `{first}`\n{out}"
        );
    }
}
