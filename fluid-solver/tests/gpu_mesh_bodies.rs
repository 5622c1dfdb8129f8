//! A resolved body from a mesh on the GPU path (issue 38): its particles are the lattice sites
//! inside the placed mesh, each with its offset from the mesh's volume centroid, which the device
//! places and sums loads over exactly as for a box body; so a cube from an STL, turned off the
//! lattice's axes, gets the CPU's loads within `gpu_bodies.rs`'s f32 bound.

use crate::gpu_bodies::{check_and_record_loads, worst_difference};
use crate::gpu_common::compare::{self, DeviceFrame};

use schemas::case::Case;
use schemas::geometry::{write_binary_stl, TriangleMesh};

/// `gpu_bodies.rs`'s settling tank (Δs = 0.02 m, 0.28 × 0.28 m, water 0.3 m deep, c = 12.1 m/s,
/// Δt = 8e-4 s) with its 12 cm box drawn as an STL cube turned 20° about x and 30° about z,
/// centred at (0.14, 0.14, 0.14) m: its lattice sites are no box.
const CASE: &str = r#"
[case]
name = "mesh-body"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
sound_speed = 12.1
output_interval = 0.05
tank = { min = [0.0, 0.0, 0.0], max = [0.28, 0.28, 0.4] }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.28, 0.28, 0.3]

[[fluid.water.body]]
name = "cube"
mesh = { file = "cube.stl", rotate = [20.0, 0.0, 30.0], translate = [0.14, 0.14, 0.14] }
"#;

/// Loads and moment within `gpu_bodies::LOAD_BOUND` of ρgV (ρgV × 0.06 m) over 10 steps with the body
/// held at its initial pose, the fluid's reaction balancing them within `gpu_bodies.rs`'s bound.
#[test]
fn gpu_loads_on_a_turned_mesh_body_match_cpu() {
    let dir = compare::folder("mesh-body");
    let half = [0.06; 3];
    write_binary_stl(
        &dir.join("cube.stl"),
        &TriangleMesh::cuboid(half.map(|h| -h), half),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let case = Case::parse(&dir.join("case.toml"), CASE.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let cfg = &case.fluid["water"];
    let buoyancy = cfg.density * cfg.gravity_magnitude() * 0.12f64.powi(3);
    let pose = [0.14, 0.14, 0.14, 1.0, 0.0, 0.0, 0.0];
    let Some((force, moment)) =
        worst_difference((cfg, DeviceFrame::Corner), buoyancy, 10, &pose, &[0.0; 6], 0.0)
    else {
        return;
    };
    check_and_record_loads(
        "gpu_mesh_bodies.rs::gpu_loads_on_a_turned_mesh_body_match_cpu",
        "mesh-cube",
        "drawn as an STL cube turned 20° about x and 30° about z, held fixed in the settling tank",
        (force, moment),
    );
}
