//! Tests of `schemas::wave_motion::ramp`.

use schemas::wave_motion::ramp::*;

#[test]
fn starts_at_rest_and_ends_at_one_with_zero_slope() {
    let ramp = Ramp::new(2.0).expect("valid");
    assert_eq!(ramp.factor(0.0), 0.0);
    assert_eq!(ramp.rate(0.0), 0.0);
    assert_eq!(ramp.factor(-1.0), 0.0);
    assert!((ramp.factor(1.0) - 0.5).abs() < 1e-15, "half way at T_r / 2");
    assert_eq!(ramp.factor(2.0), 1.0);
    assert_eq!(ramp.rate(2.0), 0.0);
    assert_eq!(ramp.factor(5.0), 1.0);
    // r' → 0 at both ends: continuous velocity at t = 0 and t = T_r.
    assert!(ramp.rate(1e-9) < 1e-8 && ramp.rate(2.0 - 1e-9) < 1e-8);
}

#[test]
fn rate_is_the_derivative_of_factor() {
    // Central differences of r against r' (truncation h²/6 |r'''| ≤ h² π³/(12 T_r³) < 1e-9 here).
    let ramp = Ramp::new(1.5).expect("valid");
    let h = 1e-5;
    for i in 1..150 {
        let t = i as f64 * 0.01;
        let fd = (ramp.factor(t + h) - ramp.factor(t - h)) / (2.0 * h);
        assert!(
            (fd - ramp.rate(t)).abs() < 1e-8,
            "t = {t}: {fd} vs {}",
            ramp.rate(t)
        );
    }
}

#[test]
fn apply_uses_the_product_rule() {
    // X₀ = sin t, X₀' = cos t: d/dt (r sin t) by central differences.
    let ramp = Ramp::new(3.0).expect("valid");
    let x = |t: f64| ramp.apply(t, t.sin(), t.cos());
    let h = 1e-5;
    for i in 1..30 {
        let t = i as f64 * 0.1;
        let fd = (x(t + h).0 - x(t - h).0) / (2.0 * h);
        assert!((fd - x(t).1).abs() < 1e-8, "t = {t}");
    }
}

#[test]
fn no_ramp_is_one_and_bad_durations_are_refused() {
    assert_eq!(Ramp::NONE.factor(0.0), 1.0);
    assert_eq!(
        Ramp::new(0.0).expect("0 allowed").apply(0.3, 2.0, 5.0),
        (2.0, 5.0)
    );
    assert!(Ramp::new(-1.0).is_err());
    assert!(Ramp::new(f64::NAN).is_err());
    assert!(Ramp::new(f64::INFINITY).is_err());
}
