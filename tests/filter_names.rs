//! One table of filter names (`illume_core::filter::FILTER_NAMES`): every name in it is
//! accepted, and means the same kernel, by `PixelFilter` (RI front end, then the hider's
//! reconstruction filter) and by `MakeTexture` (recorded in the `.tx` file's `filter`
//! attribute). `txmake -filter` is checked against the same table in its own unit test. Before
//! the table, `catrom` was a texture filter but silently became gaussian as a pixel filter.
use illume_core::filter::{FilterKind, FILTER_NAMES};
use illume_imageio::{write_display, Image, Quantize};
use illume_ri::{from_rib_diagnostic, Ri};
use illume_rib::Request;
use std::path::PathBuf;

/// The frame's pixel filter as the hider builds it, and the diagnostics of the RIB.
fn pixel_filter(name: &str) -> (illume_render::PixelFilter, Vec<String>) {
    let rib = format!("Format 8 8 1\nPixelFilter \"{name}\" 3 3\nWorldBegin\nWorldEnd\n");
    let mut ri = Ri::new();
    for item in illume_rib::Parser::new(std::io::Cursor::new(rib.into_bytes()), "test.rib") {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    let diags = ri
        .drain_diagnostics()
        .iter()
        .map(|d| d.to_string())
        .collect();
    let frames = ri.take_frames();
    let (f, xw, yw) = &frames[0].options.filter;
    (illume_render::PixelFilter::new(f, *xw, *yw), diags)
}

#[test]
fn pixelfilter_accepts_every_name_of_the_table() {
    for &(name, kind) in FILTER_NAMES {
        let (filter, diags) = pixel_filter(name);
        assert!(diags.is_empty(), "PixelFilter \"{name}\": {diags:?}");
        assert_eq!(filter.kind, kind, "PixelFilter \"{name}\"");
        assert_eq!((filter.xwidth, filter.ywidth), (3.0, 3.0));
    }
    // An unknown name warns (and says what it uses), never silently changes.
    let (filter, diags) = pixel_filter("bogus");
    assert_eq!(filter.kind, FilterKind::Gaussian);
    assert!(
        diags.len() == 1 && diags[0].contains("unknown filter `bogus`, using gaussian"),
        "{diags:?}"
    );
}

#[test]
fn maketexture_accepts_every_name_of_the_table_and_records_its_kernel() {
    let dir = std::env::temp_dir().join(format!("illume-filter-names-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let picture = dir.join("in.tif");
    let mut image = Image::new(8, 8, "rgb");
    for (k, v) in image.data.iter_mut().enumerate() {
        *v = (k % 7) as f32 / 7.0;
    }
    write_display(&picture, "tiff", &image, Quantize::default(), None).unwrap();
    let path = |p: &PathBuf| p.to_str().unwrap().to_string();
    for &(name, kind) in FILTER_NAMES {
        let out = dir.join(format!("{name}.tx"));
        let request = Request::MakeTexture {
            picture: path(&picture),
            texture: path(&out),
            swrap: "clamp".into(),
            twrap: "clamp".into(),
            filter: name.into(),
            swidth: 2.0,
            twidth: 2.0,
            params: vec![],
        };
        let warnings = illume_texture::make_from_request(&request).unwrap();
        assert!(warnings.is_empty(), "MakeTexture \"{name}\": {warnings:?}");
        // The `.tx` header as OpenEXR tools read it (the exr crate, not the texture crate).
        let meta = exr::meta::MetaData::read_from_file(&out, false).unwrap();
        let recorded = match meta.headers[0]
            .own_attributes
            .other
            .get(&exr::meta::attribute::Text::from("filter"))
        {
            Some(exr::meta::attribute::AttributeValue::Text(t)) => t.to_string(),
            other => panic!("MakeTexture \"{name}\": filter attribute {other:?}"),
        };
        assert_eq!(
            recorded.split_whitespace().next(),
            Some(kind.name()),
            "MakeTexture \"{name}\" recorded `{recorded}`"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
