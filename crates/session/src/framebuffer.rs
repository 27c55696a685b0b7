//! RIB in, pixels out: what the Python module's `illume.render()` returns instead of writing
//! the frame's displays (the same hider and texture cache as `render`).
use crate::errors::{RiError, RIE_NOFILE};
use illume_ri::Ri;

/// One rendered frame: premultiplied RGBA, top row first.
pub struct Pixels {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<f32>,
}

/// Renders RIB (a file name, or the RIB text itself when it is not an existing file) and
/// returns every frame's pixels and the problems met, in order.
pub fn render_rib(source: &str) -> (Vec<Pixels>, Vec<RiError>) {
    let path = std::path::Path::new(source);
    let parser = if !source.contains('\n') && path.is_file() {
        match illume_rib::open(path) {
            Ok(p) => p,
            Err(e) => {
                let msg = format!("{source}: {e}");
                return (
                    Vec::new(),
                    vec![RiError::new(RIE_NOFILE, crate::errors::RIE_SEVERE, msg)],
                );
            }
        }
    } else {
        let reader: Box<dyn std::io::Read + Send> =
            Box::new(std::io::Cursor::new(source.as_bytes().to_vec()));
        illume_rib::Parser::new(reader, "<string>")
    };
    let mut ri = Ri::new();
    ri.set_texture_maker(illume_render::texture_maker(|request, warning| {
        eprintln!("illume: warning: {request}: {warning}")
    }));
    let mut frames = Vec::new();
    let errors = std::cell::RefCell::new(Vec::new());
    illume_render::render_frames_in_order(
        &mut ri,
        parser,
        |d| errors.borrow_mut().push(RiError::from_ri(&d)),
        |frame| {
            let cache =
                illume_texture::TextureCache::new(frame.options.texture_memory as usize * 1024)
                    .with_searchpath(frame.options.texture_path.clone());
            let settings = illume_render::RenderSettings {
                progress: None,
                textures: Some(&cache),
            };
            let r = illume_render::render(&frame, &settings);
            errors
                .borrow_mut()
                .extend(r.warnings.iter().map(RiError::from_ri));
            frames.push(Pixels {
                width: r.width,
                height: r.height,
                rgba: r.rgba,
            });
        },
    );
    (frames, errors.into_inner())
}
