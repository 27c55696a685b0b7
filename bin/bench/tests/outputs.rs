//! The writers on known points: the CSV is rectangular and round-trips the numbers, the plot
//! is a valid PNG (decoded by the `png` crate) of the documented size with the knob colours
//! and the Pareto rings drawn, the markdown picks the fastest setting under each target.
use bench::knob::{Knob, Settings};
use bench::measure::Cost;
use bench::metrics::ErrorStats;
use bench::sweep::{mark_pareto, Point};

fn point(scene: &str, knob: Knob, value: f64, wall: f64, rmse: f64) -> Point {
    let e = ErrorStats {
        rmse,
        max_abs: 4.0 * rmse,
        psnr: bench::metrics::psnr(rmse),
        pixels: 100,
    };
    Point {
        scene: scene.into(),
        knob: Some(knob),
        value,
        settings: Settings::defaults(256, 2).with(knob, value),
        cost: Cost {
            wall_seconds: wall,
            cpu_seconds: wall * 1.8,
            peak_rss_mb: 12.0,
            micropolygons: (1000.0 / wall) as u64,
        },
        vs_converged: Some(e),
        vs_closed: None,
        pareto: false,
    }
}

fn scenes() -> Vec<(String, Vec<Point>)> {
    let mut a = vec![
        point("a", Knob::PixelSamples, 1.0, 0.05, 2e-2),
        point("a", Knob::PixelSamples, 2.0, 0.1, 8e-3),
        point("a", Knob::PixelSamples, 4.0, 0.3, 4e-3),
        point("a", Knob::ShadingRate, 4.0, 0.04, 3e-2),
        point("a", Knob::ShadingRate, 0.5, 0.2, 9e-3), // dominated by PixelSamples 2
        point("a", Knob::Threads, 1.0, 0.17, 8e-3),    // dominated
    ];
    mark_pareto(&mut a);
    let mut b = vec![
        point("b", Knob::ShadowSamples, 1.0, 1.0, 0.1),
        point("b", Knob::ShadowSamples, 64.0, 3.0, 0.01),
        point("b", Knob::RaytracedShadowBlur, 0.0, 0.5, 0.02),
    ];
    mark_pareto(&mut b);
    vec![("a".into(), a), ("b".into(), b)]
}

#[test]
fn pareto_marks_exactly_the_undominated_points() {
    let s = scenes();
    let marked: Vec<bool> = s[0].1.iter().map(|p| p.pareto).collect();
    assert_eq!(marked, [true, true, true, true, false, false]);
}

#[test]
fn csv_is_rectangular_and_keeps_the_numbers() {
    let all: Vec<Point> = scenes().into_iter().flat_map(|(_, p)| p).collect();
    let text = bench::csv::to_csv(&all);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), all.len() + 1);
    let header: Vec<&str> = lines[0].split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for (line, p) in lines[1..].iter().zip(&all) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), header.len(), "{line}");
        assert_eq!(f[col("knob")], p.knob.unwrap().name());
        let wall: f64 = f[col("wall_s")].parse().unwrap();
        assert!((wall - p.cost.wall_seconds).abs() < 1e-4);
        let rmse: f64 = f[col("rmse_converged")].parse().unwrap();
        assert!((rmse - p.error()).abs() <= 1e-6 * p.error());
        assert_eq!(f[col("rmse_closed")], "");
        assert_eq!(f[col("pareto")], if p.pareto { "1" } else { "0" });
    }
}

#[test]
fn plot_is_a_png_with_curves_and_pareto_rings() {
    let png_bytes = bench::plot::plot_png(&scenes()).unwrap();
    let decoder = png::Decoder::new(std::io::Cursor::new(png_bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    // Two panels of 600×420 side by side plus the legend: its 5 entries fit one 26-pixel row
    // with a 20-pixel margin.
    assert_eq!((info.width, info.height), (1200, 466));
    assert_eq!(info.color_type, png::ColorType::Rgba);
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks_exact(4).collect();
    let count = |rgb: [u8; 3]| px.iter().filter(|p| p[..3] == rgb).count();
    // Every knob's curve in its own colour, black rings and labels, a white ground.
    for knob in [
        Knob::PixelSamples,
        Knob::ShadingRate,
        Knob::ShadowSamples,
        Knob::Threads,
    ] {
        let n = count(bench::plot::knob_rgb(knob));
        assert!(n > 20, "{} curve missing ({n} pixels)", knob.name());
    }
    let colours: std::collections::HashSet<[u8; 3]> = bench::knob::ALL_KNOBS
        .iter()
        .map(|&k| bench::plot::knob_rgb(k))
        .collect();
    assert_eq!(
        colours.len(),
        bench::knob::ALL_KNOBS.len(),
        "two knobs share a colour"
    );
    assert!(
        count([0, 0, 0]) > 1000,
        "axes, labels and Pareto rings missing"
    );
    assert!(count([255, 255, 255]) > px.len() / 2);
}

#[test]
fn markdown_names_the_fastest_setting_under_each_target() {
    let md = bench::table::markdown(&scenes(), &Settings::defaults(256, 2), "heading");
    let row = md
        .lines()
        .find(|l| l.starts_with("| a (converged)"))
        .unwrap();
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    // CPU time = 1.8 × wall in these points. Targets 3e-2, 1e-2, 3e-3, …: ShadingRate 4
    // (0.072 s, 3e-2), then PixelSamples 2 2 = defaults (0.18 s, 8e-3; ShadingRate 0.5 at
    // 9e-3 is slower, Threads 1 is faster but time-only), then nothing reaches 3e-3.
    assert_eq!(cells[2], "ShadingRate 4: 0.07 s");
    assert_eq!(cells[3], "defaults: 0.18 s");
    assert_eq!(cells[4], "not reached");
    assert!(
        md.contains("RMSE 8.00e-3 in CPU 0.18 s (wall 0.100 s)"),
        "defaults line missing:\n{md}"
    );
}

#[test]
fn csv_reads_back_what_it_wrote() {
    let all: Vec<Point> = scenes().into_iter().flat_map(|(_, p)| p).collect();
    let back = bench::csv::from_csv(&bench::csv::to_csv(&all)).unwrap();
    assert_eq!(back.len(), all.len());
    for (a, b) in all.iter().zip(&back) {
        assert_eq!(
            (&a.scene, a.knob, a.value, a.settings, a.pareto),
            (&b.scene, b.knob, b.value, b.settings, b.pareto)
        );
        assert!((a.cost.wall_seconds - b.cost.wall_seconds).abs() < 1e-4);
        let (ea, eb) = (a.vs_converged.unwrap(), b.vs_converged.unwrap());
        assert!((ea.rmse - eb.rmse).abs() <= 1e-6 * ea.rmse);
        assert!(b.vs_closed.is_none());
    }
    assert!(bench::csv::from_csv("scene,knob\na,b\n").is_err());
    assert!(back.iter().any(|p| p.settings.raytraced_shadows));
}

#[test]
fn csv_without_the_raytraced_column_reads_as_map_shadows() {
    // A CSV written before the ray-traced knobs: drop the column from header and rows.
    let all: Vec<Point> = scenes().into_iter().flat_map(|(_, p)| p).collect();
    let text = bench::csv::to_csv(&all);
    let col = text
        .lines()
        .next()
        .unwrap()
        .split(',')
        .position(|h| h == "raytraced_shadows")
        .expect("raytraced_shadows column");
    let old: String = text
        .lines()
        .map(|l| {
            let mut f: Vec<&str> = l.split(',').collect();
            f.remove(col);
            f.join(",") + "\n"
        })
        .collect();
    let back = bench::csv::from_csv(&old).unwrap();
    assert_eq!(back.len(), all.len());
    assert!(back.iter().all(|p| !p.settings.raytraced_shadows));
    assert_eq!(back[0].settings, all[0].settings);
}
