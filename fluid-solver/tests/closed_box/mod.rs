//! The small closed box of the conservation tests: the hydrostatic-tank case's fluid in a lidded
//! tank 0.2 × 0.2 × 0.3 m at Δs = 0.02 m, holding one water block, Δt = 8e-4 s.

use schemas::case::fluid::{Aabb, TankConfig};
use schemas::case::FluidConfig;

/// The box with the water block `min` … `max` (not yet validated: callers change it first).
pub fn closed_box(min: [f64; 3], max: [f64; 3]) -> FluidConfig {
    let (_, mut cfg) = super::common::load_case("hydrostatic-tank");
    cfg.spacing = 0.02;
    cfg.tank = TankConfig {
        min: [0.0; 3],
        max: [0.2, 0.2, 0.3],
        lid: true,
    };
    cfg.block = vec![Aabb { min, max }];
    cfg.time_step = 8.0e-4;
    cfg
}
