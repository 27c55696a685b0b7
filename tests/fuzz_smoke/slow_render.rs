//! Slow `render_rib` inputs found by fuzzing (issue 21): mutated depth-of-field scenes whose
//! pieces near the lens, blurred over much of the frame, were diced at the shading rate, so
//! each of thousands of micropolygons was tested against every sample its circle of confusion
//! reached (27 to over 60 s of CPU each for a ≤ 24×24 frame). A defocused piece now dices
//! coarser by its smallest circle of confusion (`refine::Refiner::defocus`). Each renders
//! through the target's own body (24×24 at most, 2×2 samples, ShadingRate ≥ 1) with a bound
//! on the micropolygons diced instead of a time limit (tests do not time).
use crate::illume_fuzz;

fn micropolygons(name: &str) -> u64 {
    let path = crate::seeds::repo().join("fuzz/regressions").join(name);
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
        "render_rib_slow_defocus_1.rib",
        "render_rib_slow_defocus_2.rib",
        "render_rib_slow_defocus_3.rib",
    ] {
        let mp = micropolygons(name);
        // 1,600 to 7,300 after the fix. A 24×24 frame at ShadingRate ≥ 1 needs ~600 per
        // layer of surfaces it sees; 50,000 leaves room for ~80 layers and overlap, and is
        // far below what made these slow (a piece near the lens diced at the shading rate).
        assert!(mp > 0 && mp < 50_000, "{name}: {mp} micropolygons");
    }
}

/// Fuzzer blow-ups of the refiner (fifth runs): a hyperboloid reaching 1e24 whose piece, still
/// too big at the deepest split, was diced at up to 4096² micropolygons (over 2 GB; now diced
/// to the grid size, `refine::fit_grid`), and spheres flattened by a singular `Transform`
/// whose pieces, mostly off screen, were split for that reason at every depth although their
/// children kept their bound (2^26 pieces; now split only when a child's bound shrinks,
/// `refine::split_shrinks`).
#[test]
fn refiner_blow_ups_dice_a_bounded_number_of_micropolygons() {
    for name in [
        "render_rib_blowup_hyperboloid.rib",
        "render_rib_blowup_hyperboloid_min.rib",
        "render_rib_blowup_5ef713bf.rib",
        "render_rib_blowup_singular_min.rib",
    ] {
        let mp = micropolygons(name);
        // 2,000 to 61,000 after the fixes, at most 8×8 pixels; before, millions (or out of
        // memory).
        assert!(mp > 0 && mp < 200_000, "{name}: {mp} micropolygons");
    }
}

/// The last open `render_rib` blow-ups of issue 23 (fourth runs). `351f4312` (and its
/// minimised `end_on_min`: an orthographic camera down the axis of a cylinder 7.8·10³⁶ long)
/// split into millions of pieces, every one of whose bounds, padded by f32 rounding of 10³⁰,
/// covered the whole frame, so none was ever culled: over 40 s and 2.7 GB. A piece now dices
/// at the grid size after eight splits whose children all cover the frame
/// (`refine::MAX_STALLED_SPLITS`). The other three (mutated CSG and latlong scenes) already
/// rendered in milliseconds before that change: kept here so they stay fixed.
#[test]
fn last_open_blow_ups_dice_a_bounded_number_of_micropolygons() {
    for name in [
        "render_rib_blowup_351f4312.rib",
        "render_rib_blowup_end_on_min.rib",
        "render_rib_blowup_3fee5e23.rib",
        "render_rib_blowup_6cb1735c.rib",
        "render_rib_blowup_c8a56e60.rib",
    ] {
        let mp = micropolygons(name);
        // 1,100 to 66,000 after the fix (351f4312: 256 pieces of 256 at the stall limit);
        // before, an abort out of memory after tens of millions.
        assert!(mp > 0 && mp < 200_000, "{name}: {mp} micropolygons");
    }
}
