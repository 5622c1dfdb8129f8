//! Issue 38 item 3: the unresolved drag coupling with the fluid on the GPU path, through the real
//! processes (coupler, E-MPS fluid with `backend = "gpu"`, frame structure): the thin column of
//! `drag_coupling.rs` 5 mm behind the dam break's board (its short twin), explicit coupling, and
//! the same run with the CPU fluid. The fluid samples the flow at the coupler's points and spreads
//! the reactions on the device (`fluid-solver/src/gpu/drag.rs`). CI runs it on lavapipe
//! (`REQUIRE_GPU=1`). Checked:
//! - the ledger balances every window to the CPU's 1e-12: the law computes +f and −f once on the
//!   host, whatever the fluid's precision;
//! - the fluid takes the impulse the coupler gave to 1e-9 (explicit, constant predictor: the
//!   reaction is constant over each one-step window), booked in f64 on the host from the states
//!   the device found for the reactions;
//! - the fluid's momentum budget (change = gravity + walls + drag reactions) closes to the f32
//!   bound below;
//! - the drag on the column follows the CPU run's within the bound below.

use crate::drag_coupling::momentum_budget;
use schemas::validation::{largest_abs, max_or_nan, Record};
use stack_tests::{csv_rows, gpu_coupler_run, out_dir, replaced, DRAG_COLUMN_CASE};
use std::path::PathBuf;
use std::time::Instant;

/// Mass of the water: 10 × 10 × 10 particles of 1000 × 0.01³ kg.
const MASS: f64 = 1.0;

/// End of the short twin [s], as `drag_coupling.rs`'s ISPH twin: the surge reaches the column
/// 5 mm behind the board and loads it (at 0.05 s it has not yet).
const END: f64 = 0.09;

/// The drag column 5 mm behind the board, to [`END`], explicit, on `backend`.
fn case(backend: &str) -> String {
    replaced(
        DRAG_COLUMN_CASE,
        &[
            ("SCHEME", "explicit"),
            ("TOLERANCE", ""),
            ("end_time = 0.2", &format!("end_time = {END}")),
            (
                "[fluid.water]\n",
                &format!("[fluid.water]\nbackend = \"{backend}\"\n"),
            ),
            ("[0.25, 0.05, 0.0]", "[0.135, 0.05, 0.0]"),
            ("[0.25, 0.05, 0.15]", "[0.135, 0.05, 0.15]"),
        ],
    )
}

/// Runs the twin on `backend`: its output folder; `None` when there is no GPU and `REQUIRE_GPU`
/// is not 1 (skip).
fn run(backend: &str) -> Option<PathBuf> {
    let dir = out_dir(&format!("gpu-drag-column-{backend}"));
    let case_file = dir.join("case.toml");
    std::fs::write(&case_file, case(backend)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let t = Instant::now();
    gpu_coupler_run(&case_file, &out, backend)?;
    println!("{backend}: {:.1} s", t.elapsed().as_secs_f64());
    Some(out)
}

/// The momentum budget's bound on the GPU, relative to M g t: the fluid's momentum is summed on
/// the host in f64 from f32 velocities (relative rounding 6e-8 of each |u| ≲ 1 m/s: 6e-8 M ≈
/// 6e-8 N s against M g t = 0.88 N s); what the f32 pair terms leave is larger: each pair's force
/// is computed twice, once in each particle's gather, with rounding 6e-8 of its size, |P| V ∇W
/// ≈ 500 Pa · 1e-6 m³ / 0.01 m = 0.05 N, about 20 pairs per particle: per particle and step
/// 6e-8 × 0.05 N × √20 = 1.3e-8 N of random sign, over 1 000 particles √1000 × 1.3e-8 =
/// 4.2e-7 N, times Δt over 180 steps as a walk: 4.2e-7 × 5e-4 × 13.4 = 2.8e-9 N s; and the
/// walls' impulse (summed on the device in f32 over the walls' pairs, 2⁻²⁴ × depth 80 ≈ 5e-6 of
/// itself, `gpu_common/compare.rs`): 5e-6 × 0.88 N s = 4.4e-6 N s. So 1e-5 of M g t.
const BUDGET_BOUND: f64 = 1.0e-5;

/// The drag on the column, GPU against CPU: the sampled velocities differ by f32 rounding carried
/// through the flow (2e-3 m/s at most over 200 steps of the slab, `fluid-solver/tests/gpu_drag.rs`,
/// about 1e-3 of the surge's ~1.5 m/s), and the law's force goes with u²: 2 × 1e-3 of the
/// peak; with the surge's front, where the flow changes fastest, a margin of 5: 1e-2 of the peak.
const DRAG_BOUND: f64 = 1.0e-2;

#[test]
fn the_drag_column_runs_with_the_gpu_fluid_through_the_stack() {
    let started = Instant::now();
    let Some(gpu) = run("gpu") else {
        return;
    };
    let Some(cpu) = run("cpu") else {
        return;
    };
    let run_time_s = started.elapsed().as_secs_f64();
    let (g, c) = (
        csv_rows(&gpu.join("ledger.csv")),
        csv_rows(&cpu.join("ledger.csv")),
    );
    assert_eq!(g.len(), c.len(), "ledger rows");
    // window,time,iterations,residual,water_fx,water_fy,water_fz,water_work,column_fx,…,balance,status
    let balance = largest_abs(g.iter().map(|r| r[15]));
    let peak = c.iter().map(|r| r[8].abs()).fold(0.0, max_or_nan);
    let drag = g
        .iter()
        .zip(&c)
        .map(|(a, b)| (a[8] - b[8]).abs())
        .fold(0.0, max_or_nan)
        / peak;
    let window = 5.0e-4;
    let given: Vec<f64> = (0..3)
        .map(|k| g.iter().map(|r| r[4 + k] * window).sum())
        .collect();
    let [change, gravity, walls, reactions, unapplied] = momentum_budget(&gpu.join("water.log"));
    let taken = largest_abs((0..3).map(|k| reactions[k] + unapplied[k] - given[k])) / given[0].abs();
    let residual = largest_abs((0..3).map(|k| change[k] - gravity[k] - walls[k] - reactions[k]));
    let scale = MASS * 9.8 * END;
    println!(
        "{} windows: ledger balance {balance:.2e}; the fluid took {reactions:?} (+ not applied {unapplied:?}) of {given:?} N s ({taken:.2e}); momentum residual {:.2e} of M g t; drag on the column: CPU peak {peak:.4e} N, GPU differs by {drag:.2e} of it",
        g.len(),
        residual / scale
    );
    let row = Record {
        capability: "Unresolved drag coupling on the GPU (f32), coupled".into(),
        reference: "the same run with the f64 CPU fluid; the coupler's impulse; Newton's laws".into(),
        case: format!("2 × 2 mm column fixed at both ends 5 mm behind a small dam break's board (DRAG_COLUMN_CASE), to {END} s"),
        resolution: "E-MPS, Δs = 0.01 m, window = Δt = 5e-4 s, explicit coupling".into(),
        source: "tests/tests/gpu_drag_column.rs::the_drag_column_runs_with_the_gpu_fluid_through_the_stack".into(),
        run_time_s,
        ..Default::default()
    };
    for (what, measure, value, bound, bound_source, unit) in [
        (
            "action-reaction",
            "worst relative ledger balance over the windows",
            balance,
            1e-12,
            "the ledger's CPU default: the law gives +f and −f on the host",
            "",
        ),
        (
            "impulse",
            "largest |impulse the fluid took − impulse given| over the axes / |x impulse given|",
            taken,
            1e-9,
            "round-off: the reaction is constant over each one-step window, booked in f64",
            "",
        ),
        (
            "momentum-budget",
            "largest |momentum residual| over the axes / (M g t)",
            residual / scale,
            BUDGET_BOUND,
            "f32 rounding of the pair terms and the walls' impulse (gpu_drag_column.rs)",
            "",
        ),
        (
            "drag",
            "largest |column x force on the GPU − on the CPU| over the windows / the CPU's peak",
            drag,
            DRAG_BOUND,
            "f32 differences of the sampled velocity through the law's u² (gpu_drag_column.rs)",
            "",
        ),
    ] {
        schemas::validation::record(Record {
            id: format!("gpu-drag-column-vs-cpu-{what}"),
            measure: measure.into(),
            value,
            bound: Some(bound),
            bound_source: bound_source.into(),
            unit: unit.into(),
            ..row.clone()
        });
    }
    assert!(balance <= 1e-12, "ledger balance {balance:e}");
    assert!(
        taken <= 1e-9,
        "the fluid took {reactions:?} + {unapplied:?}, the coupler gave {given:?}"
    );
    assert!(
        residual <= BUDGET_BOUND * scale,
        "momentum residual {residual:e} N s"
    );
    assert!(
        peak > 1e-3,
        "the surge must load the column (CPU peak {peak:e} N)"
    );
    assert!(
        drag <= DRAG_BOUND,
        "the drag differs by {drag:e} of the CPU's peak"
    );
}
