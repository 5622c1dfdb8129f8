//! The wave maker and the run-up gauge (issue 37) in the solver: the paddle of
//! `cases/solitary-wave-flat` moves exactly by Goring's stroke and at its velocity, with both
//! methods; the run-up gauge reads the still-water line on a beach.
//!
//! The generated wave against the solitary wave's height and speed is
//! `the_solitary_wave_keeps_its_height_and_speed_over_ten_depths` (ignored for its length, see
//! `docs/notes/solitary-waves.md`).

use crate::common;

use fluid_solver::probes::{self, ProbeSet};
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidMethodName, ProbeConfig, ProbeKind};
use schemas::case::Case;
use schemas::validation::{record, Record};

/// The solitary case at Δs = 0.0125 m (d/8) in a 0.6 m flume four particles wide, with its own
/// ISPH settings or with E-MPS (c = 7 m/s, 5 √(g d)).
fn short_flume(method: FluidMethodName) -> schemas::case::FluidConfig {
    let (_, mut cfg) = common::load_case("solitary-wave-flat");
    if method == FluidMethodName::Emps {
        cfg.method = method;
        cfg.isph = None;
        cfg.sound_speed = Some(7.0);
    }
    cfg.spacing = 0.0125;
    cfg.time_step = if method == FluidMethodName::Isph {
        2.0e-3
    } else {
        9.0e-4
    };
    cfg.tank.max = [0.6, 0.05, 0.16];
    cfg.block[0].max = [0.6, 0.05, 0.1];
    if let Some(w) = cfg.wave_maker.as_mut() {
        w.max[1] = 0.05;
    }
    cfg.probe.clear();
    cfg.validate("fluid.flume").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// Goring's paddle: every paddle particle stands at its rest position plus X(t) at the end of
/// each step, exactly (the position is set, not integrated), and moves at the step's mean
/// velocity (X(t) − X(t − Δt))/Δt, which is X'(t − Δt/2) to O(Δt²): within 1 % of the top speed
/// c H/(d + H) at Δt = 2 ms (X''' Δt²/24 ≈ (k c)² X' Δt²/24 ≈ 3e-6 of it).
#[test]
fn the_paddle_moves_by_gorings_stroke_with_both_methods() {
    for method in [FluidMethodName::Emps, FluidMethodName::Isph] {
        let cfg = short_flume(method);
        let motion = cfg
            .wave_maker
            .as_ref()
            .and_then(|w| w.built.clone())
            .unwrap_or_else(|| panic!("no wave maker"));
        let mut solver = FluidSolver::new(&cfg);
        let p = solver.particles();
        let rest: std::collections::HashMap<u32, f64> = (0..p.len())
            .filter(|&i| p.kind[i] == Kind::Wall.code() && p.x[i] > 0.0 && p.x[i] < 0.05)
            .filter(|&i| p.y[i] > 0.0 && p.y[i] < 0.05 && p.z[i] > 0.0)
            .map(|i| (p.id[i], p.x[i]))
            .collect();
        assert_eq!(
            rest.len(),
            4 * 4 * 13,
            "the paddle's particles: 4 thick, 4 wide, 13 high"
        );
        let top = motion.velocity(0.95);
        let dt = cfg.time_step;
        // whole numbers of steps of both methods (9e-4 and 2e-3 s), so the last step is a whole one
        for t in [0.396, 0.954] {
            solver.advance_to(t).unwrap_or_else(|e| panic!("{method:?}: {e}"));
            let (x, x_before) = (motion.stroke(solver.time()), motion.stroke(solver.time() - dt));
            let p = solver.particles();
            let mut seen = 0;
            for i in 0..p.len() {
                let Some(&x0) = rest.get(&p.id[i]) else { continue };
                seen += 1;
                assert!(
                    (p.x[i] - (x0 + x)).abs() < 1e-12,
                    "{method:?}: at {t} s a paddle particle is at {} instead of {}",
                    p.x[i],
                    x0 + x
                );
                assert!((p.vx[i] - (x - x_before) / dt).abs() < 1e-9);
                assert!(
                    (p.vx[i] - motion.velocity(solver.time() - 0.5 * dt)).abs() < 1e-2 * top,
                    "{method:?}: {} against {}",
                    p.vx[i],
                    motion.velocity(t)
                );
            }
            assert_eq!(seen, rest.len());
            let fluid_behind = (0..p.len())
                .filter(|&i| p.kind[i] == Kind::Fluid.code() && p.x[i] < x + 0.05)
                .count();
            println!("{method:?}: at {t} s the paddle stands {x:.4} m forward, moving at {:.4} m/s; {fluid_behind} fluid particles behind its face", motion.velocity(t));
            assert_eq!(
                fluid_behind, 0,
                "{method:?}: water behind the paddle's face at {t} s"
            );
        }
    }
}

/// Still water 0.2 m deep over a 1:2 beach: the run-up gauge reads the water line, the top of
/// the water touching the beach plus Δs/2 as the water-height gauge reads it: 0.2 m, and within
/// a spacing of it after 0.2 s of ISPH (whose still water stays within 1e-3 √(gH),
/// `tests/isph.rs`) and of E-MPS (whose column settles by about 2 % of its depth, 4 mm here,
/// `tests/hydrostatic.rs`); neither finds water inside the beach.
#[test]
fn the_run_up_gauge_reads_the_still_water_line_on_a_beach() {
    for method in ["isph", "emps"] {
        run_up_on_a_beach(method);
    }
}

fn run_up_on_a_beach(method: &str) {
    let started = std::time::Instant::now();
    let dir = std::env::temp_dir().join(format!("wave-maker-beach-{method}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let text = r#"[case]
name = "beach"
end_time = 0.2

[fluid.beach]
method = "METHOD"
spacing = 0.02
sound_speed = 10.0
time_step = 2.0e-3
output_interval = 0.1
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
    let text = text.replace("METHOD", method).replace(
        "time_step = 2.0e-3",
        if method == "isph" {
            "time_step = 2.0e-3"
        } else {
            "time_step = 1.0e-3"
        },
    );
    let case = Case::parse(&dir.join("case.toml"), text).unwrap_or_else(|e| panic!("{e}"));
    let cfg = case.fluid["beach"].clone();
    let mut solver = FluidSolver::new(&cfg);
    let read = |s: &FluidSolver| probes::sample(&cfg.probe[0], s.particles(), s.kernel(), &s.tank());
    let at_start = read(&solver);
    let mut set = ProbeSet::new(&cfg.probe, &solver).unwrap_or_else(|e| panic!("{e}"));
    solver.advance_to(0.2).unwrap_or_else(|e| panic!("{e}"));
    let later = set.row(&solver)[0];
    println!(
        "{method}: run-up gauge: {at_start:.4} m at the start, {later:.4} m at 0.2 s (water line 0.2 m)"
    );
    record(Record {
        id: format!("scene-run-up-still-water-{method}"),
        capability: "run-up gauge on a beach ([[terrain]] plane, kind = \"run-up\")".into(),
        reference: "the still-water line, 0.2 m above the floor".into(),
        case: "still water 0.2 m deep over a 1:2 beach, 0.2 s".into(),
        resolution: format!("{}, Δs = 0.02 m", method.to_uppercase()),
        measure: "|reading − 0.2 m| after 0.2 s".into(),
        value: (later - 0.2).abs(),
        bound: Some(cfg.spacing),
        bound_source: "a gauge reads particle positions: one spacing".into(),
        unit: "m".into(),
        source: "fluid-solver/tests/wave_maker.rs::the_run_up_gauge_reads_the_still_water_line_on_a_beach"
            .into(),
        run_time_s: started.elapsed().as_secs_f64(),
        date: String::new(),
        machine: String::new(),
        note: None,
    });
    assert!((at_start - 0.2).abs() < 1e-9, "{at_start}");
    assert!((later - 0.2).abs() <= cfg.spacing, "{later}");
}

fn gauge(name: &str, x: f64) -> ProbeConfig {
    ProbeConfig {
        name: name.into(),
        kind: ProbeKind::WaterHeight,
        position: vec![x, 0.0125],
        ..Default::default()
    }
}

/// The generated wave against the first-order solitary wave (H = 0.02 m, d = 0.1 m) with the
/// case's settings at its resolution (d/16) in a flume cut to 1.85 m: its height at 5 and 10
/// depths from the paddle within 10 % of H, and its speed between them within 2 % of
/// √(g(d + H)) (the issue's bound), crest times by [`main_passage`]. Fails today with the case's
/// ISPH default gradient and Lind shifting: 1.06 H and 1.00 H, but 0.99 m/s, √(g d), against
/// 1.084 (`docs/notes/solitary-waves.md`); 11–17 min on 2 cores.
#[test]
#[ignore = "fails today: the heights are met, the wave travels at √(gd), 8 % slow (docs/notes/solitary-waves.md)"]
fn the_solitary_wave_keeps_its_height_and_speed_over_ten_depths() {
    let (_, mut cfg) = common::load_case("solitary-wave-flat");
    cfg.tank.max[0] = 1.85;
    cfg.block[0].max[0] = 1.85;
    cfg.probe = vec![gauge("g5", 0.55), gauge("g10", 1.05)];
    cfg.validate("fluid.flume").unwrap_or_else(|e| panic!("{e:?}"));
    let mut solver = FluidSolver::new(&cfg);
    let mut set = ProbeSet::new(&cfg.probe, &solver).unwrap_or_else(|e| panic!("{e}"));
    let level = set.row(&solver);
    let mut series: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    let mut t = 0.0;
    while t < 2.6 {
        t += 0.005;
        solver.advance_to(t).unwrap_or_else(|e| panic!("{e}"));
        let row = set.row(&solver);
        for g in 0..2 {
            series[g].push((t, row[g] - level[g]));
        }
    }
    let passages = series.map(|s| main_passage(&s));
    let height = passages.map(|p| p.0);
    let speed = 0.5 / (passages[1].1 - passages[0].1);
    let c = (9.8f64 * 0.12).sqrt();
    println!("heights {height:?} m (H = 0.02), speed {speed:.3} m/s (c = {c:.3})");
    for h in height {
        assert!((h / 0.02 - 1.0).abs() <= 0.1, "height {h}");
    }
    assert!((speed / c - 1.0).abs() <= 0.02, "speed {speed}");
}

/// A gauge's main passage: its highest η, and the η²-weighted mean time over the contiguous
/// samples around that peak where η is above half of it (the sech² core; the trailing shelf and
/// later waves, which moved an all-run mean by several per cent, are left out).
fn main_passage(series: &[(f64, f64)]) -> (f64, f64) {
    let peak = (0..series.len())
        .max_by(|&a, &b| series[a].1.total_cmp(&series[b].1))
        .unwrap_or_else(|| panic!("an empty gauge series"));
    let half = 0.5 * series[peak].1;
    let first = (0..=peak)
        .rev()
        .take_while(|&i| series[i].1 > half)
        .last()
        .unwrap_or(peak);
    let last = (peak..series.len())
        .take_while(|&i| series[i].1 > half)
        .last()
        .unwrap_or(peak);
    let core = &series[first..=last];
    let weight: f64 = core.iter().map(|(_, e)| e * e).sum();
    let time = core.iter().map(|(t, e)| e * e * t).sum::<f64>() / weight;
    (series[peak].1, time)
}
