//! The ISPH CI dam break shared by the ISPH tests: `cases/dam-break-koshizuka` at Δs = L/10 =
//! 0.0146 m as a slab 4 particles deep (800 fluid particles), Δt = 1.6e-3 s (u Δt/Δs = 0.37 with
//! the front speed u = 2√(g·2L), Ritter), with ISPH's default settings.

use schemas::case::fluid::{FluidConfig, FluidMethodName, IsphConfig};

/// The slab, validated.
pub fn isph_slab() -> FluidConfig {
    let (_, mut cfg) = crate::common::load_case("dam-break-koshizuka");
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(IsphConfig::default());
    cfg.sound_speed = None;
    cfg.spacing = 0.0146;
    cfg.tank.max = [0.584, 0.0584, 0.438];
    cfg.block[0].max = [0.146, 0.0584, 0.292];
    cfg.time_step = 1.6e-3;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}
