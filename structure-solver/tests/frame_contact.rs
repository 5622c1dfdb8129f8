//! Contact (S2 §3(2)): members land on a wall and on each other and come to rest without passing
//! through.

use crate::frame_common;

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
        .fold(0.0, schemas::validation::max_or_nan);
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

/// The prism of `cases/prism-washout` (0.05 × 0.05 m, E 7.93e7 Pa, ρ 491 kg/m³, yield stress 1e3 Pa:
/// axial yield force 2.5 N against its own weight 1.8 N) standing on a floor at z = 0, fixed at its
/// foot, under gravity; the foot element's contact particle sits at z = 0.025 = one radius.
fn standing_prism(wall: bool) -> FrameConfig {
    let mut material = steel();
    material.young_modulus = 7.93e7;
    material.poisson = 0.4;
    material.density = 491.0;
    material.yield_stress = 1.0e3;
    let mut cfg = beam(1.0, 2, 0.05, 0.05, material);
    for (n, z) in cfg.node.iter_mut().zip([0.0, 0.05, 0.15]) {
        n.position = [0.0, 0.0, z];
    }
    for m in &mut cfg.member {
        m.orientation = Some([1.0, 0.0, 0.0]);
    }
    cfg.time_step = 2e-4;
    cfg.gravity = [0.0, 0.0, -9.8];
    cfg.support.push(support(1, &ALL));
    // the lightest particle (0.031 kg) allows up to 7.7e5 N/m at Δt = 2e-4 s
    cfg.contact = Some(ContactConfig {
        stiffness: 1e4,
        damping_ratio: 0.5,
        members: true,
    });
    if wall {
        cfg.wall.push(WallConfig {
            point: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        });
    }
    cfg
}

/// A column fixed at its foot on a wall gets no force from that wall: 0.2 s of the prism standing
/// under its own weight gives the same motion to the last bit with and without the floor (before
/// the rule of `contact.rs` "held on a wall", the floor pushed the foot element's particle up against
/// its support and the foot ratcheted to 50 % axial strain within 4–60 ms).
#[test]
fn column_supported_on_a_wall_gets_no_force_from_it() {
    let run = |wall: bool| {
        let mut frame =
            Frame::from_config(&standing_prism(wall), "structure.test.frame").expect("valid test config");
        let loads = vec![0.0; 6 * frame.node_count()];
        for _ in 0..1000 {
            frame.step(2e-4, &loads).expect("stable step");
        }
        frame.node_positions()
    };
    let (with, without) = (run(true), run(false));
    let top = with[8];
    println!(
        "top node z with the floor {top:.6} m, without {:.6} m",
        without[8]
    );
    assert_eq!(with, without, "the floor changed the standing column");
    assert!((top - 0.15).abs() < 1e-3, "the column sagged to {top} m");
}

/// A free beam dropped beside a column that stands fixed on the same floor lands on the floor and
/// rests at one particle radius (to 0.5 mm = 2 % of it: the soft prism material still flexes after
/// 0.5 s), while the column stays where it stood: the floor
/// exempts only the element held on it by a support.
#[test]
fn free_piece_beside_a_standing_column_lands_on_the_wall() {
    let mut cfg = standing_prism(true);
    cfg.section.push(rectangle("piece", 0.05, 0.05));
    for (id, x) in [(11, 0.2), (12, 0.3), (13, 0.4)] {
        cfg.node.push(NodeConfig {
            id,
            position: [x, 0.0, 0.1],
        });
    }
    for pair in [[11, 12], [12, 13]] {
        cfg.member.push(MemberConfig {
            nodes: pair,
            section: "piece".into(),
            orientation: Some([0.0, 1.0, 0.0]),
        });
    }
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let piece: Vec<usize> = [11, 12, 13]
        .map(|id| frame.node_index(id).expect("node"))
        .to_vec();
    let top = frame.node_index(3).expect("node");
    let loads = vec![0.0; 6 * frame.node_count()];
    let mut lowest = f64::INFINITY;
    for _ in 0..2500 {
        frame.step(2e-4, &loads).expect("stable step");
        let x = frame.node_positions();
        lowest = piece.iter().map(|&n| x[3 * n + 2]).fold(lowest, f64::min);
    }
    let x = frame.node_positions();
    let heights: Vec<f64> = piece.iter().map(|&n| x[3 * n + 2]).collect();
    println!(
        "piece: lowest {lowest:.5} m, final heights {heights:.5?}; column top {:.5} m",
        x[3 * top + 2]
    );
    assert!(lowest > 0.5 * RADIUS, "the piece sank to {lowest} m");
    assert!(
        heights.iter().all(|z| (z - RADIUS).abs() < 5e-4),
        "the piece is not lying on the floor: {heights:?}"
    );
    assert!((x[3 * top + 2] - 0.15).abs() < 1e-3, "the column moved");
}

/// The same prism free (no support) standing on the floor, as a piece broken off its foot stands at
/// the fracture: it rests on its end node (the foot within 1 mm of the floor, never thrown up), not
/// one particle radius above it. Its foot element is 0.025 m long, so a sphere of radius 0.025 m at
/// its middle would start 12.5 mm inside the floor and be thrown off by 125 N.
#[test]
fn free_column_standing_on_a_wall_rests_on_its_end() {
    let mut cfg = standing_prism(true);
    cfg.support.clear();
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let foot = frame.node_index(1).expect("node");
    let loads = vec![0.0; 6 * frame.node_count()];
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    for _ in 0..1000 {
        frame.step(2e-4, &loads).expect("stable step");
        let z = frame.node_positions()[3 * foot + 2];
        (low, high) = (low.min(z), high.max(z));
    }
    println!("foot node between {low:.2e} and {high:.2e} m");
    assert!(low > -1e-3 && high < 1e-3, "foot between {low} and {high} m");
}

/// The standing prism (member contact on) pushed over by a 0.5 N load at its top (base moment
/// 0.075 N m against a fully plastic moment of 0.031 N m) fractures; the elements a fracture
/// separates were overlapping while joined (particles 0.025 m apart, two radii 0.05 m) and must not
/// be thrown apart by it: within 0.2 s of the fracture no node rises above the prism's top nor
/// sinks under the floor by more than 1 mm.
#[test]
fn pieces_split_by_a_fracture_are_not_thrown_apart() {
    let mut cfg = standing_prism(true);
    cfg.material.fracture_curvature = Some([0.01, 0.01]);
    let mut frame = Frame::from_config(&cfg, "structure.test.frame").expect("valid test config");
    let top = frame.node_index(3).expect("node");
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut fractured = None;
    for n in 0..2000 {
        let mut loads = vec![0.0; 6 * frame.node_count()];
        loads[6 * top] = 0.5 * (n as f64 / 100.0).min(1.0);
        frame.step(2e-4, &loads).expect("stable step");
        if frame.fracture_count() > 0 {
            fractured.get_or_insert(n);
            for p in frame.node_positions().chunks(3) {
                (low, high) = (low.min(p[2]), high.max(p[2]));
            }
        }
        if fractured.is_some_and(|f| n > f + 1000) {
            break;
        }
    }
    println!(
        "fracture at step {fractured:?} ({} fractures); nodes after it between z = {low:.2e} and {high:.4} m",
        frame.fracture_count()
    );
    assert!(fractured.is_some(), "the prism did not fracture");
    assert!(low > -1e-3 && high < 0.16, "nodes between z = {low} and {high} m");
}
