//! Shared by the integration tests: RIB text through the real parser into the RI state.
use illume_ri::{from_rib_diagnostic, Frame, Ri, Severity};

/// Parses `rib` and returns its frames, asserting that neither the parser nor the RI state
/// reported an error (warnings are allowed: real scenes have them). `crop` overrides every
/// frame's `CropWindow`, as `render --crop` does.
#[allow(dead_code)] // not every test binary parses without rendering
pub fn frames(rib: &str, crop: Option<[f32; 4]>) -> Vec<Frame> {
    let mut ri = Ri::new();
    ri.set_crop_override(crop);
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "test.rib");
    for item in parser {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    let errors: Vec<_> = ri
        .drain_diagnostics()
        .into_iter()
        .filter(|d| d.severity == Severity::Error)
        .collect();
    assert!(errors.is_empty(), "{errors:?}");
    ri.take_frames()
}

/// What `render` does with one RIB stream, through the same library loop
/// (`illume_reyes::render_frames_in_order`): frames render in file order as soon as they end,
/// their displays are written, and Make* requests between frames see the files earlier frames
/// wrote. Asserts that no parse, RI, render or display error occurred.
#[allow(dead_code)] // each test binary compiles this module; not all of them render pipelines
pub fn run_rib(rib: &str) -> Vec<illume_reyes::Rendered> {
    let mut ri = Ri::new();
    ri.set_texture_maker(illume_reyes::texture_maker(|_, _| {}));
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "test.rib");
    let mut out = Vec::new();
    illume_reyes::render_frames_in_order(
        &mut ri,
        parser,
        |d| assert!(d.severity != Severity::Error, "{d}"),
        |frame| {
            let cache =
                illume_texture::TextureCache::new(frame.options.texture_memory as usize * 1024);
            let settings = illume_reyes::RenderSettings {
                progress: None,
                textures: Some(&cache),
            };
            let r = illume_reyes::render(&frame, &settings);
            let errors: Vec<_> = r
                .warnings
                .iter()
                .filter(|d| d.severity == Severity::Error)
                .collect();
            assert!(errors.is_empty(), "{errors:?}");
            for w in illume_reyes::write_displays(&frame, &r) {
                w.unwrap();
            }
            out.push(r);
        },
    );
    out
}
