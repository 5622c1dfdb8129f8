//! Hydrostatic tank: after settling, the pressure at depth h is ρ g h within 3 % in the interior
//! (issue 3's bound), the floor carries the water's weight, and no particle gets through a wall.

use crate::hydrostatic_common;

use schemas::case::fluid::FluidBackend;

#[test]
fn settled_pressure_is_rho_g_h_and_walls_hold() {
    hydrostatic_common::settled_pressure_is_rho_g_h_and_walls_hold(FluidBackend::Cpu);
}
