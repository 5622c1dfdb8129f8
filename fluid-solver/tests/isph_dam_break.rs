//! ISPH dam break: the surge front of a column L × 2L against Koshizuka & Oka (1996) and Martin &
//! Moyce (1952, n² = 2, a = 2.25 in), as `dam_break.rs` does for E-MPS, with bounds at least as
//! tight as its (issue 12).

mod common;

use fluid_solver::probes;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidMethodName, IsphConfig, ProbeConfig, ProbeKind};

/// Koshizuka & Oka 1996, front (T, Z) (the data of `dam_break.rs`).
const KOSHIZUKA_OKA: [(f64, f64); 9] = [
    (0.0, 1.000),
    (0.381, 1.111),
    (0.769, 1.252),
    (1.153, 1.505),
    (1.537, 1.892),
    (1.935, 2.241),
    (2.323, 2.615),
    (2.719, 3.003),
    (3.096, 3.624),
];

/// Martin & Moyce 1952, n² = 2, a = 2.25 in, front (T, Z) with Z < 4.
const MARTIN_MOYCE: [(f64, f64); 6] = [
    (0.832, 1.217),
    (1.219, 1.474),
    (1.997, 2.292),
    (2.547, 2.995),
    (3.345, 4.134),
    (4.034, 4.944),
];

fn at(series: &[(f64, f64)], t: f64) -> f64 {
    match series.iter().position(|&(ti, _)| ti >= t) {
        Some(0) => series[0].1,
        Some(k) => {
            let (t0, z0) = series[k - 1];
            let (t1, z1) = series[k];
            z0 + (z1 - z0) * (t - t0) / (t1 - t0)
        }
        None => series[series.len() - 1].1,
    }
}

fn rms(series: &[(f64, f64)], data: &[(f64, f64)], shift: f64) -> f64 {
    let sum: f64 = data
        .iter()
        .map(|&(t, z)| (at(series, t + shift) - z).powi(2))
        .sum();
    (sum / data.len() as f64).sqrt()
}

#[test]
fn isph_surge_front_follows_the_experiments() {
    // CI size as the E-MPS test: Δs = L/10 = 0.0146 m, a slab 4 particles deep (800 fluid
    // particles); Δt = 2e-3 s (u_max Δt/Δs = 0.33 with u_max = √(2g·2L)), 3.4× E-MPS's 6e-4 s.
    let (_, mut cfg) = common::load_case("dam-break-koshizuka");
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(IsphConfig::default());
    cfg.sound_speed = None;
    cfg.spacing = 0.0146;
    cfg.tank.max = [0.584, 0.0584, 0.438];
    cfg.block[0].max = [0.146, 0.0584, 0.292];
    cfg.time_step = 2.0e-3;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let l = 0.146;
    let scale = (2.0 * cfg.gravity_magnitude() / l).sqrt();
    let front = ProbeConfig {
        name: "front".into(),
        kind: ProbeKind::SurgeFront,
        ..Default::default()
    };
    let mut solver = FluidSolver::new(&cfg);
    let fluid = solver.particles().count(Kind::Fluid);
    let tank = solver.tank();
    let mut series = vec![(0.0, 1.0)];
    while solver.time() * scale < 3.4 {
        solver
            .advance_to(solver.time() + 0.006)
            .unwrap_or_else(|e| panic!("{e}"));
        let z = probes::sample(&front, solver.particles(), solver.kernel(), &tank) / l;
        series.push((solver.time() * scale, z));
        if z >= 3.95 {
            break;
        }
    }
    assert_eq!(
        solver.particles().count(Kind::Fluid),
        fluid,
        "fluid particles were lost or created"
    );
    for (t, z) in series.iter().step_by(4) {
        println!("T = {t:.3}  Z = {z:.3}");
    }
    let end = series[series.len() - 1].0;
    let data_ko: Vec<(f64, f64)> = KOSHIZUKA_OKA.iter().copied().filter(|&(t, _)| t <= end).collect();
    let data_mm: Vec<(f64, f64)> = MARTIN_MOYCE
        .iter()
        .copied()
        .filter(|&(t, z)| z < 3.95 && t <= end)
        .collect();
    assert!(
        data_ko.len() >= 7 && data_mm.len() >= 3,
        "the run did not cover the data"
    );
    let koshizuka_oka = rms(&series, &data_ko, 0.0);
    // Martin & Moyce's time origin: the shift in [-0.3, 0.3] (steps of 0.01 in T) with the least RMS.
    let (shift, martin_moyce) = (-30..=30)
        .map(|k| f64::from(k) * 0.01)
        .map(|s| (s, rms(&series, &data_mm, s)))
        .fold((0.0, f64::MAX), |best, c| if c.1 < best.1 { c } else { best });
    println!("ISPH RMS of Z: Koshizuka & Oka {koshizuka_oka:.3}, Martin & Moyce {martin_moyce:.3} (shift {shift:+.2})");
    // Bounds: those of the E-MPS test at this resolution (dam_break.rs: 0.33 and 0.05).
    assert!(
        koshizuka_oka < 0.33,
        "RMS against Koshizuka & Oka {koshizuka_oka} (bound 0.33)"
    );
    assert!(
        martin_moyce < 0.05,
        "RMS against Martin & Moyce {martin_moyce} (bound 0.05)"
    );
    assert!(
        shift.abs() < 0.3,
        "the best shift {shift} sits on the search bound"
    );
}
