//! Issue 38 item 5: wide positions. Past 16 777 spacings from the device frame's origin plain
//! f32 positions round by more than 1e-3 Δs, so the device keeps each as hi + lo
//! (`src/gpu/frame.rs`). A tank of 10⁵ spacings would need millions of wall particles, so the
//! check measures the slab of `gpu_common/compare.rs` from a point 10⁵ spacings (2 km) away
//! ([`fluid_solver::FluidSolver::to_device_from`]): the device then holds the numbers a tank
//! that long holds at its far end. It must end where the CPU's f64 run does within the f32
//! bound of `compare.rs`, as the slab measured from its own corner does; in plain f32 its
//! positions would round by 1.2e-4 m there, 6 times that bound, and a slow particle's step
//! (u Δt = 5e-7 m at 1 mm/s) would be lost whole.
//!
//! 150 steps (0.075 s), before the column's front reaches the far wall, as
//! `gpu_far_from_origin.rs` (the bound holds for a random walk of rounding, which an impact's
//! collisions do not follow).

use fluid_solver::FluidSolver;
use gpu_common::compare::{self, DeviceFrame, FAR, POSITION_BOUND};

use crate::gpu_common;

/// Steps of the runs (see the module doc).
const STEPS: usize = 150;

#[test]
fn the_slab_measured_from_100_000_spacings_away_ends_where_the_cpu_run_does() {
    let dir = compare::folder("wide-positions");
    let cfg = compare::slab(&dir, "");
    let plain = (FAR + 0.4) * f64::from(f32::EPSILON) / 2.0;
    println!("plain f32 positions here would round by {plain:.2e} m");
    assert!(
        plain > 5.0 * POSITION_BOUND,
        "the frame's origin is not far enough to tell"
    );
    // compare::to_device asserts that the device keeps wide positions there
    let Some(runs) = compare::run_both_in(&cfg, STEPS, DeviceFrame::Far) else {
        return;
    };
    let quantum = runs.gpu.device().and_then(|d| d.frame().quantum);
    println!("high parts on a grid of {quantum:?} m");
    let worst = compare::check_and_record(
        &runs,
        (
            "wide-positions",
            "E-MPS with wide positions (hi + lo) 10⁵ spacings from the frame's origin",
            "the slab's column (0.4 × 0.06 × 0.3 m tank), the device measuring positions from 2 km away, 150 steps of 5e-4 s",
            "gpu_wide_positions.rs::the_slab_measured_from_100_000_spacings_away_ends_where_the_cpu_run_does",
        ),
    );
    // the run moved the water: the comparison is not of two resting states
    let start = FluidSolver::new(&cfg);
    let moved = compare::largest_fluid_distance(start.particles(), runs.cpu.particles());
    println!("the column moved by up to {moved:.3e} m; GPU within {worst:.3e} m of the CPU");
    assert!(
        moved > compare::VISIBLE * POSITION_BOUND,
        "the column moved by only {moved:e} m"
    );
}

/// Through the case, as a user poses it: a flume 340 m long (17 000 spacings, just past what
/// plain f32 keeps; 2.9 M particles, nearly all walls) with a column 0.16 m wide and high at its
/// far end, `backend = "gpu"`: the device keeps wide positions of its own accord and the column
/// ends where the CPU's does within the f32 bound, 150 steps. Ignored: minutes on lavapipe (the
/// slab from 10⁵ spacings away above is its CI twin).
#[test]
#[ignore]
fn a_flume_17_000_spacings_long_runs_in_wide_positions() {
    let dir = compare::folder("wide-flume");
    let text = r#"[case]
name = "wide-flume"
end_time = 0.075

[fluid.water]
spacing = 0.02
time_step = 5.0e-4
sound_speed = 12.1
output_interval = 0.05
tank = { min = [0.0, 0.0, 0.0], max = [340.0, 0.06, 0.2], lid = true }

[[fluid.water.block]]
min = [339.6, 0.0, 0.0]
max = [339.76, 0.06, 0.16]
"#;
    let case = schemas::case::Case::parse(&dir.join("case.toml"), text.to_string())
        .unwrap_or_else(|e| panic!("{e}"));
    let cfg = case.fluid["water"].clone();
    assert!(
        cfg.gpu_quantum().is_some(),
        "the flume should need wide positions"
    );
    let Some(runs) = compare::run_both(&cfg, STEPS) else {
        return;
    };
    assert!(runs.gpu.device().is_some_and(|d| d.frame().wide()));
    let worst = compare::check_and_record(
        &runs,
        (
            "wide-flume",
            "E-MPS in wide positions through the case (a flume of 17 000 spacings)",
            "a column 0.16 × 0.06 × 0.16 m at the far end of a 340 × 0.06 × 0.2 m flume with its lid (2.9 M particles), 150 steps of 5e-4 s",
            "gpu_wide_positions.rs::a_flume_17_000_spacings_long_runs_in_wide_positions",
        ),
    );
    println!("GPU within {worst:.3e} m of the CPU");
}
