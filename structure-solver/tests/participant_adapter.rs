//! The participant adapter without the link: windows, interpolated inputs, outputs at every
//! exchange time, checkpoints.

use schemas::case::Case;
use schemas::f64s::F64s;
use schemas::message::{Fields, Waveform};
use schemas::participant::{DiscardProgress, Participant};
use schemas::validation::{largest_abs, record, Record};
use std::f64::consts::PI;
use std::path::Path;
use std::time::Instant;
use structure_solver::participant::StructureParticipant;

/// One mass (1 kg) on a spring to ground with k = 4π² (ω = 2π), at rest at t = 0.
fn oscillator() -> StructureParticipant {
    oscillator_writing_to(None)
}

fn oscillator_writing_to(out: Option<&Path>) -> StructureParticipant {
    StructureParticipant::from_case(&oscillator_case(), "m", out).expect("builds")
}

fn oscillator_case() -> Case {
    let text = r#"
[case]
name = "one-mass"
end_time = 1.0

[structure.m]
max_step = 1e-3

[[structure.m.point_mass]]
name = "m1"
mass = 1.0
position = [0, 0, 0]

[[structure.m.spring]]
a = "m1"
b = "ground"
stiffness = 39.47841760435743

[structure.m.history]
interval = 0.01
points = ["m1"]
"#;
    Case::parse(Path::new("one-mass.toml"), text.to_string()).expect("valid test case")
}

fn force_window(t0: f64, t1: f64, samples: u32, force: impl Fn(f64) -> f64) -> Waveform {
    let times = Waveform::grid(t0, t1, samples);
    let samples = times
        .iter()
        .map(|&t| Fields {
            point_force: F64s(vec![force(t), 0.0, 0.0]),
            ..Fields::default()
        })
        .collect();
    Waveform { times, samples }
}

#[test]
fn constant_force_windows_follow_the_exact_step_response() {
    // u(t) = F/k (1 − cos ωt) for a force F switched on at t = 0. RK4 at h = 1e-3, ωh = 0.006:
    // error ~ ωt (ωh)⁴/120 · F/k ≈ 1e-13; tolerance 1e-10 leaves room for round-off.
    let mut p = oscillator();
    let decl = p.interface();
    assert_eq!(decl.points, vec!["m1".to_string()]);
    assert!(decl.bodies.is_empty());
    let initial = p.initial_outputs();
    assert_eq!(initial.point_displacement.0, vec![0.0; 3]);
    let (f, k, w) = (2.0, 4.0 * PI * PI, 2.0 * PI);
    let started = Instant::now();
    let mut windows = Vec::new();
    for window in 0..40 {
        let (t0, t1) = (0.0025 * f64::from(window), 0.0025 * f64::from(window + 1));
        let inputs = force_window(t0, t1, 3, |_| f);
        let out = p.advance(&inputs).expect("stable");
        windows.push((inputs, out));
    }
    let run_time_s = started.elapsed().as_secs_f64();
    let worst = largest_abs(
        windows
            .iter()
            .flat_map(|(inputs, out)| inputs.times.iter().zip(out))
            .map(|(t, o)| o.point_displacement[0] - f / k * (1.0 - (w * t).cos())),
    );
    record(Record {
        id: "structure-participant-step-response".into(),
        capability: "point masses and springs (RK4) through the participant adapter".into(),
        reference: "exact step response u(t) = F/k (1 − cos ωt)".into(),
        case: "1 kg on a spring k = 4π² N/m, a force of 2 N switched on at t = 0, 40 windows of 2.5 ms".into(),
        resolution: "RK4, max_step = 1e-3 s, 3 samples per window".into(),
        measure: "largest |u − exact| at the windows' sample times".into(),
        value: worst,
        bound: Some(1e-10),
        bound_source: "RK4 at ωh = 0.006: error ~ ωt (ωh)⁴/120 · F/k ≈ 1e-13, with room for round-off".into(),
        unit: "m".into(),
        source: "structure-solver/tests/participant_adapter.rs::constant_force_windows_follow_the_exact_step_response"
            .into(),
        run_time_s,
        ..Default::default()
    });
    for (inputs, out) in &windows {
        assert_eq!(out.len(), inputs.times.len());
        for (t, o) in inputs.times.iter().zip(out) {
            let exact = f / k * (1.0 - (w * t).cos());
            assert!(
                (o.point_displacement[0] - exact).abs() < 1e-10,
                "t = {t}: {} vs {exact}",
                o.point_displacement[0]
            );
            assert_eq!(o.point_velocity.len(), 3);
        }
    }
    assert!((p.time() - 0.1).abs() < 1e-15);
}

#[test]
fn restoring_a_checkpoint_repeats_the_window_exactly() {
    let mut p = oscillator();
    let first = force_window(0.0, 0.01, 2, |t| 3.0 * t);
    p.advance(&first).expect("stable");
    p.save_checkpoint();
    let second = force_window(0.01, 0.02, 2, |t| 1.0 - t);
    let a = p.advance(&second).expect("stable");
    p.restore_checkpoint().expect("saved");
    assert_eq!(p.time(), 0.01);
    let other = force_window(0.01, 0.02, 2, |_| 100.0);
    let b = p.advance(&other).expect("stable");
    assert_ne!(a.last(), b.last(), "different inputs give different outputs");
    p.restore_checkpoint().expect("saved");
    let c = p.advance(&second).expect("stable");
    assert_eq!(
        a, c,
        "same window from the same checkpoint, same answer, bit for bit"
    );
}

#[test]
fn wrong_inputs_are_reported() {
    let mut p = oscillator();
    assert!(p.restore_checkpoint().unwrap_err().contains("none was saved"));
    let late = force_window(0.5, 0.6, 1, |_| 0.0);
    let e = p.advance(&late).unwrap_err();
    assert!(e.contains("starts at t = 0.5 s") && e.contains("t = 0 s"), "{e}");
    let times = Waveform::grid(0.0, 0.01, 1);
    let samples = vec![
        Fields {
            point_force: F64s(vec![1.0; 6]),
            ..Fields::default()
        };
        2
    ];
    let e = p.advance(&Waveform { times, samples }).unwrap_err();
    assert!(
        e.contains("point_force") && e.contains("6 values") && e.contains("expects 3"),
        "{e}"
    );
}

#[test]
fn an_unstable_run_stops_with_a_diagnostic() {
    // A force that overflows to infinity within the window makes the state non-finite.
    let mut p = oscillator();
    let e = p
        .advance(&force_window(0.0, 1.0, 1, |t| 1e300 * (1.0 + 1e10 * t)))
        .unwrap_err();
    assert!(e.contains("non-finite") && e.contains("m1"), "{e}");
}

#[test]
fn histories_are_written_once_per_accepted_window() {
    // Windows of 0.004 s with 2 samples (exchange every 0.002 s) and a history every 0.01 s:
    // rows at the first exchange time at or after 0.01, 0.02, … (0.01, 0.02 exactly here).
    // Every window is repeated once after a restore, as an implicit scheme does.
    let dir = std::env::temp_dir().join(format!("structure-solver-participant-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut p = oscillator_writing_to(Some(&dir));
    for window in 0..5 {
        let (t0, t1) = (0.004 * f64::from(window), 0.004 * f64::from(window + 1));
        p.save_checkpoint();
        p.advance(&force_window(t0, t1, 2, |_| 50.0)).expect("stable");
        p.restore_checkpoint().expect("saved");
        p.advance(&force_window(t0, t1, 2, |_| 1.0)).expect("stable");
    }
    p.finish(&mut DiscardProgress).expect("written");
    let text = std::fs::read_to_string(dir.join("point-m1.csv")).expect("history file");
    let times: Vec<f64> = text
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').next()?.parse().ok())
        .collect();
    assert_eq!(times.len(), 3, "rows at 0, 0.01, 0.02: {times:?}");
    assert!(
        times[0] == 0.0 && (times[1] - 0.01).abs() < 1e-12 && (times[2] - 0.02).abs() < 1e-12,
        "{times:?}"
    );
    let u: Vec<f64> = text
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').nth(1)?.parse().ok())
        .collect();
    let exact = 1.0 / (4.0 * PI * PI) * (1.0 - (2.0 * PI * 0.02).cos());
    assert!(
        (u[2] - exact).abs() < 1e-10,
        "the row holds the accepted (F = 1 N) run: {} vs {exact}",
        u[2]
    );
}

#[test]
fn body_inputs_and_pose_outputs_follow_the_interface_layout() {
    // A 2 kg cube (I = M a²/6 = 1/3 kg m² for a = 1) spinning about z at 1 rad/s under a body_force
    // input of (4, 0, 0 | 0, 0, 0): centre x = ½ (F/M) t², quaternion (cos t/2, 0, 0, sin t/2)
    // in the order w, x, y, z; velocity (F/M t, 0, 0 | 0, 0, 1). Kick–drift–kick is exact for the
    // force; the Cayley angle 2 atan(ωΔt/2) per step is short by (ωΔt)³/12 = 8e-11 rad, 4e-8 rad
    // over 500 steps: tolerance 1e-7 on the pose.
    let text = r#"
[case]
name = "spin"
end_time = 1.0

[structure.b]
max_step = 1e-3

[[structure.b.body]]
name = "cube"
mass = 2.0
centre = [0, 0, 0]
angular_velocity = [0, 0, 1]
inertia = { box = [1, 1, 1] }
"#;
    let case = Case::parse(Path::new("spin.toml"), text.to_string()).expect("valid test case");
    let mut p = StructureParticipant::from_case(&case, "b", None).expect("builds");
    assert_eq!(p.interface().bodies, vec!["cube".to_string()]);
    let times = Waveform::grid(0.0, 0.5, 1);
    let force = Fields {
        body_force: F64s(vec![4.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
        ..Fields::default()
    };
    let out = p.advance(&Waveform::constant(times, &force)).expect("stable");
    let end = &out[1];
    let t: f64 = 0.5;
    let expect_pose = [
        0.5 * 2.0 * t * t,
        0.0,
        0.0,
        (t / 2.0).cos(),
        0.0,
        0.0,
        (t / 2.0).sin(),
    ];
    for (k, (got, want)) in end.body_pose.iter().zip(expect_pose).enumerate() {
        assert!(
            (got - want).abs() < 1e-7,
            "body_pose[{k}] = {got}, expected {want}"
        );
    }
    let expect_velocity = [2.0 * t, 0.0, 0.0, 0.0, 0.0, 1.0];
    for (k, (got, want)) in end.body_velocity.iter().zip(expect_velocity).enumerate() {
        assert!(
            (got - want).abs() < 1e-12,
            "body_velocity[{k}] = {got}, expected {want}"
        );
    }
}

/// A checkpoint file of a spinning body and a point mass on springs, read back by a new
/// participant, continues bit for bit; so does one of a point mass.
#[test]
fn a_checkpoint_file_continues_the_run_bit_for_bit() {
    let text = r#"
[case]
name = "spin"
end_time = 1.0

[structure.b]
max_step = 1e-3

[[structure.b.body]]
name = "cube"
mass = 2.0
centre = [0, 0, 0]
angular_velocity = [0.3, 0.1, 1]
inertia = { box = [1, 2, 3] }
"#;
    let case = Case::parse(Path::new("spin.toml"), text.to_string()).expect("valid test case");
    let mut p = StructureParticipant::from_case(&case, "b", None).expect("builds");
    let force = |t0: f64, t1: f64| {
        let f = Fields {
            body_force: F64s(vec![4.0, 1.0, 0.0, 0.0, 0.5, 0.0]),
            ..Fields::default()
        };
        Waveform::constant(Waveform::grid(t0, t1, 2), &f)
    };
    p.advance(&force(0.0, 0.1)).expect("stable");
    let file = std::env::temp_dir().join(format!("structure-checkpoint-{}.bin", std::process::id()));
    p.write_checkpoint(&file, &mut DiscardProgress).expect("written");
    let mut q = StructureParticipant::resume(&case, "b", None, &file).expect("resumes");
    for k in 0..3 {
        let t0 = 0.1 + 0.1 * k as f64;
        let a = p.advance(&force(t0, t0 + 0.1)).expect("stable");
        let b = q.advance(&force(t0, t0 + 0.1)).expect("stable");
        assert_eq!(
            a, b,
            "window {k} after the checkpoint answers the same, bit for bit"
        );
    }
    let _ = std::fs::remove_file(&file);
    let mut m = oscillator();
    m.advance(&force_window(0.0, 0.01, 2, |t| 3.0 * t))
        .expect("stable");
    m.write_checkpoint(&file, &mut DiscardProgress)
        .expect("point masses write checkpoints");
    let mut n = StructureParticipant::resume(&oscillator_case(), "m", None, &file).expect("resumes");
    let w = force_window(0.01, 0.02, 2, |t| 1.0 - t);
    assert_eq!(m.advance(&w).expect("stable"), n.advance(&w).expect("stable"));
    let _ = std::fs::remove_file(&file);
}
