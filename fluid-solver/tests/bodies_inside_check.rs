//! The instability detector's "inside a body" check follows the body: it tests a fluid particle
//! in the body's frame at its present pose, not against the box of the initial placement (the
//! false alarm that stopped the seed's floating box at t = 0.518 s). A body from a mesh is
//! checked against its own lattice sites, as a mesh solid is: a particle more than about half a
//! spacing inside them stops the run (the GPU path: `gpu_bodies_inside.rs`).

use crate::bodies_common;

use bodies_common::tank_with_body;
use fluid_solver::{FluidSolver, Instability, Kind};
use schemas::case::fluid::Aabb;
use schemas::case::{Case, FluidConfig};
use schemas::geometry::{write_binary_stl, TriangleMesh};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A 16 × 4 × 8 cm body above a shallow pool, moved 10 cm along x and turned 90° about z; then
/// one water particle is put at `offset` from the body's new centre and one step is taken.
fn step_with_particle_at(offset: [f64; 3]) -> Result<(), fluid_solver::Instability> {
    let body = Aabb {
        min: [0.12, 0.28, 0.20],
        max: [0.28, 0.32, 0.28],
    };
    let pool = Aabb {
        min: [0.0; 3],
        max: [0.4, 0.4, 0.08],
    };
    let mut solver = FluidSolver::new(&tank_with_body([0.4, 0.4, 0.4], 0.02, 8.0e-4, pool, body));
    let centre = [0.3, 0.3, 0.24];
    let half_turn = std::f64::consts::FRAC_1_SQRT_2;
    let pose = [centre[0], centre[1], centre[2], half_turn, 0.0, 0.0, half_turn];
    solver
        .set_body_motion(&pose, &[0.0; 6], 0.0)
        .unwrap_or_else(|e| panic!("{e}"));
    let p = solver.particles_mut();
    let i = (0..p.len())
        .find(|&i| p.kind[i] == Kind::Fluid.code())
        .unwrap_or_else(|| panic!("no water"));
    (p.x[i], p.y[i], p.z[i]) = (
        centre[0] + offset[0],
        centre[1] + offset[1],
        centre[2] + offset[2],
    );
    solver.step(8.0e-4).map(|_| ())
}

#[test]
fn a_particle_where_the_box_was_is_not_inside_it() {
    // The initial box held x ∈ [0.12, 0.28], y ∈ [0.28, 0.32] at this height; the point
    // (0.2, 0.3, 0.24) was its centre. The turned box now spans x ∈ [0.28, 0.32].
    if let Err(e) = step_with_particle_at([-0.1, 0.0, 0.0]) {
        panic!("{e}");
    }
    // Beside the turned box: inside the unturned one's extent (6 cm < 8 cm along x), but
    // 6 cm > 2 cm from the turned box's long face.
    assert!(step_with_particle_at([0.06, 0.0, 0.0]).is_ok());
}

#[test]
fn a_particle_inside_the_moved_and_turned_box_stops_the_run() {
    // 4 cm along y from the new centre: inside the turned box (its long side is now along y),
    // outside the unturned one (2 cm half-width along y).
    let err =
        step_with_particle_at([0.0, 0.04, 0.0]).expect_err("a particle inside the body must stop the run");
    println!("{err}");
    assert_eq!(err.quantity, "position");
    assert!(err.message.contains("inside body 0"), "{err}");
}

#[test]
fn a_body_pushed_through_a_wall_stops_the_run() {
    // The body's centre put on the tank's x = 0.4 m face, above the pool: its outer particle
    // layers are more than half a spacing beyond the face, inside the wall (the walls' contact
    // keeps a body resting on a wall within a fraction of a spacing of it; this is what it would
    // look like if that failed).
    let body = Aabb {
        min: [0.12, 0.28, 0.20],
        max: [0.28, 0.32, 0.28],
    };
    let pool = Aabb {
        min: [0.0; 3],
        max: [0.4, 0.4, 0.08],
    };
    let mut solver = FluidSolver::new(&tank_with_body([0.4, 0.4, 0.4], 0.02, 8.0e-4, pool, body));
    let pose = [0.4, 0.3, 0.24, 1.0, 0.0, 0.0, 0.0];
    solver
        .set_body_motion(&pose, &[0.0; 6], 0.0)
        .unwrap_or_else(|e| panic!("{e}"));
    let err = solver
        .step(8.0e-4)
        .expect_err("a body inside a wall must stop the run");
    println!("{err}");
    assert_eq!(err.quantity, "position");
    assert!(
        err.to_string().contains("a body particle went inside a wall"),
        "{err}"
    );
}

/// A 0.4 m tank at Δs = 0.02 m, Δt = 8e-4 s, c = 12.1 m/s, a pool 8 cm deep, and above it a
/// 16 × 8 × 8 cm body about (0.2, 0.2, 0.24) m: an STL cuboid written to a fresh folder `name`
/// when `mesh` (its sites are 8 × 4 × 4, those more than half a spacing inside 6 × 2 × 2), else
/// the box body of the same extent.
pub fn raised_body(name: &str, mesh: bool) -> FluidConfig {
    // a folder per call: tests run in parallel
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("inside-{name}-{call}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let half = [0.08, 0.04, 0.04];
    write_binary_stl(
        &dir.join("body.stl"),
        &TriangleMesh::cuboid(half.map(|h| -h), half),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let body = if mesh {
        r#"mesh = { file = "body.stl", translate = [0.2, 0.2, 0.24] }"#
    } else {
        "min = [0.12, 0.16, 0.2]\nmax = [0.28, 0.24, 0.28]"
    };
    let text = format!(
        r#"[case]
name = "inside-body"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
sound_speed = 12.1
output_interval = 0.05
tank = {{ min = [0.0, 0.0, 0.0], max = [0.4, 0.4, 0.4] }}

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.4, 0.4, 0.08]

[[fluid.water.body]]
name = "deck"
{body}
"#
    );
    let case = Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["water"].clone()
}

/// The raised body's pose in the tests: moved by (3, −1, 0) cm and turned 90° about z, so that
/// its long side lies along y.
pub const MOVED_AND_TURNED: [f64; 7] = [
    0.23,
    0.19,
    0.24,
    std::f64::consts::FRAC_1_SQRT_2,
    0.0,
    0.0,
    std::f64::consts::FRAC_1_SQRT_2,
];

/// The point at `local` in the frame of the body at [`MOVED_AND_TURNED`] (about its centre).
pub fn at_moved_body(local: [f64; 3]) -> [f64; 3] {
    let [cx, cy, cz] = [MOVED_AND_TURNED[0], MOVED_AND_TURNED[1], MOVED_AND_TURNED[2]];
    // 90° about z: (x, y) ↦ (−y, x)
    [cx - local[1], cy + local[0], cz + local[2]]
}

/// Puts the first fluid particle (by id) at `r`.
pub fn put_first_fluid_at(solver: &mut FluidSolver, r: [f64; 3]) {
    let p = solver.particles_mut();
    let i = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid.code())
        .min_by_key(|&i| p.id[i])
        .unwrap_or_else(|| panic!("no water"));
    (p.x[i], p.y[i], p.z[i]) = (r[0], r[1], r[2]);
}

/// One step of the raised mesh body's scene with the body at [`MOVED_AND_TURNED`] and the first
/// water particle at `r`.
fn mesh_body_step_with_particle_at(r: [f64; 3]) -> Result<(), Instability> {
    let mut solver = FluidSolver::new(&raised_body("mesh-step", true));
    solver
        .set_body_motion(&MOVED_AND_TURNED, &[0.0; 6], 0.0)
        .unwrap_or_else(|e| panic!("{e}"));
    put_first_fluid_at(&mut solver, r);
    solver.step(8.0e-4).map(|_| ())
}

#[test]
fn a_particle_deep_inside_the_moved_and_turned_mesh_body_stops_the_run() {
    // 1.5 spacings from the nearest faces of the body's inner sites (|x| < 0.06, |y|, |z| < 0.02
    // in its frame); where the body was at the start, this point is in its outer layer only.
    let err = mesh_body_step_with_particle_at(at_moved_body([0.045, 0.005, -0.005]))
        .expect_err("a particle inside the mesh body must stop the run");
    println!("{err}");
    assert_eq!((err.step, err.quantity), (1, "position"), "{err}");
    assert!(err.message.contains("inside body 0"), "{err}");
    assert!(err.message.contains("inside its lattice sites"), "{err}");
}

#[test]
fn a_particle_outside_or_barely_inside_the_mesh_body_is_no_finding() {
    for (local, what) in [
        ([0.075, 0.005, -0.005], "0.25 spacings inside its end face"),
        ([0.09, 0.005, -0.005], "0.5 spacings beyond its end face"),
        (
            [0.015, 0.08, -0.005],
            "where the unturned body held it deep inside",
        ),
    ] {
        if let Err(e) = mesh_body_step_with_particle_at(at_moved_body(local)) {
            panic!("a particle {what}: {e}");
        }
    }
}
