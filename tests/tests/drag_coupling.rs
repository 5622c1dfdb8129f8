//! Issue 13: the unresolved drag coupling through the real processes (coupler, E-MPS fluid, and
//! ISPH on a short twin; frame structure): a thin column (2 × 2 mm, fixed at both ends) stands in
//! the path of a small dam break. Explicit and implicit coupling must both
//! - keep the ledger's action–reaction balance at round-off every window (the law hands the
//!   structure S2-22/23's node forces and the fluid −f; the tolerance 1e-12 is the ledger's own
//!   default, a few additions of doubles),
//! - close the fluid's momentum budget: change = gravity + walls + drag reactions (1e-9 of
//!   M g t, the bound of the fluid's conservation test without reactions), and
//! - (explicit, constant predictor: the reaction is constant over each one-step window) have
//!   the fluid take exactly the impulse the coupler gave, Σ_w F_w Δt_w, to 1e-9 relative.

use schemas::validation::{largest_abs, record, Record};
use stack_tests::{
    breakable_drag_column_case, coupler_run, csv_rows, out_dir, stderr, DRAG_COLUMN_CASE as CASE,
};
use std::path::Path;
use std::time::Instant;

/// Mass of the water: 10 × 10 × 10 particles of 1000 × 0.01³ kg.
const MASS: f64 = 1.0;

/// The `momentum budget` line of the fluid's log: change, gravity, walls, reactions, not applied.
pub(crate) fn momentum_budget(log: &Path) -> [[f64; 3]; 5] {
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
    run_case(scheme, Fluid::Emps);
}

/// The fluid method of a run and what its momentum budget is held to.
#[derive(Clone, Copy, PartialEq)]
enum Fluid {
    /// E-MPS on the full case: its momentum budget closes (change = gravity + walls + reactions).
    Emps,
    /// ISPH's default settings (the exact projection) on the short twin (column 5 mm behind the
    /// gate, to t = 0.09 s): its pressure force is antisymmetric pair by pair, so its budget
    /// closes as E-MPS's does (issue 40 item 1: the reactions the coupler hands the fluid appear
    /// in its momentum).
    Isph,
    /// ISPH with S2-8's gradient (`pressure_gradient = "corrected-difference"`) on the short
    /// twin. Its budget does not close that way (measured: 2.8e-2 N s in x, 6.1e-2 N s in z of
    /// the 0.88 N s gravity impulse; S2-8's wall term is not the reaction of the pressure it puts
    /// on the fluid), so only the drag reactions are checked: the fluid takes what it is given.
    IsphS2_8,
}

fn run_case(scheme: &str, fluid: Fluid) {
    let name = match fluid {
        Fluid::Emps => format!("drag-column-{scheme}"),
        Fluid::Isph => format!("drag-column-isph-{scheme}"),
        Fluid::IsphS2_8 => format!("drag-column-isph-s2-8-{scheme}"),
    };
    let dir = out_dir(&name);
    let case = dir.join("case.toml");
    // Implicit: plain fixed-point iteration (ω = 1) converges in ≤ 2 sweeps to 1e-6 per field;
    // Aitken and IQN-ILS are tested on a shorter twin below.
    let tolerance = if scheme == "implicit" {
        "tolerance = 1e-6\nacceleration = \"constant\"\ninitial_relaxation = 1.0"
    } else {
        ""
    };
    let mut text = CASE.replace("SCHEME", scheme).replace("TOLERANCE", tolerance);
    if fluid != Fluid::Emps {
        // ISPH has no sound speed (its PPE makes the flow incompressible)
        text = text
            .replace("[fluid.water]\n", "[fluid.water]\nmethod = \"isph\"\n")
            .replace("sound_speed = 12.1\n", "")
            .replace("end_time = 0.2", "end_time = 0.09")
            .replace("[0.25, 0.05,", "[0.135, 0.05,");
        assert!(text.contains("method = \"isph\"") && !text.contains("sound_speed"));
    }
    text += match fluid {
        Fluid::Emps => "",
        Fluid::Isph => "",
        Fluid::IsphS2_8 => "\n[fluid.water.isph]\npressure_gradient = \"corrected-difference\"\n",
    };
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let started = Instant::now();
    let run = coupler_run(&case, &out);
    let run_time_s = started.elapsed().as_secs_f64();
    assert!(
        run.status.success(),
        "{scheme}: coupler failed:\n{}",
        stderr(&run)
    );
    let ledger = csv_rows(&out.join("ledger.csv"));
    // window,time,iterations,residual,water_fx,water_fy,water_fz,water_work,column_fx,…,balance,status
    // (balance is column 15; a NaN balance fails the bound below)
    let worst = largest_abs(ledger.iter().map(|r| r[15]));
    let peak = ledger
        .iter()
        .map(|r| r[8])
        .fold(0.0, schemas::validation::max_or_nan);
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
    let (method, tag, test) = match (fluid, scheme) {
        (Fluid::Emps, "explicit") => (
            "E-MPS",
            "emps",
            "a_thin_column_in_a_dam_break_balances_action_and_reaction_explicitly",
        ),
        (Fluid::Emps, _) => (
            "E-MPS",
            "emps",
            "a_thin_column_in_a_dam_break_balances_action_and_reaction_implicitly",
        ),
        (Fluid::Isph, _) => (
            "ISPH (default: exact projection)",
            "isph",
            "a_thin_column_in_an_isph_dam_break_balances_action_and_reaction_implicitly",
        ),
        (Fluid::IsphS2_8, _) => (
            "ISPH (S2-8 gradient)",
            "isph-s2-8",
            "a_thin_column_in_an_s2_8_isph_dam_break_takes_the_reactions_explicitly",
        ),
    };
    let drag_column =
        |what: &str, reference: &str, measure: &str, value: f64, bound: f64, bound_source: &str| Record {
            id: format!("drag-column-{tag}-{scheme}-{what}"),
            capability: "unresolved drag coupling, momentum ledger".into(),
            reference: reference.into(),
            case: "2 × 2 mm column fixed at both ends in a small dam break (DRAG_COLUMN_CASE)".into(),
            resolution: format!("{method}, Δs = 0.01 m, window = Δt = 5e-4 s, {scheme} coupling"),
            measure: measure.into(),
            value,
            bound: Some(bound),
            bound_source: bound_source.into(),
            source: format!("tests/tests/drag_coupling.rs::{test}"),
            run_time_s,
            ..Default::default()
        };
    record(drag_column(
        "action-reaction",
        "Newton's third law: the fluid takes −f of the node forces S2-22/23 hand the structure",
        "worst relative ledger balance over the windows",
        worst,
        1e-12,
        "the ledger's own default: a few additions of doubles",
    ));
    assert!(worst <= 1e-12, "{scheme}: ledger balance {worst:e}");
    assert!(
        peak > 1e-3,
        "{scheme}: the surge must load the column (peak {peak:e} N)"
    );
    let scale = MASS * 9.8 * 0.2;
    let closes = fluid != Fluid::IsphS2_8;
    if closes {
        let worst_residual = largest_abs((0..3).map(|c| change[c] - gravity[c] - walls[c] - reactions[c]));
        record(drag_column(
            "momentum-budget",
            "conservation of momentum: the fluid's change = gravity + walls + drag reactions",
            "largest |momentum residual| over the axes / (M g t)",
            worst_residual / scale,
            1e-9,
            "the fluid's conservation test without reactions",
        ));
    }
    for c in (0..3).filter(|_| closes) {
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
    let worst_impulse = largest_abs((0..3).map(|c| reactions[c] + unapplied[c] - taken_from[c]));
    record(drag_column(
        "impulse",
        "the impulse the coupler gave, Σ_w F_w Δt_w (explicit: the window's own value; implicit: the last \
         window's converged end value)",
        "largest |impulse the fluid took − impulse given| over the axes / |x impulse given|",
        worst_impulse / given[0].abs(),
        bound,
        if scheme == "explicit" {
            "round-off: the reaction is constant over each one-step window"
        } else {
            "the iteration's residual: measured 3.9e-4 of the impulse with tolerance 1e-6 per field"
        },
    ));
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

/// The drag coupling with ISPH's default (issue 13: "for both fluid methods"): implicit coupling
/// (fixed point, ω = 1) on the short twin; the surge loads the column from t ≈ 0.07 s. The
/// fluid's momentum change is gravity + walls + the drag reactions to 1e-9 of M g t, as E-MPS's
/// (issue 40 item 1).
#[test]
fn a_thin_column_in_an_isph_dam_break_balances_action_and_reaction_implicitly() {
    run_case("implicit", Fluid::Isph);
}

/// The same short twin with S2-8's gradient, explicit coupling: the fluid takes the reactions it
/// is given (its momentum budget does not close, [`Fluid::IsphS2_8`]).
#[test]
fn a_thin_column_in_an_s2_8_isph_dam_break_takes_the_reactions_explicitly() {
    run_case("explicit", Fluid::IsphS2_8);
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
    let sweeps = ledger
        .iter()
        .map(|r| r[2])
        .fold(0.0, schemas::validation::max_or_nan);
    let wet = ledger.iter().filter(|r| r[8].abs() > 1e-6).count();
    let peak = ledger
        .iter()
        .map(|r| r[8])
        .fold(0.0, schemas::validation::max_or_nan);
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

/// Fracture under implicit coupling (issue 13, topology that changes): the column of the short
/// twin above as a cantilever (its top support removed, a node at 5 cm) with a yield stress
/// lowered to 1e4 Pa (plastic moment σ_y b h²/4 = 2e-5 N m: a few thousandths of a newton of
/// drag yield its base) and S2-17's critical curvature 0.01 1/m, so the surge that reaches it
/// at t ≈ 0.06 s breaks it. The sweep in which the frame fractures ends its window (residual NaN
/// in the ledger, a note in the coupler's log); the drag law cuts the new members and the next
/// windows iterate again on the new topology. Checked: the run ends normally after the fracture,
/// the ledger balances to round-off in every window (1e-12, the ledger's own default), the
/// fracture window is the only one not converged, and later windows converge with drag on the
/// broken pieces.
#[test]
fn a_column_fractures_under_implicit_coupling_and_the_run_goes_on() {
    let dir = out_dir("drag-column-implicit-fracture");
    let case = dir.join("case.toml");
    let text = breakable_drag_column_case(0.135, 0.09, "");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    let log = stderr(&run);
    assert!(run.status.success(), "{log}");
    let events = std::fs::read_to_string(out.join("column").join("hinge-events.csv")).unwrap_or_default();
    let fractures: Vec<&str> = events.lines().filter(|l| l.contains(",fracture,")).collect();
    let ledger = csv_rows(&out.join("ledger.csv"));
    // window,time,iterations,residual,water_fx,…,column_fx (8),…,balance (15),status
    let worst = largest_abs(ledger.iter().map(|r| r[15]));
    let open: Vec<&Vec<f64>> = ledger.iter().filter(|r| r[3].is_nan()).collect();
    let after = open.first().map_or(f64::INFINITY, |r| r[1]);
    let later: Vec<&Vec<f64>> = ledger.iter().filter(|r| r[1] > after).collect();
    let dragged = later.iter().filter(|r| r[8].abs() > 1e-6).count();
    let sweeps = later
        .iter()
        .map(|r| r[2])
        .fold(0.0, schemas::validation::max_or_nan);
    eprintln!(
        "{} fractures (first {:?}); {} windows, {} ended by a topology change (first at t = {after} s), \
         {} after it: {dragged} with drag on the column, at most {sweeps} sweeps; worst balance {worst:.2e}",
        fractures.len(),
        fractures.first(),
        ledger.len(),
        open.len(),
        later.len()
    );
    assert!(!fractures.is_empty(), "no fracture:\n{events}\n{log}");
    assert!(log.contains("changed (a fracture)"), "no topology note:\n{log}");
    assert!(worst <= 1e-12, "ledger balance {worst:e}");
    assert!(
        open.len() <= fractures.len(),
        "{} windows not converged for {} fractures",
        open.len(),
        fractures.len()
    );
    assert!(
        later.len() >= 20,
        "the run must go on after the fracture at {after} s"
    );
    assert!(
        sweeps >= 2.0,
        "later windows must iterate (at most {sweeps} sweeps)"
    );
    assert!(
        dragged >= 10,
        "the broken column must take drag after the fracture ({dragged} windows)"
    );
}

/// The column standing inside the water block (x = 0.05) from t = 0, explicit coupling, to
/// t = 0.05 s: the water starts to fall past it at once, and buoyancy's reaction (down) does
/// work on that falling water (+3e-8 J a window) while the fixed column takes none. Before the
/// interface-energy scale counted the energy the drag law's forces exchange with the flow, that
/// work was judged against a scale of 0 and the run stopped at t = 0.002 s ("inf times the
/// run's physical energy scale"). It must run to its end; its largest ratio of net created
/// energy to scale is printed (a real instability is still stopped: `coupling_instability.rs`).
#[test]
fn a_column_standing_in_the_water_from_the_start_is_not_stopped_as_unstable() {
    let dir = out_dir("drag-column-in-water");
    let case = dir.join("case.toml");
    let text = CASE
        .replace("SCHEME", "explicit")
        .replace("TOLERANCE", "")
        .replace("end_time = 0.2", "end_time = 0.05")
        .replace("[0.25, 0.05,", "[0.05, 0.05,");
    std::fs::write(&case, text).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let run = coupler_run(&case, &out);
    assert!(run.status.success(), "{}", stderr(&run));
    // window,time,created,created_total,net_created,energy_scale,ratio,force_amplitude
    let energy = csv_rows(&out.join("interface_energy.csv"));
    let worst = energy
        .iter()
        .map(|r| r[6])
        .fold(0.0, schemas::validation::max_or_nan);
    let force = energy
        .iter()
        .map(|r| r[7])
        .fold(0.0, schemas::validation::max_or_nan);
    eprintln!(
        "{} windows, largest C/S {worst:.3}, largest interface force {force:.3e} N",
        energy.len()
    );
    assert_eq!(energy.len(), 100, "every window of the run");
    assert!(force > 1e-3, "the column is loaded from the start ({force:e} N)");
}
