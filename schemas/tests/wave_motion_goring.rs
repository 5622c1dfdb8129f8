//! Tests of `schemas::wave_motion::goring`.

use schemas::wave_motion::goring::*;

const G: f64 = 9.81;

/// Scenes from a small flume to a large basin, H/d from 0.05 to 0.6.
fn cases() -> Vec<GoringSolitary> {
    [(0.02, 0.4), (0.1, 0.5), (0.3, 0.5), (1.0, 4.0)]
        .iter()
        .map(|&(h, d)| GoringSolitary::new(h, d, G).expect("valid"))
        .collect()
}

#[test]
fn velocity_is_the_waves_depth_averaged_velocity_at_the_paddle() {
    // Goring's ODE: X' = c η(X, t) / (d + η(X, t)), η from the target wave at x = X(t).
    for m in cases() {
        let w = m.target_wave();
        let top = w.crest_velocity();
        for i in 0..=400 {
            let t = m.duration() * i as f64 / 400.0;
            let x = m.stroke(t);
            let ode = w.depth_averaged_velocity(x, t);
            assert!((m.velocity(t) - ode).abs() <= 1e-6 * top, "t = {t}");
        }
    }
}

#[test]
fn the_closed_form_solves_the_ode() {
    // RK4 on dX/dt = c η(X, t) / (d + η(X, t)) from X(0) = 0, 20 000 steps over the duration
    // (global error O(Δt⁴): the steps' halving changes X by < 1e-12 S); the closed form
    // must agree to 1e-9 S, and its velocity with central differences of X to 1e-6 of the top.
    for m in cases() {
        let w = *m.target_wave();
        let rhs = |t: f64, x: f64| w.depth_averaged_velocity(x, t);
        let n = 20_000;
        let dt = m.duration() / n as f64;
        let mut x = 0.0;
        for i in 0..n {
            let t = i as f64 * dt;
            let k1 = rhs(t, x);
            let k2 = rhs(t + 0.5 * dt, x + 0.5 * dt * k1);
            let k3 = rhs(t + 0.5 * dt, x + 0.5 * dt * k2);
            let k4 = rhs(t + dt, x + dt * k3);
            x += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            if (i + 1) % 500 == 0 {
                let t1 = (i + 1) as f64 * dt;
                let s = m.goring_stroke();
                assert!(
                    (x - m.stroke(t1)).abs() <= 1e-9 * s,
                    "t = {t1}: {x} vs {}",
                    m.stroke(t1)
                );
            }
        }
        let h = 1e-6 * m.duration();
        for i in 1..100 {
            let t = m.duration() * i as f64 / 100.0;
            let fd = (m.stroke(t + h) - m.stroke(t - h)) / (2.0 * h);
            assert!((fd - m.velocity(t)).abs() <= 1e-6 * w.crest_velocity(), "t = {t}");
        }
    }
}

#[test]
fn starts_at_rest_and_ends_at_goring_stroke() {
    for m in cases() {
        let w = m.target_wave();
        let s = (16.0 * w.height() * w.depth() / 3.0).sqrt();
        assert!((m.goring_stroke() / s - 1.0).abs() < 1e-14);
        assert_eq!(m.stroke(0.0), 0.0);
        // Goring's cut at |θ| = 3.8: sech²(3.8) = 2.0e-3 of the top speed (times (d + H) /
        // d at most), and 1 / (e^7.6 + 1) = 5.0e-4 of the stroke short.
        assert!(m.velocity(0.0) <= 2.1e-3 * (1.0 + w.height() / w.depth()) * w.crest_velocity());
        assert!((m.final_stroke() / s - 1.0).abs() < 5.1e-4);
        // Nearly at rest again at `duration`, and at rest long after.
        assert!((m.stroke(m.duration()) / s - 1.0).abs() < 1.1e-3);
        assert!(m.velocity(m.duration()) <= 2.1e-3 * (1.0 + w.height() / w.depth()) * w.crest_velocity());
        assert_eq!(m.stroke(1e3 * m.duration()), m.final_stroke());
        assert_eq!((m.stroke(-1.0), m.velocity(-1.0)), (0.0, 0.0));
        // The paddle moves the wave's water: S d = ∫ η dx (both 2H / k).
        assert!((m.goring_stroke() * w.depth() / w.volume_per_width() - 1.0).abs() < 1e-14);
    }
}

#[test]
fn the_top_speed_is_the_crest_velocity() {
    for m in cases() {
        let top = m.target_wave().crest_velocity();
        assert!((m.velocity(m.crest_time()) - top).abs() <= 1e-6 * top);
        let sampled = (0..=2000).map(|i| m.velocity(m.duration() * i as f64 / 2000.0));
        let sampled = schemas::validation::largest(sampled, 0.0);
        assert!(
            sampled <= top * (1.0 + 1e-12) && sampled >= top * (1.0 - 1e-4),
            "{sampled}"
        );
        // The crest is at the paddle then.
        let crest_x = m.target_wave().crest_x0() + m.target_wave().celerity() * m.crest_time();
        assert!((crest_x - m.stroke(m.crest_time())).abs() <= 1e-12 * m.goring_stroke());
    }
}

#[test]
fn goring_duration_covers_the_phases_within_3_8() {
    // θ runs from −3.8 to 3.8 in Goring's T: k c T = 7.6 + k ΔX (derivation in the doc).
    for m in cases() {
        let w = m.target_wave();
        let start = m.crest_time() - 0.5 * m.goring_duration();
        let end = m.crest_time() + 0.5 * m.goring_duration();
        let theta = |t: f64| w.wavenumber() * (w.celerity() * t - m.stroke(t)) - m.start_phase();
        // ΔX over T is S tanh 3.8, not S: the ends are within (1 − tanh 3.8) / 2 of ±3.8 in θ.
        assert!((theta(start) + 3.8).abs() < 1e-3, "{}", theta(start));
        assert!((theta(end) - 3.8).abs() < 1e-3, "{}", theta(end));
    }
}

#[test]
fn range_is_from_rest_to_the_stroke_reached() {
    let m = GoringSolitary::new(0.1, 0.5, G).expect("valid");
    assert_eq!(m.range(m.crest_time()), (0.0, m.stroke(m.crest_time())));
    assert_eq!(m.range(0.0), (0.0, 0.0));
    assert!(GoringSolitary::new(-0.1, 0.5, G).is_err());
}
