//! The scenes the bench renders: three with closed forms and the `rib/` gallery, each as RIB
//! text with the knobs of a [`Settings`] filled in. Every scene writes `out.tif`, a float TIFF
//! (`Quantize "rgba" 0 0 0 0`) so errors are not dominated by 8-bit quantization.

use crate::closed_form::{self, Reference};
use crate::knob::Settings;
use std::path::{Path, PathBuf};

/// The half-width of the orthographic screen window of the sphere scenes (object units).
pub const SPHERE_WINDOW: f64 = 1.25;
/// Disk-shadow scene geometry: light height, disk height and radius, half-width of the view.
pub const LIGHT_HEIGHT: f64 = 4.0;
pub const DISK_HEIGHT: f64 = 2.0;
pub const DISK_RADIUS: f64 = 0.5;
pub const PLANE_WINDOW: f64 = 2.0;
/// Cube-face resolution of the mirror scene's environment.
pub const FACE_SIZE: u32 = 128;

/// What a scene is.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneKind {
    /// An orthographic matte sphere under a distantlight.
    MatteSphere,
    /// A disk's shadow-map shadow from a shadowspot straight above a matte plane.
    DiskShadow,
    /// A mirror (shinymetal) sphere in a cube map of an analytic environment.
    MirrorSphere,
    /// A `rib/` scene; `scale` multiplies its `Format`.
    Gallery { path: PathBuf, scale: f64 },
}

/// One scene and its image size.
#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub kind: SceneKind,
    /// Image width and height of the closed-form scenes (square).
    pub res: u32,
}

/// The options every point sets, in the frame that writes `out.tif`.
fn common_options(s: &Settings) -> String {
    format!(
        "Option \"limits\" \"bucketsize\" [{b} {b}]\nPixelSamples {n} {n}\n\
         Display \"out.tif\" \"tiff\" \"rgb\"\nQuantize \"rgba\" 0 0 0 0\n",
        b = s.bucket_size,
        n = s.pixel_samples,
    )
}

/// The attributes every point sets at the top of its world block.
fn world_attributes(s: &Settings) -> String {
    format!(
        "ShadingRate {}\nShadingInterpolation \"{}\"\n",
        s.shading_rate,
        if s.smooth { "smooth" } else { "constant" }
    )
}

impl Scene {
    /// Writes the files the scene reads (the mirror scene's six cube faces) into `dir`.
    pub fn prepare(&self, dir: &Path) -> Result<(), String> {
        if self.kind == SceneKind::MirrorSphere {
            closed_form::write_cube_faces(dir, FACE_SIZE).map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// The RIB text for one render with settings `s`, run in the scene's directory.
    pub fn rib(&self, s: &Settings) -> Result<String, String> {
        let common = common_options(s);
        let r = self.res;
        let w = SPHERE_WINDOW;
        let attrs = world_attributes(s);
        Ok(match &self.kind {
            SceneKind::MatteSphere => format!(
                "Format {r} {r} 1\nScreenWindow -{w} {w} -{w} {w}\nProjection \"orthographic\"\n\
                 PixelFilter \"box\" 1 1\n{common}WorldBegin\n\
                 LightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [0 0 0] \"to\" [{lx} {ly} {lz}]\n\
                 {attrs}Surface \"matte\"\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n",
                lx = closed_form::LIGHT_TRAVEL[0],
                ly = closed_form::LIGHT_TRAVEL[1],
                lz = closed_form::LIGHT_TRAVEL[2],
            ),
            SceneKind::DiskShadow => disk_shadow_rib(s, r, &common),
            SceneKind::MirrorSphere => format!(
                "MakeCubeFaceEnvironment \"px.tif\" \"nx.tif\" \"py.tif\" \"ny.tif\" \"pz.tif\" \"nz.tif\" \
                 \"env.tx\" 90 \"gaussian\" {fw} {fw}\n\
                 Format {r} {r} 1\nScreenWindow -{w} {w} -{w} {w}\nProjection \"orthographic\"\n\
                 PixelFilter \"box\" 1 1\n{common}WorldBegin\n{attrs}\
                 Surface \"shinymetal\" \"Ka\" [0] \"Kd\" [0] \"Ks\" [0] \"Kr\" [1] \"blur\" [{b}] \
                 \"texturename\" [\"env.tx\"]\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n",
                fw = s.filter_width,
                b = s.env_blur,
            ),
            SceneKind::Gallery { path, scale } => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                gallery_rib(&text, *scale, s, &common)
                    .ok_or_else(|| format!("{}: no WorldBegin", path.display()))?
            }
        })
    }

    /// The closed-form image and the pixels where it is exact, if the scene has one.
    pub fn closed_form(&self) -> Option<Reference> {
        match self.kind {
            SceneKind::MatteSphere => Some(closed_form::matte_sphere(self.res)),
            SceneKind::DiskShadow => Some(closed_form::disk_shadow(self.res)),
            SceneKind::MirrorSphere => Some(closed_form::mirror_sphere(self.res)),
            SceneKind::Gallery { .. } => None,
        }
    }
}

/// Depth pass from the light (the chapter's settings, section 9.6.3), `MakeShadow`, then the
/// beauty pass looking straight down at the plane. The disk is left out of the beauty pass:
/// only its shadow is measured, and from above it would hide the shadow.
///
/// With [`Settings::raytraced_shadows`] there is no depth pass and no `MakeShadow` (so the
/// time is what a ray-traced user pays), the light's `shadowname` is "raytrace", and the disk
/// is in the beauty pass, where shadow rays can hit it, but hidden from the camera by the near
/// clipping plane (the renderer has no camera-visibility attribute; the ray-traced scene keeps
/// every shadow-casting primitive, clipped or not).
fn disk_shadow_rib(s: &Settings, r: u32, common: &str) -> String {
    let (hl, hd, rd, w) = (LIGHT_HEIGHT, DISK_HEIGHT, DISK_RADIUS, PLANE_WINDOW);
    let disk = format!(
        "AttributeBegin\nTranslate 0 {hd} 0\nRotate 90 1 0 0\nDisk 0 {rd} 360\nAttributeEnd\n"
    );
    let plane = "Polygon \"P\" [-3 0 -3  3 0 -3  3 0 3  -3 0 3]";
    if s.raytraced_shadows {
        // The camera is 10 above the plane: the disk is 10 − hd away, the plane 10.
        let near = 10.0 - 0.5 * hd;
        return format!(
            "Format {r} {r} 1\nScreenWindow -{w} {w} -{w} {w}\nProjection \"orthographic\"\n\
             Clipping {near} 100\nPixelFilter \"box\" 1 1\n{common}Rotate -90 1 0 0\nTranslate 0 -10 0\n\
             WorldBegin\n\
             LightSource \"shadowspot\" 1 \"intensity\" [{i}] \"from\" [0 {hl} 0] \"to\" [0 0 0] \
             \"coneangle\" [{cone}] \"conedeltaangle\" [0.1] \"shadowname\" [\"raytrace\"] \
             \"samples\" [{n}] \"blur\" [{b}]\n\
             {attrs}Surface \"matte\"\n{disk}{plane}\nWorldEnd\n",
            i = closed_form::SPOT_INTENSITY,
            cone = closed_form::SPOT_CONE,
            n = s.shadow_samples,
            b = s.shadow_blur,
            attrs = world_attributes(s),
        );
    }
    // The map's field of view holds the visible plane square with a margin.
    let fov = 2.0 * (1.2 * w / hl).atan().to_degrees();
    format!(
        "FrameBegin 1\nFormat {m} {m} 1\nPixelSamples 1 1\nPixelFilter \"box\" 1 1\n\
         Hider \"hidden\" \"jitter\" [0]\nDisplay \"depth.z\" \"zfile\" \"z\"\nShadingRate 4\n\
         Projection \"perspective\" \"fov\" [{fov}]\nRotate -90 1 0 0\nTranslate 0 -{hl} 0\n\
         WorldBegin\nSurface \"null\"\n{disk}{plane}\nWorldEnd\nFrameEnd\n\
         MakeShadow \"depth.z\" \"shadow.sm\"\n\
         FrameBegin 2\nFormat {r} {r} 1\nScreenWindow -{w} {w} -{w} {w}\nProjection \"orthographic\"\n\
         PixelFilter \"box\" 1 1\n{common}Rotate -90 1 0 0\nTranslate 0 -10 0\nWorldBegin\n\
         LightSource \"shadowspot\" 1 \"intensity\" [{i}] \"from\" [0 {hl} 0] \"to\" [0 0 0] \
         \"coneangle\" [{cone}] \"conedeltaangle\" [0.1] \"shadowname\" [\"shadow.sm\"] \
         \"samples\" [{n}] \"blur\" [{b}] \"bias\" [0.01]\n\
         {attrs}Surface \"matte\"\n{plane}\nWorldEnd\nFrameEnd\n",
        m = s.shadow_map_size,
        i = closed_form::SPOT_INTENSITY,
        cone = closed_form::SPOT_CONE,
        n = s.shadow_samples,
        b = s.shadow_blur,
        attrs = world_attributes(s),
    )
}

/// A gallery scene with the bench's options: its own `Display`, `Format`, `PixelSamples`,
/// `ShadingRate` and `Quantize` lines before `WorldBegin` are dropped and ours put just before
/// it (the last option before `WorldBegin` wins), `Format` scaled by `scale`.
fn gallery_rib(text: &str, scale: f64, s: &Settings, common: &str) -> Option<String> {
    let mut out = String::new();
    let mut format = String::new();
    let mut lines = text.lines();
    for line in lines.by_ref() {
        let t = line.trim_start();
        let word = t.split_whitespace().next().unwrap_or("");
        match word {
            "Format" => format = scaled_format(t, scale),
            "Display" | "PixelSamples" | "ShadingRate" | "ShadingInterpolation" | "Quantize" => {}
            "WorldBegin" => {
                out.push_str(&format);
                out.push_str(common);
                out.push_str("WorldBegin\n");
                out.push_str(&world_attributes(s));
                for rest in lines.by_ref() {
                    out.push_str(rest);
                    out.push('\n');
                }
                return Some(out);
            }
            _ => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    None
}

/// `Format w h a` with w and h multiplied by `scale` (at least 1 pixel).
fn scaled_format(line: &str, scale: f64) -> String {
    let f: Vec<f64> = line
        .split_whitespace()
        .skip(1)
        .filter_map(|x| x.parse().ok())
        .collect();
    match f.as_slice() {
        [w, h, a, ..] => format!(
            "Format {} {} {a}\n",
            ((w * scale).round() as u32).max(1),
            ((h * scale).round() as u32).max(1)
        ),
        _ => format!("{line}\n"),
    }
}

/// The RIB line `Format w h rest…` with `w` and `h` multiplied by `scale`, and its pixel
/// count; `line` (the original) names the error. Shared by `--motion` and `--threads`, which
/// rescale a gallery scene the same way (unlike [`scaled_format`], a bad line is an error).
pub fn multiplied_format(
    line: &str,
    w: &str,
    h: &str,
    rest: &[&str],
    scale: u32,
) -> Result<(String, u64), String> {
    let w: u32 = w.parse().map_err(|_| format!("bad Format line: {line}"))?;
    let h: u32 = h.parse().map_err(|_| format!("bad Format line: {line}"))?;
    let (w, h) = (w * scale, h * scale);
    Ok((
        format!("Format {w} {h} {}", rest.join(" ")),
        u64::from(w) * u64::from(h),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gallery_options_replace_the_scenes_own() {
        let text = "Display \"a.tif\" \"tiff\" \"rgba\"\nFormat 320 240 1\nPixelSamples 3 3\n\
                    Translate 0 0 5\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";
        let s = Settings::defaults(256, 2).with(crate::knob::Knob::ShadingRate, 0.5);
        let rib = gallery_rib(text, 0.5, &s, &common_options(&s)).unwrap();
        assert!(
            !rib.contains("a.tif") && !rib.contains("PixelSamples 3 3"),
            "{rib}"
        );
        assert!(rib.contains("Format 160 120 1\n"), "{rib}");
        assert!(rib.contains("PixelSamples 2 2\n") && rib.contains("ShadingRate 0.5\n"));
        assert!(rib.find("Translate").unwrap() < rib.find("out.tif").unwrap());
        assert!(rib.ends_with("Sphere 1 -1 1 360\nWorldEnd\n"));
        assert!(gallery_rib("Sphere 1 -1 1 360\n", 1.0, &s, "").is_none());
    }

    fn disk_scene() -> Scene {
        Scene {
            name: "disk_shadow".into(),
            kind: SceneKind::DiskShadow,
            res: 32,
        }
    }

    #[test]
    fn raytraced_disk_shadow_has_no_depth_pass_and_traces_the_disk() {
        let d = Settings::defaults(256, 2);
        let map = disk_scene().rib(&d).unwrap();
        assert!(map.contains("MakeShadow") && map.contains("zfile"), "{map}");
        assert!(map.contains("[\"shadow.sm\"]") && !map.contains("raytrace"));
        let s = d.with(crate::knob::Knob::RaytracedShadowSamples, 4.0);
        let rt = disk_scene().rib(&s).unwrap();
        assert!(
            !rt.contains("MakeShadow") && !rt.contains("zfile") && !rt.contains("FrameBegin"),
            "{rt}"
        );
        assert!(rt.contains("\"shadowname\" [\"raytrace\"] \"samples\" [4] \"blur\" [0.01]"));
        // The disk is in the world (shadow rays need it), between the near plane and the
        // light, and the plane beyond the near plane.
        let world = &rt[rt.find("WorldBegin").unwrap()..];
        assert!(world.contains(&format!("Disk 0 {DISK_RADIUS} 360")), "{rt}");
        let near: f64 = rt
            .lines()
            .find_map(|l| l.strip_prefix("Clipping "))
            .and_then(|l| l.split_whitespace().next())
            .and_then(|x| x.parse().ok())
            .expect("Clipping line");
        let camera_height = 10.0;
        assert!(
            camera_height - DISK_HEIGHT < near && near < camera_height,
            "{near}"
        );
    }
}
