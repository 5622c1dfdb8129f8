//! The instability detector's "inside a body" check follows the body: it tests a fluid particle
//! in the body's frame at its present pose, not against the box of the initial placement (the
//! false alarm that stopped the seed's floating box at t = 0.518 s).

use crate::bodies_common;

use bodies_common::tank_with_body;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::Aabb;

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
