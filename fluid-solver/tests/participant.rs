//! The coupled-run side: checkpoints repeat a window bit for bit, windows land exactly on
//! their end, the pressure load on a resolved body is hydrostatic at rest, and every step is
//! reported as progress.

use fluid_solver::participant::FluidParticipant;
use schemas::case::Case;
use schemas::message::{Fields, Waveform};
use schemas::participant::{DiscardProgress, Participant, ProgressSink};
use std::path::Path;

/// A 4 × 4 × 4-particle box on the floor of a 0.2 × 0.2 m tank, water 0.3 m deep around it.
const CASE: &str = r#"
[case]
name = "box-in-water"
end_time = 1.0

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [0.2, 0.2, 0.4] }

[[fluid.water.body]]
name = "box"
min = [0.06, 0.06, 0.0]
max = [0.14, 0.14, 0.08]

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.06, 0.2, 0.3]
[[fluid.water.block]]
min = [0.14, 0.0, 0.0]
max = [0.2, 0.2, 0.3]
[[fluid.water.block]]
min = [0.06, 0.0, 0.0]
max = [0.14, 0.06, 0.3]
[[fluid.water.block]]
min = [0.06, 0.14, 0.0]
max = [0.14, 0.2, 0.3]
[[fluid.water.block]]
min = [0.06, 0.06, 0.08]
max = [0.14, 0.14, 0.3]
"#;

fn participant() -> FluidParticipant {
    let case =
        Case::parse(Path::new("box-in-water.toml"), CASE.to_string()).unwrap_or_else(|e| panic!("{e}"));
    FluidParticipant::from_case(&case, "water", None).unwrap_or_else(|e| panic!("{e}"))
}

fn window(t0: f64, t1: f64, samples: u32) -> Waveform {
    let times = Waveform::grid(t0, t1, samples);
    let n = times.len();
    Waveform {
        times,
        samples: vec![Fields::default(); n],
    }
}

#[test]
fn checkpoint_repeats_a_window_and_lands_on_its_end() {
    let mut p = participant();
    assert_eq!(p.interface().bodies, vec!["box".to_string()]);
    p.advance(&window(0.0, 0.05, 1)).unwrap_or_else(|e| panic!("{e}"));
    p.save_checkpoint();
    // 0.0173 s is not a multiple of Δt = 8e-4 s, nor are the 3 exchange times inside it.
    let w = window(0.05, 0.0673, 3);
    let first = p.advance(&w).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(first.len(), 4);
    assert_eq!(p.time(), 0.0673);
    let state = p.solver().particles().clone();
    p.restore_checkpoint().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.time(), 0.05);
    let again = p.advance(&w).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(first, again, "a repeated window must answer the same");
    assert_eq!(p.solver().particles(), &state);
    // A window that does not start where the fluid is, is refused.
    assert!(p.advance(&window(0.5, 0.6, 1)).is_err());
}

#[test]
fn body_at_rest_carries_the_water_above_it() {
    let mut p = participant();
    // Settle (1 s), then average the load over 0.3 s.
    p.advance(&window(0.0, 1.0, 1)).unwrap_or_else(|e| panic!("{e}"));
    let mut sum = [0.0; 6];
    let mut top = 0.0;
    let n = 30;
    for k in 0..n {
        let t0 = 1.0 + f64::from(k) * 0.01;
        let out = p
            .advance(&window(t0, t0 + 0.01, 1))
            .unwrap_or_else(|e| panic!("{e}"));
        let load = &out[1].body_force;
        // Action and reaction: the same pair forces summed from the body's and the fluid's side.
        for a in 0..6 {
            let r = out[1].body_reaction[a];
            assert!(
                (load[a] + r).abs() <= 1e-9 * load[2].abs(),
                "component {a}: load {} reaction {r}",
                load[a]
            );
        }
        for a in 0..6 {
            sum[a] += load[a] / f64::from(n);
        }
        let s = p.solver().particles();
        top += (0..s.len())
            .filter(|&i| s.kind[i] == 0)
            .map(|i| s.z[i])
            .fold(f64::MIN, schemas::validation::max_or_nan)
            / f64::from(n);
    }
    // Hydrostatics: the box's top face (0.08 m², 0.08 m high) carries the column above it;
    // its sides cancel; the floor is a wall, so no water pushes from below.
    let surface = top + 0.01;
    let expected = -1000.0 * 9.8 * (surface - 0.08) * 0.08 * 0.08;
    println!("mean load {sum:?}; expected F_z = {expected:.2} N (surface {surface:.4} m)");
    // Bound 10 %: a body 4 particles wide has its top-face pressure sampled by 16 particles
    // within 2.1 Δs, and the top surface is known to ±Δs/2 (≈ 5 % of the 0.21 m column).
    assert!(
        (sum[2] / expected - 1.0).abs() < 0.1,
        "F_z = {} N, expected {expected} N",
        sum[2]
    );
    for a in [0, 1] {
        assert!(
            sum[a].abs() < 0.05 * expected.abs(),
            "side forces must cancel: {sum:?}"
        );
    }
}

#[test]
fn body_particles_follow_the_given_pose() {
    let mut p = participant();
    let before: Vec<(u32, [f64; 3])> = {
        let s = p.solver().particles();
        (0..s.len())
            .filter(|&i| s.kind[i] == fluid_solver::Kind::Body.code())
            .map(|i| (s.id[i], s.position(i)))
            .collect()
    };
    assert_eq!(before.len(), 64);
    // Turn the box a quarter turn about z around its centre (0.1, 0.1, 0.04), lift it by 1 cm,
    // and give it V = (0.1, 0, 0), ω = (0, 0, 1).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let pose = [0.1, 0.1, 0.05, h, 0.0, 0.0, h];
    let velocity = [0.1, 0.0, 0.0, 0.0, 0.0, 1.0];
    let mut w = window(0.0, 0.0008, 1);
    for s in &mut w.samples {
        s.body_pose = pose.to_vec().into();
        s.body_velocity = velocity.to_vec().into();
    }
    // One step: the pose is set at the step's start, then the particles move with their velocity.
    p.advance(&w).unwrap_or_else(|e| panic!("{e}"));
    let s = p.solver().particles();
    let dt = 0.0008;
    for i in (0..s.len()).filter(|&i| s.kind[i] == fluid_solver::Kind::Body.code()) {
        let (_, r0) = before
            .iter()
            .find(|(id, _)| *id == s.id[i])
            .copied()
            .unwrap_or_else(|| panic!("lost body particle"));
        let arm = [-(r0[1] - 0.1), r0[0] - 0.1, r0[2] - 0.04]; // the quarter turn of the offset
        let v = [0.1 - arm[1], arm[0], 0.0]; // V + ω × arm
        let expect = [0.1 + arm[0] + v[0] * dt, 0.1 + arm[1] + v[1] * dt, 0.05 + arm[2]];
        for a in 0..3 {
            assert!(
                (s.position(i)[a] - expect[a]).abs() < 1e-12,
                "{:?} vs {expect:?}",
                s.position(i)
            );
            assert!((s.velocity(i)[a] - v[a]).abs() < 1e-12);
        }
    }
}

/// A checkpoint file written at a window end and read back by a new participant continues the
/// run bit for bit: the same outputs and particles as the participant that wrote it, E-MPS and ISPH.
#[test]
fn a_checkpoint_file_continues_the_run_bit_for_bit() {
    for method in ["emps", "isph"] {
        let text = CASE.replace(
            "[fluid.water]\n",
            &format!("[fluid.water]\nmethod = \"{method}\"\n"),
        );
        let case = Case::parse(Path::new("box-in-water.toml"), text).unwrap_or_else(|e| panic!("{e}"));
        let mut p = FluidParticipant::from_case(&case, "water", None).unwrap_or_else(|e| panic!("{e}"));
        p.advance(&window(0.0, 0.008, 1))
            .unwrap_or_else(|e| panic!("{e}"));
        let file = std::env::temp_dir().join(format!("fluid-checkpoint-{method}-{}.bin", std::process::id()));
        let bytes = p
            .write_checkpoint(&file, &mut DiscardProgress)
            .unwrap_or_else(|e| panic!("{e}"));
        assert!(bytes > 0);
        let mut q = FluidParticipant::resume(&case, "water", None, &file).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(q.time(), p.time());
        assert_eq!(
            q.solver().save_state(),
            p.solver().save_state(),
            "{method}: the state reads back whole"
        );
        for k in 0..3 {
            let w = window(0.008 + 0.004 * k as f64, 0.012 + 0.004 * k as f64, 2);
            let a = p.advance(&w).unwrap_or_else(|e| panic!("{e}"));
            let b = q.advance(&w).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(a, b, "{method}: window {k} after the checkpoint answers the same");
        }
        let (pa, pb) = (p.solver().particles(), q.solver().particles());
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&pa.x), bits(&pb.x), "{method}: positions bit for bit");
        assert_eq!(
            bits(&pa.pressure),
            bits(&pb.pressure),
            "{method}: pressures bit for bit"
        );
        let err = match FluidParticipant::resume(&case, "other", None, &file) {
            Err(e) => e,
            Ok(_) => panic!("a checkpoint of `water` taken for `other`"),
        };
        assert!(
            err.contains("no [fluid.other] section") || err.contains("not of `other`"),
            "{err}"
        );
        let _ = std::fs::remove_file(&file);
    }
}

/// Counts the steps and bytes reported to it and keeps the times.
#[derive(Default)]
struct Reports {
    times: Vec<f64>,
    bytes: u64,
}

impl ProgressSink for Reports {
    fn step_done(&mut self, time: f64) {
        self.times.push(time);
    }

    fn bytes_written(&mut self, bytes: u64) {
        self.bytes += bytes;
    }
}

/// Writing is progress too (issue 41): the frame kept back from a window and the checkpoint are
/// reported byte for byte as they are written, so that a large frame or checkpoint that takes
/// longer than `coupling.timeout` is not taken for a hang. A frame is written on the frames'
/// thread from the next window's start while the fluid steps on (reporting its steps); its bytes
/// reach the progress sink of whoever waits for it: the next frame, a checkpoint or the end.
#[test]
fn the_bytes_of_frames_and_checkpoints_are_reported_as_they_are_written() {
    let case =
        Case::parse(Path::new("box-in-water.toml"), CASE.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let out = std::env::temp_dir().join(format!("fluid-write-progress-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap_or_else(|e| panic!("{e}"));
    let mut p = FluidParticipant::from_case(&case, "water", Some(&out)).unwrap_or_else(|e| panic!("{e}"));
    let size = |name: &str| std::fs::metadata(out.join(name)).map_or(0, |m| m.len());
    // the window reaching the frame at 0.1 s keeps it back; the next window's start begins it
    p.advance(&window(0.0, 0.1, 1)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        size("water_00001.vtu"),
        0,
        "kept back until the window is accepted"
    );
    let mut reports = Reports::default();
    p.advance_reporting(&window(0.1, 0.1008, 1), &mut reports)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(
        !reports.times.is_empty(),
        "the window's steps are reported while the frame is written"
    );
    // a checkpoint: it waits for the frame (its bytes), then every byte of its own file
    let file = out.join("water.bin");
    let mut reports = Reports::default();
    let written = p
        .write_checkpoint(&file, &mut reports)
        .unwrap_or_else(|e| panic!("{e}"));
    let frame = size("water_00001.vtu");
    assert!(
        frame > 0 && reports.bytes == frame + written,
        "frame {frame} B and checkpoint {written} B, reported {} B",
        reports.bytes
    );
    assert_eq!(written, std::fs::metadata(&file).map_or(0, |m| m.len()));
    // the end: the frame kept back from the last window
    p.advance(&window(0.1008, 0.2, 1))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut reports = Reports::default();
    p.finish(&mut reports).unwrap_or_else(|e| panic!("{e}"));
    let last = size("water_00002.vtu");
    assert!(
        last > 0 && reports.bytes == last,
        "last frame {last} B, reported {} B",
        reports.bytes
    );
    assert!(reports.times.is_empty(), "no step at the end");
    let _ = std::fs::remove_dir_all(&out);
}

/// The coupler takes a long window for a hang unless the fluid reports its steps as it goes.
#[test]
fn every_step_of_a_window_is_reported_with_the_time_it_reached() {
    let mut p = participant();
    let mut reports = Reports::default();
    let steps_before = p.solver().steps();
    let outputs = p
        .advance_reporting(&window(0.0, 0.0101, 2), &mut reports)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(outputs.len(), 3);
    let steps = p.solver().steps() - steps_before;
    assert!(steps >= 13, "0.0101 s in steps of at most 8e-4 s: {steps}");
    assert_eq!(reports.times.len() as u64, steps, "one report per step");
    assert!(
        reports.times.windows(2).all(|t| t[0] < t[1]),
        "times rise: {:?}",
        reports.times
    );
    assert_eq!(reports.times.last().copied(), Some(0.0101));
}
