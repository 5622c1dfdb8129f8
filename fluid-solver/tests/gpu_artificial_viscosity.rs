//! The E-MPS artificial viscosity on the GPU path (issue 38): the term of
//! `src/emps/artificial_viscosity.rs` (Monaghan's Π_ij as a pair pressure q_ij added to S1-3's
//! gradient at r*, u*, fluid pairs only) in `shaders/artificial_viscosity.wgsl`, between S1-3 and
//! S1-12 as on the CPU; the slab's column collapsing with α = 0.1 ends where the CPU's does
//! within the f32 bound of `gpu_common/compare.rs`.

use gpu_common::compare::{self, STEPS};

use crate::gpu_common;

/// The same particles after 200 steps within the f32 bound. The term's own rounding adds little:
/// q_ij ≈ α ρ0 c h |u_ij| / r ≈ 0.1 · 1000 · 12.1 · 1.05 · 0.1 m/s = 130 Pa at the collapse's
/// relative speeds, summed over ≈ 30 pairs with u √30 ≈ 3.3e-7 relative error: 4e-5 Pa against
/// the equation of state's 0.15 Pa the bound is made of. α = 0.1 (WCSPH's upper end) moved the
/// fluid by far more than the bound on the CPU.
#[test]
fn gpu_artificial_viscosity_matches_cpu() {
    let dir = compare::folder("artificial-viscosity");
    let cfg = compare::slab(&dir, "");
    let mut viscous = cfg.clone();
    viscous.artificial_viscosity = 0.1;
    viscous
        .validate("fluid.water")
        .unwrap_or_else(|e| panic!("{e:?}"));
    let Some(runs) = compare::run_both(&viscous, STEPS) else {
        return;
    };
    compare::check_and_record(
        &runs,
        (
            "artificial-viscosity",
            "E-MPS with the artificial viscosity α = 0.1",
            "the slab's column (0.4 × 0.06 × 0.3 m tank), artificial_viscosity = 0.1, 200 steps of 5e-4 s",
            "gpu_artificial_viscosity.rs::gpu_artificial_viscosity_matches_cpu",
        ),
    );
    let bare = compare::run_cpu(&cfg, STEPS);
    compare::assert_visible("the artificial viscosity", &runs.cpu, &bare);
}
