//! The dam-break surge front on the GPU path against Koshizuka & Oka and Martin & Moyce with the
//! CPU test's setting and bounds (`dam_break.rs`): about 500 steps of 8 000 particles, a minute
//! on lavapipe, so ignored in CI, where `gpu_dam_break.rs` compares the GPU step with the CPU step.

use crate::common;
use crate::front_common;
use crate::front_record;
use crate::gpu_common;

use front_record::FrontRecord;
use schemas::case::fluid::FluidBackend;
use std::time::Instant;

#[test]
#[ignore]
fn surge_front_follows_the_experiments_on_the_gpu() {
    let Some(gpu) = gpu_common::device().map(|d| d.description()) else {
        return;
    };
    let (_, mut cfg) = common::load_case("dam-break-koshizuka");
    cfg.spacing = 0.0146;
    cfg.tank.max = [0.584, 0.0584, 0.438];
    cfg.block[0].max = [0.146, 0.0584, 0.292];
    cfg.time_step = 6.0e-4;
    cfg.backend = FluidBackend::Gpu;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    let started = Instant::now();
    let e = front_common::front_errors(&cfg, 0.005, 8);
    // dam_break.rs's bounds: RMS of Z 0.33 against Koshizuka & Oka, 0.05 against Martin & Moyce
    // (front_common::assert_within_the_e_mps_bounds).
    front_record::record(
        &e,
        &FrontRecord {
            method: "gpu",
            scale: "l10",
            capability: "E-MPS dam-break front on the GPU (f32)",
            resolution:
                "E-MPS on the GPU, Δs = L/10 = 0.0146 m, slab 4 particles deep (800 fluid), Δt = 6e-4 s",
            source: "fluid-solver/tests/gpu_front.rs::surge_front_follows_the_experiments_on_the_gpu",
            bounds: [0.33, 0.05],
            bound_source: "the CPU test's (dam_break.rs)",
            run_time_s: started.elapsed().as_secs_f64(),
            machine: format!("{gpu}; {}", schemas::validation::machine()),
        },
    );
    front_common::assert_within_the_e_mps_bounds(&e, true);
}
