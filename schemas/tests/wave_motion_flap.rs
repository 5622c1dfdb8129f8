//! Tests of `schemas::wave_motion::flap`.

use schemas::wave_motion::flap::*;
use schemas::wave_motion::goring::GoringSolitary;
use schemas::wave_motion::regular::height_to_stroke;
use schemas::wave_motion::regular::wavenumber;
use schemas::wave_motion::{Ramp, StrokeTable};

const G: f64 = 9.81;

/// The flap's integral ∫₀ᵈ S(s) cosh(ks) ds by composite Simpson's rule (10⁴ intervals: error
/// d⁵ k⁴ cosh(kd) / (180 n⁴) relative ~1e-17 here), in the general H/S formula of the module
/// doc: an independent check of the closed form's algebra.
fn transfer_by_quadrature(kd: f64, l_over_d: f64) -> f64 {
    let (d, k, l) = (1.0, kd, l_over_d);
    let n = 10_000;
    let h = d / n as f64;
    let f = |s: f64| (s + l) / (d + l) * (k * s).cosh();
    let mut sum = f(0.0) + f(d);
    for i in 1..n {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    let integral = sum * h / 3.0;
    4.0 * k * kd.sinh() * integral / ((2.0 * kd).sinh() + 2.0 * kd)
}

#[test]
fn the_flap_transfer_function_is_dean_and_dalrymples_at_l_0_and_the_pistons_as_l_grows() {
    for kd in [0.1f64, 0.3, 1.0, 2.5, 6.0] {
        // l = 0: Dean & Dalrymple (1991, §6.3) 4 (sinh kd / kd)(kd sinh kd − cosh kd + 1) /
        // (sinh 2kd + 2kd); well conditioned for kd ≥ 0.1 (cancellation ~ (kd)² / 2 of ε).
        let dd = 4.0 * kd.sinh() / kd * (kd * kd.sinh() - kd.cosh() + 1.0) / ((2.0 * kd).sinh() + 2.0 * kd);
        let flap = flap_height_to_stroke(kd, 0.0);
        assert!((flap / dd - 1.0).abs() < 1e-12, "kd = {kd}: {flap} vs {dd}");
        // l → ∞: the piston's; the gap is tanh(kd/2) / (kd (1 + l/d)) ≤ 1 / (2 (1 + l/d)).
        for ratio in [1e3f64, 1e6, 1e12] {
            let gap = flap_height_to_stroke(kd, ratio) / height_to_stroke(kd) - 1.0;
            assert!(
                gap < 0.0 && -gap <= 0.5 / (1.0 + ratio) + 1e-15,
                "kd = {kd}, l/d = {ratio}: {gap}"
            );
        }
        // Any l: the integral form, by quadrature.
        for ratio in [0.0, 0.25, 1.0, 4.0] {
            let q = transfer_by_quadrature(kd, ratio);
            assert!(
                (flap_height_to_stroke(kd, ratio) / q - 1.0).abs() < 1e-10,
                "kd = {kd}, l/d = {ratio}"
            );
        }
    }
}

#[test]
fn the_flap_transfer_function_tends_to_the_long_wave_and_deep_water_limits() {
    // Shallow: kd (d/2 + l)/(d + l) (module doc), to O((kd)²) relative: (kd)²/12 at l = 0.
    for ratio in [0.0f64, 0.5, 3.0] {
        let kd = 1e-3;
        let long = kd * (0.5 + ratio) / (1.0 + ratio);
        assert!(
            (flap_height_to_stroke(kd, ratio) / long - 1.0).abs() < 1e-6,
            "l/d = {ratio}"
        );
    }
    // Deep: 2 (1 − 1/(kd (1 + l/d))) to e^{−kd} terms; 2 itself as kd → ∞.
    let kd = 40.0;
    assert!((flap_height_to_stroke(kd, 0.0) - 2.0 * (1.0 - 1.0 / kd)).abs() < 1e-14);
    assert!((flap_height_to_stroke(1e9, 0.0) - 2.0).abs() < 1e-8);
    // Between: a flap makes lower waves than a piston of the same stroke at the surface.
    assert!(flap_height_to_stroke(1.0, 0.0) < flap_height_to_stroke(1.0, 1.0));
    assert!(flap_height_to_stroke(1.0, 1.0) < height_to_stroke(1.0));
}

#[test]
fn the_regular_flap_strokes_by_its_transfer_function() {
    let hinge = FlapHinge::new(-0.1, 0.0, 0.5).expect("valid");
    assert_eq!((hinge.below(), hinge.lever()), (0.1, 0.6));
    let m = FlapMotion::regular(0.05, 1.2, G, Ramp::NONE, hinge).expect("valid");
    let kd = wavenumber(2.0 * std::f64::consts::PI / 1.2, 0.5, G) * 0.5;
    let s = 0.05 / flap_height_to_stroke(kd, 0.2);
    let (lo, hi) = m.range(1.2);
    assert!(
        (hi - 0.5 * s).abs() < 1e-12 && (lo + 0.5 * s).abs() < 1e-12,
        "{lo} {hi} {s}"
    );
    // θ = atan(X/L), and θ' its derivative (central differences, truncation ~1e-10 rad/s).
    let h = 1e-6;
    for i in 0..60 {
        let t = 0.02 * i as f64 + 0.01;
        assert!((m.angle(t) - (m.stroke(t) / 0.6).atan()).abs() < 1e-15);
        let fd = (m.angle(t + h) - m.angle(t - h)) / (2.0 * h);
        assert!((fd - m.angular_velocity(t)).abs() < 1e-8, "t = {t}");
    }
    let (a, b) = m.angle_range(1.2);
    assert!((a - (lo / 0.6).atan()).abs() < 1e-15 && (b - (hi / 0.6).atan()).abs() < 1e-15);
}

#[test]
fn the_solitary_flap_moves_goring_pistons_water() {
    // l = 0: twice the piston's stroke at the surface; l → ∞: the piston's.
    assert_eq!(solitary_stroke_factor(0.3, 0.0), 2.0);
    assert!((solitary_stroke_factor(0.3, 3e9) - 1.0).abs() < 1e-9);
    let hinge = FlapHinge::new(-0.05, 0.0, 0.1).expect("valid");
    let m = FlapMotion::solitary(0.02, G, hinge).expect("valid");
    let p = GoringSolitary::new(0.02, 0.1, G).expect("valid");
    // The water moved: the depth-averaged stroke ∫₀ᵈ X (s + l)/(d + l) ds / d = X (d/2 + l)/(d + l).
    for t in [0.1, 0.4, 0.9, 3.0] {
        let averaged = m.stroke(t) * (0.05 + 0.05) / (0.1 + 0.05);
        assert!((averaged - p.stroke(t)).abs() < 1e-15, "t = {t}");
        assert!((m.velocity(t) * 0.1 / 0.15 - p.velocity(t)).abs() < 1e-15);
    }
}

#[test]
fn the_table_flap_is_the_tables_stroke_and_bad_hinges_are_refused() {
    let table =
        StrokeTable::parse("0,0\n1,0.1\n", Ramp::NONE, "k", std::path::Path::new("f.csv")).expect("valid");
    let m = FlapMotion::table(table, FlapHinge::new(0.0, 0.0, 0.1).expect("valid"));
    assert!((m.stroke(0.5) - 0.05).abs() < 1e-17 && (m.velocity(0.5) - 0.1).abs() < 1e-16);
    assert!((m.angle(1.0) - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    let e = FlapHinge::new(0.01, 0.0, 0.1).unwrap_err();
    assert!(e.contains("at or below"), "{e}");
    assert!(FlapHinge::new(-0.01, 0.0, 0.0).is_err());
    assert!(FlapHinge::new(f64::NAN, 0.0, 0.1).is_err());
}

#[test]
fn a_turned_point_keeps_its_distance_and_the_swept_extent_holds_every_angle() {
    let hinge = [0.3, -0.1];
    let p = turned([0.2, 0.4], hinge, (0.5f64).sin_cos());
    let r0 = (0.1f64.powi(2) + 0.5f64.powi(2)).sqrt();
    assert!(((p[0] - 0.3).hypot(p[1] + 0.1) - r0).abs() < 1e-15);
    // +θ turns the top into +x: the point above the hinge moves forward and down.
    let top = turned([0.3, 0.9], hinge, (0.1f64).sin_cos());
    assert!(top[0] > 0.3 && top[1] < 0.9);
    // Against a dense sampling of the angles (10⁵: a corner moves < |r| Δθ² / 8 ≈ 1e-11 m
    // between samples near an extreme).
    let (lo, hi) = ([0.22, 0.0], [0.3, 0.5]);
    let range = (-0.5, 0.3);
    let (min, max) = swept_extent(lo, hi, hinge, range);
    let (mut smin, mut smax) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let n = 100_000;
    for i in 0..=n {
        let theta = range.0 + (range.1 - range.0) * i as f64 / n as f64;
        for c in [lo, [hi[0], lo[1]], [lo[0], hi[1]], hi] {
            let q = turned(c, hinge, theta.sin_cos());
            for a in 0..2 {
                smin[a] = smin[a].min(q[a]);
                smax[a] = smax[a].max(q[a]);
            }
        }
    }
    for a in 0..2 {
        assert!(
            min[a] <= smin[a] + 1e-15 && min[a] > smin[a] - 1e-10,
            "{min:?} {smin:?}"
        );
        assert!(
            max[a] >= smax[a] - 1e-15 && max[a] < smax[a] + 1e-10,
            "{max:?} {smax:?}"
        );
    }
    // The top back corner rises above its rest height while turning through 0 (an interior
    // extreme, at tan θ = 0.08 / 0.6).
    assert!(max[1] > 0.5 + 1e-3);
}
