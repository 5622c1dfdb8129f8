//! Dam break: the surge front of a column L × 2L against the experiments of Koshizuka & Oka
//! (1996) and Martin & Moyce (1952, n² = 2, a = 2.25 in), in the dimensionless variables of the
//! data: T = t √(2g/L), Z = z/L (data: cases/dam-break-koshizuka/reference/, carried by pysph's examples).

use crate::common;
use crate::front_common;
use crate::front_record;

use front_common::FrontErrors;
use front_record::FrontRecord;
use std::time::Instant;

/// Runs the case at spacing `ds` (slab `depth` deep) with time step `dt` until the front reaches
/// the far wall, and compares the front with the experiments.
fn front_errors(ds: f64, depth: f64, dt: f64) -> FrontErrors {
    let (_, mut cfg) = common::load_case("dam-break-koshizuka");
    cfg.spacing = ds;
    cfg.tank.max = [0.584, depth, 0.438];
    cfg.block[0].max = [0.146, depth, 0.292];
    cfg.time_step = dt;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    front_common::front_errors(&cfg, 0.005, 8)
}

#[test]
fn surge_front_follows_the_experiments() {
    // CI size: Δs = L/10 = 0.0146 m, a slab 4 particles deep: 10 × 4 × 20 = 800 fluid particles.
    // c = √(2 g 2L)/0.2 = 12.0 m/s, Δt = 6e-4 s (c Δt/Δs = 0.49).
    let started = Instant::now();
    let e = front_errors(0.0146, 0.0584, 6.0e-4);
    // Bounds: the RMS measured at this resolution: 0.22 against Koshizuka & Oka (the simulated
    // front runs ahead of theirs, as in most particle simulations of this experiment) and
    // 0.022 against Martin & Moyce (shift −0.20), plus about 50 %. The data are read off
    // figures (±0.05 in Z); a column 10 particles wide resolves the toe to Δs/L = 0.1.
    front_record::record(
        &e,
        &FrontRecord {
            method: "emps",
            scale: "l10",
            capability: "E-MPS dam-break front",
            resolution: "E-MPS, Δs = L/10 = 0.0146 m, slab 4 particles deep (800 fluid), Δt = 6e-4 s",
            source: "fluid-solver/tests/dam_break.rs::surge_front_follows_the_experiments",
            bounds: [BOUND_KO, BOUND_MM],
            bound_source: "the RMS measured at this resolution (0.22, 0.022) plus about 50 %; the data are \
                           read off figures (±0.05 in Z)",
            run_time_s: started.elapsed().as_secs_f64(),
            machine: String::new(),
        },
    );
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
    let started = Instant::now();
    let e = front_errors(0.0073, 0.073, 3.0e-4);
    // Measured 0.27 and 0.013 (shift −0.24): bounds with a margin of about 50 %.
    front_record::record(
        &e,
        &FrontRecord {
            method: "emps",
            scale: "l20",
            capability: "E-MPS dam-break front",
            resolution: "E-MPS, Δs = L/20 = 0.0073 m, slab 10 particles deep (8 000 fluid), Δt = 3e-4 s",
            source: "fluid-solver/tests/dam_break.rs::surge_front_at_the_case_resolution",
            bounds: [0.41, 0.03],
            bound_source: "the RMS measured at this resolution (0.27, 0.013) with a margin of about 50 %",
            run_time_s: started.elapsed().as_secs_f64(),
            machine: String::new(),
        },
    );
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
