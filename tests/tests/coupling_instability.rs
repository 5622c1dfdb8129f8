//! Issue 14: the coupler's instability detector (`coupler/src/stability`). The partitioned
//! oscillator with its interface spring 10× and 100× stiffer, coupled explicitly over long
//! windows, used to exit 0 with displacements up to 948 m ("failed silently" in `coupler report
//! --stability`). The detector measures the energy the coupling creates at the interface per
//! window (work done on both masses by the spring forces they were handed, plus the change of
//! the spring's ½ k d²) against the run's physical energy scale, and stops the run past
//! `coupling.created_energy_limit` (default 10) times that scale. Normal runs must not alarm.

use stack_tests::{csv_rows, oscillator_case, out_dir, stderr};
use std::process::Command;

/// k_middle of the case, 16π² N/m.
const K_MIDDLE: &str = "157.91367041742973";

/// Runs the oscillator with its coupling spring `factor` times stiffer and `changes`; returns
/// (exit status, stderr, the interface-energy rows, the rows of mass-left's history).
fn run(test: &str, factor: f64, changes: &[(&str, &str)]) -> (bool, String, Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let dir = out_dir(test);
    let case = oscillator_case(&dir, changes);
    let text = std::fs::read_to_string(&case).unwrap_or_default();
    let stiff = (K_MIDDLE.parse::<f64>().unwrap_or(0.0) * factor).to_string();
    std::fs::write(&case, text.replace(K_MIDDLE, &stiff)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let run = Command::new(stack_tests::binary("coupler"))
        .args([
            "run",
            case.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ])
        .output()
        .unwrap_or_else(|e| panic!("cannot start the coupler: {e}"));
    // window,time,created,created_total,net_created,energy_scale,ratio,force_amplitude
    let energy = csv_rows(&out.join("interface_energy.csv"));
    let history = csv_rows(&out.join("mass-left/point-m1.csv"));
    (run.status.success(), stderr(&run), energy, history)
}

fn explicit(window: &str, predictor: &str) -> Vec<(&'static str, String)> {
    vec![
        ("window", window.to_string()),
        ("scheme", "\"explicit\"".into()),
        ("samples", "1".into()),
        ("predictor", format!("\"{predictor}\"")),
    ]
}

fn borrowed<'a>(changes: &'a [(&'static str, String)]) -> Vec<(&'static str, &'a str)> {
    changes.iter().map(|(k, v)| (*k, v.as_str())).collect()
}

fn largest_ratio(energy: &[Vec<f64>]) -> f64 {
    energy
        .iter()
        .map(|r| r[6])
        .fold(0.0, schemas::validation::max_or_nan)
}

/// k × 100 at window 0.05 (the run that reached 948 m): stopped in its first window, with the
/// window, the energy and what to change; its outputs hold only finite values.
#[test]
fn a_stiff_spring_coupled_explicitly_is_stopped_in_its_first_window() {
    let changes = explicit("0.05", "linear");
    let (ok, err, energy, history) = run("instability-k100", 100.0, &borrowed(&changes));
    println!("{err}");
    assert!(!ok, "the run must fail");
    for needed in [
        "coupling instability in window 0",
        "the coupling created",
        "physical energy scale",
        "shorten coupling.window",
        "coupling.scheme = \"implicit\"",
    ] {
        assert!(err.contains(needed), "the diagnostic says `{needed}`:\n{err}");
    }
    assert_eq!(
        energy.len(),
        1,
        "interface_energy.csv: one row, the stopped window"
    );
    assert!(energy[0][6] > 10.0, "ratio {}", energy[0][6]);
    assert!(history.iter().flatten().all(|v| v.is_finite()));
}

/// k × 10 at window 0.02: the report found |u1| = 29.6 m, beyond the energy bound
/// √(1 + k_middle/k_left) = √41 = 6.4 m of this stiffness. Stopped at window 10 (t = 0.22 s;
/// C/S passed 10 at window 6 and stayed above it); every written displacement is still within
/// the bound (largest 4.2 m).
#[test]
fn a_growing_instability_is_stopped_before_the_motion_leaves_its_energy_bound() {
    let changes = explicit("0.02", "linear");
    let (ok, err, energy, history) = run("instability-k10", 10.0, &borrowed(&changes));
    println!("{err}");
    assert!(!ok, "the run must fail");
    assert!(err.contains("coupling instability in window"), "{err}");
    let stopped = energy.last().map(|r| r[1]).unwrap_or(f64::NAN);
    assert!(stopped < 0.25, "stopped at t = {stopped} s");
    let largest = history
        .iter()
        .map(|r| r[1].abs())
        .fold(0.0, schemas::validation::max_or_nan);
    assert!(largest <= 41f64.sqrt(), "|u1| reached {largest} m");
}

/// The implicit twin of the first test converges every window: the coupling creates nothing
/// beyond the iteration's residual (measured ratio 4e-13, bound 1e-9).
#[test]
fn the_implicit_twin_creates_no_energy() {
    let (ok, err, energy, _) = run("instability-k100-implicit", 100.0, &[("window", "0.05")]);
    assert!(ok, "{err}");
    assert!(!err.contains("warning"), "{err}");
    assert_eq!(energy.len(), 20);
    assert!(largest_ratio(&energy) < 1e-9, "{}", largest_ratio(&energy));
}

/// The CI ladders' explicit rungs run to their end. The second-order linear predictor at window
/// 0.02 creates at most 0.31 of the energy scale (no warning); the first-order constant predictor
/// at 0.01, the error-0.59 rung of the README's table, gains 3.7 times it by t = 1 s: it runs to
/// its end (stop at 10: margin 2.7) and warns there.
#[test]
fn the_explicit_ladder_rungs_run_to_their_end() {
    let changes = explicit("0.02", "linear");
    let (ok, err, energy, _) = run("instability-linear", 1.0, &borrowed(&changes));
    assert!(ok, "{err}");
    assert!(!err.contains("warning"), "{err}");
    assert_eq!(energy.len(), 50);
    assert!(largest_ratio(&energy) < 0.5, "{}", largest_ratio(&energy));
    let changes = explicit("0.01", "constant");
    let (ok, err, energy, _) = run("instability-constant", 1.0, &borrowed(&changes));
    assert!(ok, "{err}");
    assert!(err.contains("warning: coupling: over the run"), "{err}");
    assert_eq!(energy.len(), 100);
    assert!(largest_ratio(&energy) < 5.0, "{}", largest_ratio(&energy));
}
