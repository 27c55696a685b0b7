//! The conformance suite: `tests/sl/conformance/NAME.sl`, one small surface shader per
//! language feature or built-in, each writing its result into `Ci`. Every shader runs on one
//! 4×3 grid (`s = u ∈ {0, 1/3, 2/3, 1}`, `t = v ∈ {0, 1/2, 1}`, `P = (2u-1, 2v-1, 4)` so
//! `Du(P) = (2,0,0)`, `Dv(P) = (0,2,0)`, `N = Ng = (0,0,-1)`, `I = P`, `Cs = (.5,.25,1)`),
//! world space offset by (1,2,3) from camera space, and three built-in lights: ambient 0.2, a
//! distant light along +z (`L = (0,0,-1)` at the surface), and a distant light along (1,0,1)
//! with `__nonspecular 1`. The expected value of each is computed here in `f64` from the
//! definitions (RI 3.2 chapter 15) — not by the executor's own kernels.
//!
//! Tolerance: 2e-5 absolute, f32 rounding of values of magnitude ≤ 20.
use glam::{DMat4, DVec3, Vec3};
use illume_rib::{Param, Value as RibValue};
use illume_shade::{
    light, InfoValue, Light, LightCache, RenderInfo, ShadingEnv, ShadingGrid, ShadowOptions,
    TextureLookup, TextureOptions,
};
use illume_sl::types::ShaderKind;
use illume_slvm::library::{pick_shader, ShaderLibrary};
use illume_slvm::{Lights, SlInstance};
use std::path::PathBuf;

/// One grid point's inputs, in f64.
#[derive(Clone, Copy)]
struct Pt {
    s: f64,
    t: f64,
    p: DVec3,
    du: f64,
    last_u: bool,
}

fn grid() -> ShadingGrid {
    let mut g = ShadingGrid::new(4, 3);
    for i in 0..g.len() {
        let (u, v) = (g.u[i], g.v[i]);
        g.p[i] = Vec3::new(2.0 * u - 1.0, 2.0 * v - 1.0, 4.0);
        g.cs[i] = Vec3::new(0.5, 0.25, 1.0);
    }
    g.set_incident_from_p(false);
    g
}

fn fparam(name: &str, v: &[f32]) -> Param {
    Param {
        name: name.into(),
        value: RibValue::Floats(v.to_vec()),
    }
}

fn lights() -> Vec<Light> {
    let amb = light(
        "ambientlight",
        &[fparam("intensity", &[0.2])],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let along_z = light(
        "distantlight",
        &[
            fparam("from", &[0.0, 0.0, 0.0]),
            fparam("to", &[0.0, 0.0, 1.0]),
        ],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    let diagonal = light(
        "distantlight",
        &[
            fparam("from", &[0.0, 0.0, 0.0]),
            fparam("to", &[1.0, 0.0, 1.0]),
            fparam("__nonspecular", &[1.0]),
        ],
        DMat4::IDENTITY,
    )
    .unwrap()
    .0;
    vec![amb, along_z, diagonal]
}

fn splat(x: f64) -> DVec3 {
    DVec3::splat(x)
}

fn b(c: bool) -> f64 {
    if c {
        1.0
    } else {
        0.0
    }
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// HSV → RGB (hue in [0,1), the hexcone model).
fn hsv_to_rgb(h: f64, s: f64, v: f64) -> DVec3 {
    let h6 = h.rem_euclid(1.0) * 6.0;
    let c = v * s;
    let x = c * (1.0 - ((h6 % 2.0) - 1.0).abs());
    let (r, g, b) = match h6 as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    DVec3::new(r, g, b) + splat(v - c)
}

fn rgb_to_hsv(c: DVec3) -> DVec3 {
    let (max, min) = (c.max_element(), c.min_element());
    let d = max - min;
    let h = if d == 0.0 {
        0.0
    } else if max == c.x {
        ((c.y - c.z) / d).rem_euclid(6.0) / 6.0
    } else if max == c.y {
        ((c.z - c.x) / d + 2.0) / 6.0
    } else {
        ((c.x - c.y) / d + 4.0) / 6.0
    };
    DVec3::new(h, if max > 0.0 { d / max } else { 0.0 }, max)
}

fn sl_mod(a: f64, m: f64) -> f64 {
    a - m * (a / m).floor()
}

fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The queries the suite's environment answers, as a RIB would give them: `Format 64 48 1`,
/// `FrameAspectRatio 1.3333`, `FrameBegin 7`, `CropWindow 0 1 0.25 0.75`, `Clipping 1 9`;
/// `ShadingRate 0.5`, `Sides 2`, `Attribute "identifier" "name" "ball"`, `Attribute
/// "displacementbound" "sphere" 0.25`.
const ASPECT: f32 = 4.0 / 3.0;
const CLIPPING: (f32, f32) = (1.0, 9.0);

fn options() -> RenderInfo {
    RenderInfo::new()
        .with_floats("Format", &[64.0, 48.0, 1.0])
        .with_floats("DeviceResolution", &[64.0, 48.0, 1.0])
        .with_floats("FrameAspectRatio", &[ASPECT])
        .with_floats("Frame", &[7.0])
        .with_floats("CropWindow", &[0.0, 1.0, 0.25, 0.75])
}

fn attributes() -> RenderInfo {
    RenderInfo::new()
        .with_floats("ShadingRate", &[0.5])
        .with_floats("Sides", &[2.0])
        .with_string("identifier:name", "ball")
        .with_floats("displacementbound:sphere", &[0.25])
}

/// A texture system that knows two maps by name only: `grid.tx` (a 3-channel 256×128 texture)
/// and `spot.shd` (a shadow map whose viewing matrix translates by (5,6,7)).
struct InfoOnly;

impl TextureLookup for InfoOnly {
    fn texture(
        &self,
        _: &str,
        _: usize,
        _: usize,
        _: [[f32; 2]; 4],
        _: &TextureOptions,
    ) -> Option<[f32; 4]> {
        None
    }
    fn environment(
        &self,
        _: &str,
        _: usize,
        _: usize,
        _: [Vec3; 4],
        _: &TextureOptions,
    ) -> Option<[f32; 4]> {
        None
    }
    fn shadow(&self, _: &str, _: [Vec3; 4], _: &ShadowOptions) -> Option<f32> {
        None
    }
    fn textureinfo(&self, name: &str, data: &str) -> Option<InfoValue> {
        Some(match (name, data) {
            ("grid.tx", "resolution") => InfoValue::Floats(vec![256.0, 128.0]),
            ("grid.tx", "channels") => InfoValue::Floats(vec![3.0]),
            ("grid.tx", "type") => InfoValue::String("texture".into()),
            ("spot.shd", "viewingmatrix") => InfoValue::Floats(vec![
                1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 5.0, 6.0, 7.0, 1.0,
            ]),
            _ => return None,
        })
    }
}

/// What message passing reads in the suite: the surface's `Kd` 0.25, the displacement's `Km`
/// 0.3 and the atmosphere's `fogcolor` (0.1, 0.2, 0.3).
fn messages() -> illume_slvm::Messages {
    illume_slvm::Messages {
        surface: vec![("Kd".into(), illume_slvm::Value::float(0.25))],
        displacement: vec![("Km".into(), illume_slvm::Value::float(0.3))],
        atmosphere: vec![(
            "fogcolor".into(),
            illume_slvm::Value::triple(Vec3::new(0.1, 0.2, 0.3)),
        )],
    }
}

/// `Major.minor.patch` of the crate as the digits `rendererinfo("version")` returns.
fn version_code() -> f64 {
    let v: Vec<f64> = env!("CARGO_PKG_VERSION")
        .split('.')
        .map(|x| x.parse().unwrap())
        .collect();
    v[0] * 100.0 + v[1] * 10.0 + v[2]
}

/// The expected `Ci` of conformance shader `name` at `q`.
fn expected(name: &str, q: Pt) -> Option<DVec3> {
    let (s, t, p) = (q.s, q.t, q.p);
    let sqrt_half = std::f64::consts::FRAC_1_SQRT_2;
    Some(match name {
        "arithmetic" => DVec3::new(s + t * 2.0, s * t - 1.0, (s + 1.0) / (t + 1.0)),
        "precedence" => splat(2.0 + 3.0 * s - t / 2.0),
        "if_else" => splat(if s < 0.5 { s } else { 1.0 - s }),
        "nested_if" => splat(if s > 0.2 {
            if t > 0.4 {
                1.0
            } else {
                0.5
            }
        } else {
            0.0
        }),
        "for_loop" => splat((0..5).map(|i| s.powi(i)).sum()),
        "while_break" => {
            let (mut x, mut n) = (1.0, 0.0);
            while x <= 4.0 * t + 1.0 {
                x *= 1.5;
                n += 1.0;
            }
            splat(n)
        }
        "continue_loop" => splat((0..6).filter(|i| i % 2 == 1).map(|i| s * i as f64).sum()),
        "varying_for" => splat((0..100).filter(|&i| (i as f64) < 10.0 * s).count() as f64),
        "ternary" => {
            if s > t {
                DVec3::X
            } else {
                DVec3::new(0.0, s, t)
            }
        }
        "logic" => DVec3::new(b(s > 0.2 && t < 0.6), b(s < 0.1 || t > 0.9), b(s <= 0.5)),
        "output_param" => {
            let x = s * 3.5 + t;
            DVec3::new(x.floor(), x - x.floor(), 0.0)
        }
        "function_return" => splat(if s < 0.5 { 2.0 * s } else { 2.0 - 2.0 * s }),
        "arrays" => {
            let a = [1.0, s, 3.0];
            DVec3::new(1.0, s, a[(t * 2.99).floor() as usize])
        }
        "uniform_local" => splat(6.0 * s),
        "math" => DVec3::new(
            s.sin() + t.cos(),
            (s + 1.0).sqrt() * (-t).exp(),
            2f64.powf(s) + (t + 1.0).ln(),
        ),
        "math2" => DVec3::new(
            sl_mod(-3.5 * s, 1.25) + (s - t).abs(),
            (4.0 * s).floor() + (3.0 * t).ceil() + sign(t - 0.5),
            t.atan2(s + 0.1) + s.atan(),
        ),
        "clamp_mix" => DVec3::new(
            (3.0 * s - 1.0).clamp(0.0, 1.0),
            2.0 * (1.0 - t) + 5.0 * t,
            s.min(t).min(0.4) + s.max(t),
        ),
        "steps" => {
            // filterstep's width: |Du(s)·du| + |Dv(s)·dv| = du.
            let w = q.du;
            DVec3::new(
                b(s >= 0.5),
                smoothstep(0.2, 0.8, t),
                ((s + w / 2.0 - 0.5) / w).clamp(0.0, 1.0),
            )
        }
        "geometric" => {
            let (a, c) = (DVec3::new(s, t, 1.0), DVec3::new(1.0, -t, s));
            DVec3::new(a.length(), (a - c).length(), a.dot(c)) + a.cross(c)
        }
        "normalize_reflect" => {
            let d = DVec3::new(s, 1.0, t + 1.0).normalize();
            DVec3::new(d.x, -d.y, d.z)
        }
        // faceforward(N, I) flips N to face against I relative to Ng = (0,0,-1): I·Ng < 0
        // here, so N stays; the explicit form with Nref = (0,0,1) and I = (0,0,-1) too.
        "faceforward" => DVec3::new(0.0, 0.0, 1.0) + DVec3::new(s, 0.0, 1.0),
        "ptlined_rotate" => {
            let dist = if s > 0.5 {
                ((s - 0.5).powi(2) + t * t).sqrt()
            } else {
                t
            };
            // rotate (s,t,0) by 90° about +z: (-t, s, 0).
            DVec3::new(dist - t, s, 0.0)
        }
        "components" => DVec3::new(s + 3.0, 1.0 + s, 0.0),
        // world = camera - (1,2,3); vectors do not translate.
        "transform_spaces" => p - DVec3::new(1.0, 2.0, 3.0) + DVec3::X,
        "space_cast" => DVec3::new(1.0, 2.0, 3.0) + DVec3::new(s + 1.0, 2.0, 3.0),
        // scale(translate(1, (1,2,3)), 2): the scale applies first (object side, like RIB).
        "matrices" => DVec3::new(2.0 * s + 1.0, 2.0 * t + 2.0, 3.0) + splat(8.0),
        "colorspace" => hsv_to_rgb(s, 1.0, 1.0) + rgb_to_hsv(DVec3::new(t, 0.5, 0.25)),
        "noise" => DVec3::new(0.5, b((0.9 * s).floor() == (0.9 * s + 0.15).floor()), 1.0),
        "spline" => {
            let cr = [1.0, 4.0, 2.0, 3.0][(s * 3.0).round() as usize];
            let lin = 20.0 * t;
            DVec3::new(cr, lin, (0.0 + 3.0 * 2.0 + 3.0 * 5.0 + 1.0) / 8.0)
        }
        "derivatives" => {
            // Forward differences, backward on the last column: Du(s²) = 2s ± du.
            let du_s2 = if q.last_u {
                2.0 * s - q.du
            } else {
                2.0 * s + q.du
            };
            DVec3::new(du_s2, 3.0, 4.0 * q.du * 0.5)
        }
        // Du(P) × Dv(P) = (0,0,4), oriented like Ng = (0,0,-1).
        "calculatenormal" => DVec3::new(0.0, 0.0, -1.0),
        "strings" => DVec3::ONE,
        // Light 1: L = (0,0,-1) = N, Cl = 1; light 2 at 45°.
        "illuminance_loop" => splat(1.0 + sqrt_half),
        "lighting" => {
            let n = DVec3::new(0.0, 0.0, -1.0);
            let v = -p.normalize();
            let h = (n + v).normalize(); // L1 = N
            let spec = n.dot(h).max(0.0).powf(8.0 / 0.2); // the default model: PRMan's 8/roughness
            splat(1.0 + sqrt_half) + splat(0.5 * 0.2) + splat(spec)
        }
        // __nonspecular 0 and 1: (0 + 1) + (1 + 1).
        "lightsource_message" => splat(3.0),
        "globals" => DVec3::new(s + 10.0 * t, q.du, 0.5) + DVec3::new(0.5, 0.25, 1.0),
        // Five known queries; the two bad ones (unknown name, wrong type) leave `missing`/`nm`.
        "attribute_query" => DVec3::new(4.0, 0.5 + 2.0 + 0.25, 1.0 + 7.0),
        "option_query" => DVec3::new(
            5.0,
            64.0 + 0.48 + 1.0 + f64::from(ASPECT),
            7.0 + 1.0 + 0.25 + 0.064,
        ),
        "rendererinfo" => DVec3::new(
            3.0,
            1.0 + 2.0 * b(env!("CARGO_PKG_VERSION") == "0.1.0"),
            version_code(),
        ),
        // (z − near)/(far − near), near 1, far 9.
        "depth" => {
            let (near, far) = (f64::from(CLIPPING.0), f64::from(CLIPPING.1));
            let d = |z: f64| (z - near) / (far - near);
            DVec3::new(d(p.z), d(p.z + s), d(1.0))
        }
        // Three found; the three misses (unknown name, float into a color, the surface has
        // no Km) leave their variables.
        "shader_messages" => DVec3::new(3.0, 0.25 + 0.3, 0.1 + 0.3),
        "textureinfo" => DVec3::new(4.0, 256.0 + 0.128 + 3.0, 1.0 + 5.0),
        _ => return None,
    })
}

fn conformance_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/sl/conformance")
}

#[test]
fn every_conformance_shader_gives_its_expected_value() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(conformance_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "sl"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 30,
        "conformance suite incomplete: {}",
        files.len()
    );
    let lights = lights();
    let refs: Vec<&Light> = lights.iter().collect();
    let mut env = ShadingEnv::new();
    env.camera_from_world = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0));
    let (opts, attrs) = (options(), attributes());
    env.options = Some(&opts);
    env.attributes = Some(&attrs);
    env.clipping = CLIPPING;
    env.textures = Some(&InfoOnly);
    let library = ShaderLibrary::new();
    let mut failures = Vec::new();
    for path in &files {
        let name = path.file_stem().unwrap().to_str().unwrap().to_string();
        let program = match library.compile(path, &[]) {
            Ok(p) => p,
            Err(e) => {
                failures.push(format!("{name}: does not compile:\n{e}"));
                continue;
            }
        };
        let id = pick_shader(&program, ShaderKind::Surface, &name).expect("a surface");
        let shader = illume_slvm::CompiledShader { program, id };
        let (inst, warnings) = SlInstance::bind(shader, &[], DMat4::IDENTITY);
        assert!(warnings.is_empty());
        let mut g = grid();
        let cache = LightCache::run(&refs, &g, &env);
        let view = Lights::from_cache(&cache);
        inst.shade_surface_with(&mut g, &view, &env, messages());
        for i in 0..g.len() {
            let q = Pt {
                s: g.s[i] as f64,
                t: g.t[i] as f64,
                p: g.p[i].as_dvec3(),
                du: g.du as f64,
                last_u: i % g.nu == g.nu - 1,
            };
            let Some(want) = expected(&name, q) else {
                failures.push(format!("{name}: no expected value in the test"));
                break;
            };
            let got = g.ci[i].as_dvec3();
            if (got - want).abs().max_element() > 2e-5 {
                failures.push(format!(
                    "{name} at s={:.3} t={:.3}: got {got:?}, want {want:?}",
                    q.s, q.t
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
