//! The fluid in slabs ([`fluid_solver::ranks`]) steps as the whole domain does: the dam-break
//! slab in 2 and 3 slabs along x against one solver, 150 steps, every fluid particle compared
//! by id. Decomposing changes only the order in which each particle's neighbour sums are added
//! (the halo holds every particle its step depends on), so the slabs must stay within the
//! round-off spread that the same change of order makes on one solver: the whole domain with its
//! particles stored in reverse order. Mass (the fluid's particle count) is exact.

use fluid_solver::particles::Particles;
use fluid_solver::ranks::decomposed::DecomposedFluid;
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
/// slabs of at least the halo (5 × 3.1 Δs + 2 Δs = 0.35 m). Gravity leans 6 m/s² towards +x (a
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
"#;

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

/// The whole domain after [`STEPS`] steps, its particles first stored in reverse order when
/// `reversed`.
fn whole(cfg: &FluidConfig, reversed: bool) -> HashMap<u32, [f64; 3]> {
    let mut s = FluidSolver::new(cfg);
    s.remove_gates();
    if reversed {
        let mut state = s.save_state();
        let n = state.particles.len() as u32;
        let order: Vec<u32> = (0..n).rev().collect();
        state.particles.permute(&order, &mut Vec::new());
        state.grid.sort(&mut state.particles, &mut Vec::new());
        s.restore_state(&state);
    }
    for _ in 0..STEPS {
        s.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
    }
    by_id(s.particles())
}

#[test]
fn slabs_step_as_the_whole_domain_within_its_round_off_spread() {
    let cfg = tank();
    let started = std::time::Instant::now();
    let reference = whole(&cfg, false);
    let spread = largest_gap(&reference, &whole(&cfg, true));
    println!("whole domain, reversed order: largest gap {spread:.3e} m after {STEPS} steps");
    assert!(
        spread < 1e-6,
        "the reversed order alone moved a particle by {spread} m"
    );
    for parts in [2, 3] {
        let mut d = DecomposedFluid::new(&cfg, parts).unwrap_or_else(|e| panic!("{e}"));
        for _ in 0..STEPS {
            d.step(cfg.time_step).unwrap_or_else(|e| panic!("{e}"));
        }
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
        record(Record {
            id: format!("emps-slabs-{parts}-vs-undivided"),
            capability: "E-MPS fluid in slabs with halos (the decomposition of MPI ranks)".into(),
            reference: "the undivided run from the same start".into(),
            case: "tilted dam break: 1.6 × 0.06 × 0.3 m tank, column 1.2 × 0.24 m (2 160 fluid particles), gravity 6 m/s² along x".into(),
            resolution: format!("E-MPS, Δs = 0.02 m, {STEPS} steps, {parts} slabs ({moved} particles handed over)"),
            measure: "largest |r_slabs − r_undivided| over the fluid particles".into(),
            value: gap,
            bound: Some(SPREADS * spread.max(1e-15)),
            bound_source: format!("{SPREADS} × the round-off spread of the undivided run with its particles stored in reverse order ({spread:.1e} m)"),
            unit: "m".into(),
            source: "fluid-solver/tests/ranks.rs::slabs_step_as_the_whole_domain_within_its_round_off_spread".into(),
            run_time_s: started.elapsed().as_secs_f64(),
            ..Default::default()
        });
        assert!(
            gap <= SPREADS * spread.max(1e-15),
            "{parts} slabs: a particle is {gap:.3e} m from the whole domain's, more than {SPREADS} × the order's spread {spread:.3e} m"
        );
    }
}

#[test]
fn slabs_thinner_than_the_halo_and_unsupported_scenes_are_refused() {
    let cfg = tank();
    let e = DecomposedFluid::new(&cfg, 4).err().unwrap_or_default();
    assert!(
        e.contains("use fewer slabs"),
        "four slabs of 0.3 m against a 0.35 m halo: {e}"
    );
    let mut isph = cfg.clone();
    isph.method = schemas::case::fluid::FluidMethodName::Isph;
    let e = DecomposedFluid::new(&isph, 2).err().unwrap_or_default();
    assert!(e.contains("not yet method = \"isph\""), "{e}");
}
