//! Newmark steps per second of ASI-Gauss frames of about 1 000, 10 000 and 100 000 DOFs (cubic
//! building grids, fixed at the base), elastic and with plastic hinges forming.
//! Run: `cargo bench -p structure-solver --bench frame_steps`.

use schemas::case::frame::{
    FrameConfig, MaterialConfig, MemberConfig, NodeConfig, SectionConfig, SupportConfig,
};
use std::time::Instant;
use structure_solver::frame::Frame;

/// An n × n × n-bay grid of 3 m steel bays: columns and beams of 0.3 × 0.3 m.
fn building(n: usize, yield_stress: f64) -> FrameConfig {
    let id = |i: usize, j: usize, k: usize| (k * (n + 1) * (n + 1) + j * (n + 1) + i) as u32 + 1;
    let mut node = Vec::new();
    let mut member = Vec::new();
    let mut support = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                node.push(NodeConfig {
                    id: id(i, j, k),
                    position: [3.0 * i as f64, 3.0 * j as f64, 3.0 * k as f64],
                });
                if k == 0 {
                    let fixed = ["x", "y", "z", "rx", "ry", "rz"].map(String::from).to_vec();
                    support.push(SupportConfig {
                        node: id(i, j, k),
                        fixed,
                    });
                }
                let mut add = |to: u32| {
                    member.push(MemberConfig {
                        nodes: [id(i, j, k), to],
                        section: "s".into(),
                        orientation: None,
                    })
                };
                if i < n {
                    add(id(i + 1, j, k));
                }
                if j < n {
                    add(id(i, j + 1, k));
                }
                if k < n {
                    add(id(i, j, k + 1));
                }
            }
        }
    }
    FrameConfig {
        time_step: 1e-3,
        gravity: [0.0, 0.0, -9.81],
        material: MaterialConfig {
            young_modulus: 2e11,
            poisson: 0.3,
            density: 7850.0,
            yield_stress,
            fracture_curvature: None,
            fracture_axial_strain: None,
            fracture_shear_strain: None,
        },
        section: vec![SectionConfig {
            name: "s".into(),
            kind: "rectangle".into(),
            width: Some(0.3),
            depth: Some(0.3),
            area: None,
            iy: None,
            iz: None,
            j: None,
            shear_area_y: None,
            shear_area_z: None,
            plastic_modulus_y: None,
            plastic_modulus_z: None,
        }],
        node,
        member,
        support,
        contact: None,
        wall: Vec::new(),
    }
}

/// Untimed steps at most while waiting for the first hinge.
const WARM_UP_LIMIT: usize = 300;

/// What one timed run measured.
struct Measured {
    dofs: usize,
    steps_per_second: f64,
    factorizations_per_step: f64,
    hinge_nodes: usize,
    unconverged_steps: u64,
}

/// Times `steps` steps under a lateral load of `lateral` N on every node (after the first hinges
/// formed, in the plastic case).
fn run(n: usize, steps: usize, yield_stress: f64, lateral: f64) -> Result<Measured, String> {
    let cfg = building(n, yield_stress);
    let mut frame =
        Frame::from_config(&cfg, "bench.frame").map_err(|e| format!("{}: {}", e.key, e.message))?;
    let mut loads = vec![0.0; 6 * frame.node_count()];
    for v in 0..frame.node_count() {
        loads[6 * v] = lateral;
    }
    // untimed: one step, and for the plastic case on until the first hinges have formed
    frame.step(frame.time_step(), &loads)?;
    for _ in 0..WARM_UP_LIMIT {
        if yield_stress > 1e11 || !frame.hinge_nodes().is_empty() {
            break;
        }
        frame.step(frame.time_step(), &loads)?;
    }
    let solves0 = frame.factorization_count();
    let unconverged0 = frame.unconverged_steps();
    let start = Instant::now();
    for _ in 0..steps {
        frame.step(frame.time_step(), &loads)?;
    }
    let seconds = start.elapsed().as_secs_f64();
    Ok(Measured {
        dofs: 6 * frame.node_count(),
        steps_per_second: steps as f64 / seconds,
        factorizations_per_step: (frame.factorization_count() - solves0) as f64 / steps as f64,
        hinge_nodes: frame.hinge_nodes().len(),
        unconverged_steps: frame.unconverged_steps() - unconverged0,
    })
}

fn main() {
    println!(
        "| grid | DOFs | case | steps/s | ms/step | factorisations/step | hinge nodes | unconverged steps |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (n, steps) in [(3, 400), (7, 100), (15, 8)] {
        // elastic: steel that never yields; hinges: σy = 20 MPa and 20 kN on every node sideways
        for (case, yield_stress, lateral) in [("elastic", 1e12, 1e3), ("hinges forming", 2e7, 2e4)] {
            match run(n, steps, yield_stress, lateral) {
                Ok(m) => println!(
                    "| {n}×{n}×{n} | {} | {case} | {:.1} | {:.2} | {:.2} | {} | {} |",
                    m.dofs,
                    m.steps_per_second,
                    1e3 / m.steps_per_second,
                    m.factorizations_per_step,
                    m.hinge_nodes,
                    m.unconverged_steps
                ),
                Err(e) => println!("| {n}×{n}×{n} | – | {case} | failed: {e} | | | | |"),
            }
        }
    }
}
