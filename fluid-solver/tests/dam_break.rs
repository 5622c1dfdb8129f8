//! Dam break: the surge front of a column L × 2L against the experiments of Koshizuka & Oka
//! (1996) and Martin & Moyce (1952, n² = 2, a = 2.25 in), in the dimensionless variables of the
//! data: T = t √(2g/L), Z = z/L (data: cases/dam-break-koshizuka/reference/, carried by pysph's examples).

mod common;

use fluid_solver::probes;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{ProbeConfig, ProbeKind};

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
struct FrontErrors {
    koshizuka_oka: f64,
    martin_moyce: f64,
    shift: f64,
}

/// Runs the case at spacing `ds` (slab `depth` deep) with time step `dt` until the front reaches
/// the far wall, and compares the front with the experiments.
fn front_errors(ds: f64, depth: f64, dt: f64) -> FrontErrors {
    let (_, mut cfg) = common::load_case("dam-break-koshizuka");
    cfg.spacing = ds;
    cfg.tank.max = [0.584, depth, 0.438];
    cfg.block[0].max = [0.146, depth, 0.292];
    cfg.time_step = dt;
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
    // Until the front reaches the far wall (Z = 4) or T = 3.4.
    while solver.time() * scale < 3.4 {
        solver
            .advance_to(solver.time() + 0.005)
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
    for (t, z) in series.iter().step_by(8) {
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

#[test]
fn surge_front_follows_the_experiments() {
    // CI size: Δs = L/10 = 0.0146 m, a slab 4 particles deep: 10 × 4 × 20 = 800 fluid particles.
    // c = √(2 g 2L)/0.2 = 12.0 m/s, Δt = 6e-4 s (c Δt/Δs = 0.49).
    let e = front_errors(0.0146, 0.0584, 6.0e-4);
    // Bounds: the RMS measured at this resolution: 0.22 against Koshizuka & Oka (the simulated
    // front runs ahead of theirs, as in most particle simulations of this experiment) and
    // 0.022 against Martin & Moyce (shift −0.20), plus about 50 %. The data are read off
    // figures (±0.05 in Z); a column 10 particles wide resolves the toe to Δs/L = 0.1.
    assert!(
        e.koshizuka_oka < BOUND_KO,
        "RMS against Koshizuka & Oka {} (bound {BOUND_KO})",
        e.koshizuka_oka
    );
    assert!(
        e.martin_moyce < BOUND_MM,
        "RMS against Martin & Moyce {} (bound {BOUND_MM})",
        e.martin_moyce
    );
    assert!(
        e.shift.abs() < 0.3,
        "the best shift {} sits on the search bound",
        e.shift
    );
}

/// The case file's own resolution (Δs = L/20, 8 000 fluid particles, about 20 s in release on 2 cores);
/// `surge_front_follows_the_experiments` is its CI-sized twin.
#[test]
#[ignore]
fn surge_front_at_the_case_resolution() {
    let e = front_errors(0.0073, 0.073, 3.0e-4);
    // Measured 0.27 and 0.013 (shift −0.24): bounds with a margin of about 50 %.
    assert!(
        e.koshizuka_oka < 0.41,
        "RMS against Koshizuka & Oka {}",
        e.koshizuka_oka
    );
    assert!(
        e.martin_moyce < 0.03,
        "RMS against Martin & Moyce {}",
        e.martin_moyce
    );
}

/// RMS bound of Z against Koshizuka & Oka at Δs = L/10.
const BOUND_KO: f64 = 0.33;
/// RMS bound of Z against Martin & Moyce at Δs = L/10, after the time shift.
const BOUND_MM: f64 = 0.05;
