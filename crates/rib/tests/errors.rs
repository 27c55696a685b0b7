//! Bad input: each case pins the exact message and position the user sees, and checks that the
//! parser goes on with the next request.
use illume_rib::{Diagnostic, Parser, Request, Severity};
use std::io::Write;

/// Parses `bytes`, returning (diagnostics, names of the requests that came through).
fn run(bytes: &[u8]) -> (Vec<Diagnostic>, Vec<String>) {
    let mut diags = Vec::new();
    let mut names = Vec::new();
    for item in Parser::new(bytes, "scene.rib") {
        match item {
            Ok(r) => names.push(r.value.name().to_string()),
            Err(d) => diags.push(d),
        }
    }
    (diags, names)
}

fn headlines(bytes: &[u8]) -> (Vec<String>, Vec<String>) {
    let (d, n) = run(bytes);
    (d.iter().map(Diagnostic::headline).collect(), n)
}

#[test]
fn too_few_numbers_names_request_counts_and_position_with_caret() {
    let (d, names) = run(b"WorldBegin\n  Sphere 1 2 3\nTranslate 1 2 3\n");
    assert_eq!(d.len(), 1);
    assert_eq!(
        d[0].to_string(),
        "scene.rib:2:3: error: Sphere: expected 4 numbers, found 3\n  Sphere 1 2 3\n  ^"
    );
    assert_eq!(d[0].severity, Severity::Error);
    assert_eq!(d[0].request.as_deref(), Some("Sphere"));
    assert_eq!(
        (d[0].span.line, d[0].span.col, d[0].span.offset),
        (2, 3, 13)
    );
    assert_eq!(names, ["WorldBegin", "Translate"]);
}

#[test]
fn bad_number_points_at_the_token() {
    let (d, names) = run(b"Surface \"plastic\" \"Ks\" [.5 1.2.3]\nWorldEnd\n");
    assert_eq!(
        d[0].to_string(),
        "scene.rib:1:28: error: Surface: bad number `1.2.3`\n\
         Surface \"plastic\" \"Ks\" [.5 1.2.3]\n                           ^"
    );
    assert_eq!(names, ["WorldEnd"]);
}

#[test]
fn unterminated_array_resynchronises_at_the_next_request() {
    let (h, names) = headlines(b"Color [1 0 0\nSphere 1 -1 1 360\n");
    assert_eq!(
        h,
        ["scene.rib:1:7: error: Color: unterminated array: `[` at 1:7 has no `]` before request name `Sphere`"]
    );
    assert_eq!(names, ["Sphere"]);
}

#[test]
fn unterminated_string_at_end_of_file() {
    let (h, names) = headlines(b"WorldBegin\nSurface \"plastic\" \"Ks");
    assert_eq!(h, ["scene.rib:2:19: error: Surface: unterminated string"]);
    assert_eq!(names, ["WorldBegin"]);
}

#[test]
fn truncated_request_reports_what_is_missing() {
    let (h, _) = headlines(b"PatchMesh \"bilinear\" 2 \"nonperiodic\"");
    assert_eq!(
        h,
        ["scene.rib:1:1: error: PatchMesh: expected an integer, found end of request"]
    );
}

#[test]
fn wrong_argument_type_says_what_was_found() {
    let (h, _) = headlines(b"Format \"640\" 480 1\nLightSource \"spot\" [1 2]\n");
    assert_eq!(
        h,
        [
            "scene.rib:1:1: error: Format: expected an integer, found string \"640\"",
            "scene.rib:2:1: error: LightSource: expected a handle (number or string), found array of 2 numbers"
        ]
    );
}

#[test]
fn odd_parameter_list_names_the_lonely_parameter() {
    let (h, _) = headlines(b"Option \"x\" \"y\"\n");
    assert_eq!(
        h,
        ["scene.rib:1:1: error: Option: parameter \"y\" has no value"]
    );
}

#[test]
fn extra_positional_argument_is_an_error() {
    let (h, _) = headlines(b"Translate 1 2 3 4\n");
    assert_eq!(
        h,
        ["scene.rib:1:1: error: Translate: unexpected extra argument: number 4"]
    );
}

#[test]
fn unknown_request_is_one_warning_and_is_kept() {
    let items: Vec<_> = Parser::new(
        &b"IfBegin \"$x\"\n  MyThing 1 [2 3] \"a\"\nWorldBegin\n"[..],
        "s.rib",
    )
    .collect();
    let d = items[0].as_ref().unwrap_err();
    assert_eq!(d.severity, Severity::Warning);
    assert_eq!(
        d.headline(),
        "s.rib:1:1: warning: IfBegin: unknown request, its arguments are skipped"
    );
    assert!(
        matches!(&items[1], Ok(r) if r.value == Request::Unknown { name: "IfBegin".into(), args: vec![illume_rib::Value::Strings(vec!["$x".into()])] })
    );
    let d = items[2].as_ref().unwrap_err();
    assert_eq!((d.span.line, d.span.col), (2, 3));
    assert_eq!(items.len(), 5);
    assert_eq!(items[4].as_ref().unwrap().value, Request::WorldBegin);
}

#[test]
fn nul_bytes_and_invalid_utf8_are_errors_not_panics() {
    let (h, names) =
        headlines(b"WorldBegin\nAttribute \"a\" \"b\" \"\xff\xfe\"\nSides 2\0\nWorldEnd\n");
    assert_eq!(
        h,
        [
            "scene.rib:2:19: error: Attribute: string is not valid UTF-8",
            "scene.rib:3:8: error: Sides: NUL byte in the stream (is this a RIB file?)"
        ]
    );
    assert_eq!(names, ["WorldBegin", "WorldEnd"]);
}

#[test]
fn stray_numbers_before_any_request_are_one_error() {
    let (h, names) = headlines(b"1 2 3 \"x\"\nWorldBegin\n");
    assert_eq!(h, ["scene.rib:1:1: error: number 1 outside any request"]);
    assert_eq!(names, ["WorldBegin"]);
}

#[test]
fn mixed_array_is_an_error() {
    let (h, _) = headlines(b"Surface \"s\" \"a\" [1 \"b\"]\n");
    assert_eq!(
        h,
        ["scene.rib:1:20: error: Surface: array mixes numbers and strings"]
    );
}

#[test]
fn out_of_range_number_is_an_error() {
    let (h, _) = headlines(b"Scale 1e39 1 1\n");
    assert_eq!(
        h,
        ["scene.rib:1:7: error: Scale: number `1e39` is out of range for a float"]
    );
}

#[test]
fn huge_binary_string_length_does_not_allocate() {
    // 0243: string with a 4-byte length of 2^31, then three bytes and the end of file.
    let (h, _) = headlines(b"\xa3\x80\x00\x00\x00abc");
    assert_eq!(
        h[0],
        "scene.rib:1:1: error: binary string length 2147483648 exceeds 16 MiB"
    );
}

#[test]
fn huge_binary_float_array_length_reads_only_what_arrives() {
    let (h, _) = headlines(b"\xcb\x80\x00\x00\x00\x00\x00\x00\x00");
    assert_eq!(
        h,
        ["scene.rib:1:1: error: binary RIB truncated in a float array (1 of 2147483648 floats)"]
    );
}

#[test]
fn undefined_binary_request_code_is_an_error() {
    let (h, names) = headlines(b"\xa6\x07WorldBegin");
    assert_eq!(h, ["scene.rib:1:1: error: undefined binary request code 7"]);
    assert_eq!(names, ["WorldBegin"]);
}

#[test]
fn truncated_gzip_is_a_read_error_after_the_good_requests() {
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    for k in 0..2000 {
        writeln!(gz, "Translate {k} 0 0").unwrap();
    }
    let bytes = gz.finish().unwrap();
    let cut = &bytes[..bytes.len() / 2];
    let reader = illume_rib::decompress(std::io::Cursor::new(cut.to_vec())).unwrap();
    let items: Vec<_> = Parser::new(reader, "t.rib.gz").collect();
    let good = items.iter().filter(|i| i.is_ok()).count();
    let errors: Vec<_> = items.iter().filter_map(|i| i.as_ref().err()).collect();
    assert!(good > 100 && good < 2000, "{good}");
    assert!(
        errors.iter().any(|d| d.message.starts_with("read error:")),
        "{errors:?}"
    );
}

#[test]
fn binary_nan_is_an_error() {
    let (h, names) = headlines(b"\xcc\x01\x95Scale\xa6\x01\xa4\x7f\xc0\x00\x00\xa4\x00\x00\x00\x00\xa4\x00\x00\x00\x00WorldBegin");
    assert_eq!(
        h,
        ["scene.rib:1:11: error: Scale: binary float is infinite or NaN"]
    );
    assert_eq!(names, ["WorldBegin"]);
}

#[test]
fn utf8_byte_order_mark_at_the_start_is_skipped_and_columns_ignore_it() {
    let (diags, names) = run(b"\xef\xbb\xbfWorldBegin\nSphere 1 -1 1\n");
    assert_eq!(names, ["WorldBegin"]);
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert_eq!(
        diags[0].headline(),
        "scene.rib:2:1: error: Sphere: expected 4 numbers, found 3"
    );
}

#[test]
fn byte_order_mark_bytes_after_the_start_are_still_binary_rib() {
    let (diags, _) = run(b"WorldBegin\n\xef\xbb\xbf");
    assert!(!diags.is_empty(), "a BOM in mid-stream is not text");
}
