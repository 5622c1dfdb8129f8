//! Issue 17: the floating box of issue 5 (`floating_at_rest.rs`) with the fluid on the GPU
//! path (`backend = "gpu"`), through the real processes: `coupler run`, the fluid participant
//! placing the box's particles on the device from the pose the coupler hands it each window and
//! reducing the box's force and moment there, the rigid-body structure solver, explicit
//! coupling. CI has no GPU: it runs on lavapipe (`.ci/run` installs it and sets `REQUIRE_GPU=1`,
//! under which a run that finds no adapter fails instead of skipping).

use schemas::case::coupling::GPU_BALANCE_TOLERANCE;
use schemas::validation::{record, Record};
use stack_tests::{coupler_run, csv_rows, out_dir, pool_level, replaced, stderr, FLOATING_POOL_CASE};
use std::path::PathBuf;
use std::time::Instant;

/// The floating box case with the GPU fluid, ending at `end_time`, frames every
/// `output_interval` s.
fn gpu_case(backend: &str, end_time: &str, output_interval: &str) -> String {
    replaced(
        FLOATING_POOL_CASE,
        &[
            ("end_time = 2.0", &format!("end_time = {end_time}")),
            (
                "[fluid.pool]\n",
                &format!("[fluid.pool]\nbackend = \"{backend}\"\n"),
            ),
            (
                "output_interval = 0.5",
                &format!("output_interval = {output_interval}"),
            ),
        ],
    )
}

/// Runs the case on `backend`; `None` when there is no GPU and `REQUIRE_GPU` is not 1 (skip).
/// Returns the box's history (t, x, y, z, qw, …), the ledger and the output folder.
fn run(
    test: &str,
    backend: &str,
    end_time: &str,
    output_interval: &str,
) -> Option<(Vec<Vec<f64>>, String, PathBuf)> {
    let dir = out_dir(test);
    let case = dir.join("case.toml");
    std::fs::write(&case, gpu_case(backend, end_time, output_interval)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let t = std::time::Instant::now();
    let run = coupler_run(&case, &out);
    let err = stderr(&run);
    println!("{backend}: {:.1} s\n{err}", t.elapsed().as_secs_f64());
    if !run.status.success()
        && err.contains("no GPU for backend")
        && std::env::var("REQUIRE_GPU").as_deref() != Ok("1")
    {
        eprintln!("skipped (set REQUIRE_GPU=1 to fail instead): no GPU adapter");
        return None;
    }
    assert!(run.status.success(), "{err}");
    let ledger = std::fs::read_to_string(out.join("ledger.csv")).unwrap_or_default();
    Some((csv_rows(&out.join("float/body-box.csv")), ledger, out))
}

/// CI size: 0.024 s (30 windows of one fluid step) on the GPU and on the CPU. The box's centre
/// height on the GPU follows the CPU's within 1e-5 m: loads within the f32 bound of
/// `fluid-solver/tests/gpu_bodies.rs`, 1e-3 of ρgV (ρgV of this box's 2.05e-3 m³ is 20 N),
/// move the box of 0.82 kg by at most 1e-3 · 20 N / 0.82 kg · (0.024 s)²/2 = 7e-6 m; the
/// loads' measured 3e-5 of ρgV would give 2e-7 m. Measured over 0.04 s: 3.4e-8 m (the box
/// falls 2.8 mm while the water's pressure builds up). The ledger balances every window within
/// the GPU's default tolerance (`GPU_BALANCE_TOLERANCE`, 1e-5, derived from f32 rounding in
/// `schemas/src/case/coupling.rs`): the fluid's reaction is summed on the device from the fluid
/// particles' side, the box's loads from the body particles' side, two f32 sums of the pair
/// forces in different orders. Measured: at most 5.1e-8, and above 0 in every window with
/// water on the box (a reaction that merely negated the loads would give 0).
#[test]
fn the_floating_box_runs_with_the_gpu_fluid_through_the_stack() {
    let started = Instant::now();
    let Some((gpu, ledger, _)) = run("gpu-floating", "gpu", "0.024", "0.012") else {
        return;
    };
    let rows: Vec<&str> = ledger.lines().skip(1).collect();
    assert_eq!(rows.len(), 30, "one ledger row per window:\n{ledger}");
    assert!(
        rows.iter().all(|r| r.ends_with(",ok")),
        "every window balances:\n{ledger}"
    );
    let balances: Vec<f64> = rows
        .iter()
        .filter_map(|r| r.rsplit(',').nth(1)?.parse().ok())
        .collect();
    assert_eq!(balances.len(), rows.len(), "a balance per window:\n{ledger}");
    let worst = balances
        .iter()
        .cloned()
        .fold(0.0f64, schemas::validation::max_or_nan);
    let independent = balances.iter().filter(|&&b| b > 0.0).count();
    println!(
        "ledger: worst balance {worst:.3e}, {independent} of {} windows above 0",
        rows.len()
    );
    assert!(
        worst <= GPU_BALANCE_TOLERANCE,
        "the ledger's worst balance {worst:e} is above {GPU_BALANCE_TOLERANCE:e}"
    );
    assert!(
        independent >= rows.len() / 2,
        "the reaction and the loads agree exactly in {} of {} windows: are they still one sum?\n{ledger}",
        rows.len() - independent,
        rows.len()
    );
    let Some((cpu, _, _)) = run("gpu-floating-cpu", "cpu", "0.024", "0.012") else {
        return;
    };
    assert_eq!(gpu.len(), cpu.len(), "history rows");
    let worst = gpu
        .iter()
        .zip(&cpu)
        .map(|(g, c)| (g[3] - c[3]).abs())
        .fold(0.0f64, schemas::validation::max_or_nan);
    let last = (gpu.last().cloned(), cpu.last().cloned());
    println!(
        "box centre z: GPU vs CPU differ by at most {worst:.3e} m over {} rows; last rows {last:?}",
        gpu.len()
    );
    assert!(
        gpu.iter().flatten().all(|v| v.is_finite()),
        "the box's state is not finite"
    );
    record(Record {
        id: "gpu-floating-box-vs-cpu".into(),
        capability: "E-MPS on the GPU (f32) with a resolved body, coupled".into(),
        reference: "the same run with the f64 CPU fluid".into(),
        case: "16 × 16 × 8 cm box of 400 kg/m³ in still water 0.2 m deep (floating_at_rest.rs), 0.024 s"
            .into(),
        resolution: "E-MPS, Δs = 0.02 m, Δt = 8e-4 s, 30 windows of one fluid step, explicit coupling".into(),
        measure: "largest |box centre z on the GPU − on the CPU| over the history".into(),
        value: worst,
        bound: Some(1e-5),
        bound_source: "loads within the f32 bound 1e-3 of ρgV move the 0.82 kg box by at most \
                       1e-3 · 20 N / 0.82 kg · (0.024 s)²/2 = 7e-6 m"
            .into(),
        unit: "m".into(),
        source: "tests/tests/gpu_floating.rs::the_floating_box_runs_with_the_gpu_fluid_through_the_stack"
            .into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        worst < 1e-5,
        "the box's height on the GPU differs from the CPU's by {worst} m (bound 1e-5 m)"
    );
}

/// The CPU test's whole run (`floating_at_rest.rs`, 2 s, 2 500 windows: about 25 minutes on
/// lavapipe here): the box settles at its hydrostatic draft (0.4 × 0.08 m) within 5 %, measured
/// as the CPU test does from the free surface where the pressure field's P = 0, and its heave
/// over the last 0.5 s is below a tenth of the draft.
///
/// Measured 2026-11-24 on lavapipe (46 min beside other work): draft 33.09 mm for 32.00 mm
/// (+3.42 %), free surface 0.19653 m, centre z mean 0.20363 m over t ≥ 1.5 s, heave range
/// 1.32 mm, tilt ≤ 0.87°, the box drifted 1 mm sideways; all 2 500 windows balanced (then by
/// construction: the reaction summed from the fluid's side came later and has not been run over
/// the whole 2 s; the 30-window test above measures it).
#[test]
#[ignore]
fn the_gpu_fluid_floats_the_box_at_its_draft() {
    let started = Instant::now();
    let Some((rows, ledger, out)) = run("gpu-floating-draft", "gpu", "2.0", "0.5") else {
        return;
    };
    assert!(
        ledger.lines().skip(1).all(|r| r.ends_with(",ok")),
        "every window balances (within GPU_BALANCE_TOLERANCE)"
    );
    let late: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] >= 1.5).collect();
    let z_mean = late.iter().map(|r| r[3]).sum::<f64>() / late.len() as f64;
    let (z_lo, z_hi) = late
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), r| (lo.min(r[3]), hi.max(r[3])));
    let (level, top, interior) = pool_level(&out.join("pool/pool_00004.vtu"));
    assert!(interior > 1000, "interior particles: {interior}");
    let last = rows.last().cloned().unwrap_or_default();
    let (draft, expected) = (level - (last[3] - 0.04), 0.4 * 0.08);
    println!(
        "t ≥ 1.5 s: box centre z mean {z_mean:.5} m, range {:.2} mm; free surface {level:.5} m (highest particle {top:.5} m); draft {:.2} mm, hydrostatic {:.2} mm ({:+.2} %)",
        1e3 * (z_hi - z_lo),
        1e3 * draft,
        1e3 * expected,
        100.0 * (draft / expected - 1.0)
    );
    record(Record {
        id: "floating-box-draft-gpu".into(),
        capability: "resolved floating body at rest (E-MPS on the GPU, coupled)".into(),
        reference: "hydrostatic draft: body density / water density × height = 32.0 mm (Archimedes)".into(),
        case: "16 × 16 × 8 cm box of 400 kg/m³ in still water 0.2 m deep, 2 s".into(),
        resolution:
            "E-MPS on the GPU (f32), Δs = 0.02 m, Δt = 8e-4 s, explicit coupling, one fluid step per window"
                .into(),
        measure: "|draft / hydrostatic − 1| at the end, from the free surface where P = 0".into(),
        value: (draft / expected - 1.0).abs(),
        bound: Some(0.05),
        bound_source: "the CPU test's bound (the issue's 5 %)".into(),
        source: "tests/tests/gpu_floating.rs::the_gpu_fluid_floats_the_box_at_its_draft".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        (draft / expected - 1.0).abs() < 0.05,
        "draft {draft} m vs {expected} m (bound 5 %)"
    );
    assert!(
        z_hi - z_lo < 0.1 * expected,
        "heave range {} m over the last 0.5 s",
        z_hi - z_lo
    );
}
