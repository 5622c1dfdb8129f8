//! Tests of `schemas::wave_motion::regular`.

use schemas::wave_motion::ramp::Ramp;
use schemas::wave_motion::regular::*;

const G: f64 = 9.81;

#[test]
fn the_wavenumber_solves_the_dispersion_relation() {
    // From kd ≈ 0.003 (a 200 s wave on 1 m) to kd ≈ 400 (0.3 s on 20 m).
    for &(period, depth) in &[
        (200.0, 1.0),
        (20.0, 0.5),
        (2.0, 0.5),
        (1.0, 0.5),
        (0.5, 2.0),
        (12.0, 30.0),
        (0.3, 20.0),
    ] {
        let omega = 2.0 * std::f64::consts::PI / period;
        let k = wavenumber(omega, depth, G);
        let residual = (G * k * (k * depth).tanh() - omega * omega).abs() / (omega * omega);
        assert!(residual < 1e-12, "T = {period}, d = {depth}: residual {residual}");
    }
}

#[test]
fn the_wavenumber_tends_to_the_deep_and_shallow_water_limits() {
    // Deep: k → ω²/g, relative gap tanh(kd)⁻¹ − 1 ≈ 2 e^{−2kd} (below 1e-15 for kd > 18; rounding
    // of ω² d / g and k = x / d leaves a few ε).
    let omega = 2.0 * std::f64::consts::PI / 0.5;
    let k = wavenumber(omega, 10.0, G);
    assert!(k * 10.0 > 18.0 && (k * G / (omega * omega) - 1.0).abs() < 1e-14);
    // Shallow: k → ω / √(g d), relative gap ≈ (kd)² / 6 (x tanh x = x² (1 − x²/3 + …)).
    let omega = 2.0 * std::f64::consts::PI / 200.0;
    let (d, k) = (1.0, wavenumber(omega, 1.0, G));
    let shallow = omega / (G * d).sqrt();
    let gap = k / shallow - 1.0;
    assert!((gap / ((k * d).powi(2) / 6.0) - 1.0).abs() < 1e-3, "gap {gap}");
}

#[test]
fn height_to_stroke_tends_to_2_in_deep_and_kd_in_shallow_water() {
    // Deep water: H/S = 2 − (4 + 8 kd) e^{−2kd} + … (expanding tanh and 1/sinh).
    for kd in [5.0f64, 10.0, 20.0] {
        let bound = (4.0 + 8.0 * kd) * (-2.0 * kd).exp() * 1.01 + 4.0 * f64::EPSILON;
        assert!((height_to_stroke(kd) - 2.0).abs() <= bound, "kd = {kd}");
    }
    assert_eq!(height_to_stroke(400.0), 2.0, "no overflow at large kd");
    // Shallow water: H/S = kd (1 + O((kd)⁴)): the (kd)² terms of tanh and 2kd / sinh 2kd
    // cancel; at kd = 0.01 the gap is below 1e-8.
    for kd in [1e-2f64, 1e-3, 1e-6] {
        assert!((height_to_stroke(kd) / kd - 1.0).abs() < 1e-8, "kd = {kd}");
    }
    // The book's form, where it is well conditioned.
    for kd in [0.3f64, 1.0, 2.5] {
        let book = 2.0 * ((2.0 * kd).cosh() - 1.0) / ((2.0 * kd).sinh() + 2.0 * kd);
        assert!((height_to_stroke(kd) / book - 1.0).abs() < 1e-14, "kd = {kd}");
    }
}

#[test]
fn the_paddle_swings_by_s_after_a_smooth_start() {
    let ramp = Ramp::new(2.0).expect("valid");
    let w = RegularWaves::new(0.05, 1.2, 0.5, G, ramp).expect("valid");
    let s = w.stroke_length();
    assert!((w.height() / s - height_to_stroke(w.relative_depth())).abs() < 1e-15);
    assert_eq!((w.stroke(0.0), w.velocity(0.0)), (0.0, 0.0));
    // After the ramp, X = (S/2) sin ωt exactly; the velocity is X's derivative throughout.
    let t = 5.3;
    assert!((w.stroke(t) - 0.5 * s * (w.angular_frequency() * t).sin()).abs() < 1e-15);
    let h = 1e-6;
    for i in 1..200 {
        let t = i as f64 * 0.05;
        let fd = (w.stroke(t + h) - w.stroke(t - h)) / (2.0 * h);
        assert!((fd - w.velocity(t)).abs() < 1e-7, "t = {t}");
    }
    // Range: within the ramp, smaller than ±S/2; a period past it, exactly ±S/2.
    let (lo, hi) = w.range(1.0);
    assert!(lo > -0.5 * s && hi < 0.5 * s && hi > 0.0);
    let (lo, hi) = w.range(2.0 + w.period());
    assert!(
        (lo + 0.5 * s).abs() < 1e-12 * s && (hi - 0.5 * s).abs() < 1e-12 * s,
        "{lo} {hi}"
    );
}

#[test]
fn range_finds_the_extremes_within_the_ramp() {
    // Against a dense sampling (10⁶ points over 3 s: X varies by < ω² S/2 Δt² / 8 ≈ 1e-12 m
    // between samples near an extreme).
    let w = RegularWaves::new(0.1, 1.0, 0.6, G, Ramp::new(2.5).expect("valid")).expect("valid");
    let t_end = 3.0;
    let n = 1_000_000;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=n {
        let x = w.stroke(t_end * i as f64 / n as f64);
        lo = lo.min(x);
        hi = hi.max(x);
    }
    let (rlo, rhi) = w.range(t_end);
    assert!(
        (rlo - lo).abs() < 1e-11 && (rhi - hi).abs() < 1e-11,
        "{rlo} {lo} {rhi} {hi}"
    );
}

#[test]
fn refuses_non_positive_values() {
    assert!(RegularWaves::new(0.1, 0.0, 1.0, G, Ramp::NONE).is_err());
    assert!(RegularWaves::new(-0.1, 1.0, 1.0, G, Ramp::NONE).is_err());
    let e = RegularWaves::new(0.1, 1.0, f64::NAN, G, Ramp::NONE).unwrap_err();
    assert!(e.contains("depth d"), "{e}");
}
