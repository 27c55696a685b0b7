//! What `option()`, `attribute()` and `rendererinfo()` (RI 3.2 §15.7) may ask of the renderer:
//! named values as floats or a string, looked up by the shader at run time. The renderer fills
//! a [`RenderInfo`] per frame (options) and per primitive (attributes); shaders only read it.
use std::collections::HashMap;

/// One queried value (defined with `textureinfo()`'s in the texture crate).
pub use illume_texture::InfoValue;

/// A name → value table for one query family (the frame's options or one primitive's
/// attributes). A plain map: the queries are rare and the tables small.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderInfo {
    values: HashMap<String, InfoValue>,
}

impl RenderInfo {
    pub fn new() -> RenderInfo {
        RenderInfo::default()
    }

    /// Sets float data `name` (builder style, for the renderer's one-off tables).
    pub fn with_floats(mut self, name: &str, v: &[f32]) -> RenderInfo {
        self.values
            .insert(name.to_string(), InfoValue::Floats(v.to_vec()));
        self
    }

    pub fn with_string(mut self, name: &str, v: &str) -> RenderInfo {
        self.values
            .insert(name.to_string(), InfoValue::String(v.to_string()));
        self
    }

    pub fn get(&self, name: &str) -> Option<&InfoValue> {
        self.values.get(name)
    }
}

/// `rendererinfo(name)`: this renderer's name and version (the crate version).
pub fn rendererinfo(name: &str) -> Option<InfoValue> {
    let version = env!("CARGO_PKG_VERSION");
    match name {
        "renderer" => Some(InfoValue::String("Illume".to_string())),
        "version" => Some(InfoValue::Floats(
            version
                .split('.')
                .map(|x| x.parse::<f32>().unwrap_or(0.0))
                .chain(std::iter::repeat(0.0))
                .take(4)
                .collect(),
        )),
        "versionstring" => Some(InfoValue::String(version.to_string())),
        _ => None,
    }
}
