//! The fluid in slabs ([`fluid_solver::ranks`]) steps as the whole domain does: the dam-break
//! slab in 2 and 3 slabs along x against one solver, 150 steps, every fluid particle compared
//! by id. Decomposing changes only the order in which each particle's neighbour sums are added
//! (the halo holds every particle its step depends on), so the slabs must stay within the
//! round-off spread that the same change of order makes on one solver: the whole domain with its
//! particles stored in reverse order. Mass (the fluid's particle count) is exact. The probes the
//! slabs read between them (pressure on both sides of a cut, gauges, a filtered wall sensor, the
//! surge front and the run-up) are held to the same spread of the same probes' readings.

use fluid_solver::particles::Particles;
use fluid_solver::probes::ProbeSet;
use fluid_solver::ranks::decomposed::DecomposedFluid;
use fluid_solver::ranks::rebalance;
use fluid_solver::FluidSolver;
use schemas::case::{Case, FluidConfig};
use schemas::validation::{largest, record, Record};
use std::collections::HashMap;
use std::path::PathBuf;

/// Steps compared: 0.075 s of the collapse at Δt = 5e-4 s.
const STEPS: usize = 150;

/// How far a decomposed run may drift from the whole domain's, in units of the spread the
/// reversed order makes on one solver (chaotic growth of round-off is the same in both; a halo
/// short of one chained pass makes an error of order 1e-3 Δs = 2e-5 m at once, several orders
/// above that spread).
const SPREADS: f64 = 100.0;

/// A 1.6 × 0.06 × 0.3 m tank with a lid at Δs = 0.02 m (three particles deep) and a water
/// column 1.2 m wide and 0.24 m high on its left (2 160 fluid particles): long enough for three
/// slabs of at least the halo (with the viscous term 0.8 Δs + 2.1 Δs + 2 × 3.1 Δs + 2 Δs =
/// 11.1 Δs = 0.222 m). Gravity leans 6 m/s² towards +x (a
/// tilted tank), so the whole column moves along x from the start, ½ 6 t² = 1.7 cm by 0.075 s,
/// and the water crosses the cuts inside it, not only at its front.
pub(crate) const TANK: &str = r#"[case]
name = "slabs"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 5.0e-4
sound_speed = 12.1
gravity = [6.0, 0.0, -9.8]
output_interval = 0.05
tank = { min = [0.0, 0.0, 0.0], max = [1.6, 0.06, 0.3], lid = true }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [1.2, 0.06, 0.24]

# two slabs cut the column at x = 0.6 m, three at 0.4 and 0.8 m
[[fluid.water.probe]]
name = "p-left-of-cut"
kind = "pressure"
position = [0.595, 0.03, 0.05]

[[fluid.water.probe]]
name = "p-right-of-cut"
kind = "pressure"
position = [0.605, 0.03, 0.05]

[[fluid.water.probe]]
name = "gauge-cut"
kind = "water-height"
position = [0.6, 0.03]

[[fluid.water.probe]]
name = "gauge-front"
kind = "water-height"
position = [1.15, 0.03]

[[fluid.water.probe]]
name = "left-wall"
kind = "wall-pressure"
position = [0.0, 0.03, 0.06]
normal = "+x"
diameter = 0.04
window = 0.005

[[fluid.water.probe]]
name = "front"
kind = "surge-front"
axis = "+x"

[[fluid.water.probe]]
name = "run-up"
kind = "run-up"
"#;

/// Steps between two probe rows.
const ROW_EVERY: usize = 10;

/// [`TANK`]'s fluid section.
fn tank() -> FluidConfig {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("slabs.toml");
    let case = Case::parse(&path, TANK.to_string()).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["water"].clone()
}

/// Fluid positions by id.
pub(crate) fn by_id(p: &Particles) -> HashMap<u32, [f64; 3]> {
    (0..p.len())
        .filter(|&i| p.kind_of(i) == fluid_solver::Kind::Fluid)
        .map(|i| (p.id[i], p.position(i)))
        .collect()
}

/// The largest distance between the same particle in `a` and `b` (which hold the same ids).
pub(crate) fn largest_gap(a: &HashMap<u32, [f64; 3]>, b: &HashMap<u32, [f64; 3]>) -> f64 {
    assert_eq!(
        a.len(),
        b.len(),
        "fluid particles: {} against {}",
        a.len(),
        b.len()
    );
    largest(
        a.iter().map(|(id, r)| {
            let s = b.get(id).unwrap_or_else(|| panic!("particle {id} is missing"));
            ((r[0] - s[0]).powi(2) + (r[1] - s[1]).powi(2) + (r[2] - s[2]).powi(2)).sqrt()
        }),
        0.0,
    )
}

/// The whole domain after `steps` steps, its particles first stored in reverse order when
/// `reversed`, and its probe rows every [`ROW_EVERY`] steps.
fn whole(cfg: &FluidConfig, reversed: bool, steps: usize) -> (FluidSolver, Vec<Vec<f64>>) {
    let mut s = FluidSolver::new(cfg);
    let mut probes = ProbeSet::new(&cfg.probe, &s).unwrap_or_else(|e| panic!("{e}"));
    s.remove_gates();
    if reversed {
        store_in_reverse(&mut s);
    }
    let mut rows = Vec::new();
    for k in 1..=steps {
        s.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
        probes.observe(&s, next_row(k, cfg.time_step));
        if k % ROW_EVERY == 0 {
            rows.push(probes.row(&s));
        }
    }
    (s, rows)
}

/// Stores `s`'s particles in reverse order (the same state, its sums added in another order: the
/// round-off spread the slabs are held to).
fn store_in_reverse(s: &mut FluidSolver) {
    let mut state = s.save_state();
    let n = state.particles.len() as u32;
    let order: Vec<u32> = (0..n).rev().collect();
    state.particles.permute(&order, &mut Vec::new());
    state.grid.sort(&mut state.particles, &mut Vec::new());
    s.restore_state(&state);
}

/// A decomposed run's largest distance to the undivided run's particles, with what it ran.
struct Positions {
    id: String,
    capability: &'static str,
    case: &'static str,
    resolution: String,
    /// The test in this file that measured it.
    test: &'static str,
    gap: f64,
    /// The undivided run's round-off spread (its particles stored in reverse order).
    spread: f64,
    started: std::time::Instant,
}

/// Records `p` and asserts its gap within [`SPREADS`] × its spread.
fn positions_within_the_spread(p: Positions) {
    let bound = SPREADS * p.spread.max(1e-15);
    record(Record {
        id: p.id.clone(),
        capability: p.capability.into(),
        reference: "the undivided run from the same start".into(),
        case: p.case.into(),
        resolution: p.resolution,
        measure: "largest |r_slabs − r_undivided| over the fluid particles".into(),
        value: p.gap,
        bound: Some(bound),
        bound_source: format!(
            "{SPREADS} × the round-off spread of the undivided run with its particles stored in reverse order ({:.1e} m)",
            p.spread
        ),
        unit: "m".into(),
        source: format!("fluid-solver/tests/ranks.rs::{}", p.test),
        run_time_s: p.started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        p.gap <= bound,
        "{}: a particle is {:.3e} m from the whole domain's, more than {SPREADS} × the order's spread {:.3e} m",
        p.id,
        p.gap,
        p.spread
    );
}

/// The time of the probe row after step `k`.
fn next_row(k: usize, dt: f64) -> f64 {
    k.div_ceil(ROW_EVERY) as f64 * ROW_EVERY as f64 * dt
}

/// The largest difference of each probe's readings between two runs' rows.
fn probe_gaps(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<f64> {
    assert_eq!(a.len(), b.len(), "probe rows");
    (0..a[0].len())
        .map(|k| largest(a.iter().zip(b).map(|(x, y)| (x[k] - y[k]).abs()), 0.0))
        .collect()
}

#[test]
fn slabs_step_as_the_whole_domain_within_its_round_off_spread() {
    let cfg = tank();
    let names: Vec<&str> = cfg.probe.iter().map(|p| p.name.as_str()).collect();
    let started = std::time::Instant::now();
    let (reference, reference_rows) = whole(&cfg, false, STEPS);
    let (reversed, reversed_rows) = whole(&cfg, true, STEPS);
    let reference = by_id(reference.particles());
    let spread = largest_gap(&reference, &by_id(reversed.particles()));
    let probe_spread = probe_gaps(&reference_rows, &reversed_rows);
    println!("whole domain, reversed order: largest gap {spread:.3e} m after {STEPS} steps; probes {names:?}: {probe_spread:?}");
    let last = reference_rows.last().cloned().unwrap_or_default();
    println!("the probes' last row: {last:?}");
    let probe_bounds: Vec<f64> = (0..names.len())
        .map(|k| {
            let scale = largest(reference_rows.iter().map(|r| r[k].abs()), 0.0);
            SPREADS * largest([probe_spread[k]], f64::EPSILON * scale)
        })
        .collect();
    assert!(
        last.iter().all(|v| *v > 0.0),
        "every probe reads something by the end: {last:?}"
    );
    assert!(
        spread < 1e-6,
        "the reversed order alone moved a particle by {spread} m"
    );
    for parts in [2, 3] {
        let mut d = DecomposedFluid::new(&cfg, parts).unwrap_or_else(|e| panic!("{e}"));
        let mut rows = Vec::new();
        for k in 1..=STEPS {
            d.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
            d.observe_probes(next_row(k, cfg.time_step));
            if k % ROW_EVERY == 0 {
                rows.push(d.probe_row());
            }
        }
        let probe_gap = probe_gaps(&reference_rows, &rows);
        println!("{parts} slabs: probes {probe_gap:?}");
        assert_eq!(d.removed(), 0, "{parts} slabs: no fluid leaves the closed tank");
        // each probe within SPREADS × its own spread, at least SPREADS roundings of its largest
        // reading (the surge front's spread is 0: a position, where no order change moved the
        // farthest particle)
        let worst = largest(
            probe_gap
                .iter()
                .zip(&probe_bounds)
                .map(|(gap, bound)| gap / bound),
            0.0,
        );
        for ((name, gap), bound) in names.iter().zip(&probe_gap).zip(&probe_bounds) {
            assert!(
                gap <= bound,
                "{parts} slabs: probe {name} reads {gap:.3e} from the whole domain's, more than {bound:.3e} ({SPREADS} × the order's spread)"
            );
        }
        record(Record {
            id: format!("emps-slabs-{parts}-probes-vs-undivided"),
            capability: "probes read by the slabs (pressure, gauges, a filtered wall sensor, surge front, run-up)".into(),
            reference: "the undivided run's probe rows from the same start".into(),
            case: "tilted dam break of emps-slabs-2-vs-undivided, 7 probes, a pressure probe 5 mm each side of the first cut".into(),
            resolution: format!("E-MPS, Δs = 0.02 m, {STEPS} steps, a row every {ROW_EVERY} steps, {parts} slabs"),
            measure: "largest |reading_slabs − reading_undivided| over rows and probes, in units of each probe's bound".into(),
            value: worst,
            bound: Some(1.0),
            bound_source: format!("each probe: {SPREADS} × the spread of its readings in the undivided run with its particles stored in reverse order, at least {SPREADS} roundings (2.2e-16) of its largest reading"),
            unit: "1".into(),
            source: "fluid-solver/tests/ranks.rs::slabs_step_as_the_whole_domain_within_its_round_off_spread".into(),
            run_time_s: started.elapsed().as_secs_f64(),
            ..Default::default()
        });
        let cuts: Vec<f64> = d.parts().iter().skip(1).map(|s| s.lo).collect();
        let gap = largest_gap(&reference, &by_id(&d.fluid()));
        let moved = d.handed_over();
        println!(
            "{parts} slabs (cuts at x = {cuts:?}): {moved} particles handed over, largest gap {gap:.3e} m"
        );
        // a lattice plane of the column holds 3 × 12 particles: at least one plane crosses each cut
        assert!(
            moved >= 36 * (parts as u64 - 1),
            "{parts} slabs: only {moved} particles crossed a cut"
        );
        positions_within_the_spread(Positions {
            id: format!("emps-slabs-{parts}-vs-undivided"),
            capability: "E-MPS fluid in slabs with halos (the decomposition of MPI ranks)",
            case: "tilted dam break: 1.6 × 0.06 × 0.3 m tank, column 1.2 × 0.24 m (2 160 fluid particles), gravity 6 m/s² along x",
            resolution: format!("E-MPS, Δs = 0.02 m, {STEPS} steps, {parts} slabs ({moved} particles handed over)"),
            test: "slabs_step_as_the_whole_domain_within_its_round_off_spread",
            gap,
            spread,
            started,
        });
    }
}

/// A dam break that moves the fluid's mass along x: a 2.0 × 0.06 × 0.4 m tank with a lid, a
/// column 0.8 m long and 0.3 m high at its left end (1 800 fluid particles at Δs = 0.02 m), the
/// two slabs first cut at x = 0.4 m, gravity leaning 20 m/s² towards +x. As the column slides and
/// collapses the right slab fills and the cut follows the water (to x = 0.46 m at step 150). A
/// pressure probe and a filtered sensor on the floor at x = 0.43 m change their reader when the
/// cut passes them; the surge front is read by both slabs.
pub(crate) const DAM: &str = r#"[case]
name = "slab-dam-break"
end_time = 0.1

[fluid.water]
spacing = 0.02
time_step = 5.0e-4
sound_speed = 12.1
gravity = [20.0, 0.0, -9.8]
output_interval = 0.1
probe_interval = 0.005
tank = { min = [0.0, 0.0, 0.0], max = [2.0, 0.06, 0.4], lid = true }

[[fluid.water.block]]
min = [0.0, 0.0, 0.0]
max = [0.8, 0.06, 0.3]

[[fluid.water.probe]]
name = "p-floor"
kind = "pressure"
position = [0.43, 0.03, 0.03]

[[fluid.water.probe]]
name = "floor-sensor"
kind = "wall-pressure"
position = [0.43, 0.03, 0.0]
normal = "+z"
diameter = 0.04
window = 0.005

[[fluid.water.probe]]
name = "front"
kind = "surge-front"
axis = "x"
"#;

/// Steps of [`DAM`]: 0.1 s.
const DAM_STEPS: usize = 200;

/// [`DAM`]'s fluid section.
pub(crate) fn dam() -> FluidConfig {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("slab-dam-break.toml");
    let case = Case::parse(&path, DAM.to_string()).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["water"].clone()
}

/// Slabs cut again as the water moves ([`fluid_solver::ranks::rebalance`]): in the dam break the
/// cut follows the collapsing column, every particle stays within the round-off spread of the
/// undivided run, each probe's readings too (the point probes change reader as the cut passes
/// them, the filtered sensor with its window's readings), and after the last cut the slabs hold
/// equal shares within the limit.
#[test]
fn slabs_cut_again_as_a_dam_break_moves_stay_within_the_undivided_runs_spread() {
    let cfg = dam();
    let started = std::time::Instant::now();
    let (reference, reference_rows) = whole(&cfg, false, DAM_STEPS);
    let (reversed, reversed_rows) = whole(&cfg, true, DAM_STEPS);
    let reference = by_id(reference.particles());
    let spread = largest_gap(&reference, &by_id(reversed.particles()));
    let probe_spread = probe_gaps(&reference_rows, &reversed_rows);
    let mut d = DecomposedFluid::new(&cfg, 2).unwrap_or_else(|e| panic!("{e}"));
    let first_cut = d.cuts()[1];
    let mut rows = Vec::new();
    let mut cut_at = Vec::new();
    for k in 1..=DAM_STEPS {
        d.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
        d.observe_probes(next_row(k, cfg.time_step));
        if k % ROW_EVERY == 0 {
            rows.push(d.probe_row());
        }
        if cut_at.last() != Some(&d.cuts()[1]) {
            cut_at.push(d.cuts()[1]);
        }
    }
    let owned: Vec<u64> = d.parts().iter().map(|s| s.owned_count()).collect();
    let gap = largest_gap(&reference, &by_id(&d.fluid()));
    let probe_gap = probe_gaps(&reference_rows, &rows);
    println!(
        "cut at x = {cut_at:?} ({} cuts again); owned {owned:?}; gap {gap:.3e} m (spread {spread:.3e} m); probes {probe_gap:?} (spread {probe_spread:?})",
        d.recuts()
    );
    assert!(
        d.recuts() >= 1,
        "the slabs are cut again as the column collapses: {cut_at:?}"
    );
    assert!(
        first_cut < 0.43 && d.cuts()[1] > 0.43,
        "the cut passes the point probes at x = 0.43 m: {cut_at:?}"
    );
    let total: u64 = owned.iter().sum();
    assert_eq!(total, 1800, "each particle owned once");
    // the last step is a count's (200 is a multiple of CHECK_EVERY): the slabs are within the
    // limit, or were cut again there into shares equal to a bin's particles
    assert!((DAM_STEPS as u64).is_multiple_of(rebalance::CHECK_EVERY));
    assert!(
        rebalance::imbalance(&owned) <= rebalance::LIMIT,
        "the slabs hold near-equal shares after the last count: {owned:?}"
    );
    for (k, (gap, spread)) in probe_gap.iter().zip(&probe_spread).enumerate() {
        let scale = largest(reference_rows.iter().map(|r| r[k].abs()), 0.0);
        let bound = SPREADS * largest([*spread], f64::EPSILON * scale);
        assert!(
            gap <= &bound,
            "probe {k} reads {gap:.3e} off the undivided run's, more than {bound:.3e}"
        );
    }
    positions_within_the_spread(Positions {
        id: "emps-slabs-2-cut-again-vs-undivided".into(),
        capability: "E-MPS fluid in slabs cut again as the water moves (rebalancing by fluid count)",
        case: "dam break on a tilted tank: 2.0 × 0.06 × 0.4 m, column 0.8 × 0.3 m (1 800 fluid particles), gravity 20 m/s² along x, 0.1 s",
        resolution: format!(
            "E-MPS, Δs = 0.02 m, {DAM_STEPS} steps, 2 slabs cut again {} times (the cut from x = {first_cut} m to {:.2} m)",
            d.recuts(),
            d.cuts()[1]
        ),
        test: "slabs_cut_again_as_a_dam_break_moves_stay_within_the_undivided_runs_spread",
        gap,
        spread,
        started,
    });
}

/// A channel 3.8 m long at Δs = 0.05 m (4 × 4 particles of water across, 0.2 m deep): a strip
/// feeds water in at 0.5 m/s through the plane x = 0.4 m and water leaves behind x = 3.4 m;
/// gravity leans 3 m/s² towards +x (½ 3 t² = 0.24 m by 0.4 s), so the water crosses the cuts. Two
/// slabs cut it at 1.9 m, three at 1.4 and 2.4 m: every boundary more than the halo (8.0 Δs = 0.4 m, the viscous term off)
/// from the nearest cut.
pub(crate) const CHANNEL: &str = r#"[case]
name = "slab-channel"
end_time = 1.0

[fluid.water]
spacing = 0.05
time_step = 2.0e-3
viscosity_term = false
gravity = [3.0, 0.0, -9.8]
output_interval = 0.1
tank = { min = [0.0, 0.0, 0.0], max = [3.8, 0.2, 0.5] }

[fluid.water.inflow]
plane = 0.4
velocity = 0.5
strip_length = 0.3
level = 0.2

[fluid.water.outflow]
plane = 3.4

[[fluid.water.block]]
min = [0.4, 0.0, 0.0]
max = [3.4, 0.2, 0.2]
"#;

/// Inflow and outflow across the cuts: the first slab feeds the water in, the last one lets it
/// out, and the fluid in between crosses the cuts; the counts close exactly (the fluid the slabs
/// own is what was there and entered less what the outflow removed), they equal the undivided
/// run's, the ids stay unique, and every particle stays within the round-off spread of the
/// undivided run, as the closed tank's.
#[test]
fn inflow_and_outflow_run_in_the_end_slabs_and_the_balance_closes_exactly() {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("slab-channel.toml");
    let case = Case::parse(&path, CHANNEL.to_string()).unwrap_or_else(|e| panic!("{e}"));
    let cfg = case.fluid["water"].clone();
    let started = std::time::Instant::now();
    let (reference, _) = whole(&cfg, false, STEPS);
    let (reversed, _) = whole(&cfg, true, STEPS);
    let expected = reference.open_boundaries().balance();
    let at_start = FluidSolver::new(&cfg)
        .particles()
        .count(fluid_solver::Kind::Fluid) as u64;
    let reference_fluid = by_id(reference.particles());
    let spread = largest_gap(&reference_fluid, &by_id(reversed.particles()));
    println!(
        "undivided: {expected:?}, {at_start} fluid at the start; reversed order's spread {spread:.3e} m"
    );
    assert!(
        expected.entered > 0 && expected.removed > 0,
        "water must enter and leave: {expected:?}"
    );
    for parts in [2, 3] {
        let mut d = DecomposedFluid::new(&cfg, parts).unwrap_or_else(|e| panic!("{e}"));
        for _ in 0..STEPS {
            d.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
        }
        let b = d.balance();
        let fluid = d.fluid();
        let mut ids = fluid.id.clone();
        ids.sort_unstable();
        ids.dedup();
        let gap = largest_gap(&reference_fluid, &by_id(&fluid));
        println!(
            "{parts} slabs: {b:?}, {} fluid owned, {} handed over, largest gap {gap:.3e} m",
            d.fluid_count(),
            d.handed_over()
        );
        assert_eq!(ids.len(), fluid.len(), "{parts} slabs: a fluid id is owned twice");
        assert_eq!(
            d.fluid_count(),
            at_start + b.entered - b.removed,
            "{parts} slabs: the fluid owned is not what was there and entered less what left: {b:?}"
        );
        assert_eq!(
            b, expected,
            "{parts} slabs: the counts differ from the undivided run's"
        );
        assert!(
            d.handed_over() >= 16 * (parts as u64 - 1),
            "{parts} slabs: less than a lattice plane crossed the cuts: {}",
            d.handed_over()
        );
        positions_within_the_spread(Positions {
            id: format!("emps-slabs-{parts}-inflow-outflow-vs-undivided"),
            capability: "inflow and outflow with the fluid in slabs (the first runs the inflow, the last the outflow)",
            case: "channel 3.8 × 0.2 m, water 0.2 m deep fed at 0.5 m/s through x = 0.4 m and let out behind x = 3.4 m, gravity 3 m/s² along x",
            resolution: format!("E-MPS, Δs = 0.05 m, {STEPS} steps, {parts} slabs ({} entered, {} removed, all equal to the undivided run's)", b.entered, b.removed),
            test: "inflow_and_outflow_run_in_the_end_slabs_and_the_balance_closes_exactly",
            gap,
            spread,
            started,
        });
    }
}

/// A slab's state kept and restored, as an implicit coupling window does on each rank
/// (`rank_participant.rs`): after 60 steps in which fluid crossed the cut, the slabs restored
/// to their state before them step the same 60 steps again to the same bits, each particle
/// owned once. (A restore that kept the later ownership heals in the first exchange: a particle
/// that crossed is a halo copy on the other side, exact to the bit, and goes back to the slab
/// it lies in; the slabs restore the ownership with the particles all the same.)
#[test]
fn slabs_restored_after_fluid_crossed_their_cut_step_again_to_the_same_bits() {
    let cfg = tank();
    let mut d = DecomposedFluid::new(&cfg, 2).unwrap_or_else(|e| panic!("{e}"));
    let steps = |d: &mut DecomposedFluid, n: usize| {
        for _ in 0..n {
            d.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
        }
    };
    steps(&mut d, 60);
    let saved = d.save();
    let (handed, time) = (d.handed_over(), d.time());
    steps(&mut d, 60);
    let first = by_id(&d.fluid());
    let crossed = d.handed_over() - handed;
    assert!(crossed > 0, "fluid crosses the cut in the steps repeated");
    d.restore(&saved);
    assert_eq!(d.time(), time, "the clock goes back");
    steps(&mut d, 60);
    let again = by_id(&d.fluid());
    println!(
        "{crossed} particles crossed the cut; again: {} fluid particles",
        again.len()
    );
    assert_eq!(d.fluid_count(), first.len() as u64, "each particle owned once");
    assert_eq!(largest_gap(&first, &again), 0.0, "the same bits");
}

/// [`TANK`] with a box body 0.2 m long on its floor under the water, across the cut of two slabs
/// (x = 0.6 m), pressed down into the floor at 2 cm/s: the water's loads on it and, once its
/// particles come closer than Δs to the floor's, the floor's contact.
fn tank_with_a_body() -> FluidConfig {
    let column = "[[fluid.water.block]]\nmin = [0.0, 0.0, 0.0]\nmax = [1.2, 0.06, 0.24]\n";
    let around = "[[fluid.water.body]]\nname = \"box\"\nmin = [0.5, 0.0, 0.0]\nmax = [0.7, 0.06, 0.08]\n\n\
                  [[fluid.water.block]]\nmin = [0.0, 0.0, 0.0]\nmax = [0.5, 0.06, 0.24]\n\n\
                  [[fluid.water.block]]\nmin = [0.7, 0.0, 0.0]\nmax = [1.2, 0.06, 0.24]\n\n\
                  [[fluid.water.block]]\nmin = [0.5, 0.0, 0.08]\nmax = [0.7, 0.06, 0.24]\n";
    assert!(TANK.contains(column), "ranks.rs' tank has changed its column");
    let text = TANK.replace(column, around);
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("slabs-body.toml");
    let case = Case::parse(&path, text).unwrap_or_else(|e| panic!("{e}"));
    case.fluid["water"].clone()
}

/// The box's pose and velocity at time `t` (sinking at 2 cm/s from its place at rest).
fn sinking(t: f64) -> ([f64; 7], [f64; 6]) {
    let w = -0.02;
    (
        [0.6, 0.03, 0.04 + w * t, 1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, w, 0.0, 0.0, 0.0],
    )
}

/// The undivided tank with the sinking box: its loads after each step, first with its particles
/// stored in reverse order when `reversed`.
fn body_loads_whole(cfg: &FluidConfig, reversed: bool) -> Vec<Vec<f64>> {
    let mut s = FluidSolver::new(cfg);
    s.remove_gates();
    if reversed {
        store_in_reverse(&mut s);
    }
    let dt = cfg.time_step;
    (1..=STEPS)
        .map(|k| {
            let (pose, velocity) = sinking(k as f64 * dt);
            s.set_body_motion(&pose, &velocity, dt)
                .unwrap_or_else(|e| panic!("{e}"));
            s.step(dt).unwrap_or_else(|e| panic!("{e}"));
            s.body_loads()
        })
        .collect()
}

/// The largest difference of the loads' components over the steps.
fn load_gap(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    largest(
        a.iter()
            .zip(b)
            .flat_map(|(x, y)| x.iter().zip(y).map(|(u, v)| (u - v).abs())),
        0.0,
    )
}

/// A body across a cut: every slab holds all of its particles and reports the loads from the
/// fluid it owns and the floor's contact on the particles between its cuts, so the slabs' loads
/// add up to the undivided run's within the round-off spread of the same loads (the undivided
/// run with its particles stored in reverse order), and the reaction balances them.
#[test]
fn a_body_across_a_cut_takes_the_undivided_runs_loads() {
    let cfg = tank_with_a_body();
    let started = std::time::Instant::now();
    let reference = body_loads_whole(&cfg, false);
    let spread = load_gap(&reference, &body_loads_whole(&cfg, true));
    let scale = largest(reference.iter().flat_map(|l| l.iter().map(|v| v.abs())), 0.0);
    let last = reference.last().cloned().unwrap_or_default();
    println!(
        "undivided: last loads {last:?}; reversed order's spread {spread:.3e} (largest component {scale:.3})"
    );
    assert!(
        last[2] > 1.0,
        "the floor's contact pushes the sinking box up: {last:?}"
    );
    let bound = SPREADS * largest([spread], f64::EPSILON * scale);
    let dt = cfg.time_step;
    // two slabs: a third would be thinner than the halo (the box takes the column's water)
    let parts = 2;
    let mut d = DecomposedFluid::new(&cfg, parts).unwrap_or_else(|e| panic!("{e}"));
    let mut worst_balance: f64 = 0.0;
    let loads: Vec<Vec<f64>> = (1..=STEPS)
        .map(|k| {
            let (pose, velocity) = sinking(k as f64 * dt);
            d.set_body_motion(&pose, &velocity, dt)
                .unwrap_or_else(|e| panic!("{e}"));
            d.step(dt).unwrap_or_else(|e| panic!("{e}"));
            let (l, r) = (d.body_loads(), d.body_reactions());
            worst_balance = largest(
                l.iter()
                    .zip(&r)
                    .map(|(a, b)| (a + b).abs())
                    .chain([worst_balance]),
                0.0,
            );
            l
        })
        .collect();
    let gap = load_gap(&reference, &loads);
    println!("{parts} slabs: largest load difference {gap:.3e} (bound {bound:.3e}); worst |load + reaction| {worst_balance:.3e}");
    record(Record {
        id: format!("emps-slabs-{parts}-body-loads-vs-undivided"),
        capability: "resolved bodies with the fluid in slabs (each slab's loads from the fluid it owns)".into(),
        reference: "the undivided run's loads from the same start".into(),
        case: "tilted dam break of emps-slabs-2-vs-undivided with a 0.2 × 0.06 × 0.08 m box on the floor across the first cut, pressed into the floor at 2 cm/s".into(),
        resolution: format!("E-MPS, Δs = 0.02 m, {STEPS} steps, {parts} slabs"),
        measure: "largest |load_slabs − load_undivided| over the steps and the 6 components".into(),
        value: gap,
        bound: Some(bound),
        bound_source: format!("{SPREADS} × the spread of the same loads in the undivided run with its particles stored in reverse order ({spread:.1e})"),
        unit: "N, N m".into(),
        source: "fluid-solver/tests/ranks.rs::a_body_across_a_cut_takes_the_undivided_runs_loads".into(),
        run_time_s: started.elapsed().as_secs_f64(),
        ..Default::default()
    });
    assert!(
        gap <= bound,
        "{parts} slabs: the loads differ by {gap:.3e}, more than {bound:.3e}"
    );
    assert!(
        worst_balance <= 1e-9 * scale,
        "{parts} slabs: the reaction does not balance the loads: {worst_balance:e}"
    );
}

#[test]
fn slabs_thinner_than_the_halo_and_unsupported_scenes_are_refused() {
    let cfg = tank();
    let e = DecomposedFluid::new(&cfg, 6).err().unwrap_or_default();
    assert!(
        e.contains("use fewer slabs"),
        "six slabs of 0.2 m against a 0.222 m halo: {e}"
    );
    let mut isph = cfg.clone();
    isph.method = schemas::case::fluid::FluidMethodName::Isph;
    let e = DecomposedFluid::new(&isph, 2).err().unwrap_or_default();
    assert!(e.contains("not yet method = \"isph\""), "{e}");
}
