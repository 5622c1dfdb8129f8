//! Fracture (S2-17): a member loaded past its critical curvature splits off at its hinge onto a new
//! node; the two pieces move apart and the mass is conserved.

use crate::frame_common;

use frame_common::{energy_share, rectangle, steel, support, ALL};
use schemas::case::frame::{FrameConfig, MemberConfig, NodeConfig};
use schemas::case::Case;
use schemas::validation::largest;
use std::path::Path;
use structure_solver::frame::energy_check::ENERGY_WARNING_SHARE;
use structure_solver::frame::{EnergyRow, Equilibrium, Frame};

/// A 2 m cantilever along x: a strong member (0.1 × 0.1 m) from the fixed base to x = 1 m, then a
/// weak one (0.05 × 0.05 m) to the tip. A tip load in −z makes a hinge where the weak member starts
/// (its Mp = 7.3 kN·m is reached at P = 7.3 kN while the base carries 2P < Mp_strong = 58.8 kN·m).
fn two_part_cantilever() -> FrameConfig {
    let mut material = steel();
    // critical curvature ≈ 3 × the weak section's yield curvature Mp/EI = 0.07 1/m
    material.fracture_curvature = Some([0.2, 0.2]);
    let node = (0..3)
        .map(|i| NodeConfig {
            id: i + 1,
            position: [i as f64, 0.0, 0.0],
        })
        .collect();
    let member = [(1, 2, "strong"), (2, 3, "weak")]
        .into_iter()
        .map(|(a, b, s)| MemberConfig {
            nodes: [a, b],
            section: s.into(),
            orientation: Some([0.0, 1.0, 0.0]),
        })
        .collect();
    FrameConfig {
        time_step: 1e-4,
        gravity: [0.0; 3],
        material,
        section: vec![rectangle("strong", 0.1, 0.1), rectangle("weak", 0.05, 0.05)],
        node,
        member,
        support: vec![support(1, &ALL)],
        contact: None,
        wall: Vec::new(),
        equilibrium_tolerance: None,
        damping: None,
        geometry: Default::default(),
    }
}

/// The two-part cantilever under the tip load of the test below, iterated to equilibrium
/// (tolerance 1e-10, so that no unbalanced force carries over) at `dt` with the energy account kept,
/// to the step after its fracture: the account's rows before the fracture step, at it and after the
/// next one.
fn fracture_rows(dt: f64) -> [EnergyRow; 3] {
    let mut frame =
        Frame::from_config(&two_part_cantilever(), "structure.test.frame").expect("valid test config");
    frame
        .set_equilibrium(Equilibrium::Iterate { tolerance: 1e-10 })
        .expect("tolerance");
    frame.record_energy(true);
    let tip = frame.node_index(3).expect("node");
    let mut rows = Vec::new();
    for n in 1..=(0.1 / dt) as usize {
        let p = (20e3 * n as f64 * dt / 0.1).min(12e3);
        let mut loads = vec![0.0; 6 * frame.node_count()];
        loads[6 * tip + 2] = -p;
        let before = frame.energy().expect("recorded");
        frame.step(dt, &loads).expect("stable step");
        if frame.fracture_count() > 0 {
            rows.push(before);
            rows.push(frame.energy().expect("recorded"));
            if rows.len() == 4 {
                return [rows[0], rows[1], rows[3]];
            }
        }
    }
    panic!("no fracture by 0.1 s at Δt = {dt}");
}

/// A fracture does no work (positions and velocities do not jump): across it the energy account
/// must balance as across any step, with the fractured element's strain energy booked as released
/// (`frame/energy.rs`). The step after the fracture starts from the forces the fracture changed.
/// From the accelerations the step before ended with (main before this test), it left a residual
/// of ½ [[u]]ᵀ ΔF: measured 5.68, 3.90 and 2.10 J at Δt = 2e-4, 1e-4 and 5e-5 s (2.9e-2 of the
/// 132.9 J released, at 1e-4 s), shrinking like Δt^0.5–0.9. From accelerations that balance the
/// new forces (`frame/fracture.rs`) it is a step like any other, whose residual is the trapezoid
/// rule's local error, O(Δt³): measured 1.2e-5, 2.1e-6 and 4.1e-7 J (1.6e-8 of the release at
/// 1e-4 s), falling 5.9 and 5.0 times per halving. Bounds: each halving must cut it more than
/// 2^1.5 times (between first and second order; the stale start never did better than 1.9), and
/// at 1e-4 s it must stay below 1e-6 of the release (the co-rotational elements leave 3.5e-9 of the
/// energy per step in an elastic run, `tests/frame_energy.rs`; 1e-6 is 60 times the measured value
/// and 3e-5 times the stale start's).
#[test]
fn the_energy_balance_closes_across_a_fracture() {
    let mut jumps = Vec::new();
    for dt in [2e-4, 1e-4, 5e-5] {
        let [before, at, after] = fracture_rows(dt);
        let released = before.shift - at.shift;
        let jump = after.residual - at.residual;
        println!(
            "Δt = {dt:e}: released {released:.4} J (U {:.4} → {:.4} J); residual {:.3e} J before the fracture, \
             {:.3e} J after it; the step after it changed it by {jump:.3e} J ({:.2e} of the release)",
            before.strain,
            at.strain,
            before.residual,
            at.residual,
            jump / released
        );
        assert!(released > 100.0, "the weak member's release is {released} J");
        jumps.push((dt, jump.abs(), released));
    }
    for pair in jumps.windows(2) {
        let ratio = pair[0].1 / pair[1].1;
        println!(
            "Δt {:e} → {:e}: the step after the fracture's residual falls {ratio:.2} times",
            pair[0].0, pair[1].0
        );
        assert!(
            ratio > 2f64.powf(1.5),
            "halving Δt from {} s cut the residual of the step after the fracture only {ratio:.2} times: \
             that step does not start in balance",
            pair[0].0
        );
    }
    let (_, jump, released) = jumps[1];
    assert!(
        jump < 1e-6 * released,
        "the step after the fracture left {jump:e} J of the {released} J released at Δt = 1e-4 s"
    );
}

#[test]
fn overloaded_member_splits_at_its_hinge_and_the_pieces_separate() {
    let cfg = two_part_cantilever();
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let (joint, tip) = (
        frame.node_index(2).expect("node"),
        frame.node_index(3).expect("node"),
    );
    let mass_before: f64 = frame.node_masses().iter().sum();
    let exact_mass = 7850.0 * (0.1 * 0.1 + 0.05 * 0.05);
    // lumped masses add up to ρ Σ A L (round-off only)
    assert!((mass_before / exact_mass - 1.0).abs() < 1e-12);
    let nodes_before = frame.node_count();
    let dt = 1e-4;
    let mut fractured_at = None;
    let mut hinge_seen = false;
    let mut separation = Vec::new();
    let mut momentum = Vec::new();
    for n in 1..=4000 {
        let p = (20e3 * n as f64 * dt / 0.1).min(12e3);
        let mut loads = vec![0.0; 6 * frame.node_count()];
        loads[6 * tip + 2] = -p;
        frame.step(dt, &loads).expect("stable step");
        hinge_seen |= frame.hinge_nodes().contains(&joint);
        if fractured_at.is_none() && frame.fracture_count() > 0 {
            fractured_at = Some(n);
        }
        if fractured_at.is_some() {
            let x = frame.node_positions();
            let new = frame.node_count() - 1;
            let d: f64 = (0..3)
                .map(|k| (x[3 * new + k] - x[3 * joint + k]).powi(2))
                .sum::<f64>()
                .sqrt();
            separation.push(d);
            // z momentum of the free piece: the new node, the weak member's mid node and the tip
            let (m, v) = (frame.node_masses(), frame.node_velocities());
            momentum.push([new, 4, tip].iter().map(|&i| m[i] * v[6 * i + 2]).sum::<f64>());
        }
    }
    let fractured_at = fractured_at.expect("the weak member never fractured");
    println!(
        "hinge seen {hinge_seen}; fracture at step {fractured_at}; nodes {nodes_before} → {}; separation after \
         {} steps: {:.4} m",
        frame.node_count(),
        separation.len(),
        separation.last().copied().unwrap_or(0.0)
    );
    assert!(hinge_seen, "no hinge formed at the joint before fracture");
    assert_eq!(frame.fracture_count(), 1, "exactly one fracture");
    assert_eq!(frame.node_count(), nodes_before + 1, "one new node");
    assert_eq!(frame.connectivity_version(), 1);
    // the new node belongs to the weak member's first element
    let new = frame.node_count() - 1;
    assert_eq!(frame.element_nodes()[2], [new, frame.element_nodes()[3][0]]);
    // the pieces move apart: separation grows steadily to at least 0.2 m
    let last = separation.last().copied().unwrap_or(0.0);
    assert!(last > 0.2, "separation only {last} m");
    let mid = separation[separation.len() / 2];
    assert!(last > mid && mid > separation[0], "separation does not grow");
    // the free piece is pushed by the 12 kN tip load only: its momentum changes by F Δt per step
    // (internal forces cancel; Newmark's velocity update is exact for a constant force), to the
    // Newton tolerance: 1e-3 relative
    let impulse = momentum[momentum.len() - 1] - momentum[0];
    let expected = -12e3 * dt * (momentum.len() - 1) as f64;
    println!("piece impulse {impulse:.4} N s, expected {expected:.4} N s");
    assert!(
        (impulse / expected - 1.0).abs() < 1e-3,
        "impulse {impulse} vs {expected}"
    );
    // mass is conserved (lumped masses are element halves: round-off only)
    let mass_after: f64 = frame.node_masses().iter().sum();
    assert!(
        (mass_after / mass_before - 1.0).abs() < 1e-12,
        "mass {mass_before} → {mass_after}"
    );
    // the remaining cantilever stays attached and bounded: its joint is within 0.1 m of where it was
    let x = frame.node_positions();
    assert!(
        (x[3 * joint] - 1.0).abs() < 0.1 && x[3 * joint + 2].abs() < 0.1,
        "joint moved away"
    );
    // the VTU output shows the split: one more point, one fractured cell
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("frame_tests");
    std::fs::create_dir_all(&dir).expect("out folder");
    let path = dir.join("fractured_cantilever.vtu");
    frame.write_vtu(&path).expect("write vtu");
    let text = std::fs::read_to_string(&path).expect("read vtu");
    assert!(text.contains(&format!(
        "NumberOfPoints=\"{}\" NumberOfCells=\"4\"",
        frame.node_count()
    )));
    let fractures = text.split("Name=\"fractures\"").nth(1).expect("fractures column");
    let flags: Vec<i64> = fractures
        .lines()
        .skip(1)
        .take(4)
        .map(|l| l.trim().parse().expect("integer flag"))
        .collect();
    assert_eq!(flags, [0, 0, 1, 0]);
}

/// A frame written to a checkpoint file and read back (`frame/checkpoint.rs`) steps bit for bit
/// like the frame that wrote it, once that one has dropped its caches as a run does when it writes a
/// checkpoint: taken after the hinge formed (step 400) and the fracture (step 700), each continued
/// to step 1 000, every node position, velocity and the hinge events equal bit for bit.
#[test]
fn a_frame_read_back_from_a_checkpoint_steps_bit_for_bit_like_the_one_that_wrote_it() {
    let cfg = two_part_cantilever();
    let dt = 1e-4;
    let step = |frame: &mut Frame, n: usize| {
        let tip = frame.node_index(3).expect("node");
        let p = (20e3 * n as f64 * dt / 0.1).min(12e3);
        let mut loads = vec![0.0; 6 * frame.node_count()];
        loads[6 * tip + 2] = -p;
        frame.step(dt, &loads).expect("stable step");
    };
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("frame_tests");
    std::fs::create_dir_all(&dir).expect("out folder");
    for at in [400, 700] {
        let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
        frame.record_hinge_events(true);
        for n in 1..=at {
            step(&mut frame, n);
        }
        frame.drop_caches().expect("caches dropped");
        let path = dir.join(format!("frame-checkpoint-{at}.bin"));
        schemas::checkpoint::write(&path, &frame, &mut schemas::participant::DiscardProgress)
            .expect("checkpoint written");
        let mut read: Frame = schemas::checkpoint::read(&path).expect("checkpoint read");
        assert_eq!(read.node_count(), frame.node_count());
        for n in at + 1..=1000 {
            step(&mut frame, n);
            step(&mut read, n);
        }
        assert_eq!(
            frame.fracture_count(),
            1,
            "the weak member fractured by step 1000"
        );
        let bits = |v: Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(read.node_positions()), bits(frame.node_positions()));
        assert_eq!(bits(read.node_velocities()), bits(frame.node_velocities()));
        assert_eq!(read.hinge_events(), frame.hinge_events());
        println!(
            "from step {at} ({} nodes, {} fractures): equal bit for bit at step 1000",
            read.node_count(),
            read.fracture_count()
        );
    }
}

/// The frame of `cases/prism-washout` as shipped (its weakened prism, walls and equilibrium
/// tolerance), at `dt` when given (else the case's), alone under its weight and a drag-like push of
/// 0.6 N on every node in the lowest 0.1 m (the drag's base moment at the surge, 0.045 N m at
/// Δs = 0.02 m, case README), ramped in over 0.02 s from 0.02 s, for 0.3 s, in which the prism
/// breaks in 4 places and its pieces fall. Returns the frame and the worst |residual| / scale.
fn pushed_washout_frame(dt: Option<f64>) -> (Frame, f64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/prism-washout/case.toml");
    let case = Case::load(&path).expect("the shipped case loads");
    let mut cfg = case.structure["prism"].frame.clone().expect("a frame");
    cfg.time_step = dt.unwrap_or(cfg.time_step);
    let mut frame = Frame::from_config(&cfg, "structure.prism.frame").expect("valid frame");
    frame.record_energy(true);
    frame.record_hinge_events(true);
    let mut worst: f64 = 0.0;
    for n in 1..=(0.3 / cfg.time_step).round() as usize {
        let t = n as f64 * cfg.time_step;
        let x = frame.node_positions();
        let mut loads = vec![0.0; 6 * frame.node_count()];
        for i in 0..frame.node_count() {
            if x[3 * i + 2] < 0.1 {
                loads[6 * i] = 0.6 * ((t - 0.02) / 0.02).clamp(0.0, 1.0);
            }
        }
        frame.step(cfg.time_step, &loads).expect("stable step");
        let r = frame.energy().expect("recorded");
        worst = largest([worst, energy_share(&r)], 0.0);
    }
    let r = frame.energy().expect("recorded");
    println!(
        "Δt = {:e} s: {} hinge events, {} fractures, {} unconverged steps; W {:.4e} J, T {:.4e} J, \
         D_p {:.4e} J, residual {:.3e} J; worst |residual| / scale {worst:.2e}",
        cfg.time_step,
        frame.hinge_events().len(),
        frame.fracture_count(),
        frame.unconverged_steps(),
        r.external,
        r.kinetic,
        r.plastic,
        r.residual
    );
    assert!(
        frame.fracture_count() >= 2,
        "the push must break the prism: {} fractures",
        frame.fracture_count()
    );
    (frame, worst)
}

/// The washout's frame as shipped (4 steps of 5e-5 s per window, iterated to 1e-7) pushed until it
/// breaks: no warning at all, neither of the energy balance (the residual stays below
/// [`ENERGY_WARNING_SHARE`], 1 %, of the energy scale at every step: the threshold the warning
/// takes from measured good and bad runs, `frame/energy_check.rs`) nor of steps that kept an
/// unconverged iterate. Measured: worst 2.1e-4, 16 hinge events, no unconverged step; on main
/// before this test, one step kept an unconverged iterate (worst 1.2e-3, 18 events).
#[test]
fn the_washout_prism_as_shipped_breaks_without_a_warning() {
    let (frame, worst) = pushed_washout_frame(None);
    assert_eq!(frame.energy_warning(), None, "worst {worst:e}");
    assert_eq!(frame.accuracy_warning(), None);
    assert!(worst < ENERGY_WARNING_SHARE, "worst |residual| / scale {worst:e}");
}

/// No hinge at a free end (`frame/hinge.rs`, `frame/fracture.rs`): the same push at the window's
/// 2e-4 s, the step the case took before. The pieces' free ends turn faster than such a step
/// follows, and their weakened plastic moment is reached at 5e-6 rad. Measured: worst 4.6e-4, 26
/// hinge events; on main before this test, hinges formed and closed at the pieces' free ends every
/// other step, 318 events, 549 steps unconverged, worst 2.9e-2 (the energy warning). Bound: the
/// energy warning's 1 % of the scale, as above (6 steps where hinges form still keep an
/// unconverged iterate at this step, which is why the case takes four).
#[test]
fn hinges_at_the_free_ends_of_broken_pieces_do_not_make_energy() {
    let (frame, worst) = pushed_washout_frame(Some(2e-4));
    assert_eq!(frame.energy_warning(), None, "worst {worst:e}");
    assert!(worst < ENERGY_WARNING_SHARE, "worst |residual| / scale {worst:e}");
}
