//! What shaders need from the texture system: the Shading Language `texture()`,
//! `environment()`, `shadow()` and `textureinfo()` calls (chapter 9 §9.2, §9.6.3). The trait
//! lives with the texture system, which implements it over its cache ([`crate::shading`]), so
//! the dependency points one way: the shaders (`illume-shade`, `illume-slvm`) depend on the
//! texture crate, never the reverse.
use glam::Vec3;

/// One queried value of `textureinfo()`, `option()`, `attribute()`, `rendererinfo()`:
/// `float`/`float[n]`/`point`/`color`/`matrix` data, or a string.
#[derive(Clone, Debug, PartialEq)]
pub enum InfoValue {
    Floats(Vec<f32>),
    String(String),
}

/// Reconstruction filter named by the `"filter"` option.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TextureFilter {
    Box,
    Triangle,
    #[default]
    Gaussian,
}

/// Options of `texture()` / `environment()`: `"blur"`, `"width"`, `"filter"`, `"fill"`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureOptions {
    /// Extra blur as a fraction of the texture (0 = none).
    pub blur: f32,
    /// Multiplier on the filter footprint (`"width"`, 1 = the lookup's own area).
    pub width: f32,
    pub filter: TextureFilter,
    /// Value for channels the map does not have (e.g. alpha `envname[3]` of an RGB map).
    pub fill: f32,
}

impl Default for TextureOptions {
    fn default() -> Self {
        TextureOptions {
            blur: 0.0,
            width: 1.0,
            filter: TextureFilter::Gaussian,
            fill: 0.0,
        }
    }
}

/// Options of `shadow()`: `"samples"`, `"blur"`, `"bias"`, `"width"` (Listing 9.19 defaults).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowOptions {
    pub samples: f32,
    pub blur: f32,
    pub bias: f32,
    pub width: f32,
}

impl Default for ShadowOptions {
    fn default() -> Self {
        ShadowOptions {
            samples: 16.0,
            blur: 0.01,
            bias: 0.01,
            width: 1.0,
        }
    }
}

/// Filtered lookups the shaders make. Each call asks for `nchannels` (1..=4) channels starting at
/// `first_channel` (the SL `name[first]` syntax) and returns them in the first `nchannels`
/// entries; channels the map lacks read `options.fill`. A map that cannot be found or read
/// returns `None`: the shader warns once and contributes black (for `shadow`, unshadowed).
///
/// Lookups are per point with the four corners of the point's footprint, so the implementation
/// chooses the filter area (as the SL four-coordinate forms do; no derivatives are taken).
pub trait TextureLookup: Send + Sync {
    /// `texture(name[first], s, t, …)` over the quadrilateral `st` (corners in the order
    /// `(s,t)`, `(s+ds,t)`, `(s,t+dt)`, `(s+ds,t+dt)`).
    fn texture(
        &self,
        name: &str,
        first_channel: usize,
        nchannels: usize,
        st: [[f32; 2]; 4],
        options: &TextureOptions,
    ) -> Option<[f32; 4]>;

    /// `environment(name[first], R, …)` over the cone of four directions, already expressed in
    /// the space the map was made in (not necessarily unit length).
    fn environment(
        &self,
        name: &str,
        first_channel: usize,
        nchannels: usize,
        directions: [Vec3; 4],
        options: &TextureOptions,
    ) -> Option<[f32; 4]>;

    /// `shadow(name, Ptest, …)`: the fraction of the footprint in shadow, 0 (lit) to 1, for the
    /// four footprint corners given in *world* space.
    fn shadow(&self, name: &str, p_world: [Vec3; 4], options: &ShadowOptions) -> Option<f32>;

    /// `textureinfo(name, dataname, …)`: `"resolution"`, `"channels"`, `"type"`,
    /// `"viewingmatrix"`, `"projectionmatrix"` of a map; `None` when the map or the datum is
    /// unknown (the default: lookups that cannot describe their maps).
    fn textureinfo(&self, _name: &str, _dataname: &str) -> Option<InfoValue> {
        None
    }
}
