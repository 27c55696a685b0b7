//! Shared by the integration tests: RIB text through the real parser into the RI state.
use illume_ri::{from_rib_diagnostic, Frame, Ri, Severity};

/// Parses `rib` and returns its frames, asserting that neither the parser nor the RI state
/// reported an error (warnings are allowed: real scenes have them). `crop` overrides every
/// frame's `CropWindow`, as `render --crop` does.
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
