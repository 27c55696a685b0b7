//! Slow `render_rib` inputs found by fuzzing (issue 21): each rendered through the target's
//! own body (24×24 at most, 2×2 samples, ShadingRate ≥ 1), with a bound on the micropolygons
//! diced instead of a time limit (tests do not time). What each one was is in
//! `fuzz/README.md`.
use crate::illume_fuzz;

fn micropolygons(name: &str) -> u64 {
    let path = crate::seeds::repo().join("fuzz/open_findings").join(name);
    let data = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = std::time::Instant::now();
    let stats = illume_fuzz::render_rib_stats(&data);
    let mp = stats.iter().map(|s| s.micropolygons).sum();
    eprintln!(
        "{name}: {} frames, {mp} micropolygons, grids {}, pieces {}, {:.2} s",
        stats.len(),
        stats.iter().map(|s| s.grids).sum::<u64>(),
        stats.iter().map(|s| s.pieces).sum::<u64>(),
        t.elapsed().as_secs_f64()
    );
    mp
}

#[test]
fn slow_render_inputs_dice_a_bounded_number_of_micropolygons() {
    for name in [
        "render_rib_slow_1.rib",
        "render_rib_slow_2.rib",
        "render_rib_slow_3.rib",
    ] {
        let mp = micropolygons(name);
        assert!(mp < 1_000_000_000, "{name}: {mp} micropolygons");
    }
}
