//! The texture cache as the shaders see it: [`crate::texturelookup::TextureLookup`] over
//! [`TextureCache`]. Shading defines what it needs; this file translates the Shading Language
//! options into the cache's, so neither crate knows the other's internals.
use crate::cache::{TextureCache, TextureKind};
use crate::filter::FilterKind;
use crate::lookup::LookupOptions;
use crate::texturelookup::{
    InfoValue, ShadowOptions, TextureFilter, TextureLookup, TextureOptions,
};
use glam::Vec3;

fn lookup_options(o: &TextureOptions) -> LookupOptions {
    LookupOptions {
        blur: o.blur,
        // The SL `"width"` scales both axes of the footprint.
        swidth: o.width,
        twidth: o.width,
        filter: match o.filter {
            TextureFilter::Box => FilterKind::Box,
            TextureFilter::Triangle => FilterKind::Triangle,
            TextureFilter::Gaussian => FilterKind::Gaussian,
        },
        fill: o.fill,
        ..LookupOptions::default()
    }
}

fn shadow_options(o: &ShadowOptions) -> LookupOptions {
    LookupOptions {
        blur: o.blur,
        swidth: o.width,
        twidth: o.width,
        // `samples` is a float in the SL call; at least one sample, and a sane upper bound so a
        // typo cannot stall a render.
        samples: o.samples.clamp(1.0, 4096.0) as u32,
        bias: o.bias,
        ..LookupOptions::default()
    }
}

/// A missing or unreadable map is `None`: the shader warns once and falls back (black, or
/// unshadowed), as the RenderMan renderers do.
impl TextureLookup for TextureCache {
    fn texture(
        &self,
        name: &str,
        first_channel: usize,
        nchannels: usize,
        st: [[f32; 2]; 4],
        options: &TextureOptions,
    ) -> Option<[f32; 4]> {
        TextureCache::texture(
            self,
            name,
            first_channel,
            nchannels,
            st,
            &lookup_options(options),
        )
        .ok()
    }

    fn environment(
        &self,
        name: &str,
        first_channel: usize,
        nchannels: usize,
        directions: [Vec3; 4],
        options: &TextureOptions,
    ) -> Option<[f32; 4]> {
        TextureCache::environment(
            self,
            name,
            first_channel,
            nchannels,
            directions,
            &lookup_options(options),
        )
        .ok()
    }

    fn shadow(&self, name: &str, p_world: [Vec3; 4], options: &ShadowOptions) -> Option<f32> {
        TextureCache::shadow(self, name, p_world, &shadow_options(options)).ok()
    }

    /// `"resolution"` (float[2]), `"channels"`, `"type"` (`"texture"`, `"environment"`,
    /// `"shadow"`), and for shadow maps `"viewingmatrix"` (world → light camera) and
    /// `"projectionmatrix"` (world → the map's NDC, what the map stores), 16 floats in RIB
    /// (row-vector) order.
    fn textureinfo(&self, name: &str, dataname: &str) -> Option<InfoValue> {
        let info = self.info(name).ok()?;
        let matrix = |m: Option<glam::DMat4>| {
            m.map(|m| InfoValue::Floats(m.to_cols_array().iter().map(|&x| x as f32).collect()))
        };
        match dataname {
            "resolution" => Some(InfoValue::Floats(vec![
                info.width as f32,
                info.height as f32,
            ])),
            "channels" => Some(InfoValue::Floats(vec![info.channels.len() as f32])),
            "type" => Some(InfoValue::String(
                match info.kind {
                    TextureKind::Plain => "texture",
                    TextureKind::LatLong | TextureKind::Cube => "environment",
                    TextureKind::Shadow => "shadow",
                }
                .to_string(),
            )),
            "viewingmatrix" => matrix(self.file(name).ok()?.world_to_camera),
            "projectionmatrix" => matrix(self.file(name).ok()?.world_to_ndc),
            _ => None,
        }
    }
}
