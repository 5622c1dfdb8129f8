//! The dam-break surge front against the experiments of Koshizuka & Oka (1996) and Martin & Moyce
//! (1952, n² = 2, a = 2.25 in), in the data's dimensionless variables T = t √(2g/L), Z = z/L (data:
//! cases/dam-break-koshizuka/reference/); shared by the E-MPS and ISPH dam-break tests.

use fluid_solver::probes;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidConfig, ProbeConfig, ProbeKind};

/// Koshizuka & Oka 1996, front (T, Z).
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

/// Martin & Moyce 1952, n² = 2, a = 2.25 in, front (T, Z), points with Z < 4 (the tank is 4L long).
const MARTIN_MOYCE: [(f64, f64); 6] = [
    (0.832, 1.217),
    (1.219, 1.474),
    (1.997, 2.292),
    (2.547, 2.995),
    (3.345, 4.134),
    (4.034, 4.944),
];

/// Linear interpolation of the simulated Z(T).
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

/// Errors of one run: RMS against Koshizuka & Oka, RMS against Martin & Moyce and its shift.
pub struct FrontErrors {
    pub koshizuka_oka: f64,
    pub martin_moyce: f64,
    pub shift: f64,
}

/// Runs `cfg` (the Koshizuka column, L = 0.146 m), sampling the front every `interval` seconds,
/// until the front reaches the far wall or T = 3.4, and compares the front with the experiments;
/// prints every `print_every`-th sample.
pub fn front_errors(cfg: &FluidConfig, interval: f64, print_every: usize) -> FrontErrors {
    let l = 0.146;
    let scale = (2.0 * cfg.gravity_magnitude() / l).sqrt();
    let front = ProbeConfig {
        name: "front".into(),
        kind: ProbeKind::SurgeFront,
        ..Default::default()
    };
    let mut solver = FluidSolver::with_backend(cfg).unwrap_or_else(|e| panic!("{e}"));
    let fluid = solver.particles().count(Kind::Fluid);
    let tank = solver.tank();
    let mut series = vec![(0.0, 1.0)];
    // Until the front reaches the far wall (Z = 4) or T = 3.4.
    while solver.time() * scale < 3.4 {
        solver
            .advance_to(solver.time() + interval)
            .unwrap_or_else(|e| panic!("{e}"));
        solver.sync_host(); // the GPU path's copy (nothing on the CPU)
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
    for (t, z) in series.iter().step_by(print_every) {
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
    // Koshizuka & Oka's T = 0 is the release (Z = 1 there): no shift.
    let koshizuka_oka = rms(&series, &data_ko, 0.0);
    // Martin & Moyce's time origin is not exactly the release: the shift s (simulation time =
    // data time + s) is the one in [-0.3, 0.3] (steps of 0.01 in T) that minimises the RMS.
    let (shift, martin_moyce) = (-30..=30)
        .map(|k| f64::from(k) * 0.01)
        .map(|s| (s, rms(&series, &data_mm, s)))
        .fold((0.0, f64::MAX), |best, c| if c.1 < best.1 { c } else { best });
    println!(
        "RMS of Z: Koshizuka & Oka {koshizuka_oka:.3} over {} points",
        data_ko.len()
    );
    println!(
        "RMS of Z: Martin & Moyce {martin_moyce:.3} over {} points, time shift {shift:+.2} in T",
        data_mm.len()
    );
    FrontErrors {
        koshizuka_oka,
        martin_moyce,
        shift,
    }
}

/// The bounds of the E-MPS front test at this resolution (`dam_break.rs`: 0.33 against
/// Koshizuka & Oka, 0.05 against Martin & Moyce); with `shift`, also that the best time shift
/// does not sit on the search bound.
pub fn assert_within_the_e_mps_bounds(e: &FrontErrors, shift: bool) {
    assert!(
        e.koshizuka_oka < 0.33,
        "RMS against Koshizuka & Oka {} (bound 0.33)",
        e.koshizuka_oka
    );
    assert!(
        e.martin_moyce < 0.05,
        "RMS against Martin & Moyce {} (bound 0.05)",
        e.martin_moyce
    );
    if shift {
        assert!(
            e.shift.abs() < 0.3,
            "the best shift {} sits on the search bound",
            e.shift
        );
    }
}
