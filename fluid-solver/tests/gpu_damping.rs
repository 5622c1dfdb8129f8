//! Damping zones on the GPU path (issue 38): the law of `src/boundaries/damping.rs`,
//! u ← u exp(−rate s² Δt) after each step, relaxed per fluid particle on the device
//! (`shaders/damping.wgsl`) at the point of the step where the CPU relaxes it; the slab's column
//! collapsing into two zones (one growing along +x, one along −y, overlapping) ends where the
//! CPU's does within the f32 bound of `gpu_common/compare.rs`.

use gpu_common::compare::{self, STEPS};

use crate::gpu_common;

/// The right half of the tank damped towards its far wall at 50/s, and the whole tank damped
/// along −y at 20/s (0 at y = 0.06 m, the full rate at y = 0): the fluid in both takes their
/// product.
const ZONES: &str = r#"
[[fluid.water.damping]]
min = [0.2, 0.0, 0.0]
max = [0.4, 0.06, 0.3]
axis = "+x"
rate = 50.0

[[fluid.water.damping]]
min = [0.0, 0.0, 0.0]
max = [0.4, 0.06, 0.3]
axis = "-y"
rate = 20.0
"#;

/// The same particles after 200 steps (0.1 s: the front runs through the +x zone to the far
/// wall) within the f32 bound; the factor's own f32 rounding, u |u| ≈ 6e-8 m/s per step at
/// 1 m/s, is 4e-4 of the equation of state's 2.2e-5 m/s per step that the bound is made of.
/// The zones moved the fluid by far more than the bound on the CPU.
#[test]
fn gpu_damping_zones_match_cpu() {
    let dir = compare::folder("damping");
    let cfg = compare::slab(&dir, ZONES);
    let Some(runs) = compare::run_both(&cfg, STEPS) else {
        return;
    };
    compare::check_and_record(
        &runs,
        (
            "damping",
            "E-MPS with damping zones",
            "the slab's column (0.4 × 0.06 × 0.3 m tank) into a +x zone at 50/s over the right half and a −y zone at 20/s over the tank, 200 steps of 5e-4 s",
            "gpu_damping.rs::gpu_damping_zones_match_cpu",
        ),
    );
    let bare = compare::run_cpu(&compare::slab(&dir, ""), STEPS);
    compare::assert_visible("the damping zones", &runs.cpu, &bare);
}
