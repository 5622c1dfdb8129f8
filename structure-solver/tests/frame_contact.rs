//! Contact (S2 §3(2)): members land on a wall and on each other and come to rest without passing
//! through.

mod frame_common;

use frame_common::{beam, rectangle, steel, support, ALL};
use schemas::case::frame::{ContactConfig, FrameConfig, MemberConfig, NodeConfig, WallConfig};
use structure_solver::frame::Frame;

/// Contact particles of a 0.05 × 0.05 m section have radius 0.025 m.
const RADIUS: f64 = 0.025;

fn contact() -> Option<ContactConfig> {
    // the lightest particle (0.98 kg) allows up to 9.8e7 N/m at Δt = 1e-4 s
    Some(ContactConfig {
        stiffness: 1e7,
        damping_ratio: 0.5,
        members: true,
    })
}

/// A free 1 m steel beam dropped flat from 0.2 m onto a floor at z = 0 comes to rest on it: it never
/// sinks into the floor by more than 10 % of the particle radius (the impact overlap is about
/// v √(m/k) = 0.6 mm = 2 % of it) and ends still, lying at z = radius to 0.1 mm.
#[test]
fn beam_dropped_on_a_wall_comes_to_rest_on_it() {
    let mut cfg = beam(1.0, 2, 0.05, 0.05, steel());
    cfg.gravity = [0.0, 0.0, -9.81];
    for n in &mut cfg.node {
        n.position[2] = 0.2;
    }
    cfg.contact = contact();
    cfg.wall.push(WallConfig {
        point: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
    });
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let loads = vec![0.0; 6 * frame.node_count()];
    let mut lowest = f64::INFINITY;
    for _ in 0..8000 {
        frame.step(1e-4, &loads).expect("stable step");
        let z = frame
            .node_positions()
            .chunks(3)
            .map(|p| p[2])
            .fold(f64::INFINITY, f64::min);
        lowest = lowest.min(z);
    }
    let x = frame.node_positions();
    let speed = frame
        .node_velocities()
        .chunks(6)
        .map(|v| v[2].abs())
        .fold(0.0, f64::max);
    let heights: Vec<f64> = x.chunks(3).map(|p| p[2]).collect();
    println!("lowest node height {lowest:.5} m; final heights {heights:.5?}; largest vertical speed {speed:.2e} m/s");
    assert!(lowest > 0.9 * RADIUS, "the beam sank to {lowest} m");
    assert!(
        heights.iter().all(|z| (z - RADIUS).abs() < 1e-4),
        "not lying on the floor: {heights:?}"
    );
    assert!(speed < 1e-2, "still moving at {speed} m/s");
}

/// A free beam dropped across a fixed–fixed beam rests on it: the two axes end two radii apart (to
/// 10 % of a radius) and never come closer than one radius. The crossing is placed where a particle
/// of each beam sits (x = 0.525 on the lower beam, y = 0 on the upper one), so that two radii is the
/// resting distance of the particle model.
#[test]
fn beam_dropped_across_another_rests_on_it() {
    let mut cfg = beam(1.0, 2, 0.05, 0.05, steel());
    cfg.gravity = [0.0, 0.0, -9.81];
    cfg.support.push(support(1, &ALL));
    cfg.support.push(support(3, &ALL));
    cfg.contact = contact();
    // the crossing beam, along y above the first one's midpoint
    cfg.section.push(rectangle("cross", 0.05, 0.05));
    for (id, y) in [(11, -0.475), (12, 0.025), (13, 0.525)] {
        cfg.node.push(NodeConfig {
            id,
            position: [0.525, y, 0.15],
        });
    }
    for pair in [[11, 12], [12, 13]] {
        cfg.member.push(MemberConfig {
            nodes: pair,
            section: "cross".into(),
            orientation: Some([1.0, 0.0, 0.0]),
        });
    }
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let (lower, upper) = (
        frame.node_index(2).expect("node"),
        frame.node_index(12).expect("node"),
    );
    let loads = vec![0.0; 6 * frame.node_count()];
    let mut closest = f64::INFINITY;
    for _ in 0..6000 {
        frame.step(1e-4, &loads).expect("stable step");
        let x = frame.node_positions();
        closest = closest.min(x[3 * upper + 2] - x[3 * lower + 2]);
    }
    let x = frame.node_positions();
    let gap = x[3 * upper + 2] - x[3 * lower + 2];
    println!(
        "closest axis distance {closest:.5} m; final {gap:.5} m (two radii: {:.3} m)",
        2.0 * RADIUS
    );
    assert!(
        closest > RADIUS,
        "the beams passed through each other: {closest} m"
    );
    assert!(
        (gap - 2.0 * RADIUS).abs() < 0.1 * RADIUS,
        "final axis distance {gap} m"
    );
}

/// Too stiff a penalty for the time step, or a wall without a contact table, is refused.
#[test]
fn unstable_contact_stiffness_is_refused() {
    let mut cfg: FrameConfig = beam(1.0, 2, 0.05, 0.05, steel());
    cfg.contact = Some(ContactConfig {
        stiffness: 1e9,
        damping_ratio: 0.0,
        members: true,
    });
    let err = Frame::from_config(&cfg, "structure.a.frame")
        .err()
        .expect("refused");
    assert_eq!(err.key, "structure.a.frame.contact.stiffness");
    assert!(err.message.contains("too stiff"), "{}", err.message);
    cfg.contact = None;
    cfg.wall.push(WallConfig {
        point: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
    });
    let err = Frame::from_config(&cfg, "structure.a.frame")
        .err()
        .expect("refused");
    assert_eq!(err.key, "structure.a.frame.wall[0]");
}

/// A beam thrown at a far too soft wall goes through it: the run stops with a diagnostic.
#[test]
fn passing_through_a_wall_stops_the_run() {
    let mut cfg = beam(1.0, 2, 0.05, 0.05, steel());
    for n in &mut cfg.node {
        n.position[2] = 0.2;
    }
    cfg.contact = Some(ContactConfig {
        stiffness: 1e2,
        damping_ratio: 0.0,
        members: true,
    });
    cfg.wall.push(WallConfig {
        point: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
    });
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let mut v = vec![0.0; 6 * frame.node_count()];
    v.chunks_mut(6).for_each(|n| n[2] = -50.0);
    frame.set_node_velocities(&v).expect("velocities");
    let loads = vec![0.0; 6 * frame.node_count()];
    let err = (0..200)
        .try_for_each(|_| frame.step(1e-4, &loads))
        .expect_err("must stop");
    assert!(err.contains("went through wall 0"), "{err}");
}
