//! Tests of `schemas::waveform`.

use schemas::f64s::F64s;
use schemas::message::{Fields, Waveform};

fn wave(times: Vec<f64>, f: impl Fn(f64) -> f64) -> Waveform {
    let samples = times
        .iter()
        .map(|&t| Fields {
            point_force: F64s(vec![f(t), 2.0 * f(t)]),
            ..Fields::default()
        })
        .collect();
    Waveform { times, samples }
}

#[test]
fn linear_data_are_extrapolated_exactly() {
    let w = wave(Waveform::grid(0.0, 1.0, 3), |t| 3.0 * t + 1.0);
    assert!((w.extrapolate(1.5).point_force[0] - 5.5).abs() < 1e-13);
}

#[test]
fn grid_lands_exactly_on_the_end() {
    let g = Waveform::grid(0.1, 0.13, 3);
    assert_eq!(g.len(), 4);
    assert_eq!(g[3], 0.13);
    assert_eq!(g[0], 0.1);
}

#[test]
fn two_samples_interpolate_linearly() {
    let w = wave(Waveform::grid(0.0, 1.0, 1), |t| 3.0 * t + 1.0);
    let f = w.at(0.25).unwrap_or_else(|e| panic!("{e}"));
    assert!((f.point_force[0] - 1.75).abs() < 1e-15);
    assert!((f.point_force[1] - 3.5).abs() < 1e-15);
}

#[test]
fn cubic_data_are_reproduced_exactly_with_four_or_more_samples() {
    let cubic = |t: f64| 2.0 * t * t * t - t * t + 0.5 * t - 3.0;
    let w = wave(Waveform::grid(0.0, 1.0, 6), cubic);
    for t in [0.0, 0.05, 0.33, 0.5, 0.71, 0.99, 1.0] {
        let f = w.at(t).unwrap_or_else(|e| panic!("{e}"));
        assert!((f.point_force[0] - cubic(t)).abs() < 1e-13, "t = {t}");
    }
}

#[test]
fn interpolation_error_falls_as_h_to_the_fourth() {
    // sin on [0, 1]: the max error with 8 and 16 samples should drop ~16× (order 4).
    let err = |n: u32| {
        let w = wave(Waveform::grid(0.0, 1.0, n), f64::sin);
        (0..=200)
            .map(|i| f64::from(i) / 200.0)
            .map(|t| (w.at(t).unwrap_or_else(|e| panic!("{e}")).point_force[0] - t.sin()).abs())
            .fold(0.0, schemas::validation::max_or_nan)
    };
    let ratio = err(8) / err(16);
    assert!(ratio > 12.0, "error ratio {ratio} shows less than 4th order");
}

/// Issue 13: samples of one window whose array lengths differ (nodes added within it) are
/// refused by name, not read with zeros for the missing values; equal lengths still pass.
#[test]
fn samples_of_different_lengths_are_refused() {
    let mut w = wave(Waveform::grid(0.0, 1.0, 2), |t| t);
    w.samples[2].point_force.0.push(7.0);
    let e = w.at(0.75).map(|_| ()).unwrap_err();
    assert!(
        e.contains("`point_force`") && e.contains("2 values") && e.contains("3 at t = 1"),
        "{e}"
    );
    w.samples[2].point_force.0.pop();
    assert!(w.at(0.75).is_ok());
}
