//! `bench --scaling`: how time and peak memory grow with image size, primitive count (instanced
//! and unique), pixel samples and AOV count (issue 21 part 6). Every point renders a
//! generated field of spheres with the real `render` binary, measured as the kernel accounts
//! the process ([`crate::child`]); one knob moves per axis from a base scene. Outputs
//! `scaling.csv`, `scaling.png` and `scaling.md` (with each axis's growth exponent: the slope
//! of log CPU time, and of log peak RSS, against log work).

use crate::child::run_measured;
use std::fmt::Write as _;
use std::path::Path;

/// The AOVs the AOV axis adds, one `Display "+aovK.tif"` each, in this order.
pub const AOV_VARIABLES: [&str; 8] = ["N", "P", "s", "t", "u", "v", "__diffuse", "__specular"];

/// One generated scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldSpec {
    pub prims: usize,
    pub instanced: bool,
    pub width: u32,
    pub height: u32,
    /// PixelSamples per axis.
    pub samples: u32,
    /// Extra AOV displays (at most [`AOV_VARIABLES`]' length).
    pub aovs: usize,
}

/// A square grid of `prims` spheres filling the frame, lit by a distant and an ambient light,
/// `plastic`. Instanced: one `ObjectBegin` sphere placed by `ObjectInstance`; unique: a
/// `Sphere` per place. Both place each with its own `Translate`, so they differ only in
/// instancing.
pub fn sphere_field(spec: &FieldSpec) -> String {
    let n = spec.prims;
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    let spacing = 4.0 / side as f64;
    let radius = 0.4 * spacing;
    let mut s = String::with_capacity(64 * n + 1024);
    let _ = writeln!(
        s,
        "##RenderMan RIB\n# bench --scaling: {n} spheres\nversion 3.03"
    );
    let _ = writeln!(s, "Display \"out.tif\" \"file\" \"rgba\"");
    for (k, var) in AOV_VARIABLES.iter().take(spec.aovs).enumerate() {
        let _ = writeln!(s, "Display \"+aov{k}.tif\" \"file\" \"{var}\"");
    }
    let _ = writeln!(s, "Format {} {} 1", spec.width, spec.height);
    let _ = writeln!(s, "PixelSamples {0} {0}", spec.samples);
    s.push_str("Projection \"perspective\" \"fov\" [45]\nTranslate 0 0 5\nWorldBegin\n");
    s.push_str("  LightSource \"ambientlight\" 1 \"intensity\" [0.15]\n");
    s.push_str(
        "  LightSource \"distantlight\" 2 \"intensity\" [1] \"from\" [-1 1 -1] \"to\" [0 0 0]\n",
    );
    s.push_str("  Surface \"plastic\" \"Ks\" [0.5] \"roughness\" [0.1]\n");
    let sphere = format!("Sphere {radius} {} {radius} 360", -radius);
    if spec.instanced {
        let _ = writeln!(s, "  ObjectBegin 1\n    {sphere}\n  ObjectEnd");
    }
    let body = if spec.instanced {
        "ObjectInstance 1"
    } else {
        sphere.as_str()
    };
    for i in 0..n {
        let x = -2.0 + ((i % side) as f64 + 0.5) * spacing;
        let y = -2.0 + ((i / side) as f64 + 0.5) * spacing;
        let _ = writeln!(
            s,
            "  AttributeBegin\n    Translate {x:.6} {y:.6} 0\n    {body}\n  AttributeEnd"
        );
    }
    s.push_str("WorldEnd\n");
    s
}

/// The four axes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    Image,
    Prims,
    Samples,
    Aovs,
}

impl Axis {
    pub const ALL: [Axis; 4] = [Axis::Image, Axis::Prims, Axis::Samples, Axis::Aovs];

    pub fn name(self) -> &'static str {
        match self {
            Axis::Image => "image",
            Axis::Prims => "prims",
            Axis::Samples => "samples",
            Axis::Aovs => "aovs",
        }
    }

    pub fn from_name(s: &str) -> Option<Axis> {
        Axis::ALL.into_iter().find(|a| a.name() == s)
    }

    /// What the axis multiplies: pixels, primitives, samples per pixel, AOVs + 1 (the beauty).
    pub fn work(self, p: &FieldSpec) -> f64 {
        match self {
            Axis::Image => f64::from(p.width) * f64::from(p.height),
            Axis::Prims => p.prims as f64,
            Axis::Samples => f64::from(p.samples * p.samples),
            Axis::Aovs => (p.aovs + 1) as f64,
        }
    }

    pub fn work_label(self) -> &'static str {
        match self {
            Axis::Image => "pixels",
            Axis::Prims => "spheres",
            Axis::Samples => "samples per pixel",
            Axis::Aovs => "AOVs + 1",
        }
    }
}

/// One measured point.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingRow {
    pub axis: Axis,
    pub spec: FieldSpec,
    pub wall_seconds: f64,
    pub cpu_seconds: f64,
    pub peak_rss_mb: f64,
}

impl ScalingRow {
    /// "instanced"/"unique" on the primitive axis, empty elsewhere.
    pub fn series(&self) -> &'static str {
        match (self.axis, self.spec.instanced) {
            (Axis::Prims, true) => "instanced",
            (Axis::Prims, false) => "unique",
            _ => "",
        }
    }
}

/// The points to measure: each axis moves one knob from the base scene (1000 unique spheres,
/// 2×2 samples, no AOVs). `quick` keeps CI's run to well under a minute.
pub fn plan(quick: bool, max_prims: usize) -> Vec<(Axis, FieldSpec)> {
    let (w, h) = if quick { (160, 120) } else { (320, 240) };
    let base = FieldSpec {
        prims: 1000,
        instanced: false,
        width: w,
        height: h,
        samples: 2,
        aovs: 0,
    };
    let mut v = Vec::new();
    let scales: &[u32] = if quick { &[1, 2, 4] } else { &[1, 2, 4, 8] };
    for &k in scales {
        v.push((
            Axis::Image,
            FieldSpec {
                width: w * k,
                height: h * k,
                ..base
            },
        ));
    }
    let prims: &[usize] = if quick {
        &[1000, 10_000]
    } else {
        &[1000, 10_000, 100_000, 1_000_000]
    };
    for instanced in [true, false] {
        for &n in prims.iter().filter(|&&n| n <= max_prims) {
            v.push((
                Axis::Prims,
                FieldSpec {
                    prims: n,
                    instanced,
                    ..base
                },
            ));
        }
    }
    let samples: &[u32] = if quick {
        &[1, 2, 4]
    } else {
        &[1, 2, 3, 4, 6, 8]
    };
    for &n in samples {
        v.push((Axis::Samples, FieldSpec { samples: n, ..base }));
    }
    let aovs: &[usize] = if quick { &[0, 4, 8] } else { &[0, 1, 2, 4, 8] };
    for &n in aovs {
        v.push((Axis::Aovs, FieldSpec { aovs: n, ..base }));
    }
    v
}

/// Renders every point of `plan` in `scratch` (fastest of `repeat` per number).
pub fn run(
    render: &Path,
    scratch: &Path,
    plan: &[(Axis, FieldSpec)],
    threads: usize,
    repeat: usize,
) -> Result<Vec<ScalingRow>, String> {
    let mut rows = Vec::new();
    for (i, (axis, spec)) in plan.iter().enumerate() {
        let dir = scratch.join(format!("scaling_{i:02}"));
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        std::fs::write(dir.join("scene.rib"), sphere_field(spec))
            .map_err(|e| format!("{}: {e}", dir.display()))?;
        let args = [
            "-q".to_string(),
            "--threads".into(),
            threads.to_string(),
            "scene.rib".into(),
        ];
        let mut row = ScalingRow {
            axis: *axis,
            spec: *spec,
            wall_seconds: f64::INFINITY,
            cpu_seconds: f64::INFINITY,
            peak_rss_mb: f64::INFINITY,
        };
        for _ in 0..repeat.max(1) {
            let u = run_measured(render, &args, &dir)?;
            if u.exit_code != 0 {
                return Err(format!(
                    "{}: render exited with {}: {}",
                    dir.display(),
                    u.exit_code,
                    u.stderr.trim()
                ));
            }
            row.wall_seconds = row.wall_seconds.min(u.wall_seconds);
            row.cpu_seconds = row.cpu_seconds.min(u.cpu_seconds);
            row.peak_rss_mb = row.peak_rss_mb.min(u.peak_rss_mb);
        }
        // The images are not kept: a 10⁶-sphere point's AOVs would fill the scratch disk.
        let _ = std::fs::remove_dir_all(&dir);
        eprintln!(
            "bench: scaling {} {} {}x{} spheres {} samples {} aovs {}: {:.2} s wall, {:.2} s CPU, {:.0} MB",
            axis.name(),
            rows.len(),
            spec.width,
            spec.height,
            spec.prims,
            spec.samples,
            spec.aovs,
            row.wall_seconds,
            row.cpu_seconds,
            row.peak_rss_mb
        );
        rows.push(row);
    }
    Ok(rows)
}

/// The CSV header.
pub const HEADER: &str =
    "axis,series,width,height,prims,instanced,samples,aovs,wall_s,cpu_s,peak_rss_mb";

pub fn to_csv(rows: &[ScalingRow]) -> String {
    let mut s = format!("{HEADER}\n");
    for r in rows {
        let p = &r.spec;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{}",
            r.axis.name(),
            r.series(),
            p.width,
            p.height,
            p.prims,
            u8::from(p.instanced),
            p.samples,
            p.aovs,
            r.wall_seconds,
            r.cpu_seconds,
            r.peak_rss_mb
        );
    }
    s
}

pub fn from_csv(text: &str) -> Result<Vec<ScalingRow>, String> {
    let mut rows = Vec::new();
    for (n, f) in crate::csv::records(text, HEADER, 11)? {
        let bad = |k: usize| format!("line {}: field {}: unexpected {:?}", n + 1, k + 1, f[k]);
        let int = |k: usize| f[k].parse::<u64>().map_err(|_| bad(k));
        let num = |k: usize| f[k].parse::<f64>().map_err(|_| bad(k));
        rows.push(ScalingRow {
            axis: Axis::from_name(f[0]).ok_or_else(|| bad(0))?,
            spec: FieldSpec {
                width: int(2)? as u32,
                height: int(3)? as u32,
                prims: int(4)? as usize,
                instanced: int(5)? == 1,
                samples: int(6)? as u32,
                aovs: int(7)? as usize,
            },
            wall_seconds: num(8)?,
            cpu_seconds: num(9)?,
            peak_rss_mb: num(10)?,
        });
    }
    Ok(rows)
}

/// Least-squares slope of log y against log x (the growth exponent; 1 = linear).
pub fn log_slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

/// The rows of one axis and series, in plan order.
pub fn series<'a>(rows: &'a [ScalingRow], axis: Axis, name: &str) -> Vec<&'a ScalingRow> {
    rows.iter()
        .filter(|r| r.axis == axis && r.series() == name)
        .collect()
}

/// Every (axis, series) present, in plan order.
pub fn all_series(rows: &[ScalingRow]) -> Vec<(Axis, &'static str)> {
    let mut v: Vec<(Axis, &'static str)> = Vec::new();
    for r in rows {
        if !v.contains(&(r.axis, r.series())) {
            v.push((r.axis, r.series()));
        }
    }
    v
}

pub fn markdown(rows: &[ScalingRow], heading: &str) -> String {
    let mut md = format!("{heading}\n\n");
    md.push_str("| axis | series | points | CPU growth exponent | peak RSS growth exponent |\n|---|---|---|---|---|\n");
    for (axis, name) in all_series(rows) {
        let s = series(rows, axis, name);
        let cpu: Vec<(f64, f64)> = s
            .iter()
            .map(|r| (axis.work(&r.spec), r.cpu_seconds))
            .collect();
        let rss: Vec<(f64, f64)> = s
            .iter()
            .map(|r| (axis.work(&r.spec), r.peak_rss_mb))
            .collect();
        let _ = writeln!(
            md,
            "| {} ({}) | {} | {} | {:.2} | {:.2} |",
            axis.name(),
            axis.work_label(),
            name,
            s.len(),
            log_slope(&cpu),
            log_slope(&rss)
        );
    }
    md.push_str(
        "\nGrowth exponent: least-squares slope of log cost against log work (1 = linear).\n\n\
         | axis | series | image | spheres | samples | AOVs | wall s | CPU s | peak MB |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let p = &r.spec;
        let _ = writeln!(
            md,
            "| {} | {} | {}×{} | {} | {}×{} | {} | {:.2} | {:.2} | {:.0} |",
            r.axis.name(),
            r.series(),
            p.width,
            p.height,
            p.prims,
            p.samples,
            p.samples,
            p.aovs,
            r.wall_seconds,
            r.cpu_seconds,
            r.peak_rss_mb
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use illume_rib::Request;

    /// Counts the requests the real RIB parser reads from `text`: (Sphere, ObjectInstance,
    /// Display, errors).
    fn census(text: &str) -> (usize, usize, usize, usize) {
        let mut c = (0, 0, 0, 0);
        for item in illume_rib::Parser::new(std::io::Cursor::new(text.as_bytes().to_vec()), "t.rib")
        {
            match item {
                Ok(r) => match r.value {
                    Request::Sphere { .. } => c.0 += 1,
                    Request::ObjectInstance(_) => c.1 += 1,
                    Request::Display { .. } => c.2 += 1,
                    _ => {}
                },
                Err(_) => c.3 += 1,
            }
        }
        c
    }

    #[test]
    fn the_generator_emits_the_requested_primitive_count() {
        let base = FieldSpec {
            prims: 1000,
            instanced: false,
            width: 32,
            height: 24,
            samples: 2,
            aovs: 0,
        };
        assert_eq!(census(&sphere_field(&base)), (1000, 0, 1, 0));
        let inst = FieldSpec {
            prims: 777,
            instanced: true,
            aovs: 3,
            ..base
        };
        // One Sphere inside the ObjectBegin block, placed 777 times; the beauty + 3 AOVs.
        assert_eq!(census(&sphere_field(&inst)), (1, 777, 4, 0));
    }

    #[test]
    fn the_csv_round_trips() {
        let plan = plan(true, 1000);
        let rows: Vec<ScalingRow> = plan
            .iter()
            .enumerate()
            .map(|(i, (axis, spec))| ScalingRow {
                axis: *axis,
                spec: *spec,
                wall_seconds: 0.125 * i as f64,
                cpu_seconds: 1.0 / (i + 1) as f64,
                peak_rss_mb: 17.25 + i as f64,
            })
            .collect();
        assert!(rows.iter().all(|r| r.spec.prims <= 1000));
        assert_eq!(from_csv(&to_csv(&rows)).unwrap(), rows);
        assert!(from_csv("axis\n").is_err());
        assert!(from_csv(&format!("{HEADER}\nwidth,,1,1,1,0,1,0,1,1,1\n")).is_err());
    }

    #[test]
    fn the_growth_exponent_of_a_power_law_is_its_power() {
        let pts: Vec<(f64, f64)> = [1.0, 4.0, 16.0, 64.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.5)))
            .collect();
        assert!((log_slope(&pts) - 1.5).abs() < 1e-12);
        assert!(log_slope(&pts[..1]).is_nan());
    }
}
