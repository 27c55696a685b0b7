//! Issue 23, part 4, at test sizes: object instances share their definition (one primitive
//! per instance, split by the hider) and render the pixels of the replayed object, and the
//! RIB parser streams. The 10⁶- and 10⁷-sphere scenes and the 1 GB RIB are measurements
//! (`rib/bench/big_scenes.py`, README "Big scenes"), not tests.
use illume_ri::Frame;
use std::fmt::Write;
use std::io::Read;

mod support;

/// A 96×96 orthographic frame, lit, with `world` inside.
fn scene(world: &str) -> String {
    format!(
        "Format 96 96 1\nPixelSamples 2 2\nProjection \"orthographic\"\nScreenWindow -1 1 -1 1\n\
         Translate 0 0 10\nWorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 -1] \"to\" [0 0 0]\n\
         Surface \"plastic\"\n{world}WorldEnd\n"
    )
}

/// An object of `m`² small spheres and tori on a grid, with nested blocks, a rotation and
/// a skew, so that the instance's build has to follow the same matrix products as replaying.
fn object_body(m: usize) -> String {
    let mut s = String::new();
    for i in 0..m * m {
        let (x, y) = (
            (i % m) as f32 / m as f32 - 0.45,
            (i / m) as f32 / m as f32 - 0.45,
        );
        let r = 0.4 / m as f32;
        write!(
            s,
            "TransformBegin\nTranslate {x} {y} 0\nRotate {} 0.3 1 0.2\n",
            17 * i
        )
        .unwrap();
        if i % 3 == 0 {
            writeln!(
                s,
                "AttributeBegin\nSkew 20 0 1 0 1 0 0\nTorus {} {} 0 360 360\nAttributeEnd",
                r * 0.7,
                r * 0.3
            )
            .unwrap();
        } else {
            writeln!(s, "Sphere {r} {} {r} 300", -r).unwrap();
        }
        s.push_str("TransformEnd\n");
    }
    s
}

/// `k`² placements (one of them mirrored by a negative scale) of whatever `instance` writes.
fn placements(k: usize, instance: &str) -> String {
    let mut s = String::new();
    for i in 0..k * k {
        let (x, y) = (
            ((i % k) as f32 + 0.5) * 2.0 / k as f32 - 1.0,
            ((i / k) as f32 + 0.5) * 2.0 / k as f32 - 1.0,
        );
        let sx = if i == 1 { -1.0 } else { 1.0 };
        let c = 2.0 / k as f32;
        write!(
            s,
            "AttributeBegin\nColor [{} 0.5 {}]\nTranslate {x} {y} {}\nScale {} {c} {c}\n{instance}AttributeEnd\n",
            (i % 5) as f32 / 4.0,
            (i % 3) as f32 / 2.0,
            i as f32 * 0.01,
            sx * c
        )
        .unwrap();
    }
    s
}

fn one_frame(rib: &str) -> Frame {
    let mut frames = support::frames(rib, None);
    assert_eq!(frames.len(), 1);
    frames.remove(0)
}

fn pixels(frame: &Frame) -> Vec<f32> {
    let settings = illume_render::RenderSettings {
        progress: None,
        textures: None,
    };
    illume_render::render(frame, &settings).rgba
}

/// The same scene as instances of one object and with the object's requests written out at
/// every placement: one primitive per instance instead of one per request, and the same bits
/// (the instance builds its primitives under the same matrices and attributes).
#[test]
fn shared_instances_render_the_pixels_of_replayed_ones() {
    let (k, m) = (4, 3);
    let body = object_body(m);
    let instanced = scene(&format!(
        "ObjectBegin 7\n{body}ObjectEnd\n{}",
        placements(k, "ObjectInstance 7\n")
    ));
    let explicit = scene(&placements(
        k,
        &format!("AttributeBegin\n{body}AttributeEnd\n"),
    ));
    let (a, b) = (one_frame(&instanced), one_frame(&explicit));
    assert_eq!(a.primitives.len(), k * k, "one primitive per instance");
    assert_eq!(b.primitives.len(), k * k * m * m);
    assert_eq!(a.primitives.iter().filter(|p| p.mirrored).count(), 1);
    let (pa, pb) = (pixels(&a), pixels(&b));
    let covered = pb.chunks(4).filter(|p| p[3] > 0.0).count();
    assert!(
        covered > 96 * 96 / 10,
        "the scene is on screen: {covered} pixels"
    );
    let differ = pa.iter().zip(&pb).filter(|(x, y)| x != y).count();
    assert_eq!(differ, 0, "{differ} of {} values differ", pa.len());
}

/// `n` overlapping placements at one depth on a grid (so that which instance wins a sample
/// depends on the order they were given in), `instance` inside each `TransformBegin` block,
/// with a sphere of its own after the `cut`-th (ending the run of instances there).
fn run_of_placements(n: usize, cut: usize, instance: &str) -> String {
    let k = (n as f32).sqrt().ceil() as usize;
    let c = 2.0 / k as f32;
    let mut s = String::new();
    for i in 0..n {
        let (x, y) = (
            ((i % k) as f32 + 0.5) * c - 1.0,
            ((i / k) as f32 + 0.5) * c - 1.0,
        );
        let sc = 1.6 * c;
        write!(
            s,
            "TransformBegin\nTranslate {x} {y} 0\nRotate {} 0 0 1\nScale {sc} {sc} {sc}\n{instance}TransformEnd\n",
            7 * i
        )
        .unwrap();
        if i == cut {
            s.push_str("Sphere 0.05 -0.05 0.05 360\n");
        }
    }
    s
}

/// A run of instances under the same attributes is one primitive (a batch the hider splits
/// into parts and then instances) and renders the bits of the replayed object, overlaps at
/// equal depth included (the batch keeps the instances' order). A primitive between them
/// ends the run.
#[test]
fn a_run_of_instances_is_one_batch_with_the_pixels_of_replayed_ones() {
    let (n, m) = (300, 2);
    // Overlapping coplanar disks, turned differently, tie in depth: their colours show which
    // instance comes first.
    let body = format!(
        "{}Disk 0 0.5 360 \"varying color Cs\" [1 0 0 0 1 0 0 0 1 1 1 0]\n",
        object_body(m)
    );
    let instanced = scene(&format!(
        "ObjectBegin 7\n{body}ObjectEnd\n{}",
        run_of_placements(n, 100, "ObjectInstance 7\n")
    ));
    let explicit = scene(&run_of_placements(
        n,
        100,
        &format!("AttributeBegin\n{body}AttributeEnd\n"),
    ));
    let (a, b) = (one_frame(&instanced), one_frame(&explicit));
    let batches: Vec<String> = a
        .primitives
        .iter()
        .map(|p| format!("{:?}", p.primitive))
        .collect();
    assert_eq!(batches.len(), 3, "two runs and the sphere: {batches:?}");
    assert!(batches[0].contains("instances: 101"), "{}", batches[0]);
    assert!(batches[2].contains("instances: 199"), "{}", batches[2]);
    assert_eq!(b.primitives.len(), n * (m * m + 1) + 1);
    let (pa, pb) = (pixels(&a), pixels(&b));
    let covered = pb.chunks(4).filter(|p| p[3] > 0.0).count();
    assert!(
        covered > 96 * 96 / 2,
        "the scene is on screen: {covered} pixels"
    );
    let differ = pa.iter().zip(&pb).filter(|(x, y)| x != y).count();
    assert_eq!(differ, 0, "{differ} of {} values differ", pa.len());
}

/// A batch splits into at most 16 parts of contiguous instances, each inside the batch's
/// bound (a part outside it would reach a band of buckets already rendered), down to the
/// instances themselves, in the order they were given.
#[test]
fn a_batch_splits_into_parts_inside_its_bound_keeping_the_order() {
    let n = 1000;
    let rib = scene(&format!(
        "ObjectBegin 1\nSphere 0.5 -0.5 0.5 360\nObjectEnd\n{}",
        run_of_placements(n, n, "ObjectInstance 1\n")
    ));
    let mut frame = one_frame(&rib);
    assert_eq!(frame.primitives.len(), 1);
    let inside = |inner: illume_geom::Bound, outer: illume_geom::Bound| {
        inner.min.cmpge(outer.min).all() && inner.max.cmple(outer.max).all()
    };
    // Depth first, the leaves' x centres in visiting order: the placements' order.
    let mut stack = vec![(frame.primitives.remove(0).primitive, 0)];
    let mut centres = Vec::new();
    while let Some((p, depth)) = stack.pop() {
        let name = format!("{p:?}");
        if !name.starts_with("InstanceBatch") {
            let b = p.bound();
            centres.push(((b.min + b.max) / 2.0).truncate());
            continue;
        }
        let parts = p.split();
        assert!((2..=16).contains(&parts.len()), "{name}: {}", parts.len());
        for part in &parts {
            assert!(inside(part.bound(), p.bound()), "{part:?} outside {name}");
        }
        assert!(depth < 4, "{name} at depth {depth}");
        stack.extend(parts.into_iter().rev().map(|q| (q, depth + 1)));
    }
    assert_eq!(centres.len(), n);
    let k = (n as f32).sqrt().ceil() as usize;
    let c = 2.0 / k as f32;
    for (i, got) in centres.iter().enumerate() {
        let want = glam::Vec2::new(
            ((i % k) as f32 + 0.5) * c - 1.0,
            ((i / k) as f32 + 0.5) * c - 1.0,
        );
        assert!(
            (*got - want).length() < 1e-4,
            "instance {i} at {got}, want {want}"
        );
    }
}

/// Objects that change attributes or use absolute transformations keep being replayed (their
/// primitives depend on the state at the instance), with the same result as before.
#[test]
fn objects_with_attributes_or_absolute_transforms_are_replayed() {
    for inside in [
        "Color [1 0 0]\n",
        "Identity\n",
        "Basis \"bezier\" 3 \"bezier\" 3\n",
    ] {
        let rib = scene(&format!(
            "ObjectBegin 1\n{inside}Sphere 0.1 -0.1 0.1 360\nObjectEnd\n{}",
            placements(2, "ObjectInstance 1\n")
        ));
        let frame = one_frame(&rib);
        assert_eq!(frame.primitives.len(), 4, "{inside}");
        assert!(
            frame
                .primitives
                .iter()
                .all(|p| format!("{:?}", p.primitive).starts_with("Parametric")),
            "{inside}: replayed primitives are the built spheres"
        );
    }
}

/// A reader of `total` bytes of RIB (one sphere per line) that counts how much was read.
struct Spheres {
    total: u64,
    read: std::rc::Rc<std::cell::Cell<u64>>,
}

const LINE: &[u8] = b"Sphere 1 -1 1 360 \"uniform float k\" [0.5]\n";

impl Read for Spheres {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let at = self.read.get();
        let n = (buf.len() as u64).min(self.total - at) as usize;
        for (i, b) in buf[..n].iter_mut().enumerate() {
            *b = LINE[((at + i as u64) % LINE.len() as u64) as usize];
        }
        self.read.set(at + n as u64);
        Ok(n)
    }
}

/// The parser streams: from a 1 GB input it hands out the first request after reading one
/// chunk, and after 10⁵ requests it has read only what they took (plus one chunk), so parse
/// memory does not grow with the file.
#[test]
fn the_parser_reads_a_gigabyte_stream_a_chunk_at_a_time() {
    let read = std::rc::Rc::new(std::cell::Cell::new(0));
    let source = Spheres {
        total: 1 << 30,
        read: read.clone(),
    };
    let mut parser = illume_rib::Parser::new(source, "big.rib");
    let first = parser.next().unwrap().unwrap();
    assert_eq!(first.value.name(), "Sphere");
    assert!(
        read.get() <= 1 << 20,
        "read {} bytes for one request",
        read.get()
    );
    let line = LINE.len() as u64;
    for _ in 1..100_000 {
        parser.next().unwrap().unwrap();
    }
    let ahead = read.get() - 100_000 * line;
    assert!(ahead <= 1 << 20, "read {ahead} bytes beyond 10⁵ requests");
}

/// A 16×16-quad `PointsPolygons` with per-vertex colour: as one request (kept as its request
/// and built when the hider splits it) and cut into strips of 8 faces with their own vertices
/// (below the deferral threshold: built at once, one primitive per face). Same faces, same
/// numbers, same bits.
#[test]
fn a_deferred_mesh_renders_the_pixels_of_its_faces() {
    let q = 16;
    let vertex = |i: usize, j: usize| {
        let (x, y) = (
            i as f32 / q as f32 * 1.6 - 0.8,
            j as f32 / q as f32 * 1.6 - 0.8,
        );
        let z = 0.1 * (3.0 * x + 2.0 * y).sin();
        (
            format!("{x} {y} {z} "),
            format!("{} {} 0.5 ", i as f32 / q as f32, j as f32 / q as f32),
        )
    };
    // The quads of columns i0..i1 in rows j0..j1, indexing their own vertex block.
    let mesh = |i0: usize, i1: usize, j0: usize, j1: usize| {
        let w = i1 - i0 + 1;
        let (mut p, mut cs, mut verts) = (String::new(), String::new(), String::new());
        for j in j0..=j1 {
            for i in i0..=i1 {
                let (pv, cv) = vertex(i, j);
                p.push_str(&pv);
                cs.push_str(&cv);
            }
        }
        for j in 0..j1 - j0 {
            for i in 0..w - 1 {
                let a = j * w + i;
                write!(verts, "{a} {} {} {} ", a + 1, a + w + 1, a + w).unwrap();
            }
        }
        let nverts = "4 ".repeat((w - 1) * (j1 - j0));
        format!("PointsPolygons [{nverts}] [{verts}] \"P\" [{p}] \"Cs\" [{cs}]\n")
    };
    let whole = scene(&format!("Rotate 30 1 0.5 0\n{}", mesh(0, q, 0, q)));
    let strips: String = (0..q)
        .flat_map(|j| [mesh(0, 8, j, j + 1), mesh(8, q, j, j + 1)])
        .collect();
    let cut = scene(&format!("Rotate 30 1 0.5 0\n{strips}"));
    let (a, b) = (one_frame(&whole), one_frame(&cut));
    assert_eq!(a.primitives.len(), 1, "kept as one request");
    assert_eq!(b.primitives.len(), q * q);
    let (pa, pb) = (pixels(&a), pixels(&b));
    let covered = pb.chunks(4).filter(|p| p[3] > 0.0).count();
    assert!(
        covered > 96 * 96 / 4,
        "the mesh is on screen: {covered} pixels"
    );
    let differ = pa.iter().zip(&pb).filter(|(x, y)| x != y).count();
    assert_eq!(differ, 0, "{differ} of {} values differ", pa.len());
}
