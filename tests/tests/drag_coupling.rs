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
    // Implicit: plain fixed-point iteration (ω = 1) converges in ≤ 2 sweeps to 1e-6 per field;
    // Aitken and IQN-ILS are tested on a shorter twin below.
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

/// The column 2 mm behind the gate, so the surge reaches it at t ≈ 0.06 s (window 119 of 140).
/// Aitken and IQN-ILS must converge every window within `SWEEP_BOUND` sweeps. Before the fix
/// (block scales from the first sweep, where the dry column's velocity is at round-off size,
/// and secant steps that went back to an input already tried) Aitken stopped unconverged in
/// window 126 and IQN-ILS took up to 12 sweeps (on the full case above both stopped at
/// t ≈ 0.151 s); now Aitken takes ≤ 4 and IQN-ILS ≤ 5 (constant relaxation ω = 1: ≤ 2).
fn accelerated(acceleration: &str) {
    let dir = out_dir(&format!("drag-column-{acceleration}"));
    let case = dir.join("case.toml");
    let settings = format!("tolerance = 1e-6\nacceleration = \"{acceleration}\"\nmax_iterations = 30");
    let text = CASE
        .replace("SCHEME", "implicit")
        .replace("TOLERANCE", &settings)
        .replace("end_time = 0.2", "end_time = 0.07")
        .replace("[0.25, 0.05,", "[0.135, 0.05,");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    assert!(run.status.success(), "{acceleration}: {}", stderr(&run));
    let ledger = csv_rows(&out.join("ledger.csv"));
    let sweeps = ledger.iter().map(|r| r[2]).fold(0.0, f64::max);
    let wet = ledger.iter().filter(|r| r[8].abs() > 1e-6).count();
    let peak = ledger.iter().map(|r| r[8]).fold(0.0, f64::max);
    eprintln!(
        "{acceleration}: {} windows, {wet} with drag on the column (peak {peak:.3e} N), at most {sweeps} sweeps",
        ledger.len()
    );
    assert!(
        wet >= 10,
        "{acceleration}: the surge must reach the column ({wet} windows)"
    );
    assert!(
        sweeps <= SWEEP_BOUND,
        "{acceleration}: {sweeps} sweeps in a window, bound {SWEEP_BOUND}"
    );
}

/// Measured 4 (Aitken) and 5 (IQN-ILS); the constant-relaxation run converges in 2.
const SWEEP_BOUND: f64 = 6.0;

#[test]
fn aitken_converges_on_the_drag_column() {
    accelerated("aitken");
}

#[test]
fn iqn_ils_converges_on_the_drag_column() {
    accelerated("iqn-ils");
}
