//! The regular waves of a flap wave maker (`[fluid.NAME.wave_maker]`, `motion = "regular"`)
//! against their target height: a resolution study at d/8, d/12 and d/16 that prints a table
//! (minutes on 2 cores); `cargo bench -p fluid-solver --bench wave_maker_resolution -- 8` runs
//! one size. The wave maker's tests are `tests/wave_maker.rs`.

use fluid_solver::probes::ProbeSet;
use fluid_solver::FluidSolver;
use schemas::case::fluid::ProbeConfig;
use schemas::case::Case;

/// A water-height gauge at x, in the middle of the flume's four particles.
fn gauge(name: &str, x: f64) -> ProbeConfig {
    ProbeConfig::water_height(name, [x, 0.0125])
}

/// A flume 2 m long (still water d = 0.1 m from x = 0.1 m, a damping zone over its last 0.6 m)
/// at `spacing` Δs, four particles wide, with a flap hinged on the floor at x = 0.1 m making
/// regular waves H = 0.02 m, T = 0.7 s (kd = 1.05, L = 0.60 m, H/S = 0.556: the flap swings by
/// ±10°), ramped in over two periods; ISPH with S2-8's gradient and Lind shifting (the solitary
/// case's settings until 1 Dec 2026), no viscous term, Δt = 0.16 Δs/(m/s) (Courant 0.32 at
/// u = 2√(gd)).
fn regular_flap_flume(spacing: f64) -> schemas::case::FluidConfig {
    let width = 4.0 * spacing;
    let text = format!(
        r#"[case]
name = "flap"
end_time = 4.6

[fluid.flume]
method = "isph"
isph = {{ shifting = "lind", pressure_gradient = "corrected-difference" }}
spacing = {spacing}
time_step = {dt}
viscosity_term = false
output_interval = 0.1
tank = {{ min = [0.0, 0.0, 0.0], max = [2.1, {width}, 0.16] }}

[fluid.flume.wave_maker]
kind = "flap"
hinge_z = 0.0
min = [0.05, 0.0, 0.0]
max = [0.1, {width}, 0.16]
motion = "regular"
wave_height = 0.02
period = 0.7
depth = 0.1
ramp = 1.4

[[fluid.flume.damping]]
min = [1.5, 0.0, 0.0]
max = [2.1, {width}, 0.16]
rate = 9.0

[[fluid.flume.block]]
min = [0.1, 0.0, 0.0]
max = [2.1, {width}, 0.1]
"#,
        dt = 0.16 * spacing
    );
    let dir = std::env::temp_dir().join(format!("wave-maker-flap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let case = Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["flume"].clone()
}

/// The height of the waves at a gauge 4 d in front of the flap's face: twice the amplitude of
/// the first harmonic (period T) of η over the three periods from 2.5 s (the ramp over, the front
/// past the gauge at c_g = 0.65 m/s, the far end 1.5 m further on), from the gauge's readings
/// at every step (T is a whole number of steps: 350, 525, 700 at d/8, d/12, d/16) less its
/// reading at rest. A per-period max − min reads the surface particles' jitter (a reading moves
/// by Δs as a particle joins or leaves the top of the column; at d/8 the three periods read
/// 0.023, 0.039 and 0.024 m); the harmonic averages it out.
fn regular_flap_wave_height(spacing: f64) -> f64 {
    let mut cfg = regular_flap_flume(spacing);
    cfg.probe = vec![gauge("g4", 0.5)];
    cfg.probe[0].position = vec![0.5, 2.0 * spacing];
    let dt = cfg.time_step;
    let per_period = (0.7 / dt).round() as u32;
    assert!(
        (f64::from(per_period) * dt / 0.7 - 1.0).abs() < 1e-9,
        "T is not a whole number of steps"
    );
    let first = (2.5 / dt).round() as u32;
    let mut solver = FluidSolver::new(&cfg);
    let mut set = ProbeSet::new(&cfg.probe, &solver).unwrap_or_else(|e| panic!("{e}"));
    let level = set.row(&solver)[0];
    let omega = 2.0 * std::f64::consts::PI / 0.7;
    // Σ η (sin, cos) ωt over the 3 periods
    let mut sum = [0.0; 2];
    for i in 1..=first + 3 * per_period {
        let t = f64::from(i) * dt;
        solver
            .advance_to(t)
            .unwrap_or_else(|e| panic!("Δs = {spacing}: {e}"));
        if i > first {
            let eta = set.row(&solver)[0] - level;
            let (sin, cos) = (omega * t).sin_cos();
            sum = [sum[0] + eta * sin, sum[1] + eta * cos];
        }
    }
    2.0 * (2.0 / f64::from(3 * per_period)) * sum[0].hypot(sum[1])
}

fn main() {
    let mut sizes: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![8.0, 12.0, 16.0];
    }
    println!("| Δs | H at 4 d [m] | H / 0.02 m | wall time [s] |");
    println!("|---|---|---|---|");
    for n in sizes {
        let started = std::time::Instant::now();
        let h = regular_flap_wave_height(0.1 / n);
        println!(
            "| d/{n} | {h:.5} | {:.3} | {:.0} |",
            h / 0.02,
            started.elapsed().as_secs_f64()
        );
    }
}
