//! The quality knobs the bench sweeps, the settings a render point uses, and the values each
//! knob takes.
//!
//! A sweep varies one knob away from [`Settings::defaults`] (the renderer's own defaults: RI
//! spec PixelSamples 2 2 and ShadingRate 1, Listing 9.19's shadow samples 16 and blur 0.01),
//! except [`Knob::SamplesAndRate`], which moves PixelSamples and ShadingRate together because
//! that pairing is what a user picking "one quality level" wants to see.
//!
//! New knobs go here: add a variant to [`Knob`], its values to [`Knob::values`], where it applies
//! to [`Knob::applies_to`], and how it changes a render to [`Settings::with`]. Ray-traced
//! shadows (issue 9) enter as [`Knob::RaytracedShadowSamples`] on
//! [`crate::scene::SceneKind::DiskShadow`], beside the shadow-map knobs, so "ray-traced vs
//! shadow-map shadows at equal error" reads straight off the plot.

use crate::scene::SceneKind;

/// One quality knob.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Knob {
    PixelSamples,
    ShadingRate,
    /// PixelSamples n n with ShadingRate chosen per n (see [`SAMPLES_AND_RATE`]).
    SamplesAndRate,
    /// `ShadingInterpolation`: 0 "constant" (RI default: a micropolygon takes the colour
    /// shaded at one of its vertices), 1 "smooth" (Gouraud).
    ShadingInterpolation,
    ShadowSamples,
    ShadowBlur,
    /// The shadow map's resolution (square), the depth pass's `Format`.
    ShadowMapSize,
    /// `shadowname "raytrace"` instead of a map (no depth pass, no `MakeShadow`), sweeping
    /// `samples` at the default blur 0.01, as [`Knob::ShadowSamples`] does for the map. Not at
    /// blur 0: there the renderer traces one ray whatever `samples` says, so every point would
    /// be the same image (blur 0 is [`Knob::RaytracedShadowBlur`]'s first point).
    RaytracedShadowSamples,
    /// `shadowname "raytrace"`, sweeping `blur` (cone half-angle, radians) at the default 16
    /// samples, as [`Knob::ShadowBlur`] does for the map. Blur 0 is one hard-edged ray: the
    /// point light's shadow the closed form has.
    RaytracedShadowBlur,
    /// `shadowname "raytrace"` at blur 0 (one hard ray per shaded point) with PixelSamples and
    /// ShadingRate moved together as [`Knob::SamplesAndRate`] (same index): a ray answers
    /// lit-or-not at one point per micropolygon, where a map lookup filters over the
    /// micropolygon's footprint, so a traced edge is antialiased only by finer shading.
    RaytracedSamplesAndRate,
    /// [`Knob::RaytracedSamplesAndRate`] with `ShadingInterpolation "smooth"`: Gouraud
    /// interpolation between the traced vertices puts the edge between them instead of at
    /// one corner of each micropolygon.
    RaytracedSmoothSamplesAndRate,
    /// `MakeCubeFaceEnvironment` filter width (the mip-map build filter, in texels).
    TextureFilterWidth,
    /// `blur` of the environment lookup (shinymetal), a fraction of the map.
    EnvironmentBlur,
    BucketSize,
    Threads,
}

/// Every knob, in the order the CSV, plot legend and table list them.
pub const ALL_KNOBS: [Knob; 15] = [
    Knob::PixelSamples,
    Knob::ShadingRate,
    Knob::SamplesAndRate,
    Knob::ShadingInterpolation,
    Knob::ShadowSamples,
    Knob::ShadowBlur,
    Knob::ShadowMapSize,
    Knob::RaytracedShadowSamples,
    Knob::RaytracedShadowBlur,
    Knob::RaytracedSamplesAndRate,
    Knob::RaytracedSmoothSamplesAndRate,
    Knob::TextureFilterWidth,
    Knob::EnvironmentBlur,
    Knob::BucketSize,
    Knob::Threads,
];

/// (PixelSamples n, ShadingRate) pairs of [`Knob::SamplesAndRate`]: more samples with finer
/// shading, so neither dominates the error.
pub const SAMPLES_AND_RATE: [(f64, f64); 6] = [
    (1.0, 4.0),
    (2.0, 2.0),
    (3.0, 1.0),
    (4.0, 0.5),
    (6.0, 0.25),
    (8.0, 0.25),
];

impl Knob {
    /// Short name used in the CSV and on the plot (upper-case: the plot font has no lower case).
    pub fn name(self) -> &'static str {
        match self {
            Knob::PixelSamples => "PIXELSAMPLES",
            Knob::ShadingRate => "SHADINGRATE",
            Knob::SamplesAndRate => "SAMPLES+RATE",
            Knob::ShadingInterpolation => "SMOOTH SHADING",
            Knob::ShadowSamples => "SHADOW SAMPLES",
            Knob::ShadowBlur => "SHADOW BLUR",
            Knob::ShadowMapSize => "SHADOW MAP SIZE",
            Knob::RaytracedShadowSamples => "RAYTRACED SAMPLES",
            Knob::RaytracedShadowBlur => "RAYTRACED BLUR",
            Knob::RaytracedSamplesAndRate => "RAYTRACED SAMPLES+RATE",
            Knob::RaytracedSmoothSamplesAndRate => "RAYTRACED SMOOTH S+R",
            Knob::TextureFilterWidth => "TEX FILTER WIDTH",
            Knob::EnvironmentBlur => "ENV BLUR",
            Knob::BucketSize => "BUCKETSIZE",
            Knob::Threads => "THREADS",
        }
    }

    /// The values swept; `quick` keeps fewer so `bench --quick` stays well under 2 minutes.
    /// For [`Knob::SamplesAndRate`] and the ray-traced samples-and-rate knobs the value is
    /// the index into [`SAMPLES_AND_RATE`].
    pub fn values(self, quick: bool) -> Vec<f64> {
        let (full, fast): (&[f64], &[f64]) = match self {
            Knob::PixelSamples => (&[1.0, 2.0, 3.0, 4.0, 6.0, 8.0], &[1.0, 2.0, 4.0]),
            Knob::ShadingRate => (&[8.0, 4.0, 2.0, 1.0, 0.5, 0.25], &[4.0, 1.0, 0.25]),
            Knob::SamplesAndRate => (&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], &[0.0, 1.0, 3.0]),
            Knob::ShadingInterpolation => (&[0.0, 1.0], &[0.0, 1.0]),
            Knob::ShadowSamples => (&[1.0, 4.0, 16.0, 64.0, 256.0], &[1.0, 16.0, 64.0]),
            Knob::ShadowBlur => (&[0.0, 0.005, 0.01, 0.02, 0.05], &[0.0, 0.01, 0.05]),
            Knob::ShadowMapSize => (&[64.0, 128.0, 256.0, 512.0, 1024.0], &[64.0, 256.0]),
            Knob::RaytracedShadowSamples => (&[1.0, 4.0, 16.0, 64.0], &[1.0, 16.0]),
            Knob::RaytracedShadowBlur => (&[0.0, 0.005, 0.01, 0.02], &[0.0, 0.01]),
            Knob::RaytracedSamplesAndRate | Knob::RaytracedSmoothSamplesAndRate => {
                (&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], &[0.0, 3.0])
            }
            Knob::TextureFilterWidth => (&[0.5, 1.0, 2.0, 4.0], &[1.0, 4.0]),
            Knob::EnvironmentBlur => (&[0.0, 0.005, 0.01, 0.02, 0.05], &[0.0, 0.02]),
            Knob::BucketSize => (&[8.0, 16.0, 32.0, 64.0], &[8.0, 32.0]),
            Knob::Threads => (&[1.0, 2.0], &[1.0, 2.0]),
        };
        if quick { fast } else { full }.to_vec()
    }

    /// Whether the knob changes anything in a scene of this kind (shadow knobs need a
    /// shadowing light, texture knobs an environment map).
    pub fn applies_to(self, kind: &SceneKind) -> bool {
        match self {
            Knob::ShadowSamples
            | Knob::ShadowBlur
            | Knob::ShadowMapSize
            | Knob::RaytracedShadowSamples
            | Knob::RaytracedShadowBlur
            | Knob::RaytracedSamplesAndRate
            | Knob::RaytracedSmoothSamplesAndRate => {
                matches!(kind, SceneKind::DiskShadow)
            }
            Knob::TextureFilterWidth | Knob::EnvironmentBlur => {
                matches!(kind, SceneKind::MirrorSphere)
            }
            _ => true,
        }
    }

    /// Whether the knob changes the image at all. Bucket size and thread count change only
    /// the time (the renderer writes the same bits whatever the thread count, and buckets do
    /// not change sampling), so they are left out of the Pareto front and the target table
    /// and reported on their own.
    pub fn changes_image(self) -> bool {
        !matches!(self, Knob::BucketSize | Knob::Threads)
    }

    /// The knob with this [`Knob::name`].
    pub fn from_name(name: &str) -> Option<Knob> {
        ALL_KNOBS.into_iter().find(|k| k.name() == name)
    }

    /// The knob's value as the user writes it (for [`Knob::SamplesAndRate`], "n n / rate").
    pub fn describe(self, value: f64) -> String {
        match self {
            Knob::SamplesAndRate => {
                let (n, r) = samples_and_rate(value);
                format!("PixelSamples {n} {n}, ShadingRate {r}")
            }
            Knob::PixelSamples => format!("PixelSamples {value} {value}"),
            Knob::ShadingInterpolation => format!(
                "ShadingInterpolation \"{}\"",
                if value > 0.5 { "smooth" } else { "constant" }
            ),
            Knob::ShadingRate => format!("ShadingRate {value}"),
            Knob::ShadowSamples => format!("shadow samples {value}"),
            Knob::ShadowBlur => format!("shadow blur {value}"),
            Knob::ShadowMapSize => format!("shadow map {value}²"),
            Knob::RaytracedShadowSamples => format!("raytraced, samples {value}"),
            Knob::RaytracedShadowBlur => format!("raytraced, blur {value}"),
            Knob::RaytracedSamplesAndRate => {
                let (n, r) = samples_and_rate(value);
                format!("raytraced blur 0, PixelSamples {n} {n}, ShadingRate {r}")
            }
            Knob::RaytracedSmoothSamplesAndRate => {
                let (n, r) = samples_and_rate(value);
                format!("raytraced blur 0, smooth, PixelSamples {n} {n}, ShadingRate {r}")
            }
            Knob::TextureFilterWidth => format!("env filter width {value}"),
            Knob::EnvironmentBlur => format!("env blur {value}"),
            Knob::BucketSize => format!("bucketsize {value}"),
            Knob::Threads => format!("--threads {value}"),
        }
    }
}

fn samples_and_rate(index: f64) -> (f64, f64) {
    let i = (index.max(0.0) as usize).min(SAMPLES_AND_RATE.len() - 1);
    SAMPLES_AND_RATE[i]
}

/// Everything a render point sets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub pixel_samples: u32,
    pub shading_rate: f64,
    /// `ShadingInterpolation "smooth"` rather than "constant".
    pub smooth: bool,
    pub shadow_samples: u32,
    pub shadow_blur: f64,
    pub shadow_map_size: u32,
    /// `shadowname "raytrace"`: shadow rays instead of the map (`shadow_map_size` unused).
    pub raytraced_shadows: bool,
    pub filter_width: f64,
    pub env_blur: f64,
    pub bucket_size: u32,
    pub threads: usize,
}

impl Settings {
    /// The renderer's defaults (RI spec, Listing 9.19, `Option "limits" "bucketsize"` 16, every
    /// core), with `shadow_map_size` and `threads` given by the run.
    pub fn defaults(shadow_map_size: u32, threads: usize) -> Settings {
        Settings {
            pixel_samples: 2,
            shading_rate: 1.0,
            smooth: false,
            shadow_samples: 16,
            shadow_blur: 0.01,
            shadow_map_size,
            raytraced_shadows: false,
            filter_width: 1.0,
            env_blur: 0.0,
            bucket_size: 16,
            threads,
        }
    }

    /// The converged reference of issue 8: PixelSamples 16 16, ShadingRate 0.1, 256 shadow
    /// samples, a shadow map 4× the default's size. Knobs that are a choice rather than an
    /// approximation (interpolation, blur, filter width, bucket size) keep their defaults, so
    /// the reference is what the default settings converge to.
    pub fn converged(self) -> Settings {
        Settings {
            pixel_samples: 16,
            shading_rate: 0.1,
            shadow_samples: 256,
            shadow_map_size: self.shadow_map_size * 4,
            ..self
        }
    }

    /// These settings with `knob` set to `value`.
    pub fn with(self, knob: Knob, value: f64) -> Settings {
        let mut s = self;
        match knob {
            Knob::PixelSamples => s.pixel_samples = value as u32,
            Knob::ShadingRate => s.shading_rate = value,
            Knob::SamplesAndRate => {
                let (n, r) = samples_and_rate(value);
                s.pixel_samples = n as u32;
                s.shading_rate = r;
            }
            Knob::ShadingInterpolation => s.smooth = value > 0.5,
            Knob::ShadowSamples => s.shadow_samples = value as u32,
            Knob::ShadowBlur => s.shadow_blur = value,
            Knob::ShadowMapSize => s.shadow_map_size = value as u32,
            Knob::RaytracedShadowSamples => {
                s.raytraced_shadows = true;
                s.shadow_samples = value as u32;
            }
            Knob::RaytracedShadowBlur => {
                s.raytraced_shadows = true;
                s.shadow_blur = value;
            }
            Knob::RaytracedSamplesAndRate | Knob::RaytracedSmoothSamplesAndRate => {
                let (n, r) = samples_and_rate(value);
                s.pixel_samples = n as u32;
                s.shading_rate = r;
                s.raytraced_shadows = true;
                s.shadow_blur = 0.0;
                s.smooth = knob == Knob::RaytracedSmoothSamplesAndRate;
            }
            Knob::TextureFilterWidth => s.filter_width = value,
            Knob::EnvironmentBlur => s.env_blur = value,
            Knob::BucketSize => s.bucket_size = value as u32,
            Knob::Threads => s.threads = value as usize,
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_changes_only_its_knob() {
        let d = Settings::defaults(256, 2);
        assert_eq!(d.with(Knob::PixelSamples, 4.0).pixel_samples, 4);
        assert_eq!(d.with(Knob::PixelSamples, 4.0).shading_rate, 1.0);
        let sr = d.with(Knob::SamplesAndRate, 3.0);
        assert_eq!((sr.pixel_samples, sr.shading_rate), (4, 0.5));
        assert_eq!(sr.shadow_samples, 16);
        let c = d.converged();
        assert_eq!(
            (c.pixel_samples, c.shading_rate, c.shadow_samples),
            (16, 0.1, 256)
        );
        assert_eq!(c.shadow_blur, d.shadow_blur);
        assert!(!d.raytraced_shadows && !c.raytraced_shadows);
    }

    #[test]
    fn raytraced_shadow_knobs_switch_the_light_and_sweep_like_the_map_knobs() {
        let d = Settings::defaults(256, 2);
        let rt = d.with(Knob::RaytracedShadowSamples, 4.0);
        assert!(rt.raytraced_shadows);
        assert_eq!((rt.shadow_samples, rt.shadow_blur), (4, d.shadow_blur));
        let hard = d.with(Knob::RaytracedShadowBlur, 0.0);
        assert!(hard.raytraced_shadows);
        assert_eq!((hard.shadow_samples, hard.shadow_blur), (16, 0.0));
        // Everything else stays at the defaults.
        for s in [rt, hard] {
            let back = Settings {
                raytraced_shadows: false,
                shadow_samples: d.shadow_samples,
                shadow_blur: d.shadow_blur,
                ..s
            };
            assert_eq!(back, d);
        }
        // The ray-traced defaults are the map defaults with rays: one shared point each.
        assert_eq!(
            d.with(Knob::RaytracedShadowSamples, 16.0),
            d.with(Knob::RaytracedShadowBlur, 0.01)
        );
        // The map knobs leave the light on its map.
        for k in [Knob::ShadowSamples, Knob::ShadowBlur, Knob::ShadowMapSize] {
            assert!(!d.with(k, 4.0).raytraced_shadows, "{k:?}");
        }
        for k in [Knob::RaytracedShadowSamples, Knob::RaytracedShadowBlur] {
            assert!(k.applies_to(&SceneKind::DiskShadow));
            assert!(!k.applies_to(&SceneKind::MatteSphere));
            assert!(!k.applies_to(&SceneKind::MirrorSphere));
            assert!(k.changes_image());
            assert!(k.values(true).len() < k.values(false).len());
            assert!(k.values(true).iter().all(|v| k.values(false).contains(v)));
        }
        assert_eq!(
            Knob::RaytracedShadowSamples.values(false),
            [1.0, 4.0, 16.0, 64.0]
        );
        assert_eq!(Knob::RaytracedShadowBlur.values(false)[0], 0.0);
        // Samples and rate: the map knob's pairs, with one hard ray.
        for k in [
            Knob::RaytracedSamplesAndRate,
            Knob::RaytracedSmoothSamplesAndRate,
        ] {
            assert!(k.applies_to(&SceneKind::DiskShadow));
            assert!(!k.applies_to(&SceneKind::MatteSphere));
            assert_eq!(k.values(false), Knob::SamplesAndRate.values(false));
            for v in k.values(false) {
                let (rt, map) = (d.with(k, v), d.with(Knob::SamplesAndRate, v));
                assert!(rt.raytraced_shadows && rt.shadow_blur == 0.0);
                assert_eq!(rt.smooth, k == Knob::RaytracedSmoothSamplesAndRate);
                assert_eq!(
                    (rt.pixel_samples, rt.shading_rate),
                    (map.pixel_samples, map.shading_rate)
                );
            }
        }
    }

    #[test]
    fn knob_names_are_distinct_and_round_trip() {
        for (i, a) in ALL_KNOBS.iter().enumerate() {
            assert_eq!(Knob::from_name(a.name()), Some(*a));
            assert!(ALL_KNOBS[..i].iter().all(|b| b.name() != a.name()));
        }
    }
}
