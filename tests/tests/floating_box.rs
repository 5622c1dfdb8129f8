//! Seed 1's dam break with a floating box through the three processes, at a CI-sized resolution
//! (Δs = 2 cm instead of 1 cm, the first 0.1 s): the fluid, the structure and the coupler run,
//! the action–reaction ledger closes every window, and the structure solver replays against the
//! recording.

use stack_tests::{binary, case_from, coupler_run, csv_rows, out_dir, stderr};
use std::process::Command;

/// The floating-box case at the CI size (Δs = 2 cm, a lower tank) with `changes` applied.
fn ci_case(dir: &std::path::Path, end_time: &str, changes: &[(&str, &str)]) -> std::path::PathBuf {
    let mut all = vec![
        ("end_time", end_time),
        ("spacing", "0.02"),
        ("output_interval", "0.05"),
        (
            "tank",
            "{ min = [0.0, 0.0, 0.0], max = [0.6, 0.44, 0.4], lid = true }",
        ),
    ];
    all.extend_from_slice(changes);
    case_from("dam-break-floating-box", dir, &all)
}

#[test]
fn coupled_dam_break_runs_closes_the_ledger_and_replays() {
    let dir = out_dir("floating-box-ci");
    let case = ci_case(&dir, "0.1", &[]);
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    let err = stderr(&run);
    println!("{err}");
    assert!(run.status.success(), "{err}");
    assert!(
        err.contains("started tank") && err.contains("started floater"),
        "both solvers run as processes"
    );

    // Ledger: one row per window (Δt_c = 5e-4 s), the force given to the box against the
    // reaction the fluid took; both come from the same pair forces, so they cancel to round-off.
    let ledger = std::fs::read_to_string(out.join("ledger.csv")).unwrap_or_default();
    let rows: Vec<&str> = ledger.lines().skip(1).collect();
    assert_eq!(rows.len(), 200, "one row per window");
    assert!(
        rows.iter().all(|r| r.ends_with(",ok")),
        "every window balances:\n{ledger}"
    );
    let header: Vec<&str> = ledger.lines().next().unwrap_or_default().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    };
    let last: Vec<f64> = rows
        .last()
        .unwrap_or(&"")
        .split(',')
        .map(|v| v.parse().unwrap_or(f64::NAN))
        .collect();
    let (given, taken) = (last[col("floater_fz")], last[col("tank_fz")]);
    println!("last window: force on the box {given:.4} N, reaction taken by the fluid {taken:.4} N");
    assert!(given > 0.0, "the water pushes the box up");
    assert!(
        (given + taken).abs() <= 1e-12 * given.abs().max(1.0),
        "action = −reaction"
    );

    // The box moved and stayed in the tank.
    let z: Vec<f64> = csv_rows(&out.join("floater/body-box.csv"))
        .iter()
        .map(|r| r[3])
        .collect();
    assert!(
        z.len() > 5 && z.iter().all(|z| (0.0..0.4).contains(z)),
        "box heights {z:?}"
    );

    // Replay the structure solver against the recorded fluid forces.
    let replay = Command::new(binary("coupler"))
        .args([
            "replay",
            out.join("recording.rec").to_str().unwrap_or_default(),
            "--participant",
            "floater",
        ])
        .args(["--out", dir.join("replay").to_str().unwrap_or_default()])
        .output()
        .unwrap_or_else(|e| panic!("{e}"));
    let text = format!("{}{}", String::from_utf8_lossy(&replay.stdout), stderr(&replay));
    println!("{text}");
    assert!(replay.status.success(), "{text}");
    assert!(text.contains("PASS"), "{text}");
}

/// Runs the CI-sized floating box for 0.15 s with a box of `density` and the given scheme;
/// returns (success, stderr, the box's history rows).
fn light_box(scheme: &str, density: f64) -> (bool, String, Vec<Vec<f64>>) {
    let dir = out_dir(&format!("light-box-{scheme}"));
    let mass = density * 0.14 * 0.14 * 0.04;
    let case = ci_case(
        &dir,
        "0.15",
        &[("mass", &mass.to_string()), ("scheme", &format!("\"{scheme}\""))],
    );
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    let rows = csv_rows(&out.join("floater/body-box.csv"));
    (run.status.success(), stderr(&run), rows)
}

/// A very light box (100 kg/m³, a quarter of the seed's) is where partitioned coupling meets
/// added-mass trouble. Recorded outcome: with one fluid step per window, explicit coupling runs
/// stably, and implicit coupling converges (3 sweeps per window) to the same trajectory, because
/// the explicit fluid reads the body's kinematics at the start of its step, so a window's force
/// depends only on the state at the window start.
#[test]
fn a_very_light_box_runs_stably_with_explicit_and_implicit_coupling() {
    let (ok_e, err_e, explicit) = light_box("explicit", 100.0);
    println!("explicit: {}", err_e.lines().last().unwrap_or_default());
    assert!(
        ok_e || err_e.contains("stopped") || err_e.contains("unstable"),
        "explicit coupling either runs or is stopped with a diagnostic: {err_e}"
    );
    let (ok_i, err_i, implicit) = light_box("implicit", 100.0);
    println!("implicit: {}", err_i.lines().last().unwrap_or_default());
    assert!(ok_i, "implicit coupling runs stably: {err_i}");
    let speed = |row: &Vec<f64>| (row[8] * row[8] + row[9] * row[9] + row[10] * row[10]).sqrt();
    let fastest = implicit.iter().map(speed).fold(0.0, f64::max);
    // The collapsing column moves at most √(2 g H) ≈ 2.3 m/s in this time; a box faster than
    // that would be an instability, not physics.
    assert!(fastest < 2.5, "implicit: box speed {fastest} m/s");
    assert!(
        implicit.iter().all(|r| (0.0..0.4).contains(&r[3])),
        "implicit: the box stays in the tank"
    );
    if ok_e {
        let last = |h: &Vec<Vec<f64>>| h.last().cloned().unwrap_or_default();
        let (a, b) = (last(&explicit), last(&implicit));
        let gap = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        println!("explicit and implicit box states differ by {gap:.2e} at the end");
        assert!(
            gap < 1e-9,
            "explicit and implicit reach the same trajectory: {gap}"
        );
    }
}

/// The coupled fluid writes its probe CSV like a standalone run: one row at each probe time
/// (every 0.01 s here), sampled after the window is accepted, never twice for an implicit window.
#[test]
fn the_coupled_fluid_writes_its_probes_once_per_probe_time() {
    for scheme in ["explicit", "implicit"] {
        let dir = out_dir(&format!("floating-box-probes-{scheme}"));
        let case = ci_case(&dir, "0.05", &[("scheme", &format!("\"{scheme}\""))]);
        let out = dir.join("out");
        let run = coupler_run(&case, &out);
        assert!(run.status.success(), "{}", stderr(&run));
        let probes = std::fs::read_to_string(out.join("tank/tank_probes.csv")).unwrap_or_default();
        let rows = csv_rows(&out.join("tank/tank_probes.csv"));
        let times: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        println!("{scheme}: probe times {times:?}");
        assert_eq!(rows.len(), 6, "{scheme}: rows at 0, 0.01, …, 0.05 s:\n{probes}");
        for (k, t) in times.iter().enumerate() {
            assert!((t - 0.01 * k as f64).abs() < 1e-6, "{scheme}: row {k} at t = {t}");
        }
        // The surge front moves forward from the column's face (0.3 m) once the gate is gone.
        let front: Vec<f64> = rows.iter().map(|r| r[1]).collect();
        assert!(
            front.windows(2).all(|w| w[1] >= w[0] - 1e-12),
            "{scheme}: the front never retreats: {front:?}"
        );
        assert!(front[5] > front[0], "{scheme}: the front advances: {front:?}");
    }
}
