//! One row per request kind of RI Spec 3.2: the RIB text as users write it, the typed request
//! it must produce, and the check that the canonical printout reads back to the same request.
//!
//! The rows live in one module per request family, in the order of the spec; this file holds
//! the helpers they share and the tests run over the whole table; `random` holds the random
//! round trips built from it.
use illume_rib::{write_binary, BasisSpec, Handle, Param, Parser, Request as R, Value};
use std::collections::BTreeSet;

mod attributes;
mod options;
mod other_geometry;
mod polygons_patches;
mod quadrics;
mod random;
mod structure;
mod textures;

fn parse_one(text: &str) -> R {
    let items: Vec<_> = Parser::new(text.as_bytes(), "t.rib").collect();
    assert_eq!(items.len(), 1, "{text:?} gave {items:?}");
    match items.into_iter().next().unwrap() {
        Ok(r) => r.value,
        Err(d) => panic!("{text:?}: {d}"),
    }
}

fn p(name: &str, value: Value) -> Param {
    Param {
        name: name.into(),
        value,
    }
}
fn f(v: &[f32]) -> Value {
    Value::Floats(v.to_vec())
}
fn i(v: &[i32]) -> Value {
    Value::Ints(v.to_vec())
}
fn s(v: &[&str]) -> Value {
    Value::Strings(v.iter().map(|x| x.to_string()).collect())
}
fn st(x: &str) -> String {
    x.to_string()
}
fn strs(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}
fn m16() -> [f32; 16] {
    std::array::from_fn(|k| k as f32 * 0.5)
}
const M16: &str = "[0 .5 1 1.5 2 2.5 3 3.5 4 4.5 5 5.5 6 6.5 7 7.5]";

/// Every row of every family, in the order of the spec.
fn table() -> Vec<(String, R)> {
    [
        structure::rows(),
        options::rows(),
        attributes::rows(),
        polygons_patches::rows(),
        quadrics::rows(),
        other_geometry::rows(),
        textures::rows(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

#[test]
fn table_covers_every_request_of_the_spec() {
    // 102 requests of RI 3.2 plus `##` comments; `Unknown` is not a request of the spec.
    let names: BTreeSet<String> = table().iter().map(|(_, r)| r.name().to_string()).collect();
    assert_eq!(names.len(), 103, "{names:?}");
}

#[test]
fn every_request_kind_parses_to_its_typed_request() {
    for (text, expected) in table() {
        assert_eq!(parse_one(&text), expected, "parsing {text:?}");
    }
}

#[test]
fn every_request_kind_survives_ascii_printing() {
    for (text, expected) in table() {
        let printed = illume_rib::to_ascii(&expected);
        assert!(!printed.contains('\n'), "one line per request: {printed:?}");
        assert_eq!(
            parse_one(&printed),
            expected,
            "{text:?} printed as {printed:?}"
        );
    }
}

#[test]
fn every_request_kind_survives_binary_encoding() {
    for (text, expected) in table() {
        let mut bytes = Vec::new();
        write_binary(&expected, &mut bytes).unwrap();
        let back: Vec<_> = Parser::new(&bytes[..], "t.rib").collect();
        assert_eq!(back.len(), 1, "{text:?}: {back:?}");
        assert_eq!(back[0].as_ref().unwrap().value, expected, "{text:?}");
    }
}

#[test]
fn scalars_and_arrays_are_interchangeable_where_the_spec_allows() {
    let pairs = [
        ("Color [1 0 0]", "Color 1 0 0"),
        ("Sphere [1 -1 1 360]", "Sphere 1 -1 1 360"),
        (r#"Surface "x" "Ka" .5"#, r#"Surface "x" "Ka" [.5]"#),
        ("MotionBegin 0 1", "MotionBegin [0 1]"),
        (
            r#"GeneralPolygon 3 "P" [0 0 0 1 0 0 1 1 0]"#,
            r#"GeneralPolygon [3] "P" [0 0 0 1 0 0 1 1 0]"#,
        ),
        (
            r#"Procedural "RunProgram" "gen" [0 1 0 1 0 1]"#,
            r#"Procedural "RunProgram" ["gen"] [0 1 0 1 0 1]"#,
        ),
        ("Translate [1 2 3]", "Translate 1 2 3"),
        ("Format 640.0 480 1", "Format 640 480 1"),
    ];
    for (a, b) in pairs {
        assert_eq!(parse_one(a), parse_one(b), "{a} vs {b}");
    }
}

#[test]
fn number_forms_of_the_spec_all_read() {
    let r = parse_one("Surface \"x\" \"v\" [1 -.5 1.e-3 1E+4 +2 -7 .25e1]");
    assert_eq!(
        r,
        R::Surface {
            name: st("x"),
            params: vec![p("v", f(&[1.0, -0.5, 1e-3, 1e4, 2.0, -7.0, 2.5]))]
        }
    );
}

#[test]
fn comments_inside_arrays_and_between_parameters_are_skipped() {
    let text = "Surface \"plastic\" # the shader\n  \"Ks\" [ .5 # specular\n ] # end\n \"Kd\" # diffuse\n [1]\n";
    assert_eq!(
        parse_one(text),
        R::Surface {
            name: st("plastic"),
            params: vec![p("Ks", f(&[0.5])), p("Kd", i(&[1]))]
        }
    );
}

#[test]
fn string_escapes_follow_c() {
    let r = parse_one("Attribute \"a\" \"s\" \"q\\\"b\\\\n\\n\\t\\101\\\nz\"");
    assert_eq!(
        r,
        R::Attribute {
            name: st("a"),
            params: vec![p("s", s(&["q\"b\\n\n\tAz"]))]
        }
    );
}

#[test]
fn subdivision_mesh_tags_are_optional() {
    let r = parse_one(r#"SubdivisionMesh "loop" [3] [0 1 2] "P" [0 0 0 1 0 0 0 1 0]"#);
    let R::SubdivisionMesh { tags, params, .. } = r else {
        panic!("{r:?}")
    };
    assert!(tags.is_empty());
    assert_eq!(params.len(), 1);
}

#[test]
fn structure_comments_keep_their_text_and_plain_comments_vanish() {
    let items: Vec<R> = Parser::new(
        "##RenderMan RIB\n# plain\nWorldBegin ##Include x.rib\n".as_bytes(),
        "t",
    )
    .map(|i| i.unwrap().value)
    .collect();
    assert_eq!(
        items,
        vec![
            R::StructureComment(st("RenderMan RIB")),
            R::WorldBegin,
            R::StructureComment(st("Include x.rib"))
        ]
    );
}

#[test]
fn spans_point_at_request_names() {
    let spans: Vec<(u32, u32, u64)> = Parser::new(
        "WorldBegin\n  Sphere 1\n -1 1 360\n\tWorldEnd".as_bytes(),
        "s.rib",
    )
    .map(|i| {
        let s = i.unwrap().span;
        assert_eq!(&*s.file, "s.rib");
        (s.line, s.col, s.offset)
    })
    .collect();
    assert_eq!(spans, vec![(1, 1, 0), (2, 3, 13), (4, 2, 33)]);
}
