//! Time to solution of `cases/solitary-runup` (a solitary wave, H/d = 0.2, running up a 1:3
//! beach; ISPH with Lind's shifting, as shipped, or E-MPS) on this machine's CPU threads: the
//! run-up R the probe reads against Synolakis' (1987) law R/d = 2.831 √(cot β) (H/d)^{5/4}, the
//! wall time, and particle-steps per second, in a table.
//!
//! `cargo bench -p fluid-solver --bench solitary_runup` runs the shipped resolution (d/16,
//! about 3.5 min on 2 cores); `… -- 16 24` runs d/16 and d/24 (Δt scaled with Δs, as the case's
//! c Δt/Δs); `… -- 8` a quick d/8 to check the bench itself; `emps` among the arguments runs
//! E-MPS instead (at c Δt/Δs = 0.5, c the case's default sound speed); `isph-default` runs ISPH
//! with its default settings (the exact projection with its kernel correction, no shifting)
//! instead of the case's (S2-8's gradient with Lind's shifting); `width=N` makes the flume N
//! spacings wide at every resolution (the case's is 0.025 m, four spacings at d/16) with the
//! gauges on its centre line (docs/notes/standing-wave.md: narrow flumes slow waves).

use fluid_solver::probes::ProbeSet;
use fluid_solver::FluidSolver;
use schemas::case::fluid::{FluidConfig, FluidMethodName, IsphConfig};
use schemas::case::Case;
use std::path::PathBuf;
use std::time::Instant;

/// Still-water depth d and wave height H of the case [m]; the beach's slope cot β.
const DEPTH: f64 = 0.1;
const HEIGHT: f64 = 0.02;
const COT_BETA: f64 = 3.0;

/// E-MPS's acoustic Courant number c Δt/Δs in this bench.
const EMPS_COURANT: f64 = 0.5;

/// One run at Δs = d/`n` with `method`, `width` spacings wide if given: (R [m], wall time [s],
/// particles, steps).
fn run(
    base: &FluidConfig,
    n: f64,
    method: FluidMethodName,
    width: Option<f64>,
) -> Result<(f64, f64, usize, u64), String> {
    let mut cfg = base.clone();
    let scale = (DEPTH / n) / base.spacing;
    cfg.spacing = DEPTH / n;
    cfg.time_step = base.time_step * scale;
    if let Some(w) = width {
        let across = w * cfg.spacing;
        cfg.tank.max[1] = cfg.tank.min[1] + across;
        cfg.block.iter_mut().for_each(|b| b.max[1] = cfg.tank.max[1]);
        for p in cfg.probe.iter_mut().filter(|p| p.position.len() == 2) {
            p.position[1] = cfg.tank.min[1] + 0.5 * across;
        }
    }
    if method == FluidMethodName::Emps {
        cfg.method = method;
        cfg.isph = None;
        cfg.time_step = EMPS_COURANT * cfg.spacing / cfg.sound_speed();
    }
    cfg.validate("fluid.flume").map_err(|e| format!("{e:?}"))?;
    let started = Instant::now();
    let mut solver = FluidSolver::new(&cfg);
    let mut probes = ProbeSet::new(&cfg.probe, &solver)?;
    let column = probes
        .names()
        .iter()
        .position(|&p| p == "run-up")
        .ok_or("the case has no `run-up` probe")?;
    let mut highest = f64::MIN;
    let end = 1.3;
    let interval = cfg.probe_interval.unwrap_or(cfg.time_step);
    let mut t = 0.0;
    while t < end - 1e-9 {
        t = (t + interval).min(end);
        solver.advance_to(t).map_err(|e| e.to_string())?;
        highest = schemas::validation::max_or_nan(highest, probes.row(&solver)[column]);
    }
    Ok((
        highest - DEPTH,
        started.elapsed().as_secs_f64(),
        solver.particle_count(),
        solver.steps(),
    ))
}

fn main() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/solitary-runup/case.toml");
    let case = match Case::load(&path) {
        Ok(c) => c,
        Err(e) => {
            println!("error: {e}");
            return;
        }
    };
    let Some(mut base) = case.fluid.get("flume").cloned() else {
        println!("error: the case has no fluid section `flume`");
        return;
    };
    let mut sizes: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes.push(16.0);
    }
    let method = match std::env::args().any(|a| a == "emps") {
        true => FluidMethodName::Emps,
        false => FluidMethodName::Isph,
    };
    let isph_default = std::env::args().any(|a| a == "isph-default");
    let width = std::env::args().find_map(|a| a.strip_prefix("width=").and_then(|w| w.parse::<f64>().ok()));
    if isph_default {
        base.isph = Some(IsphConfig::default());
    }
    let law = DEPTH * 2.831 * COT_BETA.sqrt() * (HEIGHT / DEPTH).powf(1.25);
    println!(
        "solitary-runup, {}, to t = 1.3 s on {} threads; Synolakis' law R = {:.1} mm",
        match method {
            FluidMethodName::Emps => "E-MPS (c Δt/Δs = 0.5)",
            FluidMethodName::Isph if isph_default => "ISPH, default settings",
            FluidMethodName::Isph => "ISPH + Lind shifting",
        },
        rayon::current_num_threads(),
        1e3 * law
    );
    if let Some(w) = width {
        println!("the flume {w} spacings wide");
    }
    println!("| Δs | particles | steps | R [mm] | R / law | wall time [s] | particle-steps/s |");
    println!("|---|---|---|---|---|---|---|");
    for n in sizes {
        match run(&base, n, method, width) {
            Ok((r, wall, particles, steps)) => println!(
                "| d/{n} | {particles} | {steps} | {:.1} | {:.2} | {wall:.1} | {:.3e} |",
                1e3 * r,
                r / law,
                (particles as f64 * steps as f64) / wall
            ),
            Err(e) => println!("| d/{n} | error: {e} |"),
        }
    }
}
