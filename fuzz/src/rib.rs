//! The RIB targets: the parser alone (with a print/re-parse round trip), and the whole path
//! RIB → `Ri` → REYES render of a small frame.
use illume_ri::{from_rib_diagnostic, RequestSource, Ri};
use illume_rib::{Param, Request, Spanned, Value};
use std::io::Read;

/// The RIB parser on arbitrary bytes (ASCII, binary and gzip paths): it must never panic, must
/// terminate, and whatever parses must print and re-parse to the same requests.
pub fn parse_rib(data: &[u8]) {
    let mut requests = Vec::new();
    let reader = illume_rib::decompress(std::io::Cursor::new(data.to_vec())).expect("in memory");
    for (n, item) in illume_rib::Parser::new(reader, "fuzz.rib").enumerate() {
        // Each item consumes at least one byte of the decompressed stream or ends it; gzip
        // may expand, so the bound is generous.
        assert!(n < 1 << 24, "parser does not terminate");
        if let Ok(r) = item {
            requests.push(r.value);
        }
    }
    if requests.is_empty() {
        return; // nothing to print: most mutated inputs end here
    }
    let mut text = Vec::new();
    for r in &requests {
        illume_rib::write_ascii(r, &mut text).unwrap();
    }
    let back: Vec<_> = illume_rib::Parser::new(&text[..], "printed")
        .filter_map(Result::ok)
        .map(|r| r.value)
        .collect();
    // Compare printouts: NaN-free by construction (the lexer rejects non-finite numbers), and
    // bit-exact where PartialEq would equate 0.0 and -0.0.
    let mut again = Vec::new();
    for r in &back {
        illume_rib::write_ascii(r, &mut again).unwrap();
    }
    // Bytes compared; text made only for the message.
    assert!(
        again == text,
        "print/re-parse differs:\n{}\n---\n{}",
        String::from_utf8_lossy(&text),
        String::from_utf8_lossy(&again)
    );
}

/// Applies [`render_rib`]'s limits to one request (`None`: drop it).
fn clamp(mut req: Spanned<Request>) -> Option<Spanned<Request>> {
    match &mut req.value {
        Request::Format { xres, yres, .. } => {
            // Not `min`: a non-positive size means the device default, 640×480.
            *xres = (*xres).clamp(1, MAX_RESOLUTION);
            *yres = (*yres).clamp(1, MAX_RESOLUTION);
        }
        Request::Option { name, params } if name == "limits" => cap_limits(params),
        Request::PixelSamples { x, y } => {
            *x = x.min(2.0);
            *y = y.min(2.0);
        }
        Request::ShadingRate(r) => *r = r.max(1.0),
        Request::Procedural { name, .. } if name == "RunProgram" => return None,
        _ => {}
    }
    Some(req)
}

/// Largest `Format` width and height. 8×8 takes the same code paths as the 24×24 of the first
/// runs (one bucket of the default 16×16, clipping at the frame edge, the filter's border) at
/// a ninth of the pixels: rendering, not parsing, is what makes this target slow.
const MAX_RESOLUTION: i32 = 8;

/// `Option "limits"` values the target sets before the input (`DEFAULTS`) and the most an input
/// may set them to: the renderer's own checks run on every primitive and nested read, within
/// what renders in well under a second. Other limits (image size, samples, shading rate) are
/// held by [`clamp`] on the requests themselves.
const LIMITS: [(&str, f32); 5] = [
    ("vertices", 65536.0),
    ("memory", 256.0),
    ("nesting", 16.0),
    ("gridsize", 256.0),
    ("eyesplits", 10.0),
];

/// Lowers an input's `Option "limits"` values to [`LIMITS`] (the name may carry an inline
/// type, `"int vertices"`); values below them, zero or negative ones included, pass as given.
fn cap_limits(params: &mut [Param]) {
    for p in params {
        let key = p.name.rsplit(' ').next().unwrap_or_default();
        let Some(&(_, cap)) = LIMITS.iter().find(|(n, _)| *n == key) else {
            continue;
        };
        match &mut p.value {
            Value::Floats(v) => v.iter_mut().for_each(|x| *x = x.min(cap)),
            Value::Ints(v) => v.iter_mut().for_each(|x| *x = (*x).min(cap as i32)),
            Value::Strings(_) => {}
        }
    }
}

/// The stream with [`clamp`] applied to every request.
fn limited<E>(
    source: impl Iterator<Item = Result<Spanned<Request>, E>>,
) -> impl Iterator<Item = Result<Spanned<Request>, E>> {
    source.filter_map(|item| match item {
        Ok(req) => clamp(req).map(Ok),
        Err(d) => Some(Err(d)),
    })
}

/// Prepended to every input: a frame small enough to render in milliseconds.
const DEFAULTS: &str = "Format 8 6 1\nPixelSamples 1 1\nShadingRate 4\n\
    Option \"limits\" \"vertices\" [65536] \"memory\" [256] \"nesting\" [16]\n";

/// The whole path RIB → RI state → REYES render of a small frame: parser, option and attribute
/// handling, archives and object instances, geometry, dicing, shading with the built-in and
/// standard shaders, sampling and filtering. The displays are not written.
///
/// So that each input renders in well under a second, the target (not the renderer) clamps
/// what the RIB may ask for: `Format` to 1×1 to 8×8, `PixelSamples` to at most 2×2,
/// `ShadingRate` to at least 1 and `Option "limits"` to [`LIMITS`], with an 8×6, 1×1, rate-4
/// default and those limits prepended. `RunProgram`
/// procedurals are dropped (they would run arbitrary programs named by the input), `Make*`
/// requests build nothing, and archives read from disk are capped at 64 KiB and clamped the
/// same way. Rendering runs on one thread (rayon's global pool, set on the first call).
pub fn render_rib(data: &[u8]) {
    let _ = render_rib_stats(data);
}

/// [`render_rib`], returning each rendered frame's statistics (the regression tests of slow
/// inputs bound their micropolygon counts).
pub fn render_rib_stats(data: &[u8]) -> Vec<illume_render::Stats> {
    static POOL: std::sync::Once = std::sync::Once::new();
    POOL.call_once(|| {
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build_global();
    });
    let Ok(reader) = illume_rib::decompress(std::io::Cursor::new(data.to_vec())) else {
        return Vec::new();
    };
    let mut ri = Ri::new();
    ri.set_parser(Box::new(
        |reader: Box<dyn Read>, name: &str| -> RequestSource {
            let parser = illume_rib::Parser::new(reader.take(64 << 10), name);
            Box::new(limited(parser.map(|r| r.map_err(from_rib_diagnostic))))
        },
    ));
    ri.set_texture_maker(Box::new(|_, _| Ok(())));
    let defaults = illume_rib::Parser::new(DEFAULTS.as_bytes(), "defaults");
    let input = illume_rib::Parser::new(reader, "fuzz.rib");
    let requests = limited(defaults.chain(input));
    let cache = illume_texture::TextureCache::new(1 << 20);
    let settings = illume_render::RenderSettings {
        progress: None,
        textures: Some(&cache),
    };
    let mut stats = Vec::new();
    illume_render::render_frames_in_order(
        &mut ri,
        requests,
        |_| {},
        |frame| {
            let max = MAX_RESOLUTION as u32;
            assert!(frame.options.xres <= max && frame.options.yres <= max);
            stats.push(illume_render::render(&frame, &settings).stats);
        },
    );
    stats
}
