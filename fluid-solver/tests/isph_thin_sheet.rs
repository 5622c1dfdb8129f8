//! A sheet of still water one particle deep on a tank's floor with ISPH's default settings (the
//! exact projection): every particle is on the free surface, so no PPE unknown holds it and the
//! walls alone carry it (`isph::surface_walls`). Before the walls completed its support it
//! carried half its weight, sank to 0.3 Δs above the floor's face within 0.4 s and put a particle
//! through it at t = 1.9 s (stopped by the detector); S2-8's gradient held it.

use crate::common;

use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidMethodName, IsphConfig};

/// Water 0.02 m deep (one layer at Δs = 0.02 m, 25 particles) in a 0.1 × 0.1 m tank, Δt = 2e-3 s,
/// for 2 s (1 000 steps): it stays where it is, every particle within the hydrostatic tank's bound
/// on speed (issue 12: 1e-3 √(gH), H the water's depth) and within 0.05 Δs of its start height.
/// Measured: 1.6e-14 m/s at most, heights unchanged (1 Dec 2026).
#[test]
fn a_sheet_one_particle_deep_rests_on_the_floor() {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(IsphConfig::default());
    cfg.sound_speed = None;
    cfg.spacing = 0.02;
    cfg.tank.max = [0.1, 0.1, 0.16];
    cfg.block[0].max = [0.1, 0.1, 0.02];
    cfg.time_step = 2.0e-3;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let mut solver = FluidSolver::new(&cfg);
    let (ds, depth) = (cfg.spacing, 0.02);
    let bound = 1e-3 * (cfg.gravity_magnitude() * depth).sqrt();
    for t in [0.5, 1.0, 1.5, 2.0] {
        solver.advance_to(t).unwrap_or_else(|e| panic!("t = {t}: {e}"));
        let p = solver.particles();
        let fluid: Vec<usize> = (0..p.len()).filter(|&i| p.kind_of(i) == Kind::Fluid).collect();
        let fastest = fluid
            .iter()
            .map(|&i| p.velocity(i).iter().map(|v| v * v).sum::<f64>().sqrt())
            .fold(0.0, schemas::validation::max_or_nan);
        let moved = fluid
            .iter()
            .map(|&i| (p.z[i] - 0.5 * ds).abs())
            .fold(0.0, schemas::validation::max_or_nan);
        println!("t = {t} s: fastest {fastest:.2e} m/s, largest height change {moved:.2e} m");
        assert_eq!(fluid.len(), 25, "t = {t}: particles lost");
        assert!(
            fastest < bound,
            "t = {t}: a particle moves at {fastest:.3e} m/s (bound {bound:.3e})"
        );
        assert!(
            moved < 0.05 * ds,
            "t = {t}: a particle moved {moved:.3e} m off its height"
        );
    }
}
