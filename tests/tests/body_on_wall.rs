//! A resolved body resting on a wall (issue 5: the bridge deck must rest on its piers once its
//! bearings let go, not sink through them): a box of 3 000 kg/m³ dropped 2 Δs onto the floor of a
//! dry tank, through the real processes. The walls' contact on a body particle is a spring of
//! k = m ω² (m = ρ0 Δs³, ω = 2π/(10 Δt)) per wall particle closer than Δs, with a dashpot
//! (`fluid-solver/src/body_wall_contact.rs`). The box's 8 × 8 bottom particles rest each on one
//! floor particle, so at rest the box's weight M g = 64 k δ: δ = (M / 64) g / (m ω²) =
//! (ρ_b/ρ0) · 4 · g/ω² (4 particle layers) = 0.19 mm, about 1 % of Δs.

use schemas::validation::{record, Record};
use stack_tests::{coupler_run, csv_rows, out_dir, stderr};
use std::time::Instant;

const CASE: &str = r#"
[case]
name = "box-on-floor"
description = "A box of 3000 kg/m³ dropped 2 Δs onto a dry tank's floor comes to rest on it."
end_time = 0.4

[fluid.tank]
spacing = 0.02
time_step = 8.0e-4
viscosity_term = false
sound_speed = 12.1
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [0.8, 0.4, 0.32] }

# a puddle far from the box (a fluid participant needs water)
[[fluid.tank.block]]
min = [0.74, 0.0, 0.0]
max = [0.8, 0.4, 0.02]

[[fluid.tank.body]]
name = "box"
min = [0.12, 0.12, 0.04]
max = [0.28, 0.28, 0.12]

[structure.drop]
max_step = 1.0e-4
gravity = [0.0, 0.0, -9.8]

[[structure.drop.body]]
name = "box"
mass = 6.144
centre = [0.2, 0.2, 0.08]
inertia = { box = [0.16, 0.16, 0.08] }

[structure.drop.history]
interval = 0.004
bodies = ["box"]

[coupling]
window = 8.0e-4
scheme = "explicit"
order = ["tank", "drop"]
predictor = "linear"

[[coupling.body]]
fluid = "tank/box"
structure = "drop/box"
"#;

const SPACING: f64 = 0.02;
const TIME_STEP: f64 = 8.0e-4;
/// Body density over water density, and the box's particle layers.
const DENSITY_RATIO: f64 = 3.0;
const LAYERS: f64 = 4.0;
/// The box's centre when its bottom layer sits exactly Δs above the floor's first wall layer.
const TOUCHING_CENTRE_Z: f64 = 0.04;

#[test]
fn a_heavy_box_dropped_on_the_floor_rests_on_it_at_the_contact_springs_deflection() {
    let dir = out_dir("box-on-floor");
    let case = dir.join("case.toml");
    std::fs::write(&case, CASE).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let started = Instant::now();
    let run = coupler_run(&case, &out);
    let run_time_s = started.elapsed().as_secs_f64();
    let err = stderr(&run);
    assert!(run.status.success(), "{err}");

    // columns t, x, y, z, qw, qx, qy, qz, vx, vy, vz, …
    let rows = csv_rows(&out.join("drop/body-box.csv"));
    assert!(rows.len() > 90, "history rows: {}", rows.len());
    let omega = 2.0 * std::f64::consts::PI / (10.0 * TIME_STEP);
    let expected = DENSITY_RATIO * LAYERS * 9.8 / (omega * omega);
    let last = rows.last().cloned().unwrap_or_default();
    let sunk = TOUCHING_CENTRE_Z - last[3];
    let deepest = rows
        .iter()
        .map(|r| TOUCHING_CENTRE_Z - r[3])
        .fold(f64::MIN, schemas::validation::max_or_nan);
    println!(
        "rest: sunk {:.4} mm into the floor's contact range (spring equilibrium {:.4} mm, {:+.3} %); \
         deepest {:.2} mm at impact; final speed {:.2e} m/s",
        1e3 * sunk,
        1e3 * expected,
        100.0 * (sunk / expected - 1.0),
        1e3 * deepest,
        last[10].abs()
    );
    // The linear springs' equilibrium is exact once the bounce has died out: 1 % covers what is
    // left of it after 0.4 s (about 14 periods of the box on its 64 springs, damping ratio 0.29).
    record(Record {
        id: "body-on-wall-rest-depth".into(),
        capability: "body–wall contact of a resolved body".into(),
        reference: "static equilibrium of the contact springs: δ = (ρ_b/ρ0) · 4 · g/ω² = 0.19 mm".into(),
        case: "box of 3 000 kg/m³ dropped 2 Δs onto a dry tank's floor, 0.4 s".into(),
        resolution: "E-MPS walls, Δs = 0.02 m, Δt = 8e-4 s, explicit coupling".into(),
        measure: "|rest depth / spring equilibrium − 1| at the end".into(),
        value: (sunk / expected - 1.0).abs(),
        bound: Some(0.01),
        bound_source: "what is left of the bounce after 0.4 s (about 14 periods, damping ratio 0.29)".into(),
        source: "tests/tests/body_on_wall.rs::a_heavy_box_dropped_on_the_floor_rests_on_it_at_the_contact_springs_deflection"
            .into(),
        run_time_s,
        ..Default::default()
    });
    assert!(
        (sunk / expected - 1.0).abs() < 0.01,
        "sunk {sunk} m vs {expected} m"
    );
    // The 0.89 m/s impact is stopped within the first half of the floor's first particle layer.
    assert!(deepest < 0.5 * SPACING, "deepest {deepest} m");
    assert!(last[10].abs() < 1e-3, "still moving at {} m/s", last[10]);
    // upright: no rotation from a symmetric contact
    assert!((last[4] - 1.0).abs() < 1e-9, "qw {}", last[4]);
}
