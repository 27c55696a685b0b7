//! The RI C binding (crates/libillume, include/ri.h) from real C programs built with `cc`:
//! every request's RIB output equals `catrib`'s canonical form of the same request written by
//! hand, bad calls reach the error handler with their RI codes, `RiTransformPoints` matches a
//! closed form, and a program renders the same bits in-process as its captured RIB does.
//!
//! Needs `cargo build -p libillume -p render -p catrib` (as .ci/run does) and a C compiler.
#[path = "support/c_programs.rs"]
mod c_programs;
use c_programs::{compile, run, scratch, tools};
use std::path::Path;
use std::process::Command;

/// (C statement, the same request as hand-written RIB). Floats that the C side passes as
/// parameter values are written with a `.` so the RIB reads them as floats too.
const TABLE: &[(&str, &str)] = &[
    ("RiDeclare(\"Kq\", \"uniform float\");", "Declare \"Kq\" \"uniform float\""),
    ("RiFrameBegin(3);", "FrameBegin 3"),
    ("RiFormat(320, 240, 1.5f);", "Format 320 240 1.5"),
    ("RiFrameAspectRatio(1.25f);", "FrameAspectRatio 1.25"),
    ("RiScreenWindow(-1, 1, -0.75f, 0.75f);", "ScreenWindow -1 1 -0.75 0.75"),
    ("RiCropWindow(0, 0.5f, 0.25f, 1);", "CropWindow 0 0.5 0.25 1"),
    ("RiProjection(RI_PERSPECTIVE, RI_FOV, f1, RI_NULL);", "Projection \"perspective\" \"fov\" [0.5]"),
    ("RiClipping(0.1f, 100);", "Clipping 0.1 100"),
    ("RiClippingPlane(0, 0, 1, 0, 0, -1);", "ClippingPlane 0 0 1 0 0 -1"),
    ("RiDepthOfField(2.8f, 0.05f, 4);", "DepthOfField 2.8 0.05 4"),
    ("RiShutter(0, 0.5f);", "Shutter 0 0.5"),
    ("RiPixelVariance(0.01f);", "PixelVariance 0.01"),
    ("RiPixelSamples(3, 2);", "PixelSamples 3 2"),
    ("RiPixelFilter(RiCatmullRomFilter, 4, 3);", "PixelFilter \"catmull-rom\" 4 3"),
    ("RiPixelFilter(RiBoxFilter, 1, 1);", "PixelFilter \"box\" 1 1"),
    ("RiExposure(1.5f, 2.2f);", "Exposure 1.5 2.2"),
    ("RiImager(\"background\", \"color background\", c3, RI_NULL);", "Imager \"background\" \"color background\" [1.0 0.5 0.25]"),
    ("RiQuantize(RI_RGBA, 255, 0, 255, 0.5f);", "Quantize \"rgba\" 255 0 255 0.5"),
    ("RiDisplay(\"out.tif\", RI_FILE, RI_RGBA, RI_NULL);", "Display \"out.tif\" \"file\" \"rgba\""),
    ("RiHider(RI_HIDDEN, \"uniform integer jitter\", i1, RI_NULL);", "Hider \"hidden\" \"uniform integer jitter\" [1]"),
    ("RiColorSamples(1, c3, c3);", "ColorSamples [1 0.5 0.25] [1 0.5 0.25]"),
    ("RiRelativeDetail(0.5f);", "RelativeDetail 0.5"),
    ("RiOption(\"searchpath\", \"string shader\", s1, RI_NULL);", "Option \"searchpath\" \"string shader\" [\"a:b\"]"),
    ("RiWorldBegin();", "WorldBegin"),
    ("RiAttributeBegin();", "AttributeBegin"),
    ("RiColor(c3);", "Color [1 0.5 0.25]"),
    ("RiOpacity(c3);", "Opacity [1 0.5 0.25]"),
    ("RiTextureCoordinates(0, 0, 1, 0, 0, 1, 1, 1);", "TextureCoordinates 0 0 1 0 0 1 1 1"),
    ("RiLightSource(RI_POINTLIGHT, RI_INTENSITY, f1, RI_NULL);", "LightSource \"pointlight\" 1 \"intensity\" [0.5]"),
    ("RiAreaLightSource(\"arealight\", RI_NULL);", "AreaLightSource \"arealight\" 2"),
    ("RiIlluminate((RtLightHandle)1, RI_FALSE);", "Illuminate 1 0"),
    ("RiSurface(RI_PLASTIC, RI_KS, f1, \"Kq\", f1, RI_NULL);", "Surface \"plastic\" \"Ks\" [0.5] \"Kq\" [0.5]"),
    ("RiDisplacement(\"bumpy\", RI_AMPLITUDE, f1, RI_NULL);", "Displacement \"bumpy\" \"amplitude\" [0.5]"),
    ("RiAtmosphere(\"fog\", RI_NULL);", "Atmosphere \"fog\""),
    ("RiInterior(\"water\", RI_NULL);", "Interior \"water\""),
    ("RiExterior(\"smoke\", RI_NULL);", "Exterior \"smoke\""),
    ("RiDeformation(\"twist\", RI_NULL);", "Deformation \"twist\""),
    ("RiShadingRate(2);", "ShadingRate 2"),
    ("RiShadingInterpolation(RI_SMOOTH);", "ShadingInterpolation \"smooth\""),
    ("RiMatte(RI_TRUE);", "Matte 1"),
    ("RiBound(b6);", "Bound [-1 1 -2 2 -3 3]"),
    ("RiDetail(b6);", "Detail [-1 1 -2 2 -3 3]"),
    ("RiDetailRange(0, 1, 10, 20);", "DetailRange [0 1 10 20]"),
    ("RiGeometricApproximation(RI_FLATNESS, 0.5f);", "GeometricApproximation \"flatness\" 0.5"),
    ("RiGeometricRepresentation(\"lines\");", "GeometricRepresentation \"lines\""),
    ("RiOrientation(RI_RH);", "Orientation \"rh\""),
    ("RiReverseOrientation();", "ReverseOrientation"),
    ("RiSides(1);", "Sides 1"),
    ("RiAttribute(\"identifier\", RI_NAME, s1, RI_NULL);", "Attribute \"identifier\" \"name\" [\"a:b\"]"),
    ("RiIdentity();", "Identity"),
    ("RiTransform(m16);", "Transform [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1]"),
    ("RiConcatTransform(m16);", "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1]"),
    ("RiPerspective(45);", "Perspective 45"),
    ("RiTranslate(1, 2, 3);", "Translate 1 2 3"),
    ("RiRotate(30, 0, 1, 0);", "Rotate 30 0 1 0"),
    ("RiScale(1, 2, 0.5f);", "Scale 1 2 0.5"),
    ("RiSkew(45, 0, 1, 0, 1, 0, 0);", "Skew 45 0 1 0 1 0 0"),
    ("RiCoordinateSystem(\"lamp\");", "CoordinateSystem \"lamp\""),
    ("RiCoordSysTransform(\"lamp\");", "CoordSysTransform \"lamp\""),
    ("RiTransformBegin();", "TransformBegin"),
    ("RiTransformEnd();", "TransformEnd"),
    ("RiMotionBegin(2, 0.0, 1.0);", "MotionBegin [0 1]"),
    ("RiTranslate(0, 0, 0);", "Translate 0 0 0"),
    ("RiTranslate(1, 0, 0);", "Translate 1 0 0"),
    ("RiMotionEnd();", "MotionEnd"),
    ("RiSolidBegin(RI_UNION);", "SolidBegin \"union\""),
    ("RiSolidBegin(RI_PRIMITIVE);", "SolidBegin \"primitive\""),
    ("RiSphere(1, -1, 1, 360, RI_NULL);", "Sphere 1 -1 1 360"),
    ("RiSolidEnd();", "SolidEnd"),
    ("RiSolidEnd();", "SolidEnd"),
    ("RiPolygon(4, RI_P, p12, RI_CS, c12, RI_NULL);", "Polygon \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0] \"Cs\" [1 0 0 0 1 0 0 0 1 1 1 1.0]"),
    ("RiGeneralPolygon(1, nv4, RI_P, p12, RI_NULL);", "GeneralPolygon [4] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0]"),
    ("RiPointsPolygons(1, nv4, v4, RI_P, p12, \"uniform float Kq\", f1, RI_NULL);", "PointsPolygons [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0] \"uniform float Kq\" [0.5]"),
    ("RiPointsGeneralPolygons(1, nl1, nv4, v4, RI_P, p12, RI_NULL);", "PointsGeneralPolygons [1] [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0]"),
    ("RiBasis(RiBezierBasis, RI_BEZIERSTEP, RiCatmullRomBasis, RI_CATMULLROMSTEP);", "Basis \"bezier\" 3 \"catmull-rom\" 1"),
    ("RiBasis(m16, 2, RiPowerBasis, 4);", "Basis [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1] 2 \"power\" 4"),
    ("RiBasis(RiBezierBasis, 3, RiBezierBasis, 3);", "Basis \"bezier\" 3 \"bezier\" 3"),
    ("RiPatch(RI_BILINEAR, RI_P, p12, RI_NULL);", "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0]"),
    ("RiPatchMesh(RI_BILINEAR, 2, RI_NONPERIODIC, 2, RI_NONPERIODIC, RI_P, p12, \"varying float Kq\", f4, RI_NULL);", "PatchMesh \"bilinear\" 2 \"nonperiodic\" 2 \"nonperiodic\" \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0] \"varying float Kq\" [0.5 0.5 0.5 0.5]"),
    ("RiNuPatch(2, 2, k4, 0, 1, 2, 2, k4, 0, 1, RI_P, p12, RI_NULL);", "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0]"),
    ("RiTrimCurve(1, nl1, o2, k4, f0, f1, n2, f4, f4, f4);", "TrimCurve [1] [2] [0 0 1 1] [0] [0.5] [2] [0.5 0.5] [0.5 0.5] [0.5 0.5]"),
    ("RiCone(1, 0.5f, 360, RI_NULL);", "Cone 1 0.5 360"),
    ("RiCylinder(1, -1, 1, 270, RI_NULL);", "Cylinder 1 -1 1 270"),
    ("RiHyperboloid(p12, p12 + 3, 360, RI_NULL);", "Hyperboloid 0 0 0 1 0 0 360"),
    ("RiParaboloid(1, 0, 2, 360, RI_NULL);", "Paraboloid 1 0 2 360"),
    ("RiDisk(0.5f, 1, 360, RI_NULL);", "Disk 0.5 1 360"),
    ("RiTorus(1, 0.25f, 0, 360, 360, \"varying color Cs\", c12, RI_NULL);", "Torus 1 0.25 0 360 360 \"varying color Cs\" [1 0 0 0 1 0 0 0 1 1 1 1.0]"),
    ("RiPoints(4, RI_P, p12, RI_CONSTANTWIDTH, f1, RI_NULL);", "Points \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0] \"constantwidth\" [0.5]"),
    ("RiCurves(RI_LINEAR, 1, nv4, RI_NONPERIODIC, RI_P, p12, RI_WIDTH, f4, RI_NULL);", "Curves \"linear\" [4] \"nonperiodic\" \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0] \"width\" [0.5 0.5 0.5 0.5]"),
    ("RiCurves(RI_CUBIC, 1, nv4, RI_NONPERIODIC, RI_P, p12, RI_WIDTH, f4, RI_NULL);", "Curves \"cubic\" [4] \"nonperiodic\" \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0] \"width\" [0.5 0.5]"),
    ("RiSubdivisionMesh(\"catmull-clark\", 1, nv4, v4, 1, tags, na2, i1, f0, RI_P, p12, RI_NULL);", "SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"interpolateboundary\"] [1 0] [1] [] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0.0]"),
    ("RiBlobby(1, 2, code2, 16, m16f, 0, NULL, RI_NULL);", "Blobby 1 [1001 0] [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1] []"),
    ("RiProcedural((RtPointer)dra, b6, RiProcDelayedReadArchive, NULL);", "Procedural \"DelayedReadArchive\" [\"part.rib\"] [-1 1 -2 2 -3 3]"),
    ("RiProcedural((RtPointer)prog, b6, RiProcRunProgram, NULL);", "Procedural \"RunProgram\" [\"gen\" \"1 2\"] [-1 1 -2 2 -3 3]"),
    ("RiGeometry(\"teapot\", RI_NULL);", "Geometry \"teapot\""),
    ("RiObjectBegin();", "ObjectBegin 3"),
    ("RiObjectEnd();", "ObjectEnd"),
    ("RiObjectInstance((RtObjectHandle)3);", "ObjectInstance 3"),
    ("RiArchiveRecord(RI_STRUCTURE, \"Frames %d\", 5);", "##Frames 5"),
    ("RiArchiveRecord(RI_VERBATIM, \"Sides 2\\n\");", "Sides 2"),
    ("RiReadArchive(\"part.rib\", NULL, RI_NULL);", "ReadArchive \"part.rib\""),
    ("RiAttributeEnd();", "AttributeEnd"),
    ("RiWorldEnd();", "WorldEnd"),
    ("RiMakeTexture(\"a.tif\", \"a.tx\", RI_PERIODIC, RI_CLAMP, RiGaussianFilter, 2, 2, RI_NULL);", "MakeTexture \"a.tif\" \"a.tx\" \"periodic\" \"clamp\" \"gaussian\" 2 2"),
    ("RiMakeBump(\"a.tif\", \"a.bump\", RI_BLACK, RI_CLAMP, RiTriangleFilter, 2, 2, RI_NULL);", "MakeBump \"a.tif\" \"a.bump\" \"black\" \"clamp\" \"triangle\" 2 2"),
    ("RiMakeLatLongEnvironment(\"a.tif\", \"a.env\", RiSincFilter, 2, 2, RI_NULL);", "MakeLatLongEnvironment \"a.tif\" \"a.env\" \"sinc\" 2 2"),
    ("RiMakeCubeFaceEnvironment(\"px\", \"nx\", \"py\", \"ny\", \"pz\", \"nz\", \"c.env\", 95, RiBoxFilter, 1, 1, RI_NULL);", "MakeCubeFaceEnvironment \"px\" \"nx\" \"py\" \"ny\" \"pz\" \"nz\" \"c.env\" 95 \"box\" 1 1"),
    ("RiMakeShadow(\"d.z\", \"d.sm\", RI_NULL);", "MakeShadow \"d.z\" \"d.sm\""),
    ("RiFrameEnd();", "FrameEnd"),
];

/// The variables the table's C statements use.
const PRELUDE: &str = r#"
  RtFloat f0[1] = {0}, f1[1] = {0.5f}, f4[4] = {0.5f, 0.5f, 0.5f, 0.5f};
  RtColor c3 = {1, 0.5f, 0.25f};
  RtFloat p12[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  RtFloat c12[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  RtBound b6 = {-1, 1, -2, 2, -3, 3};
  RtMatrix m16 = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {1, 2, 3, 1}};
  RtFloat *m16f = &m16[0][0];
  RtFloat k4[4] = {0, 0, 1, 1};
  RtInt i1[1] = {1}, nv4[1] = {4}, v4[4] = {0, 1, 2, 3}, nl1[1] = {1}, o2[1] = {2}, n2[1] = {2};
  RtInt na2[2] = {1, 0}, code2[2] = {1001, 0};
  RtToken tags[1] = {"interpolateboundary"};
  RtString s1[1] = {"a:b"}, dra[1] = {"part.rib"}, prog[2] = {"gen", "1 2"};
  (void)f0; (void)f4; (void)c12; (void)k4; (void)tags; (void)m16f;
"#;

#[test]
fn every_request_writes_catribs_canonical_rib() {
    let Some(t) = tools() else { return };
    let dir = scratch("table");
    let body: String = TABLE.iter().map(|(c, _)| format!("  {c}\n")).collect();
    let prog = format!(
        "#include <ri.h>\n#include <stddef.h>\nint main(void) {{\n{PRELUDE}\n  RiErrorHandler(RiErrorIgnore);\n  RiBegin(\"c.rib\");\n{body}  RiEnd();\n  return 0;\n}}\n"
    );
    let exe = compile(&t, &dir, &prog);
    run(&exe, &dir, &[]);
    let hand: String = TABLE.iter().map(|(_, r)| format!("{r}\n")).collect();
    std::fs::write(dir.join("hand.rib"), format!("##RenderMan RIB\n{hand}")).unwrap();
    let out = Command::new(&t.catrib)
        .arg("hand.rib")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "catrib: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let want = String::from_utf8(out.stdout).unwrap();
    let got = std::fs::read_to_string(dir.join("c.rib")).unwrap();
    let (want, got): (Vec<&str>, Vec<&str>) = (want.lines().collect(), got.lines().collect());
    // Line 0 is the header; line i+1 is table row i.
    for (i, (w, g)) in want.iter().zip(&got).enumerate() {
        let call = if i == 0 { "header" } else { TABLE[i - 1].0 };
        assert_eq!(g, w, "{call}");
    }
    assert_eq!(got.len(), want.len(), "request count");
    assert_eq!(got.len(), TABLE.len() + 1);
}

/// The table's requests, as the parser reads them back from `path` (ASCII, binary or gzip).
fn parsed(path: &Path) -> Vec<illume_rib::Request> {
    illume_rib::open(path)
        .unwrap()
        .map(|r| {
            r.unwrap_or_else(|d| panic!("{}: {d}", path.display()))
                .value
        })
        .collect()
}

#[test]
fn binary_and_gzip_rib_output_read_back_as_the_ascii_requests() {
    let Some(t) = tools() else { return };
    let dir = scratch("formats");
    let body: String = TABLE.iter().map(|(c, _)| format!("  {c}\n")).collect();
    // One session per encoding; the options go right after RiBegin, as PRMan's do.
    let sessions = [
        ("ascii.rib", ""),
        (
            "binary.rib",
            "RiOption(\"rib\", \"string format\", fmt, RI_NULL);",
        ),
        (
            "gzip.rib",
            "RiOption(\"rib\", \"string compression\", gz, RI_NULL);",
        ),
        (
            "both.rib",
            "RiOption(\"rib\", \"string format\", fmt, \"string compression\", gz, RI_NULL);",
        ),
        ("suffix.rib.gz", ""),
    ];
    let runs: String = sessions
        .iter()
        .map(|(file, opt)| format!("  RiBegin(\"{file}\");\n  {opt}\n{body}  RiEnd();\n"))
        .collect();
    let prog = format!(
        "#include <ri.h>\n#include <stddef.h>\nint main(void) {{\n{PRELUDE}\n  RtString fmt[1] = {{\"binary\"}}, gz[1] = {{\"gzip\"}};\n  RiErrorHandler(RiErrorIgnore);\n{runs}  return 0;\n}}\n"
    );
    let exe = compile(&t, &dir, &prog);
    run(&exe, &dir, &[]);
    let ascii = parsed(&dir.join("ascii.rib"));
    assert_eq!(ascii.len(), TABLE.len() + 1, "header + one request per row");
    for (file, _) in &sessions[1..] {
        let bytes = std::fs::read(dir.join(file)).unwrap();
        let gzip = bytes.starts_with(&[0x1f, 0x8b]);
        assert_eq!(
            gzip,
            file.contains("gz") || file.starts_with("both"),
            "{file}"
        );
        let got = parsed(&dir.join(file));
        for (i, (g, w)) in got.iter().zip(&ascii).enumerate() {
            let call = if i == 0 { "header" } else { TABLE[i - 1].0 };
            assert_eq!(g, w, "{file}: {call}");
        }
        assert_eq!(got.len(), ascii.len(), "{file}");
    }
    // The binary files really are binary (request definitions, RI 3.2 Appendix C: 0314).
    let binary = std::fs::read(dir.join("binary.rib")).unwrap();
    assert!(
        binary.contains(&0xcc) && binary.contains(&0xa6),
        "no binary request codes"
    );
    // And an independent reader agrees: catrib of the binary file is the ASCII file.
    let out = Command::new(&t.catrib)
        .arg("binary.rib")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        std::fs::read_to_string(dir.join("ascii.rib")).unwrap()
    );
}

#[test]
fn ribout_captures_can_be_binary_and_compressed_from_the_environment() {
    let Some(t) = tools() else { return };
    let dir = scratch("ribout_formats");
    let src = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/c/quadrics.c"),
    )
    .unwrap();
    let exe = compile(&t, &dir, &src);
    run(&exe, &dir, &[("ILLUME_RIBOUT", "a.rib")]);
    let env = [
        ("ILLUME_RIBOUT", "b.rib"),
        ("ILLUME_RIBFORMAT", "binary"),
        ("ILLUME_RIBCOMPRESSION", "gzip"),
    ];
    run(&exe, &dir, &env);
    assert!(std::fs::read(dir.join("b.rib"))
        .unwrap()
        .starts_with(&[0x1f, 0x8b]));
    assert_eq!(parsed(&dir.join("b.rib")), parsed(&dir.join("a.rib")));
}

/// A handler that prints `code severity` per error, and the calls the issue names as bad.
const BAD_CALLS: &str = r#"#include <ri.h>
#include <stdio.h>
static void h(RtInt code, RtInt severity, char *msg) { printf("%d %d %s\n", code, severity, msg); }
int main(void) {
  RtPoint p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  RiErrorHandler(h);
  RiEnd();
  RiSphere(1, -1, 1, 360, RI_NULL);
  RiBegin(RI_NULL);
  RiSphere(1, -1, 1, 360, RI_NULL);
  RiWorldBegin();
  RiPolygonV(3, 2, NULL, NULL);
  RiPolygon(3, RI_P, p, "nosuchtoken", p, RI_NULL);
  RiPolygon(3, (RtToken)RI_P, (RtPointer)NULL, RI_NULL);
  RiIlluminate((RtLightHandle)42, RI_TRUE);
  RiWorldEnd();
  RiAttributeEnd();
  RiEnd();
  printf("alive %d\n", RiLastError);
  return 0;
}
"#;

#[test]
fn bad_calls_reach_the_error_handler_with_ri_codes() {
    let Some(t) = tools() else { return };
    let dir = scratch("errors");
    let exe = compile(&t, &dir, BAD_CALLS);
    let out = run(&exe, &dir, &[]);
    let codes: Vec<(i32, i32)> = out
        .lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            Some((w.next()?.parse().ok()?, w.next()?.parse().ok()?))
        })
        .collect();
    eprintln!("{out}");
    // RiEnd and RiSphere before RiBegin: RIE_NOTSTARTED (23).
    assert_eq!(&codes[..2], &[(23, 2), (23, 2)], "{out}");
    // Geometry before WorldBegin: RIE_NOTPRIMS (27).
    assert_eq!(codes[2], (27, 2), "{out}");
    // NULL token list: RIE_MISSINGDATA (46); an undeclared token: RIE_BADTOKEN (41); a NULL
    // value: RIE_MISSINGDATA.
    assert!(
        codes.contains(&(46, 2)) && codes.contains(&(41, 2)),
        "{out}"
    );
    assert!(out.contains("parameter `P` has a NULL value"), "{out}");
    assert!(out.contains("nosuchtoken"), "{out}");
    // AttributeEnd without AttributeBegin is an error the renderer reports.
    assert!(out.lines().any(|l| l.contains("AttributeEnd")), "{out}");
    assert!(
        out.ends_with(&format!("alive {}\n", codes.last().unwrap().0)),
        "{out}"
    );
}

#[test]
fn transform_points_matches_the_closed_form() {
    let Some(t) = tools() else { return };
    let dir = scratch("transform_points");
    let prog = r#"#include <ri.h>
#include <stdio.h>
int main(void) {
  RtPoint p[2] = {{0, 0, 0}, {1, 0, 0}};
  RiBegin("t.rib");
  RiWorldBegin();
  RiTranslate(1, 2, 3);
  RiRotate(90, 0, 0, 1);
  RiCoordinateSystem("lamp");
  RiIdentity();
  RtPoint *r = RiTransformPoints("lamp", RI_CURRENT, 2, p);
  RtPoint *bad = RiTransformPoints("nosuchspace", RI_CURRENT, 2, p);
  printf("%d %d %g %g %g %g %g %g\n", r == p, bad == NULL, p[0][0], p[0][1], p[0][2], p[1][0], p[1][1], p[1][2]);
  RiWorldEnd();
  RiEnd();
  return 0;
}
"#;
    let exe = compile(&t, &dir, prog);
    let out = run(&exe, &dir, &[]);
    let v: Vec<f64> = out.split_whitespace().map(|s| s.parse().unwrap()).collect();
    // lamp = Translate(1 2 3) * Rotate(90 about z); current = world: (0 0 0) -> (1 2 3) and
    // (1 0 0) -> (1 3 3).
    let want = [1.0, 1.0, 1.0, 2.0, 3.0, 1.0, 3.0, 3.0];
    for (g, w) in v.iter().zip(want) {
        assert!((g - w).abs() < 1e-5, "{out}");
    }
    assert_eq!(v.len(), want.len(), "{out}");
}

#[test]
fn a_c_program_renders_the_bits_of_its_captured_rib() {
    let Some(t) = tools() else { return };
    let dir = scratch("same_bits");
    let src = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/c/procedural.c"),
    )
    .unwrap();
    let exe = compile(&t, &dir, &src);
    run(&exe, &dir, &[]);
    let direct = std::fs::read(dir.join("procedural.tif")).unwrap();
    std::fs::remove_file(dir.join("procedural.tif")).unwrap();
    run(&exe, &dir, &[("ILLUME_RIBOUT", "captured.rib")]);
    assert!(
        !dir.join("procedural.tif").exists(),
        "ILLUME_RIBOUT must not render"
    );
    let st = Command::new(&t.render)
        .args(["-q", "captured.rib"])
        .current_dir(&dir)
        .status()
        .unwrap();
    assert!(st.success());
    let via_rib = std::fs::read(dir.join("procedural.tif")).unwrap();
    assert!(direct == via_rib, "in-process and RIB renders differ");
    // And the image is not empty: the spheres cover part of the frame.
    let img = illume_imageio::read_image(&dir.join("procedural.tif")).unwrap();
    let lit = img
        .data
        .chunks(img.channels.len())
        .filter(|p| p[0] > 0.05)
        .count();
    assert!(lit > 100, "only {lit} lit pixels");
}

/// The C tests refuse a `libillume.a` older than a source it was built from (cargo's dep-info
/// beside it names them, with the paths of the checkout that built it).
#[test]
fn a_library_older_than_its_sources_is_found_stale() {
    let dir = scratch("stale");
    let lib = dir.join("libillume.a");
    std::fs::write(&lib, b"!<arch>\n").unwrap();
    let source = "/some/other/checkout/crates/ri/src/lib.rs";
    let info = format!("{}: {source} /registry/glam/src/lib.rs\n", lib.display());
    std::fs::write(dir.join("libillume.d"), info).unwrap();
    // Written just now: newer than this checkout's crates/ri/src/lib.rs.
    assert_eq!(c_programs::newer_source(&lib), None);
    let old = std::time::SystemTime::UNIX_EPOCH + std::time::Duration::from_secs(1);
    let file = std::fs::File::options().write(true).open(&lib).unwrap();
    file.set_modified(old).unwrap();
    let here = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/ri/src/lib.rs");
    assert_eq!(c_programs::newer_source(&lib), Some(here));
}
