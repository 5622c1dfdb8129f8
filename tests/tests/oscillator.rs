//! The partitioned two-mass oscillator through the real launcher: `coupler run` starts two
//! structure-solver processes (one mass each) and couples them through the middle spring.
//! Exact: u1 = ½(cos 2πt + cos 6πt), u2 = ½(cos 2πt − cos 6πt).
//!
//! Reference (preCICE 3.4 with Newmark participants, window 0.01, error at t = 1): serial
//! explicit 0.16 (order 1); implicit, constant data 0.21 (order 1); implicit, linear in the
//! window 7.1e-3 (order 2); implicit, cubic waveforms with substeps 1.6e-3 (order 2).

use stack_tests::{oscillator_error, oscillator_max_error, run_oscillator, stderr, OscillatorCoupling};

/// Errors of one run: at t = 1 (where preCICE measures; both velocities vanish there, which can
/// hide the leading error term) and the largest over all window ends.
struct Errors {
    at_one: f64,
    max: f64,
}

/// Runs the oscillator with the given coupling settings.
fn run(test: &str, window: f64, scheme: &str, samples: u32, predictor: &str, acceleration: &str) -> Errors {
    let coupling = OscillatorCoupling {
        window,
        scheme,
        samples,
        predictor,
        acceleration,
    };
    let (out, run) = run_oscillator(test, &coupling);
    assert!(run.status.success(), "coupler run failed:\n{}", stderr(&run));
    let ledger = std::fs::read_to_string(out.join("ledger.csv")).unwrap_or_default();
    let rows: Vec<&str> = ledger.lines().skip(1).collect();
    assert_eq!(
        rows.len(),
        (1.0 / window).round() as usize,
        "one ledger row per window"
    );
    assert!(
        rows.iter().all(|r| r.ends_with(",0.000e0,ok")),
        "action = reaction exactly in every window"
    );
    let rec = out.join("recording.rec");
    Errors {
        at_one: oscillator_error(&rec),
        max: oscillator_max_error(&rec),
    }
}

fn order(coarse: f64, fine: f64) -> f64 {
    (coarse / fine).log2()
}

#[test]
fn explicit_with_constant_data_is_first_order() {
    let a = run(
        "explicit-constant-1",
        0.005,
        "explicit",
        1,
        "constant",
        "constant",
    );
    let b = run(
        "explicit-constant-2",
        0.0025,
        "explicit",
        1,
        "constant",
        "constant",
    );
    let p = order(a.max, b.max);
    println!(
        "explicit, constant: max error {:.3e} (0.005), {:.3e} (0.0025), order {p:.2}",
        a.max, b.max
    );
    // preCICE's serial explicit: order 1. (Measured here: 1.30 between 0.01 and 0.005, 1.15 below.)
    assert!((0.9..1.5).contains(&p), "observed order {p}, expected 1");
}

#[test]
fn explicit_with_linear_predictor_is_second_order_and_beats_precice_explicit() {
    let a = run("explicit-linear-1", 0.01, "explicit", 1, "linear", "constant");
    let b = run("explicit-linear-2", 0.005, "explicit", 1, "linear", "constant");
    let p = order(a.max, b.max);
    println!(
        "explicit, linear predictor: error at t = 1 {:.3e}, max {:.3e} (0.01) / {:.3e} (0.005), order {p:.2}",
        a.at_one, a.max, b.max
    );
    // preCICE serial explicit at window 0.01: 0.16 at t = 1.
    assert!(a.at_one < 0.16, "error at t = 1: {}", a.at_one);
    assert!((1.8..2.3).contains(&p), "observed order {p}, expected 2");
}

#[test]
fn implicit_linear_in_window_is_second_order_and_beats_precice_linear() {
    let a = run("implicit-linear-1", 0.02, "implicit", 1, "linear", "iqn-ils");
    let b = run("implicit-linear-2", 0.01, "implicit", 1, "linear", "iqn-ils");
    let p = order(a.max, b.max);
    println!(
        "implicit, linear: error at t = 1 {:.3e}, max {:.3e} (0.02) / {:.3e} (0.01), order {p:.2}",
        b.at_one, a.max, b.max
    );
    // preCICE implicit with linear interpolation at window 0.01: 7.1e-3 at t = 1, order 2.
    assert!(b.at_one < 7.1e-3, "error at t = 1: {}", b.at_one);
    assert!((1.8..2.3).contains(&p), "observed order {p}, expected 2");
}

#[test]
fn implicit_cubic_waveforms_are_fourth_order_and_beat_precice_best() {
    let a = run("implicit-cubic-1", 0.02, "implicit", 4, "linear", "iqn-ils");
    let b = run("implicit-cubic-2", 0.01, "implicit", 4, "linear", "iqn-ils");
    let p = order(a.max, b.max);
    println!(
        "implicit, cubic: error at t = 1 {:.3e}, max {:.3e} (0.02) / {:.3e} (0.01), order {p:.2}",
        b.at_one, a.max, b.max
    );
    // preCICE's best at window 0.01 (cubic waveforms with substeps): 1.6e-3 at t = 1, order 2.
    // Here the largest error over the whole run must beat it 1000-fold.
    assert!(b.max < 1.6e-6, "largest error {}", b.max);
    assert!(b.at_one < 1.6e-6, "error at t = 1: {}", b.at_one);
    assert!(
        (3.7..4.3).contains(&p),
        "observed order {p}, expected 4 (cubic waveform, RK4 participants)"
    );
}

#[test]
fn aitken_and_iqn_ils_converge_to_the_same_answer() {
    let a = run("aitken", 0.01, "implicit", 4, "linear", "aitken");
    let b = run("iqn-ils", 0.01, "implicit", 4, "linear", "iqn-ils");
    // Both stop at a relative residual of 1e-10: their answers agree to about that.
    assert!(
        (a.max - b.max).abs() < 1e-9,
        "Aitken {:.3e}, IQN-ILS {:.3e}",
        a.max,
        b.max
    );
}
