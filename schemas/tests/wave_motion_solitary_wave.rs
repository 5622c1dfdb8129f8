//! Tests of `schemas::wave_motion::solitary_wave`.

use schemas::wave_motion::solitary_wave::*;

const G: f64 = 9.81;

#[test]
fn wavenumber_and_celerity_follow_goring_and_synolakis() {
    let w = SolitaryWave::new(0.1, 0.5, G).expect("valid");
    let k = (3.0 * 0.1 / (4.0 * 0.125f64)).sqrt();
    assert!((w.wavenumber() - k).abs() < 1e-15);
    // Synolakis (1987): γ = √(3H / (4d)), k = γ / d.
    let gamma = (3.0 * 0.1 / (4.0 * 0.5f64)).sqrt();
    assert!((w.wavenumber() - gamma / 0.5).abs() < 1e-14);
    assert!((w.celerity() - (G * 0.6f64).sqrt()).abs() < 1e-15);
}

#[test]
fn the_crest_travels_at_c_and_the_profile_is_symmetric() {
    let w = SolitaryWave::new(0.05, 0.4, G)
        .expect("valid")
        .with_crest_at(-2.0);
    let t = 1.3;
    let crest = -2.0 + w.celerity() * t;
    assert_eq!(w.elevation(crest, t), w.height());
    for dx in [0.01, 0.3, 1.0, 4.0] {
        let (a, b) = (w.elevation(crest - dx, t), w.elevation(crest + dx, t));
        assert!((a - b).abs() <= 1e-15 * w.height(), "dx = {dx}");
        assert!(a < w.height());
    }
    assert_eq!(
        w.elevation(1e6, 0.0),
        0.0,
        "sech² underflows to 0 far from the crest"
    );
    assert!((w.depth_averaged_velocity(crest, t) - w.crest_velocity()).abs() < 1e-15);
}

#[test]
fn the_velocity_satisfies_mass_conservation() {
    // ∂η/∂t + ∂q/∂x = 0 with q = u (d + η) = c η (Goring 1978, §2), by central differences
    // (truncation ~ h² |η'''| c: below 1e-9 H/s at h = 1e-5 m here).
    let w = SolitaryWave::new(0.2, 0.5, G).expect("valid");
    let h = 1e-5;
    for i in -40..40 {
        let x = i as f64 * 0.05;
        let t = 0.0;
        let deta_dt = (w.elevation(x, t + h / w.celerity()) - w.elevation(x, t - h / w.celerity()))
            / (2.0 * h / w.celerity());
        let q = |x: f64| w.depth_averaged_velocity(x, t) * (w.depth() + w.elevation(x, t));
        let dq_dx = (q(x + h) - q(x - h)) / (2.0 * h);
        assert!((deta_dt + dq_dx).abs() < 1e-8, "x = {x}: {deta_dt} + {dq_dx}");
    }
}

#[test]
fn the_vertical_velocity_meets_the_kinematic_surface_condition() {
    // At the surface w = ∂η/∂t + u ∂η/∂x (the profile moves at c: ∂η/∂t = −c η_x), ∂w/∂z =
    // −∂u/∂x inside (central differences, h = 1e-6 m: truncation far below 1e-8 m/s here),
    // and η_x matches a central difference of η.
    let w = SolitaryWave::new(0.2, 0.5, G).expect("valid").with_crest_at(0.3);
    let h = 1e-6;
    for i in -30..30 {
        let x = i as f64 * 0.07;
        let eta = w.elevation(x, 0.0);
        let fd = (w.elevation(x + h, 0.0) - w.elevation(x - h, 0.0)) / (2.0 * h);
        assert!((w.slope(x, 0.0) - fd).abs() < 1e-8, "x = {x}");
        let [u, ws] = w.velocity_at(x, w.depth() + eta, 0.0);
        let kinematic = -w.celerity() * w.slope(x, 0.0) + u * w.slope(x, 0.0);
        assert!(
            (ws - kinematic).abs() < 1e-12,
            "x = {x}: {ws} against {kinematic}"
        );
        let z = 0.3;
        let dw_dz = (w.velocity_at(x, z + h, 0.0)[1] - w.velocity_at(x, z - h, 0.0)[1]) / (2.0 * h);
        let du_dx = (w.velocity_at(x + h, z, 0.0)[0] - w.velocity_at(x - h, z, 0.0)[0]) / (2.0 * h);
        assert!((dw_dz + du_dx).abs() < 1e-7, "x = {x}: {dw_dz} + {du_dx}");
        assert_eq!(w.velocity_at(x, 0.0, 0.0)[1], 0.0);
    }
}

#[test]
fn volume_and_width_are_the_integrals_of_the_profile() {
    let w = SolitaryWave::new(0.1, 0.5, G).expect("valid");
    // Midpoint rule over ±40/k (sech² < 1e-34 there): error far below 1e-10 relative.
    let (half, n) = (40.0 / w.wavenumber(), 200_000);
    let dx = 2.0 * half / n as f64;
    let sum: f64 = (0..n)
        .map(|i| w.elevation(-half + (i as f64 + 0.5) * dx, 0.0) * dx)
        .sum();
    assert!((sum / w.volume_per_width() - 1.0).abs() < 1e-10, "{sum}");
    // η equals fraction · H at the width's ends.
    let b = w.width_above(0.002);
    assert!((w.elevation(b / 2.0, 0.0) / w.height() - 0.002).abs() < 1e-15);
    assert!((w.passage_time(0.002) - b / w.celerity()).abs() < 1e-15);
    // Goring's cut: sech²(3.8) ≈ 0.002.
    assert!((sech_squared(GORING_PHASE) - 0.002).abs() < 1e-5);
}

#[test]
fn refuses_non_positive_or_non_finite_values() {
    assert!(SolitaryWave::new(0.0, 1.0, G).is_err());
    assert!(SolitaryWave::new(0.1, -1.0, G).is_err());
    assert!(SolitaryWave::new(0.1, 1.0, f64::NAN).is_err());
    let e = SolitaryWave::new(f64::INFINITY, 1.0, G).unwrap_err();
    assert!(e.contains("wave height H"), "{e}");
}
