//! The run-up gauge on the GPU path reads what the CPU's reads: the highest water resting on a
//! solid, reduced on the device without a copy of the particles, on a 1:2 beach of still water
//! that an E-MPS run settles (`wave_maker.rs`'s beach at Δs = 0.02 m, 0.05 s).

use crate::gpu_common;
use crate::gpu_common::probe_rows::probe_rows;

const CASE: &str = r#"[case]
name = "beach"
end_time = 0.05

[fluid.beach]
spacing = 0.02
sound_speed = 10.0
time_step = 1.0e-3
output_interval = 0.05
probe_interval = 0.01
tank = { min = [0.0, 0.0, 0.0], max = [0.8, 0.1, 0.4] }

[[fluid.beach.terrain]]
plane = { point = [0.3, 0.0, 0.0], normal = [-1.0, 0.0, 2.0] }

[[fluid.beach.block]]
min = [0.0, 0.0, 0.0]
max = [0.8, 0.1, 0.2]

[[fluid.beach.probe]]
name = "run-up"
kind = "run-up"
"#;

/// The run-up column on `backend`, and the run's whole copies from the GPU.
fn run_up(backend: &str) -> (Vec<f64>, u64) {
    let (rows, copies) = probe_rows(CASE, "beach", backend);
    (rows.iter().map(|r| r[1]).collect(), copies)
}

#[test]
fn the_run_up_gauge_reads_on_the_device_what_it_reads_on_the_cpu() {
    if gpu_common::device().is_none() {
        return;
    }
    let ((cpu, _), (gpu, copies)) = (run_up("cpu"), run_up("gpu"));
    assert_eq!(cpu.len(), 6, "rows at t = 0, 0.01 … 0.05: {cpu:?}");
    // the still water line at z = 0.2 m, read as the top particle's centre + Δs/2
    assert!((cpu[0] - 0.2).abs() < 0.02, "CPU at t = 0: {}", cpu[0]);
    // positions agree to ~1e-7 m after 50 steps (gpu_dam_break.rs): 1e-4 m
    for (t, (c, g)) in cpu.iter().zip(&gpu).enumerate() {
        println!("row {t}: CPU {c}, GPU {g}");
        assert!((c - g).abs() <= 1e-4, "row {t}: CPU {c}, GPU {g}");
    }
    // frames at t = 0 (the host's particles are current) and 0.05
    assert_eq!(
        copies, 1,
        "whole copies from the GPU: only the frame at t = 0.05 needs one"
    );
}
