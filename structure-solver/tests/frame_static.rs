//! Static accuracy of the ASI-Gauss element: one member reproduces the Timoshenko cantilever.

use crate::frame_common;

use frame_common::{beam, steel, support, ALL};
use schemas::validation::{record, Record};
use std::time::Instant;
use structure_solver::frame::Frame;

/// Tip deflection (z) and rotation (about y) of a one-member cantilever under a tip load P in z.
fn cantilever_tip(length: f64, width: f64, depth: f64, p: f64, members: usize) -> (f64, f64) {
    let mut cfg = beam(length, members, width, depth, steel());
    cfg.support.push(support(1, &ALL));
    let frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let tip = frame.node_index(members as u32 + 1).expect("tip node");
    let mut loads = vec![0.0; 6 * frame.node_count()];
    loads[6 * tip + 2] = p;
    let u = frame.linear_static_displacements(&loads).expect("static solve");
    (u[6 * tip + 2], u[6 * tip + 4])
}

/// `a_cantilever_static.csv`: closed form PL³/3EI + PL/kGA. Tolerance 1e-10 relative: the brief
/// (ASI-Gauss with s = ±(2/√3 − 1) is exact for one member, so only round-off remains).
#[test]
fn one_member_cantilever_matches_timoshenko_closed_form() {
    // (case, L, b, h, exact tip deflection, exact tip rotation) from a_cantilever_static.csv, P = 10 kN
    let cases: [(&str, f64, f64, f64, f64, f64); 2] = [
        ("A_deep", 1.0, 0.1, 0.3, 7.927407407e-5, 1.111111111e-4),
        ("B_slender", 3.0, 0.1, 0.15, 1.60312e-2, 8e-3),
    ];
    // midpoint integration (the older ASI rule), one member: f_asigauss_linear_check.csv
    let midpoint = [7.464444444e-5, 1.50312e-2];
    for ((name, l, b, h, exact, rotation), mid) in cases.into_iter().zip(midpoint) {
        let e = 200e9;
        let g = e / 2.6;
        let (iy, a) = (b * h * h * h / 12.0, b * h);
        let closed_form = 1e4 * l.powi(3) / (3.0 * e * iy) + 1e4 * l / (5.0 / 6.0 * g * a);
        assert!(
            ((closed_form - exact) / exact).abs() < 1e-9,
            "{name}: reference numbers"
        );
        let started = Instant::now();
        let (w, theta) = cantilever_tip(l, b, h, 1e4, 1);
        let run_time_s = started.elapsed().as_secs_f64();
        let err = (w - closed_form) / closed_form;
        println!("{name}: tip {w:.10e} m, closed form {closed_form:.10e}, rel err {err:.2e}");
        let slug = name.to_lowercase().replace('_', "-");
        let one_member = |quantity: &str, value: f64, reference: &str| Record {
            id: format!("asi-gauss-cantilever-tip-{quantity}-{slug}"),
            capability: format!("ASI-Gauss cantilever tip {quantity}"),
            reference: reference.into(),
            case: format!("{name}: steel cantilever {l} m, {b} × {h} m, tip load 10 kN"),
            resolution: "one member (two ASI-Gauss elements), linear static".into(),
            measure: format!("relative error of the tip {quantity}"),
            value,
            bound: Some(1e-10),
            bound_source: "the brief: ASI-Gauss with s = ±(2/√3 − 1) is exact for one member, so only \
                           round-off remains"
                .into(),
            source:
                "structure-solver/tests/frame_static.rs::one_member_cantilever_matches_timoshenko_closed_form"
                    .into(),
            run_time_s,
            ..Default::default()
        };
        record(one_member(
            "deflection",
            err.abs(),
            "Timoshenko closed form PL³/3EI + PL/κGA (a_cantilever_static.csv)",
        ));
        assert!(
            err.abs() < 1e-10,
            "{name}: tip deflection {w} vs {closed_form} (rel {err:e})"
        );
        // rotation about y of a +z deflection is negative (right-hand rule); PL²/2EI
        let rotation_closed_form = 1e4 * l * l / (2.0 * e * iy);
        assert!(
            ((rotation_closed_form - rotation) / rotation).abs() < 1e-9,
            "{name}: reference rotation"
        );
        let err = (-theta - rotation_closed_form) / rotation_closed_form;
        record(one_member(
            "rotation",
            err.abs(),
            "closed form PL²/2EI (a_cantilever_static.csv)",
        ));
        assert!(
            err.abs() < 1e-10,
            "{name}: tip rotation {theta} (rel err {err:e})"
        );
        // not the midpoint rule (15/16 of the bending part) nor the wrong-signed s (0.884)
        assert!(
            (w / mid - 1.0).abs() > 0.01,
            "{name}: looks like midpoint integration"
        );
    }
}

/// Several members are exact too (f_asigauss_linear_check.csv: ratio 1.000000 for 2, 4, 8 members).
#[test]
fn multi_member_cantilever_is_exact() {
    for members in [2, 4, 8] {
        let started = Instant::now();
        let (w, _) = cantilever_tip(3.0, 0.1, 0.15, 1e4, members);
        let run_time_s = started.elapsed().as_secs_f64();
        let err = (w - 1.60312e-2) / 1.60312e-2;
        record(Record {
            id: format!("asi-gauss-cantilever-tip-deflection-{members}-members"),
            capability: "ASI-Gauss cantilever tip deflection".into(),
            reference: "Timoshenko closed form PL³/3EI + PL/κGA = 1.60312e-2 m (a_cantilever_static.csv)"
                .into(),
            case: "B_slender: steel cantilever 3 m, 0.1 × 0.15 m, tip load 10 kN".into(),
            resolution: format!("{members} members, linear static"),
            measure: "relative error of the tip deflection".into(),
            value: err.abs(),
            bound: Some(1e-9),
            bound_source: "f_asigauss_linear_check.csv: ratio 1.000000 for 2, 4 and 8 members".into(),
            source: "structure-solver/tests/frame_static.rs::multi_member_cantilever_is_exact".into(),
            run_time_s,
            ..Default::default()
        });
        assert!(err.abs() < 1e-9, "{members} members: rel err {err:e}");
    }
}
