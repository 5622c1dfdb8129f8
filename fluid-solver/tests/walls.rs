//! Wall layers: a wall particle of the first layer under water at rest on the lattice has the
//! complete number density n0 (water on one side, four wall layers on the other), so walls get
//! pressure (S1-14) only from water that presses on them, not from missing neighbours.

use fluid_solver::{FluidSolver, Kind};
use schemas::case::Case;
use std::path::Path;

const CASE: &str = r#"
[case]
name = "walls"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 8.0e-4
output_interval = 0.05
tank = { min = [0.0, 0.0, 0.0], max = [0.4, 0.3, 0.3] }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.3, 0.3, 0.2]
"#;

#[test]
fn wall_layers_under_water_have_a_complete_number_density() {
    let case = Case::parse(Path::new("walls.toml"), CASE.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let solver = FluidSolver::new(&case.fluid["water"]);
    let p = solver.particles();
    let n0 = solver.kernel().n0;
    let re = solver.kernel().re;
    let ds = 0.02;
    let (mut first, mut second) = (0, 0);
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Wall.code()) {
        let r = p.position(i);
        // Covered: every point within r_e is wall or water (away from the water's open faces
        // x = 0.3 and z = 0.2 by r_e).
        if r[0] > 0.3 - re || r[2] > 0.2 - re {
            continue;
        }
        let in_first_layer = r
            .iter()
            .zip([0.4, 0.3, 0.3])
            .all(|(c, hi)| *c > -ds && *c < hi + ds);
        let ratio = p.number_density[i] / n0;
        if in_first_layer {
            assert!(
                (ratio - 1.0).abs() < 1e-12,
                "first-layer wall particle at {r:?}: n/n0 = {ratio}"
            );
            // Round-off only (ρ g Δs = 196 Pa for scale).
            assert!(
                p.pressure[i] < 1e-6,
                "first-layer wall particle at {r:?}: P = {}",
                p.pressure[i]
            );
            first += 1;
        } else {
            // The second layer misses only the tail of w beyond the fourth layer (w(3 Δs) ≈ 4e-5 n0 each).
            assert!(
                ratio > 0.999 && ratio <= 1.0 + 1e-12,
                "second-layer wall particle at {r:?}: n/n0 = {ratio}"
            );
            second += 1;
        }
    }
    println!("checked {first} first-layer and {second} second-layer wall particles");
    assert!(first > 200 && second > 200);
}
