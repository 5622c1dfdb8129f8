//! The hydrostatic tank on the GPU path with the CPU test's bounds (`hydrostatic.rs`): 2 s of
//! 1 500 fluid particles, 2 500 steps: 14 min on lavapipe here, so ignored in CI, where
//! `gpu_dam_break.rs` compares the GPU step with the CPU step.
//!
//! Measured 2026-11-24 on lavapipe: floor force 117.667 N for a weight of 117.600 N (CPU
//! 117.673 N), free surface 0.2922 m (CPU 0.2921 m), but the worst interior pressure error is
//! 4.18 % at z = 0.22 m (3.6 Δs deep), above the 3 % bound (CPU 2.26 % there). The same CPU run
//! with one particle moved by 1e-7 m at the start gives 3.70 % at that point: after 2 500 steps
//! the trajectory has forgotten its start, and the 3 % bound lies inside the scatter of the
//! 0.5 s time average near the surface, on the CPU as on the GPU. The bound is left as the CPU
//! test's until that test's averaging is settled; this test fails with it.
//!
//! Why (measured 2026-11-24, CPU f64, five starts): at z = 0.22 m the CPU's error is +2.26 %
//! (the test's start), +2.87 % (positions rounded to f32, what the GPU's upload does), +2.43 %
//! and +3.20 % (every 97th / 89th fluid particle moved by 1e-7 m) and +3.70 % (one particle
//! moved): a near-surface bias of about +2.9 % with a scatter of about 0.6 % (one standard
//! deviation) of the 0.5 s mean. The GPU's 4.18 % is 2 standard deviations above that mean;
//! f32 is not seen (the f32-rounded start is inside the CPU's scatter) and the walls are not in
//! it (the floor force is right to 0.06 %). The 3 % bound sits on the CPU's own mean there, so
//! the CPU test passes by chance too (2 of the 5 starts are above it). From one settled state,
//! the GPU's number density and pressure equal the CPU's to f32 rounding with no sign, and its
//! mean pressures follow the CPU's within 0.1 % over 1 s (`gpu_pressure_stages.rs`): no GPU
//! bias was found.

use crate::gpu_common;
use crate::hydrostatic_common;

use schemas::case::fluid::FluidBackend;

#[test]
#[ignore]
fn settled_pressure_is_rho_g_h_and_walls_hold_on_the_gpu() {
    if gpu_common::device().is_none() {
        return;
    }
    hydrostatic_common::settled_pressure_is_rho_g_h_and_walls_hold(FluidBackend::Gpu);
}
