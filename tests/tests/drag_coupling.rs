//! Issue 13: the unresolved drag coupling through the real processes (coupler, E-MPS fluid,
//! frame structure): a thin column (2 × 2 mm, fixed at both ends) stands in the path of a small
//! dam break. Explicit and implicit coupling must both
//! - keep the ledger's action–reaction balance at round-off every window (the law hands the
//!   structure S2-22/23's node forces and the fluid −f; the tolerance 1e-12 is the ledger's own
//!   default, a few additions of doubles),
//! - close the fluid's momentum budget: change = gravity + walls + drag reactions (1e-9 of
//!   M g t, the bound of the fluid's conservation test without reactions), and
//! - (explicit, constant predictor: the reaction is constant over each one-step window) have
//!   the fluid take exactly the impulse the coupler gave, Σ_w F_w Δt_w, to 1e-9 relative.

use stack_tests::{coupler_run, csv_rows, out_dir, stderr, DRAG_COLUMN_CASE as CASE};
use std::path::Path;

/// Mass of the water: 10 × 10 × 10 particles of 1000 × 0.01³ kg.
const MASS: f64 = 1.0;

/// The `momentum budget` line of the fluid's log: change, gravity, walls, reactions, not applied.
fn momentum_budget(log: &Path) -> [[f64; 3]; 5] {
    let text = std::fs::read_to_string(log).unwrap_or_else(|e| panic!("cannot read {}: {e}", log.display()));
    let line = text
        .lines()
        .find(|l| l.contains("momentum budget"))
        .unwrap_or_else(|| panic!("no momentum budget in {}:\n{text}", log.display()));
    let parts: Vec<[f64; 3]> = line
        .split('|')
        .map(|part| {
            let v: Vec<f64> = part
                .split_whitespace()
                .rev()
                .take(3)
                .map(|w| w.parse().unwrap_or(f64::NAN))
                .collect();
            [v[2], v[1], v[0]]
        })
        .collect();
    [parts[0], parts[1], parts[2], parts[3], parts[4]]
}

fn run(scheme: &str) {
    let dir = out_dir(&format!("drag-column-{scheme}"));
    let case = dir.join("case.toml");
    // Implicit: plain fixed-point iteration converges in ≤ 4 sweeps to 1e-6 per field; Aitken
    // (the default) and IQN-ILS stall at 1e-2 … 1e-1 in the mid-node velocity of the stiff bar
    // (≈ 460 Hz, 4 steps a period) once the surge reaches it (t ≈ 0.15 s).
    let tolerance = if scheme == "implicit" {
        "tolerance = 1e-6\nacceleration = \"constant\"\ninitial_relaxation = 1.0"
    } else {
        ""
    };
    let text = CASE.replace("SCHEME", scheme).replace("TOLERANCE", tolerance);
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    assert!(
        run.status.success(),
        "{scheme}: coupler failed:\n{}",
        stderr(&run)
    );
    let ledger = csv_rows(&out.join("ledger.csv"));
    // window,time,iterations,residual,water_fx,water_fy,water_fz,water_work,column_fx,…,balance,status
    let worst = ledger.iter().map(|r| r[16]).fold(0.0, f64::max);
    let peak = ledger.iter().map(|r| r[8]).fold(0.0, f64::max);
    let window = 5.0e-4;
    let given: Vec<f64> = (0..3)
        .map(|c| ledger.iter().map(|r| r[4 + c] * window).sum())
        .collect();
    let [change, gravity, walls, reactions, unapplied] = momentum_budget(&out.join("water.log"));
    eprintln!(
        "{scheme}: {} windows, peak drag on the column {peak:.4e} N, worst balance {worst:.2e}; fluid reaction \
         impulse {reactions:?}, given {given:?}, not applied {unapplied:?}",
        ledger.len()
    );
    assert!(worst <= 1e-12, "{scheme}: ledger balance {worst:e}");
    assert!(
        peak > 1e-3,
        "{scheme}: the surge must load the column (peak {peak:e} N)"
    );
    let scale = MASS * 9.8 * 0.2;
    for c in 0..3 {
        let residual = change[c] - gravity[c] - walls[c] - reactions[c];
        assert!(
            residual.abs() <= 1e-9 * scale,
            "{scheme}: axis {c}: momentum residual {residual:e}"
        );
    }
    assert!(
        reactions[0] < 0.0,
        "{scheme}: the column slows the water: {reactions:?}"
    );
    // One fluid step per window reads the reaction at the window start: in explicit coupling
    // with a constant predictor that is the window's own (the ledger's) value; in implicit
    // coupling it is the last window's converged end value, which differs from the ledger's row
    // before (evaluated on the iterate the last sweep started from) by the iteration's residual:
    // measured 3.9e-4 of the impulse with tolerance 1e-6 per field, bound 1e-3. (Why it is
    // that large against the per-field tolerance is not settled; see the issue-13 report.)
    let taken_from: Vec<f64> = (0..3)
        .map(|c| match scheme {
            "explicit" => given[c],
            _ => ledger.iter().rev().skip(1).map(|r| r[4 + c] * window).sum(),
        })
        .collect();
    let bound = if scheme == "explicit" { 1e-9 } else { 1e-3 };
    for c in 0..3 {
        let err = (reactions[c] + unapplied[c] - taken_from[c]).abs();
        assert!(
            err <= bound * given[0].abs(),
            "{scheme}: axis {c}: impulse taken {} vs given {}",
            reactions[c],
            taken_from[c]
        );
    }
}

#[test]
fn a_thin_column_in_a_dam_break_balances_action_and_reaction_explicitly() {
    run("explicit");
}

#[test]
fn a_thin_column_in_a_dam_break_balances_action_and_reaction_implicitly() {
    run("implicit");
}
