//! Scenes for the rigid-body tests: a tank of still water with a box-shaped body in it.

use schemas::case::fluid::{Aabb, BodyConfig, FluidConfig};
use schemas::case::Case;
use std::path::PathBuf;

/// Water filling `water` except where `hole` is: up to six blocks (below, above, then the four
/// sides of the hole, each clipped to `water`), so no water particle starts inside the body.
pub fn water_around(water: Aabb, hole: Aabb) -> Vec<Aabb> {
    let (w, h) = (water, hole);
    let blocks = [
        ([w.min[0], w.min[1], w.min[2]], [w.max[0], w.max[1], h.min[2]]),
        ([w.min[0], w.min[1], h.max[2]], [w.max[0], w.max[1], w.max[2]]),
        ([w.min[0], w.min[1], h.min[2]], [h.min[0], w.max[1], h.max[2]]),
        ([h.max[0], w.min[1], h.min[2]], [w.max[0], w.max[1], h.max[2]]),
        ([h.min[0], w.min[1], h.min[2]], [h.max[0], h.min[1], h.max[2]]),
        ([h.min[0], h.max[1], h.min[2]], [h.max[0], w.max[1], h.max[2]]),
    ];
    blocks
        .into_iter()
        .map(|(min, max)| Aabb {
            min: std::array::from_fn(|a| min[a].max(w.min[a])),
            max: std::array::from_fn(|a| max[a].min(w.max[a])),
        })
        .filter(|b| (0..3).all(|a| b.max[a] - b.min[a] > 1e-9))
        .collect()
}

/// A tank `[0, tank]` with spacing `ds`, time step `dt` and c = 12.1 m/s (the seed's), water
/// filling `water` around one body `body` named "box"; no viscous term (as the seed's cases).
pub fn tank_with_body(tank: [f64; 3], ds: f64, dt: f64, water: Aabb, body: Aabb) -> FluidConfig {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/hydrostatic-tank/case.toml");
    let case = Case::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let mut cfg = case
        .fluid
        .values()
        .next()
        .cloned()
        .unwrap_or_else(|| panic!("no fluid section"));
    cfg.spacing = ds;
    cfg.time_step = dt;
    cfg.sound_speed = Some(12.1);
    cfg.viscosity_term = false;
    cfg.tank.max = tank;
    cfg.probe.clear();
    cfg.block = water_around(water, body);
    cfg.body = vec![BodyConfig::from_box("box", body.min, body.max)];
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}
