//! Bending frequencies of the slender cantilever by a dense eigen-analysis of the assembled tangent
//! stiffness and the lumped mass (with rotary inertia).

use crate::frame_common;

use frame_common::{beam, steel, support, ALL};
use nalgebra::SymmetricEigen;
use schemas::validation::{record, Record};
use std::time::Instant;
use structure_solver::frame::Frame;

/// Frequencies [Hz] of the modes that move mostly in z (bending about local y), lowest first.
fn vertical_bending_frequencies(members: usize) -> Vec<f64> {
    let mut cfg = beam(3.0, members, 0.1, 0.15, steel());
    cfg.support.push(support(1, &ALL));
    let frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let m = frame.dense_matrices();
    // K φ = ω² M φ with M = L Lᵀ  →  (L⁻¹ K L⁻ᵀ) y = ω² y, φ = L⁻ᵀ y
    let l = m
        .mass
        .clone()
        .cholesky()
        .expect("lumped mass is positive definite")
        .l();
    let l_inv = l.clone().try_inverse().expect("invertible");
    let a = &l_inv * &m.stiffness * l_inv.transpose();
    let eigen = SymmetricEigen::new(a);
    let mut modes: Vec<(f64, f64)> = (0..eigen.eigenvalues.len())
        .map(|i| {
            let phi = l_inv.transpose() * eigen.eigenvectors.column(i);
            let energy = |pick: &dyn Fn(usize) -> bool| -> f64 {
                (0..phi.len())
                    .filter(|&r| pick(m.dofs[r]))
                    .map(|r| m.mass[(r, r)] * phi[r] * phi[r])
                    .sum()
            };
            let share = energy(&|g| g % 6 == 2) / energy(&|_| true);
            (
                eigen.eigenvalues[i].max(0.0).sqrt() / (2.0 * std::f64::consts::PI),
                share,
            )
        })
        .collect();
    modes.sort_by(|x, y| x.0.total_cmp(&y.0));
    modes
        .into_iter()
        .filter(|&(_, share)| share > 0.5)
        .map(|(f, _)| f)
        .collect()
}

/// b_cantilever_modal.csv, "analytic Timoshenko (shear+rotary inertia)": 13.562668, 84.005880,
/// 230.978128 Hz. Tolerance 1 %: the brief. 20 members (40 elements).
#[test]
fn slender_cantilever_first_three_frequencies_within_one_percent() {
    let exact = [13.562668, 84.005880, 230.978128];
    let started = Instant::now();
    let f = vertical_bending_frequencies(20);
    let run_time_s = started.elapsed().as_secs_f64();
    for (i, (fi, ei)) in f.iter().zip(exact).enumerate() {
        let err = fi / ei - 1.0;
        println!(
            "mode {}: {fi:.4} Hz, Timoshenko {ei:.4} Hz, rel err {err:+.3e}",
            i + 1
        );
        record(Record {
            id: format!("asi-gauss-cantilever-frequency-mode-{}", i + 1),
            capability: "ASI-Gauss bending frequencies".into(),
            reference: format!(
                "analytic Timoshenko frequency (shear and rotary inertia), {ei} Hz (b_cantilever_modal.csv)"
            ),
            case: "steel cantilever 3 m, 0.1 × 0.15 m, vertical bending".into(),
            resolution: "20 members (40 elements), lumped mass with rotary inertia, dense eigen-analysis".into(),
            measure: format!("relative error of mode {}'s frequency", i + 1),
            value: err.abs(),
            bound: Some(0.01),
            bound_source: "the brief".into(),
            source: "structure-solver/tests/frame_modal.rs::slender_cantilever_first_three_frequencies_within_one_percent"
                .into(),
            run_time_s,
            ..Default::default()
        });
        assert!(err.abs() < 0.01, "mode {}: {fi} Hz vs {ei} Hz", i + 1);
    }
    assert!(f.len() >= 3, "found only {} vertical bending modes", f.len());
}
