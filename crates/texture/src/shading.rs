//! The texture cache as the shaders see it: [`illume_shade::TextureLookup`] over
//! [`TextureCache`]. Shading defines what it needs; this file translates the Shading Language
//! options into the cache's, so neither crate knows the other's internals.
use crate::cache::TextureCache;
use crate::filter::FilterKind;
use crate::lookup::LookupOptions;
use glam::Vec3;
use illume_shade::{ShadowOptions, TextureFilter, TextureLookup, TextureOptions};

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
}
