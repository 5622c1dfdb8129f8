//! Frame configs shared by the frame tests: straight beams along x made of rectangular steel members.
#![allow(dead_code)]

use schemas::case::frame::{
    FrameConfig, MaterialConfig, MemberConfig, NodeConfig, SectionConfig, SupportConfig,
};

/// Steel of the reference data (`cases/structure-cantilever/reference/README.md`): E = 200 GPa, ν = 0.3,
/// ρ = 7850 kg/m³; yield stress 235 MPa.
pub fn steel() -> MaterialConfig {
    MaterialConfig {
        young_modulus: 200e9,
        poisson: 0.3,
        density: 7850.0,
        yield_stress: 235e6,
        fracture_curvature: None,
        fracture_axial_strain: None,
        fracture_shear_strain: None,
    }
}

/// A rectangular section `width` (local y) × `depth` (local z).
pub fn rectangle(name: &str, width: f64, depth: f64) -> SectionConfig {
    SectionConfig {
        name: name.into(),
        kind: "rectangle".into(),
        width: Some(width),
        depth: Some(depth),
        area: None,
        iy: None,
        iz: None,
        j: None,
        shear_area_y: None,
        shear_area_z: None,
        plastic_modulus_y: None,
        plastic_modulus_z: None,
        yield_function: None,
    }
}

/// A straight beam from x = 0 to x = `length` of `members` equal members (node ids 1 … members + 1),
/// depth vertical (local z = global z), no gravity.
pub fn beam(length: f64, members: usize, width: f64, depth: f64, material: MaterialConfig) -> FrameConfig {
    let node = (0..=members)
        .map(|i| NodeConfig {
            id: i as u32 + 1,
            position: [length * i as f64 / members as f64, 0.0, 0.0],
        })
        .collect();
    let member = (0..members)
        .map(|i| MemberConfig {
            nodes: [i as u32 + 1, i as u32 + 2],
            section: "rect".into(),
            orientation: Some([0.0, 1.0, 0.0]),
        })
        .collect();
    FrameConfig {
        time_step: 1e-4,
        gravity: [0.0; 3],
        material,
        section: vec![rectangle("rect", width, depth)],
        node,
        member,
        support: Vec::new(),
        contact: None,
        wall: Vec::new(),
        equilibrium_tolerance: None,
        damping: None,
        geometry: Default::default(),
    }
}

/// A support of node `id` fixing the named DOFs.
pub fn support(id: u32, fixed: &[&str]) -> SupportConfig {
    SupportConfig {
        node: id,
        fixed: fixed.iter().map(|s| s.to_string()).collect(),
    }
}

pub const ALL: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

/// An n × n × n-bay building grid of 3 m bays, fixed at the base: columns and beams of 0.3 × 0.3 m
/// steel with the given yield stress (the quadratic yield function), gravity along −z, Δt = 1 ms (the
/// frame benchmark's building).
pub fn building(n: usize, yield_stress: f64) -> FrameConfig {
    let id = |i: usize, j: usize, k: usize| (k * (n + 1) * (n + 1) + j * (n + 1) + i) as u32 + 1;
    let mut node = Vec::new();
    let mut member = Vec::new();
    let mut supports = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                node.push(NodeConfig {
                    id: id(i, j, k),
                    position: [3.0 * i as f64, 3.0 * j as f64, 3.0 * k as f64],
                });
                if k == 0 {
                    supports.push(support(id(i, j, k), &ALL));
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
            yield_stress,
            ..steel()
        },
        // the quadratic interaction with which the benchmark and the collapse tests were measured
        section: vec![SectionConfig {
            yield_function: Some("quadratic".into()),
            ..rectangle("s", 0.3, 0.3)
        }],
        node,
        member,
        support: supports,
        contact: None,
        wall: Vec::new(),
        equilibrium_tolerance: None,
        damping: None,
        geometry: Default::default(),
    }
}

/// Loads of `force` N along +x on every one of `node_count` frame nodes (member mid nodes too), 6
/// per node: the sideways push of the benchmark's building.
pub fn sideways_loads(node_count: usize, force: f64) -> Vec<f64> {
    let mut loads = vec![0.0; 6 * node_count];
    loads.iter_mut().step_by(6).for_each(|f| *f = force);
    loads
}

/// |residual| / energy scale of an energy row, the scale being the largest of |W|, T + U and the
/// dissipation so far (`frame/energy_check.rs` adds T + U at the start of recording: 0 for a frame
/// started at rest); NaN when the residual or a term is NaN.
pub fn energy_share(row: &structure_solver::frame::EnergyRow) -> f64 {
    let scale = schemas::validation::largest(
        [
            row.kinetic + row.strain,
            row.plastic + row.damping + row.algorithmic,
        ],
        row.external.abs(),
    );
    row.residual.abs() / scale
}
