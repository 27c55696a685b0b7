//! Displays that other stages read back: `Display "shadow"` writes a shadow map directly.
use glam::Vec3;
use illume_render::{render, write_displays, RenderSettings};
mod support;

use illume_texture::{LookupOptions, TextureCache, TextureKind};
use support::frames;

#[test]
fn shadow_display_writes_a_shadow_map_that_shadows_behind_the_surface() {
    let dir = std::env::temp_dir().join(format!("illume-shadow-display-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let sm = dir.join("plane.sm");
    // The light's camera is the world: a square at z = 5 fills the view.
    let rib = format!(
        "Format 64 64 1\nProjection \"perspective\" \"fov\" [60]\nPixelSamples 1 1\n\
         PixelFilter \"box\" 1 1\nHider \"hidden\" \"jitter\" [0]\n\
         Display \"{}\" \"shadow\" \"z\"\nWorldBegin\nSurface \"null\"\n\
         Polygon \"P\" [-10 -10 5  10 -10 5  10 10 5  -10 10 5]\nWorldEnd\n",
        sm.display()
    );
    let frames = frames(&rib, None);
    let rendered = render(&frames[0], &RenderSettings::default());
    for written in write_displays(&frames[0], &rendered) {
        written.unwrap();
    }
    let cache = TextureCache::new(1 << 22);
    let name = sm.to_str().unwrap();
    assert_eq!(cache.info(name).unwrap().kind, TextureKind::Shadow);
    let opts = LookupOptions {
        bias: 0.01,
        ..LookupOptions::default()
    };
    let quad = |z: f32| {
        let d = 0.05;
        [
            Vec3::new(0.0, 0.0, z),
            Vec3::new(d, 0.0, z),
            Vec3::new(0.0, d, z),
            Vec3::new(d, d, z),
        ]
    };
    assert_eq!(
        cache.shadow(name, quad(4.0), &opts).unwrap(),
        0.0,
        "in front of the plane is lit"
    );
    assert_eq!(
        cache.shadow(name, quad(6.0), &opts).unwrap(),
        1.0,
        "behind the plane is shadowed"
    );
    assert_eq!(
        cache.shadow(name, quad(5.0), &opts).unwrap(),
        0.0,
        "the plane itself is lit with bias"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
