//! Motion blocks in the RI state: what keys the primitives get, and the errors.
use illume_ri::{from_rib_diagnostic, Frame, Ri, Severity};

fn run(rib: &str) -> (Vec<Frame>, Vec<String>) {
    let mut ri = Ri::new();
    let parser = illume_rib::Parser::new(std::io::Cursor::new(rib.as_bytes().to_vec()), "t.rib");
    for item in parser {
        match item {
            Ok(r) => ri.request(r),
            Err(d) => ri.report(from_rib_diagnostic(d)),
        }
    }
    ri.finish();
    let errors = ri
        .drain_diagnostics()
        .into_iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| d.to_string())
        .collect();
    (ri.take_frames(), errors)
}

/// Centre of a primitive's camera-space bound.
fn centre(p: &dyn illume_geom::Primitive) -> [f32; 3] {
    let b = p.bound();
    ((b.min + b.max) * 0.5).to_array()
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-4)
}

#[test]
fn blocks_that_cancel_leave_the_primitive_still() {
    // Aqsis transmb_test's first ball: +1/−1 then −1/+1 over [0 1] is no motion at all.
    let (f, e) = run("WorldBegin\nTranslate 1 0 5\nMotionBegin [0 1]\nTranslate 1 0 0\nTranslate -1 0 0\nMotionEnd\n\
         MotionBegin [0 1]\nTranslate -1 0 0\nTranslate 1 0 0\nMotionEnd\nSphere 1 -1 1 360\nWorldEnd\n");
    assert!(e.is_empty(), "{e:?}");
    let p = &f[0].primitives[0];
    assert!(p.motion.is_none());
    assert!(close(centre(p.primitive.as_ref()), [1.0, 0.0, 5.0]));
}

#[test]
fn transforms_after_the_block_apply_to_every_key_and_camera_motion_reaches_the_world() {
    let (f, e) = run(
        "MotionBegin [0 1]\nTranslate 0 0 5\nTranslate 0 2 5\nMotionEnd\nWorldBegin\n\
         MotionBegin [0 0.5 1]\nTranslate 0 0 0\nTranslate 1 0 0\nTranslate 4 0 0\nMotionEnd\n\
         Scale 2 2 2\nTranslate 1 0 0\nSphere 1 -1 1 360\nWorldEnd\n",
    );
    assert!(e.is_empty(), "{e:?}");
    let p = &f[0].primitives[0];
    let m = p.motion.as_ref().expect("moving");
    assert_eq!(m.times, vec![0.0, 0.5, 1.0]);
    // Centre: camera (0, 2t, 5) + object x(t) + Scale 2 · Translate 1 = x(t) + 2.
    assert!(close(centre(p.primitive.as_ref()), [2.0, 0.0, 5.0]));
    assert!(close(centre(m.later[0].as_ref()), [3.0, 1.0, 5.0]));
    assert!(close(centre(m.later[1].as_ref()), [6.0, 2.0, 5.0]));
}

#[test]
fn a_block_with_the_wrong_count_is_an_error_with_its_span() {
    let (f, e) = run(
        "WorldBegin\nMotionBegin [0 0.5 1]\nTranslate 1 0 0\nTranslate 2 0 0\nMotionEnd\n\
         Translate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n",
    );
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(
        e[0].starts_with("t.rib:3:1: error: Translate: MotionBegin gave 3 times"),
        "{}",
        e[0]
    );
    // The first transformation is used.
    let p = &f[0].primitives[0];
    assert!(p.motion.is_none());
    assert!(close(centre(p.primitive.as_ref()), [1.0, 0.0, 5.0]));
}

#[test]
fn deformation_keys_of_another_topology_are_an_error() {
    let (f, e) = run("WorldBegin\nTranslate 0 0 5\nMotionBegin [0 1]\nPolygon \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n\
         PointsPolygons [4 4] [0 1 2 3 1 4 5 2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 2 0 0 2 1 0]\nMotionEnd\nWorldEnd\n");
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(e[0].contains("topology"), "{}", e[0]);
    assert_eq!(f[0].primitives.len(), 1);
    assert!(f[0].primitives[0].motion.is_none());
}

#[test]
fn shutter_and_depth_of_field_options() {
    let (f, e) = run(
        "Shutter 0.25 0.75\nDepthOfField 2.8 0.5 4\nWorldBegin\nWorldEnd\n\
         Shutter 1 0\nDepthOfField\nWorldBegin\nWorldEnd\n",
    );
    assert_eq!(e.len(), 1, "{e:?}");
    assert!(e[0].contains("Shutter"), "{}", e[0]);
    assert_eq!(f[0].options.shutter, [0.25, 0.75]);
    assert_eq!(f[0].options.depth_of_field, Some([2.8, 0.5, 4.0]));
    assert_eq!(f[1].options.shutter, [0.25, 0.75]);
    assert_eq!(f[1].options.depth_of_field, None);
}
