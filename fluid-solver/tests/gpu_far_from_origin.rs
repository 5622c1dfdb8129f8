//! Issue 38 item 5 (its first part): a tank far from the origin on the GPU path. The device keeps
//! positions from the tank's lower corner (`src/gpu/frame.rs`), so georeferenced coordinates
//! round as a tank at the origin does: the slab of `gpu_common/compare.rs` moved 300 km east,
//! 40 km south and 1.2 km up (UTM-like numbers; in absolute f32 its positions would round by
//! 1.8e-2 m, 900 times the position bound) ends where the CPU's f64 run of the same moved case
//! does within the f32 bound of `compare.rs`, and where the GPU run of the slab at the origin
//! does (the device sees the same f32 numbers).
//!
//! 150 steps (0.075 s), before the column's front reaches the far wall: the bound is derived
//! from the equation of state's rounding as a random walk, which the impact's collisions do not
//! follow (the bare slab at 200 steps, after it: 2.1e-4 m between GPU and CPU at the origin as
//! far away; at 150 steps 2.8e-7 m).

use gpu_common::compare::{self, POSITION_BOUND};

use crate::gpu_common;

/// Steps of the runs (see the module doc).
const STEPS: usize = 150;

/// Where the slab is moved to [m].
const AWAY: [f64; 3] = [3.0e5, -4.0e4, 1.2e3];

#[test]
fn a_tank_300_km_from_the_origin_runs_on_the_gpu_as_one_at_the_origin() {
    let dir = compare::folder("far-from-origin");
    let cfg = compare::slab_at(&dir, "", AWAY);
    cfg.gpu_support("fluid.water")
        .unwrap_or_else(|e| panic!("`{}`: {}", e.key, e.message));
    let Some(runs) = compare::run_both(&cfg, STEPS) else {
        return;
    };
    let Some(dev) = gpu_common::device() else {
        return;
    };
    let near = compare::slab(&dir, "");
    let mut at_origin = fluid_solver::FluidSolver::new(&near);
    at_origin.to_device(&near, dev).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..STEPS {
        at_origin.step(near.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    at_origin.sync_host();
    let mut back = runs.gpu.particles().clone();
    for i in 0..back.len() {
        (back.x[i], back.y[i], back.z[i]) = (back.x[i] - AWAY[0], back.y[i] - AWAY[1], back.z[i] - AWAY[2]);
    }
    let translated = compare::largest_fluid_distance(at_origin.particles(), &back);
    println!("the GPU run far away, moved back, is {translated:.3e} m from the GPU run at the origin");
    assert!(
        translated < POSITION_BOUND,
        "the GPU run far away ends {translated:e} m from the one at the origin"
    );
    let absolute = schemas::validation::largest_abs(AWAY) * f64::from(f32::EPSILON) / 2.0;
    println!("absolute f32 positions here would round by {absolute:.2e} m");
    assert!(
        absolute > 100.0 * POSITION_BOUND,
        "the slab is not far enough to tell"
    );
    let worst = compare::check_and_record(
        &runs,
        (
            "far-from-origin",
            "E-MPS 300 km from the origin",
            "the slab's column (0.4 × 0.06 × 0.3 m tank) moved by (3e5, −4e4, 1.2e3) m, 150 steps of 5e-4 s",
            "gpu_far_from_origin.rs::a_tank_300_km_from_the_origin_runs_on_the_gpu_as_one_at_the_origin",
        ),
    );
    // the run moved the water: the comparison is not of two resting states
    let start = fluid_solver::FluidSolver::new(&cfg);
    let moved = compare::largest_fluid_distance(start.particles(), runs.cpu.particles());
    println!("the column moved by up to {moved:.3e} m; GPU within {worst:.3e} m of the CPU");
    assert!(
        moved > compare::VISIBLE * POSITION_BOUND,
        "the column moved by only {moved:e} m"
    );
}
