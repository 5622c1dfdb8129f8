//! The coupler's accuracy table: error of the partitioned two-mass oscillator at t = 1 against the
//! coupling window, for each scheme, with the observed order and the wall time of each run.
//! Run: `cargo bench -p stack-tests --bench oscillator_table` (builds and starts real processes).
//!
//! Reference, preCICE 3.4 with Newmark participants at window 0.01: serial explicit 0.16 (order 1),
//! implicit constant 0.21 (order 1), implicit linear 7.1e-3 (order 2), implicit cubic + substeps
//! 1.6e-3 (order 2).

use stack_tests::{
    advances, oscillator_error, oscillator_max_error, run_oscillator, stderr, OscillatorCoupling,
};
use std::time::Instant;

const WINDOWS: [f64; 5] = [0.04, 0.02, 0.01, 0.005, 0.0025];

/// (label, scheme, samples per window, predictor, acceleration)
const SCHEMES: [(&str, &str, u32, &str, &str); 6] = [
    (
        "explicit, constant predictor",
        "explicit",
        1,
        "constant",
        "constant",
    ),
    ("explicit, linear predictor", "explicit", 1, "linear", "constant"),
    (
        "implicit, linear in window, Aitken",
        "implicit",
        1,
        "linear",
        "aitken",
    ),
    (
        "implicit, linear in window, IQN-ILS",
        "implicit",
        1,
        "linear",
        "iqn-ils",
    ),
    (
        "implicit, 4 samples (cubic), Aitken",
        "implicit",
        4,
        "linear",
        "aitken",
    ),
    (
        "implicit, 4 samples (cubic), IQN-ILS",
        "implicit",
        4,
        "linear",
        "iqn-ils",
    ),
];

fn main() {
    println!("two-mass oscillator: error at t = 1 and largest error over all window ends (max over both masses of |u - u_exact|)");
    println!(
        "{:<38} {:>7} {:>11} {:>6} {:>11} {:>6} {:>10} {:>8}",
        "scheme", "window", "err t=1", "order", "max err", "order", "sweeps/win", "wall [s]"
    );
    for (label, scheme, samples, predictor, acceleration) in SCHEMES {
        let mut previous: Option<(f64, f64)> = None;
        for window in WINDOWS {
            let test = format!("table-{scheme}-{samples}-{predictor}-{acceleration}-{window}");
            let coupling = OscillatorCoupling {
                window,
                scheme,
                samples,
                predictor,
                acceleration,
            };
            let t0 = Instant::now();
            let (out, run) = run_oscillator(&test, &coupling);
            let wall = t0.elapsed().as_secs_f64();
            if !run.status.success() {
                println!(
                    "{label:<38} {window:>7} failed: {}",
                    stderr(&run).lines().last().unwrap_or_default()
                );
                continue;
            }
            let rec = out.join("recording.rec");
            let error = oscillator_error(&rec);
            let max_error = oscillator_max_error(&rec);
            let sweeps = advances(&rec, "mass-left") as f64 / (1.0 / window).round();
            let order = |e: f64, now: f64| format!("{:.2}", (e / now).log2());
            let (o1, o2) = previous
                .map(|(e, m)| (order(e, error), order(m, max_error)))
                .unwrap_or_else(|| ("-".into(), "-".into()));
            println!(
                "{label:<38} {window:>7} {error:>11.3e} {o1:>6} {max_error:>11.3e} {o2:>6} {sweeps:>10.2} {wall:>8.3}"
            );
            previous = Some((error, max_error));
        }
    }
}
