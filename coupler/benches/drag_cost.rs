//! Cost of the unresolved drag coupling against the fluid step (issue 13: under 10 % for
//! 10 000 sub-members): the drag law (coupler), the sampling and the spreading (fluid), on the
//! dam-break tank of `cases/dam-break-tank` (Δs = 0.01 m) at t = 0.3 s, with 336 vertical
//! columns 0.3 m high over the whole tank floor, cut into 10 080 sub-members of one Δs, wet
//! and dry alike.
//!
//! Per coupling window of one fluid step (samples = 1) the stack evaluates the law 4 times (two
//! participants × two window times), samples once (the window end; the window start repeats
//! the last window's end samples) and spreads once (every fluid step). As in the fluid
//! participant, the sampling also finds the shares of the window's reactions and the next
//! step's spreading reuses them (the particles have not moved, the columns are fixed);
//! `DRAG_COST_REUSE=0` spreads by searching the cell list again. `cargo bench -p coupler --bench drag_cost`.
//!
//! `DRAG_COST_AT` (s, default 0.3) and `DRAG_COST_REPS` (default 15) shorten it, e.g. to count
//! instructions under `valgrind --tool=callgrind` (wall times on a shared machine are noisy);
//! `DRAG_COST_ONLY` = law, sampling, spreading or step runs that part alone (the difference of
//! two instruction counts with different `DRAG_COST_REPS` is then that part's count). It
//! prints a digest of the last samples and spread forces (FNV-1a of their bits): a faster
//! sampling or spreading must leave it unchanged.

use coupler::laws::drag::{Drag, DragSettings};
use coupler::laws::Law;
use fluid_solver::FluidSolver;
use schemas::case::drag::square_prism_drag;
use schemas::case::Case;
use schemas::message::{Fields, Geometry};
use schemas::F64s;
use std::path::PathBuf;
use std::time::Instant;

/// Wall time [ms] of one run of `f`.
fn time_ms(f: impl FnOnce()) -> f64 {
    let s = Instant::now();
    f();
    s.elapsed().as_secs_f64() * 1e3
}

/// The median of `v`.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// FNV-1a over the bits of `values`: equal outputs to the last bit give equal digests.
fn bits_digest<'a>(values: impl Iterator<Item = &'a f64>) -> u64 {
    values.fold(0xcbf2_9ce4_8422_2325, |h, v| {
        v.to_bits()
            .to_le_bytes()
            .iter()
            .fold(h, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
    })
}

fn main() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../cases/dam-break-tank/case.toml");
    let case = Case::load(&path).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(2)
    });
    let Some(cfg) = case.fluid.get("tank") else {
        eprintln!("error: {} has no [fluid.tank]", path.display());
        std::process::exit(2)
    };
    let threads = rayon::current_num_threads();
    let env = |name: &str, default: f64| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(default)
    };
    let at = env("DRAG_COST_AT", 0.3);
    let mut solver = FluidSolver::new(cfg);
    if let Err(e) = solver.advance_to(at) {
        eprintln!("error: {e}");
        std::process::exit(1)
    }
    // Columns: 14 × 24 over the floor, 0.3 m high, each one member.
    let (mut positions, mut members) = (Vec::new(), Vec::new());
    for i in 0..14 {
        for j in 0..24 {
            let (x, y) = (0.02 + 0.04 * f64::from(i), 0.01 + 0.0187 * f64::from(j));
            let n = (positions.len() / 3) as u32;
            positions.extend_from_slice(&[x, y, 0.0, x, y, 0.3]);
            members.extend_from_slice(&[n, n + 1]);
        }
    }
    let nodes = positions.len() / 3;
    let count = members.len() / 2;
    let geometry = Geometry {
        member_nodes: members,
        member_width: F64s(vec![0.002; count]),
        member_area: F64s(vec![4e-6; count]),
    };
    let structure = Fields {
        node_position: F64s(positions),
        node_velocity: F64s::zeros(6 * nodes),
        ..Fields::default()
    };
    let settings = DragSettings {
        density: cfg.density,
        gravity: cfg.gravity,
        width: None,
        sub_member_length: cfg.spacing,
        initial_flow: Some([1.0, 0.0, 0.0]),
        section_axis: None,
        axial_drag: false,
        drag_coefficient: square_prism_drag(),
    };
    let mut law = Drag::new(settings, 0, 1, nodes);
    if let Err(e) = law.geometry(1, &geometry, &structure) {
        eprintln!("error: {e}");
        std::process::exit(1)
    }
    let subs = law.sub_members().len();
    let points: Vec<f64> = law
        .evaluate(&structure, &Fields::default())
        .iter()
        .flat_map(|l| l.sample_point.iter().copied())
        .collect();
    let reuse = std::env::var("DRAG_COST_REUSE").map_or(true, |v| v != "0");
    let (v, lambda) = solver.sample_points(&points);
    let fluid = Fields {
        sampled_velocity: F64s(v),
        sampled_lambda_min: F64s(lambda),
        ..Fields::default()
    };
    let loads = law.evaluate(&structure, &fluid);
    let wet = loads.iter().filter(|l| l.force.norm() > 0.0).count();
    let reactions: Vec<f64> = loads
        .iter()
        .flat_map(|l| l.centroid.iter().copied().chain(l.force.iter().map(|f| -f)))
        .collect();
    // the members' widths, as the law sends them (2 mm: points, S2-24)
    let widths: Vec<f64> = law.sub_members().iter().map(|s| s.width).collect();
    if reuse {
        // the shares of these reactions, as the window end's sampling finds them (the parts run
        // alone, DRAG_COST_ONLY, spread with them; run together, each repetition's sampling does)
        solver.sample_points_for(&points, &reactions, &widths);
    }
    // The parts are timed in turn within each repetition, so a busy machine slows them alike.
    let reps = env("DRAG_COST_REPS", 15.0).max(1.0) as usize;
    let dt = cfg.time_step;
    let mut times = vec![Vec::new(); 4];
    let only = std::env::var("DRAG_COST_ONLY").ok();
    let runs = |part: &str| only.as_deref().is_none_or(|o| o == part);
    let mut timed = |k: usize, part: &str, f: &mut dyn FnMut()| {
        if runs(part) {
            times[k].push(time_ms(f));
        } else {
            times[k].push(f64::NAN);
        }
    };
    for _ in 0..reps {
        timed(0, "law", &mut || {
            std::hint::black_box(law.evaluate(&structure, &fluid));
        });
        timed(1, "sampling", &mut || {
            if reuse {
                std::hint::black_box(solver.sample_points_for(&points, &reactions, &widths));
            } else {
                std::hint::black_box(solver.sample_points(&points));
            }
        });
        timed(2, "spreading", &mut || {
            std::hint::black_box(solver.spread_point_reactions(&reactions, &points, &widths));
        });
        timed(3, "step", &mut || {
            if let Err(e) = solver.step(dt) {
                eprintln!("error: {e}");
                std::process::exit(1)
            }
        });
    }
    // outputs that a faster sampling or spreading must keep to the last bit
    let (v, lambda) = if reuse {
        solver.sample_points_for(&points, &reactions, &widths)
    } else {
        solver.sample_points(&points)
    };
    let spread = solver.spread_point_reactions(&reactions, &points, &widths);
    let digest = bits_digest(v.iter().chain(&lambda).chain(&spread.force).chain(&spread.total));
    let [law_ms, sample_ms, spread_ms, step_ms] = [0, 1, 2, 3].map(|k| median(times[k].clone()));
    let window = 4.0 * law_ms + sample_ms + spread_ms;
    println!(
        "Drag coupling cost, dam-break tank Δs = {} m at t = {at} s ({} particles), {threads} threads, median of {reps}:",
        cfg.spacing,
        solver.particles().len()
    );
    println!(
        "  sub-members {subs} ({wet} wet); particles' drift from their cells since the sort {:.3} Δs; shares {}",
        solver.cell_grid().drift(solver.particles()) / cfg.spacing,
        if reuse { "found while sampling, reused" } else { "searched again by the spreading" }
    );
    println!("  digest of the last samples and spread forces (bits, FNV-1a): {digest:016x}");
    println!(
        "{:>34} {:>10} {:>8} {:>12}",
        "part", "ms", "× window", "% of step"
    );
    for (name, ms, times) in [
        ("drag law (coupler, per evaluation)", law_ms, 4.0),
        ("sampling (fluid, per window end)", sample_ms, 1.0),
        ("spreading (fluid, per step)", spread_ms, 1.0),
    ] {
        println!(
            "{name:>34} {ms:>10.3} {times:>8} {:>12.2}",
            100.0 * times * ms / step_ms
        );
    }
    println!("{:>34} {step_ms:>10.3}", "fluid step (E-MPS, no coupling)");
    println!(
        "{:>34} {window:>10.3} {:>8} {:>12.2}",
        "coupling per window",
        "",
        100.0 * window / step_ms
    );
}
