//! Issue 38 item 3: the CI twin of `cases/prism-dam-break` (`prism_cases.rs`: Δs = 0.02 m, to
//! 0.3 s) with the fluid on the GPU path, through the real processes, against the same twin on
//! the CPU: S2 §5's 0.05 m prism, 2.5 particles wide, so its reactions are spread over a footprint
//! (`fluid-solver/src/gpu/drag.rs`), on a frame that bends. The case's `[report]` ladders (they
//! include an ISPH rung, which the GPU refuses) are left out; they do not change the run.
//!
//! Checked: the ledger balances every window to the CPU's 1e-12 (the law gives +f and −f on the
//! host), the fluid's momentum budget closes to the f32 bound of `gpu_drag_column.rs` (1e-5 of
//! the gravity impulse), and the prism's x impulse equals the CPU run's within 1e-2: the sampled
//! velocities differ by f32 rounding carried through the flow (2e-3 m/s at most,
//! `fluid-solver/tests/gpu_drag.rs`, against the surge's ~1 m/s) and the law's force goes with u²,
//! 4e-3, with a margin for the front's arrival. Measured on lavapipe (29 Nov 2026): 3.1e-3.

use crate::drag_coupling::momentum_budget;
use crate::prism_cases::{coarse_case, column, impulse_x, unresolved_twin};
use schemas::validation::{largest_abs, record, Record};
use stack_tests::{csv_header, csv_rows, gpu_coupler_run, out_dir};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The bound on |impulse_gpu / impulse_cpu − 1| (see the module doc).
const IMPULSE_BOUND: f64 = 1.0e-2;

/// The bound on the GPU's momentum residual, relative to the gravity impulse (`gpu_drag_column.rs`).
const BUDGET_BOUND: f64 = 1.0e-5;

/// The CI twin on `backend` without its `[report]` tables, written into `dir`.
fn twin(dir: &Path, backend: &str) -> PathBuf {
    let sub = dir.join(backend);
    std::fs::create_dir_all(&sub).unwrap_or_else(|e| panic!("{e}"));
    // the resolved prism the case names as its reference must sit beside it
    coarse_case("prism-dam-break", "resolved.toml", &sub, 0.3);
    let path = coarse_case("prism-dam-break", "case.toml", &sub, 0.3);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let mut report = false;
    let mut kept: Vec<String> = Vec::new();
    for line in text.lines() {
        if line.starts_with('[') {
            report = line.starts_with("[report") || line.starts_with("[[report");
        }
        if !report {
            kept.push(line.to_string());
        }
        if line == "[fluid.water]" {
            kept.push(format!("backend = \"{backend}\""));
        }
    }
    assert!(
        kept.iter().any(|l| l == &format!("backend = \"{backend}\"")),
        "no [fluid.water] section in {}",
        path.display()
    );
    std::fs::write(&path, kept.join("\n")).unwrap_or_else(|e| panic!("{e}"));
    path
}

/// Runs the twin on `backend`: its output folder; `None` when there is no GPU and `REQUIRE_GPU`
/// is not 1 (skip).
fn run(dir: &Path, backend: &str) -> Option<PathBuf> {
    let case = twin(dir, backend);
    let out = dir.join(backend).join("out");
    gpu_coupler_run(&case, &out, backend)?;
    Some(out)
}

#[test]
fn the_prism_twin_runs_with_the_gpu_fluid_and_takes_the_cpu_runs_impulse() {
    let dir = out_dir("gpu-prism");
    let started = Instant::now();
    let Some(gpu) = run(&dir, "gpu") else {
        return;
    };
    // the CPU twin is the one prism_cases.rs runs (with its [report] ladders, which do not
    // change the run)
    let cpu = unresolved_twin().0.clone();
    let run_time_s = started.elapsed().as_secs_f64();
    let header = csv_header(&gpu.join("ledger.csv"));
    let (g, c) = (
        csv_rows(&gpu.join("ledger.csv")),
        csv_rows(&cpu.join("ledger.csv")),
    );
    assert_eq!(g.len(), c.len(), "ledger rows");
    let balance = largest_abs(g.iter().map(|r| r[column(&header, "balance")]));
    let fx = column(&header, "prism_fx");
    let (jg, jc) = (impulse_x(&g, fx), impulse_x(&c, fx));
    let impulse = (jg / jc - 1.0).abs();
    let [change, gravity, walls, reactions, _] = momentum_budget(&gpu.join("water.log"));
    let residual = largest_abs((0..3).map(|k| change[k] - gravity[k] - walls[k] - reactions[k]));
    let scale = largest_abs(gravity);
    println!(
        "ledger balance {balance:.2e}; prism x impulse GPU {jg:.6} N s, CPU {jc:.6} N s ({impulse:.2e}); momentum residual {:.2e} of the gravity impulse",
        residual / scale
    );
    record(Record {
        id: "gpu-prism-vs-cpu-impulse".into(),
        capability: "Unresolved drag coupling on the GPU (f32), coupled".into(),
        reference: "the same twin with the f64 CPU fluid".into(),
        case: "cases/prism-dam-break's CI twin (prism_cases.rs), 0.3 s, its [report] left out".into(),
        resolution: "E-MPS, Δs = 0.02 m, Δt = window = 8e-4 s, D = 0.05 m (2.5 particles: a footprint)".into(),
        measure: "|prism x impulse on the GPU / on the CPU − 1|".into(),
        value: impulse,
        bound: Some(IMPULSE_BOUND),
        bound_source: "f32 differences of the sampled velocity (gpu_drag.rs) through the law's u², with a margin (gpu_prism.rs)".into(),
        source: "tests/tests/gpu_prism.rs::the_prism_twin_runs_with_the_gpu_fluid_and_takes_the_cpu_runs_impulse".into(),
        run_time_s,
        ..Default::default()
    });
    assert!(balance <= 1e-12, "ledger balance {balance:e}");
    assert!(
        residual <= BUDGET_BOUND * scale,
        "momentum residual {residual:e} N s"
    );
    assert!(jc > 0.1, "the surge must load the prism: {jc} N s");
    assert!(
        impulse <= IMPULSE_BOUND,
        "the GPU's impulse differs by {impulse:e} of the CPU's"
    );
}
