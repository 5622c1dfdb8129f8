//! Fracture (S2-17): a member loaded past its critical curvature splits off at its hinge onto a new
//! node; the two pieces move apart and the mass is conserved.

mod frame_common;

use frame_common::{rectangle, steel, support, ALL};
use schemas::case::frame::{FrameConfig, MemberConfig, NodeConfig};
use std::path::Path;
use structure_solver::frame::Frame;

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
        schemas::checkpoint::write(&path, &frame).expect("checkpoint written");
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
