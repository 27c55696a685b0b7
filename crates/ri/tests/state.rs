//! The RI state machine fed with requests built in code.
use illume_ri::{Ri, Severity};
use illume_rib::{Handle, Request, Span, Spanned};
use std::sync::Arc;

fn at(line: u32, value: Request) -> Spanned<Request> {
    Spanned {
        span: Span::new(Arc::from("scene.rib"), line, 1, 0),
        value,
    }
}

fn feed(reqs: Vec<Request>) -> Ri {
    let mut ri = Ri::new();
    for (i, r) in reqs.into_iter().enumerate() {
        ri.request(at(i as u32 + 1, r));
    }
    ri
}

#[test]
fn mismatched_end_is_an_error_with_span_and_the_stack_recovers() {
    let mut ri = feed(vec![
        Request::WorldBegin,
        Request::AttributeBegin,
        Request::Color(vec![1.0, 0.0, 0.0]),
        Request::TransformBegin,
        Request::AttributeEnd, // closes TransformBegin implicitly: an error
        Request::Color(vec![0.5, 0.5, 0.5]),
    ]);
    let d = ri.drain_diagnostics();
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].severity, Severity::Error);
    assert!(
        d[0].to_string()
            .starts_with("scene.rib:5:1: error: AttributeEnd: TransformBegin at scene.rib:4:1"),
        "{}",
        d[0]
    );
    // The attribute block was closed too: the colour set inside it is gone.
    assert_eq!(ri.attributes().color, [0.5, 0.5, 0.5]);
    ri.request(at(7, Request::WorldEnd));
    assert_eq!(ri.take_frames().len(), 1);
    assert_eq!(ri.error_count(), 1);
}

#[test]
fn options_inside_world_are_errors_and_ignored() {
    let mut ri = feed(vec![
        Request::WorldBegin,
        Request::Format {
            xres: 10,
            yres: 10,
            pixel_aspect: 1.0,
        },
    ]);
    assert_eq!(ri.options().xres, 640);
    assert_eq!(ri.drain_diagnostics()[0].severity, Severity::Error);
}

#[test]
fn display_plus_appends_and_plain_replaces() {
    let d = |name: &str| Request::Display {
        name: name.into(),
        kind: "tiff".into(),
        mode: "rgba".into(),
        params: vec![],
    };
    let ri = feed(vec![d("a.tif"), d("+b.tif"), d("+c.tif")]);
    let names: Vec<_> = ri
        .options()
        .displays
        .iter()
        .map(|d| d.name.as_str())
        .collect();
    assert_eq!(names, ["a.tif", "b.tif", "c.tif"]);
    let ri = feed(vec![d("a.tif"), d("z.tif")]);
    assert_eq!(ri.options().displays.len(), 1);
}

#[test]
fn reused_light_handle_replaces_the_light() {
    let light = |name: &str| Request::LightSource {
        name: name.into(),
        handle: Handle::Int(1),
        params: vec![],
    };
    let mut ri = feed(vec![
        Request::WorldBegin,
        light("pointlight"),
        light("distantlight"),
        Request::Illuminate {
            handle: Handle::Str("nope".into()),
            on: true,
        },
        Request::WorldEnd,
    ]);
    let f = ri.take_frames();
    assert_eq!(f[0].lights.len(), 1);
    assert_eq!(f[0].lights[0].shader.name, "distantlight");
    assert_eq!(ri.error_count(), 1, "unknown handle");
}

#[test]
fn warnings_are_deduplicated() {
    // RelativeDetail is still unsupported (warned); Shutter, used here before, now works.
    let mut ri = feed(vec![
        Request::RelativeDetail(1.0),
        Request::RelativeDetail(1.0),
    ]);
    assert_eq!(ri.drain_diagnostics().len(), 1);
}

#[test]
fn inline_archive_and_object_instance_replay() {
    let sphere = Request::Sphere {
        radius: 1.0,
        zmin: -1.0,
        zmax: 1.0,
        thetamax: 360.0,
        params: vec![],
    };
    let mut ri = feed(vec![
        Request::ArchiveBegin {
            name: "a".into(),
            params: vec![],
        },
        sphere.clone(),
        Request::ArchiveEnd,
        Request::ObjectBegin(Handle::Int(3)),
        sphere,
        Request::ObjectEnd,
        Request::WorldBegin,
        Request::Translate([0.0, 0.0, 5.0]),
        Request::ReadArchive {
            name: "a".into(),
            params: vec![],
        },
        Request::ObjectInstance(Handle::Int(3)),
        Request::ObjectInstance(Handle::Int(3)),
        Request::WorldEnd,
    ]);
    assert_eq!(ri.error_count(), 0, "{:?}", ri.drain_diagnostics());
    let f = ri.take_frames();
    // The archive's sphere, and the two instances in a row as one batch of two.
    assert_eq!(f[0].primitives.len(), 2);
    let batch = format!("{:?}", f[0].primitives[1].primitive);
    assert!(batch.contains("instances: 2"), "{batch}");
}

#[test]
fn dynamic_load_is_a_clear_error() {
    let mut ri = feed(vec![
        Request::WorldBegin,
        Request::Procedural {
            name: "DynamicLoad".into(),
            args: vec!["x.so".into()],
            bound: [0.0; 6],
        },
    ]);
    let d = ri.drain_diagnostics();
    assert!(d[0].message.contains("unsupported"), "{}", d[0]);
}

#[test]
fn light_shadows_and_nsamples_go_to_lights_declared_under_them_and_transmission_to_geometry() {
    use illume_rib::{Param, Value};
    let attr = |name: &str, p: &str, value: Value| Request::Attribute {
        name: name.into(),
        params: vec![Param {
            name: p.into(),
            value,
        }],
    };
    let s = |v: &str| Value::Strings(vec![v.into()]);
    let light = |h: i32| Request::LightSource {
        name: "pointlight".into(),
        handle: Handle::Int(h),
        params: vec![],
    };
    let sphere = Request::Sphere {
        radius: 1.0,
        zmin: -1.0,
        zmax: 1.0,
        thetamax: 360.0,
        params: vec![],
    };
    let mut ri = feed(vec![
        Request::WorldBegin,
        light(1),
        attr("light", "shadows", s("on")),
        attr("light", "nsamples", Value::Ints(vec![64])),
        light(2),
        sphere.clone(),
        attr("visibility", "string transmission", s("transparent")),
        sphere.clone(),
        attr("render", "casts_shadows", s("Os")),
        sphere.clone(),
        attr("visibility", "transmission", Value::Ints(vec![0])),
        sphere,
        attr("light", "shadows", s("maybe")),
        Request::WorldEnd,
    ]);
    let f = ri.take_frames();
    let lights: Vec<(bool, u32)> = f[0].lights.iter().map(|l| (l.shadows, l.samples)).collect();
    assert_eq!(lights, [(false, 16), (true, 64)]);
    let casts: Vec<bool> = f[0]
        .primitives
        .iter()
        .map(|p| p.attributes.casts_shadows)
        .collect();
    assert_eq!(casts, [true, false, true, false]);
    assert_eq!(ri.error_count(), 1, "\"maybe\" is neither on nor off");
}

/// `Hider "stochastic"` is PRMan's name for the hidden hider: no warning; `"raytrace"` falls back
/// to hidden with one warning, and the hider's parameters still apply.
#[test]
fn hider_stochastic_is_hidden_and_unknown_hiders_warn() {
    let hider = |name: &str| Request::Hider {
        name: name.into(),
        params: Default::default(),
    };
    let mut ri = feed(vec![hider("stochastic"), hider("hidden")]);
    let d = ri.drain_diagnostics();
    assert!(d.is_empty(), "{d:?}");
    let mut ri = feed(vec![hider("raytrace")]);
    let d = ri.drain_diagnostics();
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].severity, Severity::Warning);
    assert!(d[0].to_string().contains("raytrace"), "{}", d[0]);
}
