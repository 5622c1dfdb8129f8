//! The wave maker and the run-up gauge (issue 37) in the solver: the paddle of
//! `cases/solitary-wave-flat` moves exactly by Goring's stroke and at its velocity, with both
//! methods, and so does a flap turning about its hinge, whose ISPH wall normals turn with it;
//! the run-up gauge reads the still-water line on a beach; an initial solitary wave is laid out
//! with its volume and velocity.
//!
//! The generated wave against the solitary wave's height and speed is
//! `the_solitary_wave_keeps_its_height_and_speed_over_ten_depths` (ignored for its length, see
//! `docs/notes/solitary-waves.md`).

use crate::common;

use fluid_solver::isph::kernel::Wendland;
use fluid_solver::isph::neighbour_list::{cell_edge, NeighbourList};
use fluid_solver::isph::walls::{self, TurnedSolids, WallFields};
use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::probes::{self, ProbeSet};
use fluid_solver::vector_field::VectorField;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidMethodName, PaddleKind, ProbeConfig};
use schemas::case::Case;
use schemas::validation::{largest, record, Record};
use schemas::wave_motion::flap::turned;
use schemas::wave_motion::{FlapMotion, WaveMakerMotion};
use std::collections::HashMap;

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

/// The short flume of [`short_flume`] with a flap instead of the piston, hinged l = 0.2 m under
/// the floor at the paddle's front face (x = 0.05 m), making the same solitary wave: its stroke
/// at the still-water level is (d + l)/(d/2 + l) = 6/5 of Goring's √(16 H d / 3) = 0.103 m, so
/// it turns forward by up to atan(0.103 / 0.25) = 22° over the case's 4.2 s.
fn short_flap(method: FluidMethodName) -> (schemas::case::FluidConfig, FlapMotion) {
    let mut cfg = short_flume(method);
    if let Some(w) = cfg.wave_maker.as_mut() {
        w.kind = PaddleKind::Flap;
        w.hinge_z = Some(-0.2);
    }
    cfg.validate("fluid.flume").unwrap_or_else(|e| panic!("{e:?}"));
    cfg.build_wave_maker(std::path::Path::new("."), "fluid.flume", 4.2)
        .unwrap_or_else(|e| panic!("{e:?}"));
    let motion = cfg.wave_maker.as_ref().and_then(|w| w.built.clone());
    let Some(WaveMakerMotion::Flap(flap)) = motion.as_deref() else {
        panic!("no flap: {motion:?}")
    };
    let flap = flap.clone();
    (cfg, flap)
}

/// The paddle's particles at rest (x, z) by id: the walls inside its box.
fn paddle_at_rest(solver: &FluidSolver) -> HashMap<u32, [f64; 2]> {
    let p = solver.particles();
    (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Wall.code() && p.x[i] > 0.0 && p.x[i] < 0.05)
        .filter(|&i| p.y[i] > 0.0 && p.y[i] < 0.05 && p.z[i] > 0.0)
        .map(|i| (p.id[i], [p.x[i], p.z[i]]))
        .collect()
}

/// The flap: at the end of each step every paddle particle stands where its rest position turned
/// by θ(t) = atan(X(t)/L) about the hinge (x_h, z_h) = (0.05, −0.2) m puts it, to rounding (the
/// position is set: x = x_h + r_x cos θ + r_z sin θ, z = z_h − r_x sin θ + r_z cos θ, the
/// formula of `docs/physics.md` §7 evaluated here), y unchanged; its velocity is the chord of
/// its arc over the step, and that is the analytic ω × r = θ'(z − z_h, −(x − x_h)) at the
/// step's middle within 1 % of the particle's top speed max|θ'| |r| (the chord differs from it
/// by O(θ''' Δt²) and O(θ' Δθ²), about 1e-6 of it at Δt = 2 ms). No water gets behind the
/// turned face, with either method (ISPH let 18 particles slip between the flap's edges and the
/// side walls by 0.954 s while the side walls' normals were found with the flap in their kernel
/// sums; `isph::walls` leaves it out of them).
#[test]
fn the_flap_turns_about_its_hinge_with_both_methods() {
    for method in [FluidMethodName::Emps, FluidMethodName::Isph] {
        let (cfg, flap) = short_flap(method);
        let mut solver = FluidSolver::new(&cfg);
        let rest = paddle_at_rest(&solver);
        let rest_y: HashMap<u32, f64> = {
            let p = solver.particles();
            (0..p.len())
                .filter(|&i| rest.contains_key(&p.id[i]))
                .map(|i| (p.id[i], p.y[i]))
                .collect()
        };
        assert_eq!(
            rest.len(),
            4 * 4 * 13,
            "the paddle's particles: 4 thick, 4 wide, 13 high"
        );
        let hinge = [0.05, -0.2];
        let top_rate = largest(
            (0..=1000).map(|i| flap.angular_velocity(1e-3 * f64::from(i)).abs()),
            0.0,
        );
        let dt = cfg.time_step;
        for t in [0.396, 0.954] {
            solver.advance_to(t).unwrap_or_else(|e| panic!("{method:?}: {e}"));
            let now = solver.time();
            let (theta, before) = (flap.angle(now), flap.angle(now - dt));
            let (mid, rate) = (flap.angle(now - 0.5 * dt), flap.angular_velocity(now - 0.5 * dt));
            let p = solver.particles();
            let mut seen = 0;
            let mut worst: f64 = 0.0;
            for i in 0..p.len() {
                let Some(&r0) = rest.get(&p.id[i]) else { continue };
                seen += 1;
                let at = turned(r0, hinge, theta.sin_cos());
                assert!(
                    (p.x[i] - at[0]).abs() < 1e-12 && (p.z[i] - at[1]).abs() < 1e-12,
                    "{method:?}: at {t} s a flap particle is at ({}, {}) instead of {at:?}",
                    p.x[i],
                    p.z[i]
                );
                assert_eq!(p.y[i], rest_y[&p.id[i]]);
                let from = turned(r0, hinge, before.sin_cos());
                assert!((p.vx[i] - (at[0] - from[0]) / dt).abs() < 1e-9);
                assert!((p.vz[i] - (at[1] - from[1]) / dt).abs() < 1e-9 && p.vy[i] == 0.0);
                let m = turned(r0, hinge, mid.sin_cos());
                let r = [m[0] - hinge[0], m[1] - hinge[1]];
                let analytic = [rate * r[1], -rate * r[0]];
                let miss = (p.vx[i] - analytic[0]).hypot(p.vz[i] - analytic[1]);
                let reach = (r0[0] - hinge[0]).hypot(r0[1] - hinge[1]);
                worst = largest([worst, miss / (top_rate * reach)], 0.0);
                assert!(
                    miss <= 1e-2 * top_rate * reach,
                    "{method:?}: at {t} s velocity ({}, {}) against ω × r = {analytic:?}",
                    p.vx[i],
                    p.vz[i]
                );
            }
            assert_eq!(seen, rest.len());
            // behind the face: in the flap's frame (turned back by θ), x − x_h < 0 below its top
            let (sin, cos) = theta.sin_cos();
            let behind = (0..p.len())
                .filter(|&i| p.kind[i] == Kind::Fluid.code())
                .filter(|&i| {
                    let d = [p.x[i] - hinge[0], p.z[i] - hinge[1]];
                    let (along, up) = (d[0] * cos - d[1] * sin, d[0] * sin + d[1] * cos);
                    along < 0.0 && up < 0.3625
                })
                .count();
            println!(
                "{method:?}: at {t} s the flap stands at {:.2}°, turning at {rate:.4} rad/s; velocities within {worst:.2e} of the top speed of ω × r; {behind} fluid particles behind its face",
                theta.to_degrees()
            );
            assert_eq!(behind, 0, "{method:?}: water behind the flap's face at {t} s");
        }
    }
}

/// ISPH keeps a wall particle's normal once found; a flap's are kept as at rest and read turned
/// by θ ([`TurnedSolids`]). At rest the normals of the flap's front layer away from its top and
/// bottom (at least 3 Δs, beyond the kernel's support) point along +x in the x–z plane by the
/// lattice's symmetry; after 0.954 s (θ = 11.7°, the crest at the paddle) the kept ones must point along the turned face's
/// normal (cos θ, −sin θ), the analytic reference, to rounding (1e-12 rad). Freshly computed
/// normals there are printed for comparison (their kernel sums also see the fixed side walls
/// and the floor, which do not turn).
#[test]
fn the_flaps_isph_wall_normals_turn_with_it() {
    let (cfg, flap) = short_flap(FluidMethodName::Isph);
    let radius = cfg.isph_settings().support();
    let k = Wendland::new(cfg.spacing, radius);
    let mut solver = FluidSolver::new(&cfg);
    let rest = paddle_at_rest(&solver);
    let first = rest.keys().copied().min().unwrap_or_else(|| panic!("no paddle"));
    let ids = first..first + rest.len() as u32;
    assert!(
        rest.keys().all(|id| ids.contains(id)),
        "the paddle's ids are contiguous"
    );
    let ds = cfg.spacing;
    // the front layer, at least 3 Δs from the paddle's bottom (z = 0) and top (z = 0.1625)
    let front = |id: u32| {
        let r = rest[&id];
        (r[0] - (0.05 - 0.5 * ds)).abs() < 1e-9 && r[1] > 3.0 * ds && r[1] < 0.1625 - 3.0 * ds
    };
    let mut fields = WallFields::default();
    let mut geometry = |solver: &FluidSolver, angle: f64| {
        let mut p = solver.particles().clone();
        let d = solver.domain();
        let mut grid = CellGrid::with_cell(d.lo, d.hi, cell_edge(ds, radius));
        grid.sort(&mut p, &mut Vec::new());
        let mut list = NeighbourList::default();
        list.build(&grid, &p, &k);
        fields.turned = Some(TurnedSolids {
            ids: ids.clone(),
            angle,
        });
        fields.update_geometry(&k, &list, &p, true);
        let mut fresh = VectorField::default();
        walls::normals(&k, &list, &p, &mut fresh);
        let kept = |w: usize| [fields.normals.x[w], fields.normals.z[w]];
        let out: Vec<([f64; 2], [f64; 2])> = (0..p.len())
            .filter(|&w| ids.contains(&p.id[w]) && front(p.id[w]) && !list.of(w).is_empty())
            .map(|w| (kept(w), [fresh.x[w], fresh.z[w]]))
            .collect();
        out
    };
    // the direction of an x–z normal below +x, rad
    let tilt = |n: [f64; 2]| (-n[1]).atan2(n[0]);
    let at_rest = geometry(&solver, 0.0);
    assert!(
        at_rest.len() >= 4 * 6,
        "{} front particles with water near",
        at_rest.len()
    );
    for (kept, _) in &at_rest {
        assert!(tilt(*kept).abs() < 1e-12, "a rest normal {kept:?} off +x");
    }
    solver.advance_to(0.954).unwrap_or_else(|e| panic!("{e}"));
    let theta = flap.angle(solver.time());
    let turned_now = geometry(&solver, theta);
    assert!(turned_now.len() >= 4 * 6);
    let (mut kept_off, mut fresh_off): (f64, f64) = (0.0, 0.0);
    for (kept, fresh) in &turned_now {
        kept_off = largest([kept_off, (tilt(*kept) - theta).abs()], 0.0);
        fresh_off = largest([fresh_off, (tilt(*fresh) - theta).abs()], 0.0);
    }
    println!(
        "θ = {:.3}°: kept normals within {kept_off:.1e} rad of the face's normal, fresh ones within {fresh_off:.2e} rad ({:.2}°), over {} front particles",
        theta.to_degrees(),
        fresh_off.to_degrees(),
        turned_now.len()
    );
    assert!(theta.to_degrees() > 10.0, "the flap has turned: {theta}");
    assert!(
        kept_off < 1e-12,
        "the kept normals did not turn with the flap: {kept_off} rad off"
    );
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

/// A water-height gauge at x on the flume's centre line.
fn gauge(name: &str, x: f64) -> ProbeConfig {
    ProbeConfig::water_height(name, [x, 0.025])
}

/// The generated wave against the first-order solitary wave (H = 0.02 m, d = 0.1 m) with the
/// case's settings (ISPH's defaults, d/16, eight particles wide) in a flume cut to 1.85 m: its
/// height at 5 and 10 depths from the paddle within 10 % of H, and its speed between them within
/// 2 % of √(g(d + H)) (the issue's bound), crest times by [`main_passage`], the gauges on the
/// flume's centre line. Measured (1 Dec 2026, 2 cores, 325 s): 0.947 H and 0.912 H, 1.1007 m/s
/// against 1.0844 (+1.5 %); on a line a quarter of the width off the centre, 1.018 H and 0.968 H,
/// 1.0797 m/s (−0.4 %): a gauge reads the highest water within Δs of it, so it carries the
/// surface particles' scatter. Four particles wide the wave read 1.043 H and 1.030 H at 2.5 %
/// below c (off the centre): particle side walls read the pressure as flat along them, and in so
/// narrow a flume that slows the wave (docs/notes/standing-wave.md). Off the centre, d/24 reads
/// 1.014 H and 0.979 H at 1.7 % slow (25 min), d/12 0.960 H and 0.920 H at 4.4 % slow, d/8 1.07 H
/// and 0.78 H at 3.9 % fast (docs/notes/solitary-waves.md). Its CI-sized twin for the height is
/// [`the_solitary_wave_keeps_its_height_over_five_depths_at_ci_size`]; no CI size holds the
/// speed's bound.
#[test]
#[ignore = "a long run: about 5 min on 2 cores"]
fn the_solitary_wave_keeps_its_height_and_speed_over_ten_depths() {
    let (_, mut cfg) = common::load_case("solitary-wave-flat");
    cfg.tank.max[0] = 1.85;
    cfg.block[0].max[0] = 1.85;
    cfg.probe = vec![gauge("g5", 0.55), gauge("g10", 1.05)];
    cfg.validate("fluid.flume").unwrap_or_else(|e| panic!("{e:?}"));
    let started = std::time::Instant::now();
    let passages = passages(&cfg, 2.6);
    let height = passages.map(|p| p.0);
    let speed = 0.5 / (passages[1].1 - passages[0].1);
    let c = (9.8f64 * 0.12).sqrt();
    println!("heights {height:?} m (H = 0.02), speed {speed:.4} m/s (c = {c:.4})");
    let row = Record {
        case: "cases/solitary-wave-flat on a flume cut to 1.85 m: a Goring piston's solitary wave, H/d = 0.2, d = 0.1 m".into(),
        resolution: "ISPH defaults, Δs = d/16, Δt = 1.25 ms, eight particles wide".into(),
        source: "fluid-solver/tests/wave_maker.rs::the_solitary_wave_keeps_its_height_and_speed_over_ten_depths (ignored: a long run)".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    };
    record(Record {
        id: "solitary-wave-flat-speed".into(),
        capability: "wave maker: solitary wave speed over 5 to 10 depths".into(),
        reference: "first-order solitary wave, c = √(g(d + H)) = 1.084 m/s".into(),
        measure: "|speed / c − 1|".into(),
        value: (speed / c - 1.0).abs(),
        bound: Some(0.02),
        bound_source: "issue 37: the speed within 2 %".into(),
        unit: "".into(),
        ..row.clone()
    });
    record(Record {
        id: "solitary-wave-flat-height-10d".into(),
        capability: "wave maker: solitary wave height after 10 depths".into(),
        reference: "first-order solitary wave, height H = 0.02 m".into(),
        measure: "|η_max / H − 1| at 10 depths".into(),
        value: (height[1] / 0.02 - 1.0).abs(),
        bound: Some(0.1),
        bound_source: "10 % of H, this test's bound since issue 37; the resolution study off the centre line reads 0.92, 0.97 and 0.98 H at d/12, d/16 and d/24, and the two gauge lines differ by 0.06 H at d/16 (docs/notes/solitary-waves.md)".into(),
        unit: "".into(),
        ..row
    });
    for h in height {
        assert!((h / 0.02 - 1.0).abs() <= 0.1, "height {h}");
    }
    assert!((speed / c - 1.0).abs() <= 0.02, "speed {speed}");
}

/// The CI-sized twin of [`the_solitary_wave_keeps_its_height_and_speed_over_ten_depths`] for the
/// height: the case at d/12 in a flume cut to 1.0 m and kept eight particles wide, its height at
/// 3 and 5 depths from the paddle on the centre line within the same 10 % of H. Measured (1 Dec
/// 2026, 36 s on 2 cores): 0.968 H and 0.960 H (the long flume at d/12 read 0.960 H at 5 depths
/// off the centre). The speed is left to the long run: over these two depths the crest times
/// still move with the wave's forming (0.975 m/s here) and at d/12 the long run reads 4.4 % slow.
#[test]
fn the_solitary_wave_keeps_its_height_over_five_depths_at_ci_size() {
    let (_, mut cfg) = common::load_case("solitary-wave-flat");
    cfg.spacing = 0.1 / 12.0;
    cfg.time_step = 0.2 * cfg.spacing;
    let width = 8.0 * cfg.spacing;
    cfg.tank.max = [1.0, width, 0.16];
    cfg.block[0].max = [1.0, width, 0.1];
    if let Some(w) = cfg.wave_maker.as_mut() {
        w.max[1] = width;
    }
    cfg.probe = [("g3", 0.35), ("g5", 0.55)]
        .map(|(name, x)| ProbeConfig::water_height(name, [x, 0.5 * width]))
        .to_vec();
    cfg.validate("fluid.flume").unwrap_or_else(|e| panic!("{e:?}"));
    let passages = passages(&cfg, 1.6);
    println!(
        "heights {:.3} H and {:.3} H at 3 and 5 depths, crests at {:.3} and {:.3} s",
        passages[0].0 / 0.02,
        passages[1].0 / 0.02,
        passages[0].1,
        passages[1].1
    );
    assert!(
        passages[1].1 > passages[0].1,
        "the crest reached 5 depths before 3: {passages:?}"
    );
    for (h, _) in passages {
        assert!((h / 0.02 - 1.0).abs() <= 0.1, "height {h}");
    }
}

/// [`main_passage`] of each of `cfg`'s two gauges, read every 5 ms to `end` [s], η from the
/// gauge's reading at the start.
fn passages(cfg: &schemas::case::FluidConfig, end: f64) -> [(f64, f64); 2] {
    let mut solver = FluidSolver::new(cfg);
    let mut set = ProbeSet::new(&cfg.probe, &solver).unwrap_or_else(|e| panic!("{e}"));
    let level = set.row(&solver);
    let mut series: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    let mut t = 0.0;
    while t < end {
        t += 0.005;
        solver.advance_to(t).unwrap_or_else(|e| panic!("{e}"));
        let row = set.row(&solver);
        for g in 0..2 {
            series[g].push((t, row[g] - level[g]));
        }
    }
    series.map(|s| main_passage(&s))
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

/// `[initial_wave]` (H = 0.02 m on d = 0.1 m, crest at 0.5 m) in a flume four particles wide
/// with a 1:3 beach from x = 1 m, as laid out at t = 0:
/// - the water above the still level is the wave's volume 2H/k per width, within the lattice's
///   rounding: a column holds round(η/Δs) sites, so it is off by at most min(η, Δs/2), summed
///   over the columns from the profile itself;
/// - every water particle moves with the wave's velocity at its place ([`SolitaryWave::velocity_at`],
///   whose continuity and surface condition the schemas crate tests), along +x;
/// - the run-up gauge reads the still-water line on the beach (0.1 m plus at most Δs/2 of
///   rounding), not the crest, which touches only the flume's side walls.
#[test]
fn the_initial_wave_carries_the_solitary_waves_volume_and_velocity() {
    let dir = std::env::temp_dir().join(format!("initial-wave-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let text = r#"[case]
name = "initial-wave"
end_time = 0.1

[fluid.flume]
method = "isph"
spacing = 0.005
time_step = 1.0e-3
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [1.4, 0.02, 0.2] }

[fluid.flume.initial_wave]
height = 0.02
depth = 0.1
crest = 0.5

[[fluid.flume.terrain]]
plane = { point = [1.0, 0.0, 0.0], normal = [-1.0, 0.0, 3.0] }

[[fluid.flume.block]]
min = [0.0, 0.0, 0.0]
max = [1.4, 0.02, 0.1]

[[fluid.flume.probe]]
name = "run-up"
kind = "run-up"
"#;
    let case = Case::parse(&dir.join("case.toml"), text.into()).unwrap_or_else(|e| panic!("{e}"));
    let cfg = case.fluid["flume"].clone();
    let wave = cfg
        .initial_wave
        .as_ref()
        .and_then(|w| w.wave(9.8).ok())
        .unwrap_or_else(|| panic!("the case has an initial wave"));
    let solver = FluidSolver::new(&cfg);
    let p = solver.particles();
    let (ds, width, still) = (cfg.spacing, 0.02, 0.1);
    let fluid: Vec<usize> = (0..p.len()).filter(|&i| p.kind_of(i) == Kind::Fluid).collect();
    let raised = fluid.iter().filter(|&&i| p.z[i] > still).count() as f64 * ds * ds * ds / width;
    // the columns left of the beach's toe (the beach takes the still water's place beyond it)
    let columns = (0..(1.0 / ds).round() as usize).map(|c| (c as f64 + 0.5) * ds);
    let theory: f64 = columns.clone().map(|x| wave.elevation(x, 0.0) * ds).sum();
    let rounding: f64 = columns.map(|x| wave.elevation(x, 0.0).min(0.5 * ds) * ds).sum();
    println!(
        "raised water {raised:.6} m² per width, the profile's {theory:.6} (2H/k = {:.6}), rounding bound {rounding:.6}",
        wave.volume_per_width()
    );
    assert!(
        (raised - theory).abs() <= rounding,
        "{raised} against {theory} ± {rounding}"
    );
    let mut worst: f64 = 0.0;
    for &i in &fluid {
        let [u, w] = wave.velocity_at(p.x[i], p.z[i], 0.0);
        worst = largest(
            [worst, (p.vx[i] - u).abs(), p.vy[i].abs(), (p.vz[i] - w).abs()],
            0.0,
        );
    }
    assert!(
        worst < 1e-12,
        "a particle's velocity is {worst} m/s off the wave's"
    );
    assert!(fluid.iter().any(|&i| p.vx[i] > 0.9 * wave.crest_velocity()));
    let reading = probes::sample(&cfg.probe[0], p, solver.kernel(), &solver.tank());
    println!(
        "run-up gauge at t = 0: {reading:.4} m (the crest's top is {:.4} m)",
        still + 0.02
    );
    assert!(
        reading >= still - 1e-12 && reading <= still + 0.5 * ds + 1e-12,
        "the run-up gauge reads {reading} m"
    );
}
