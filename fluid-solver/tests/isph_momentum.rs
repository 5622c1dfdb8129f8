//! ISPH's momentum budget (issue 12): the fluid's momentum change against gravity's impulse and
//! the impulse of the walls and bodies as the solver books it (`wall_impulse`: the walls'
//! symmetric pressure pair law, the bodies' face law reversed, the viscous and collision pair
//! terms).
//!
//! E-MPS closes this budget to round-off (`conservation.rs`, `bodies_momentum.rs`): its pressure
//! gradient S1-3 is a sum of antisymmetric pair terms. ISPH's is not: S2-8's difference form
//! `Σ_j V (p_j − p_i) ∇W_ij` (corrected by the moment matrix) is symmetric in the pair, so the
//! fluid–fluid terms do not cancel, and no pair law for the walls or bodies can be the reaction
//! of what the fluid feels; the fluid carries its own weight by those internal terms. What is
//! checked here is what holds: at rest the walls' law carries the weight, and the load the
//! bodies get is exactly what the fluid's budget books for them. The gap of the whole budget
//! in motion is measured and printed; `isph_momentum_budget_closes_in_motion` is the open
//! criterion.
//!
//! Measured (gap = Δp − gravity − walls, z, against the gravity impulse):
//! - tank at rest, 0.2 s: −4.3e-3 of 23.5 N s (1.8e-4);
//! - a 12 cm block dropped 10 cm onto the floor of a closed box, 0.4 s: +2.37 of 6.78 N s
//!   (35 %): the walls' law books 4.25 N s where E-MPS's walls give 6.68 N s in the same scene,
//!   and the fluid's momentum ends near E-MPS's (−0.16 against −0.09 N s);
//! - an 8 cm cube thrown at 1.5 m/s onto a fixed box, 0.09 s: the box's loads and the booked
//!   impulse agree (1.666 N s), but the fluid's momentum changed by only 1.115 N s more than
//!   gravity's impulse: gap −0.55 N s of 0.45 N s (E-MPS, `bodies_momentum.rs`: 1.21 N s by
//!   0.1 s, both ways). The face law's pressure × area is more than the difference-form gradient
//!   takes out of the fluid.

mod bodies_common;
mod common;

use bodies_common::tank_with_body;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{Aabb, FluidConfig, FluidMethodName, IsphConfig, TankConfig};

fn isph(mut cfg: FluidConfig) -> FluidConfig {
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(IsphConfig::default());
    cfg.sound_speed = None;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// The hydrostatic tank of `isph.rs`: water 0.3 m deep in a 0.2 × 0.2 m tank, Δs = 0.02 m,
/// Δt = 2e-3 s.
fn tank_at_rest() -> FluidConfig {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.4];
    cfg.block[0].max = [0.2, 0.2, 0.3];
    cfg.time_step = 2.0e-3;
    isph(cfg)
}

/// The closed box of `conservation.rs` with its 12 cm block held 10 cm above the floor, with
/// ISPH (Δt = 2e-3 s).
fn drop_on_the_floor() -> FluidConfig {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    cfg.spacing = 0.02;
    cfg.tank = TankConfig {
        min: [0.0; 3],
        max: [0.2, 0.2, 0.3],
        lid: true,
    };
    cfg.block = vec![Aabb {
        min: [0.04, 0.04, 0.1],
        max: [0.16, 0.16, 0.22],
    }];
    cfg.viscosity = 1.0e-4;
    cfg.viscosity_term = true;
    cfg.time_step = 2.0e-3;
    isph(cfg)
}

/// The scene of `bodies_momentum.rs` with ISPH (Δt = 2e-3 s): an 8 cm cube of water thrown
/// down at 1.5 m/s onto a 16 × 16 × 8 cm box held fixed; in 0.09 s it touches nothing else (at
/// 0.098 s its spill over the box's edge reaches the floor).
fn drop_on_a_box() -> FluidSolver {
    let body = Aabb {
        min: [0.12, 0.12, 0.04],
        max: [0.28, 0.28, 0.12],
    };
    let drop = Aabb {
        min: [0.16, 0.16, 0.16],
        max: [0.24, 0.24, 0.24],
    };
    let mut cfg = tank_with_body([0.4, 0.4, 0.4], 0.02, 8.0e-4, drop, body);
    cfg.viscosity_term = true;
    cfg.viscosity = 1.0e-3;
    cfg.time_step = 2.0e-3;
    let mut solver = FluidSolver::new(&isph(cfg));
    let fluid = Kind::Fluid.code();
    let p = solver.particles_mut();
    for i in (0..p.len()).filter(|&i| p.kind[i] == fluid) {
        p.vz[i] = -1.5;
    }
    solver
}

/// What one run to `t_end` gave: the budget's gap and the scale of gravity's impulse (N s), and
/// the impulse of the bodies' loads reversed (the reaction on the fluid).
struct Budget {
    gap: [f64; 3],
    scale: f64,
    walls: [f64; 3],
    body_reaction: [f64; 3],
}

fn run(solver: &mut FluidSolver, t_end: f64) -> Budget {
    let mass = solver.particles().count(Kind::Fluid) as f64 * solver.particle_mass();
    let g = solver.physics().gravity;
    let start = solver.fluid_momentum();
    let mut body_reaction = [0.0; 3];
    while let Some(dt) = solver.next_step_towards(t_end) {
        solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
        let r = solver.body_reactions();
        if !r.is_empty() {
            (0..3).for_each(|a| body_reaction[a] += r[a] * dt);
        }
    }
    let t = solver.time();
    let end = solver.fluid_momentum();
    let walls = solver.totals().wall_impulse;
    let gap = std::array::from_fn(|a| end[a] - start[a] - mass * g[a] * t - walls[a]);
    let scale = mass * g.iter().map(|v| v * v).sum::<f64>().sqrt() * t;
    println!(
        "momentum {start:?} → {end:?} N s; gravity {:?}; walls and bodies {walls:?}; bodies' loads reversed {body_reaction:?}; gap {gap:?} ({:.2e} of {scale:.3})",
        g.map(|v| mass * v * t),
        gap[2].abs() / scale
    );
    Budget {
        gap,
        scale,
        walls,
        body_reaction,
    }
}

/// At rest the budget is the walls' load against the weight: within 1e-3 of gravity's impulse
/// (a tenth of issue 12's 1 % bound on ρgh; measured 1.8e-4).
#[test]
fn isph_walls_carry_the_weight_of_water_at_rest() {
    let mut solver = FluidSolver::new(&tank_at_rest());
    let b = run(&mut solver, 0.2);
    for (a, gap) in b.gap.iter().enumerate() {
        assert!(
            gap.abs() < 1e-3 * b.scale,
            "axis {a}: budget gap {gap} N s of {} N s",
            b.scale
        );
    }
}

/// The load the box gets is what the fluid's budget books for it: with nothing else touched,
/// the booked impulse of walls and bodies is the bodies' loads reversed, to round-off, forces
/// by pressure (the face law), viscosity and collisions together. (Before the face law took
/// only the wet body particles, the box took 9.0 N s while the budget booked 0.82 N s.)
#[test]
fn isph_body_loads_are_the_reaction_the_fluid_is_booked_with() {
    let mut solver = drop_on_a_box();
    let b = run(&mut solver, 0.09);
    let hit = 0.5 * 0.512 * 1.5;
    assert!(
        b.body_reaction[2] > hit,
        "the box was hardly hit: {:?} N s",
        b.body_reaction
    );
    for a in 0..3 {
        assert!(
            (b.walls[a] - b.body_reaction[a]).abs() < 1e-9 * b.scale.max(hit),
            "axis {a}: booked {} N s, the box's loads reversed {} N s",
            b.walls[a],
            b.body_reaction[a]
        );
    }
}

/// The open criterion of issue 12: the budget in motion closes to round-off as E-MPS's does
/// (`conservation.rs`: 1e-9 of gravity's impulse). Fails with S2-8's pressure gradient (module
/// doc): gaps +2.37 N s of 6.77 (drop on the floor) and −0.55 N s of 0.45 (drop on a box).
/// Measured with the symmetric gradient `Σ_j V (p_i + p_j) ∇W_ij` (walls at p_i + Δp_ij,
/// bodies by the same pair term) instead: both close to 1e-15 of the scale, the box takes
/// 1.15 N s, the CI dam break's fronts improve (Koshizuka & Oka 0.124, Martin & Moyce 0.026),
/// but the hydrostatic tank's corner columns rise from 0.3 s (0.12 m/s at 0.5 s, the same at
/// Δt/2), as `isph::operators::pressure_gradient` records.
#[test]
#[ignore = "open (issue 12): S2-8's difference-form gradient is not antisymmetric"]
fn isph_momentum_budget_closes_in_motion() {
    let mut solver = FluidSolver::new(&drop_on_the_floor());
    let floor = run(&mut solver, 0.4);
    let body = run(&mut drop_on_a_box(), 0.09);
    for b in [floor, body] {
        for (a, gap) in b.gap.iter().enumerate() {
            assert!(
                gap.abs() < 1e-9 * b.scale,
                "axis {a}: budget gap {gap} N s of {} N s",
                b.scale
            );
        }
    }
}
