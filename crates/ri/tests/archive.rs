//! `ReadArchive` is textual inclusion (RI Spec 3.2 appendix D, PRMan and Aqsis alike): what an
//! archive sets stays set for its reader, which exporters rely on (Blender's write the camera
//! into an archive read before `WorldBegin`). Procedurals and object instances stay scoped.
use illume_ri::{from_rib_diagnostic, Frame, Projection, Ri};

/// Renders `main.rib` of a scratch directory holding `files` into frames (no errors allowed).
fn frames_of(dir_name: &str, files: &[(&str, &str)]) -> Vec<Frame> {
    let dir = std::env::temp_dir().join(format!("illume-ri-{dir_name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let main = dir.join("main.rib");
    let name = main.display().to_string();
    let reader = std::fs::File::open(&main).unwrap();
    let mut ri = Ri::new();
    ri.run(Box::new(
        illume_rib::Parser::new(reader, &name).map(|r| r.map_err(from_rib_diagnostic)),
    ));
    ri.finish();
    let diagnostics = ri.drain_diagnostics();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    ri.take_frames()
}

fn translation(m: &glam::DMat4) -> [f64; 3] {
    m.transform_point3(glam::DVec3::ZERO).to_array()
}

/// The camera-space bound of a unit sphere is centred on the sphere's centre.
fn assert_centred_at(p: &illume_ri::FramePrimitive, centre: [f32; 3]) {
    let b = p.primitive.bound();
    let got = (b.min + b.max) * 0.5;
    let ok = (0..3).all(|i| (got[i] - centre[i]).abs() < 1e-4);
    assert!(ok, "bound {b:?} is not centred at {centre:?}");
}

#[test]
fn an_archive_read_before_world_begin_sets_the_camera_for_the_frame() {
    let camera =
        "Format 32 24 1\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 5\nColor [1 0 0]\n";
    let main = "FrameBegin 1\nReadArchive \"camera.rib\"\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";
    let frames = frames_of("camera", &[("camera.rib", camera), ("main.rib", main)]);
    assert_eq!(frames.len(), 1);
    let f = &frames[0];
    assert_eq!((f.options.xres, f.options.yres), (32, 24));
    assert_eq!(f.options.projection, Projection::Perspective { fov: 40.0 });
    // Camera from world: the archive's Translate, so the sphere sits 5 units in front of the eye.
    let world = f
        .coordinate_systems
        .iter()
        .find(|(n, _)| n == "world")
        .map(|(_, m)| *m)
        .expect("a world space");
    assert_eq!(translation(&world), [0.0, 0.0, 5.0]);
    assert_eq!(f.primitives.len(), 1);
    assert_eq!(f.primitives[0].attributes.color, [1.0, 0.0, 0.0]);
    assert_centred_at(&f.primitives[0], [0.0, 0.0, 5.0]);
}

#[test]
fn lights_and_attributes_of_an_archive_in_the_world_persist_but_procedurals_are_scoped() {
    let lights = "LightSource \"pointlight\" 1\nColor [1 0 0]\n";
    // A delayed archive's state must not leak into what follows it.
    let leaf = "Color [0 1 0]\nIlluminate 1 0\nSphere 1 -1 1 360\n";
    let main = "Format 32 24 1\nProjection \"perspective\" \"fov\" [40]\nWorldBegin\n\
        Translate 0 0 5\nReadArchive \"lights.rib\"\n\
        Procedural \"DelayedReadArchive\" [\"leaf.rib\"] [-1 1 -1 1 -1 1]\n\
        Sphere 1 -1 1 360\nWorldEnd\n";
    let frames = frames_of(
        "lights",
        &[
            ("lights.rib", lights),
            ("leaf.rib", leaf),
            ("main.rib", main),
        ],
    );
    let f = &frames[0];
    assert_eq!(f.lights.len(), 1);
    assert_eq!(f.primitives.len(), 2);
    let (inside, after) = (&f.primitives[0].attributes, &f.primitives[1].attributes);
    assert_eq!(
        (inside.color, inside.lights.clone()),
        ([0.0, 1.0, 0.0], vec![])
    );
    assert_eq!(
        (after.color, after.lights.clone()),
        ([1.0, 0.0, 0.0], vec![0])
    );
    // The main file's Translate holds for both, the archives changed no transformation.
    assert_centred_at(&f.primitives[0], [0.0, 0.0, 5.0]);
    assert_centred_at(&f.primitives[1], [0.0, 0.0, 5.0]);
}
