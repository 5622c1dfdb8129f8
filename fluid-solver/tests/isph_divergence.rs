//! ISPH (issue 12): the velocity divergence after the projection, term by term.
//!
//! One step of S2-3 … S2-5 (docs/physics.md §4) at the positions r^n: `v* = v^n + gΔt` (S2-3, the
//! viscous term off), the PPE (S2-5) `L p = (ρ/Δt) D(v*) + α_d ρ (1 − ρ̂/ρ0)/Δt² + r`, solved to
//! `|r| ≤ tol |b|` (b the solver's right-hand side, boundary data included), and the correction
//! (S2-4) `v^{n+1} = v* − (Δt/ρ) G p`, with
//! - D the divergence of S2-8 over fluid neighbours (walls enter the PPE as Neumann differences),
//!   corrected by the moment matrix as G is ([`fluid_solver::isph::operators::DivergenceSum`];
//!   with the symmetric gradient, uncorrected as G),
//! - G the pressure gradient the step moves the fluid by (S2-8's difference form corrected by the
//!   moment matrix, [`fluid_solver::isph::operators::pressure_gradient`]),
//! - L the PPE's Laplacian (S2-9) with the walls' Neumann differences and the surface's
//!   Dirichlet pressures.
//!
//! D is linear, so in every PPE row (a fluid particle off the free surface)
//! `D(v^{n+1}) = (Δt/ρ)(L − D∘G) p − α_d (1 − ρ̂/ρ0)/Δt − (Δt/ρ) r`.
//! The divergence left after the projection is not bounded by the PPE's tolerance alone: L is
//! not D∘G (S2-9's Laplacian is a one-pass pair sum, D∘G a two-pass one, and G is corrected),
//! and the mismatch term `(Δt/ρ)(L − D∘G) p` is computed here explicitly. The test checks, on
//! the real step of the solver:
//! 1. the step's v^{n+1} is `v* − (Δt/ρ) G p` (to round-off);
//! 2. the identity above in every PPE row (to round-off);
//! 3. the PPE part: `|r|₂ ≤ tol |b|₂` (the bound the solver promises) over the rows whose support
//!    holds no pressure the solver clamped to 0 (no tension: there L p is not the PPE's own);
//!    fewer than a tenth of the rows may have one;
//!
//! and prints the size of each term (RMS over the PPE rows, in 1/s) for the hydrostatic tank
//! and a dam break.
//!
//! Measured (RMS over the PPE rows, 1/s): hydrostatic tank at t = 0.1 s, D(v*) 4.1e-3 →
//! D(v^{n+1}) 4.1e-3 = mismatch 5.7e-3 + relaxation 1.6e-3 + residual 2.2e-7 (in the 360 rows
//! whose support holds neither a wall nor the surface: D(v*) 2.8e-4, mismatch 3.7e-4); CI dam
//! break at t = 0.15 s (a slab 4 particles deep: no row has a full fluid support), D(v*) 1.11 →
//! D(v^{n+1}) 1.02 = mismatch 1.08 + relaxation 0.15 + residual 9.1e-7 (no pressure clamped at
//! this step), and the collision stage then changes 390 of the 800 particles' velocities (bottom
//! layers closer than 0.8 Δs) and leaves 1.07. The projection removes almost none of the
//! divergence D measures: L and D∘G differ by as much as the PPE's right-hand side, so the
//! PPE's tolerance bounds only the residual's share, 1e-6 of it. (With D uncorrected, before 25
//! Nov 2026: dam break 1.08 → 1.06, mismatch 1.10.)
//!
//! With `pressure_gradient = "symmetric"` at 2.0 Δs (G the uncorrected symmetric sum; 24 Nov
//! 2026): tank D(v*) 8.6e-4 → D(v^{n+1}) 8.6e-4 = mismatch 9.9e-4 + relaxation 1.7e-4 +
//! residual 2.2e-7 (interior 1.5e-4); dam break D(v*) 2.80 → 2.95 = mismatch 2.96 + relaxation
//! 0.14 + residual 2.4e-6 (146 interior rows: 2.91 → 2.68), 3.00 after the collision stage: the
//! still water is 4.7× less divergent than with S2-8, the dam break 2.7× more (its gradient's
//! zero-order part moves particles that D reads as divergence; the PPE does not see it).

mod common;
mod isph_slab;

use fluid_solver::collision::COLLISION_DISTANCE;
use fluid_solver::isph::free_surface::{self, SURFACE};
use fluid_solver::isph::kernel::Wendland;
use fluid_solver::isph::neighbour_list::NeighbourList;
use fluid_solver::isph::operators;
use fluid_solver::isph::walls::{self, NeumannPair};
use fluid_solver::method::MethodState;
use fluid_solver::neighbour_search::CellGrid;
use fluid_solver::particles::Particles;
use fluid_solver::vector_field::VectorField;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{FluidConfig, FluidMethodName, IsphConfig, PressureGradient};
use std::collections::HashMap;

/// RMS over the PPE rows of each term of the identity [1/s].
#[derive(Debug)]
struct Terms {
    rows: usize,
    collided: usize,
    before: f64,
    after: f64,
    after_collisions: f64,
    /// Rows with neither a solid nor a surface particle in their support: their count and the
    /// RMS of D(v*), D(v^{n+1}) and the mismatch there.
    interior_rows: usize,
    interior: [f64; 3],
    predicted: f64,
    mismatch: f64,
    relaxation: f64,
    residual: f64,
}

fn isph(cfg: FluidConfig) -> FluidConfig {
    isph_with(cfg, IsphConfig::default())
}

/// `pressure_gradient = "symmetric"` at a support of 2.0 Δs.
fn symmetric(cfg: FluidConfig) -> FluidConfig {
    let settings = IsphConfig {
        influence_radius: 2.0,
        pressure_gradient: PressureGradient::Symmetric,
        ..IsphConfig::default()
    };
    isph_with(cfg, settings)
}

fn isph_with(mut cfg: FluidConfig, settings: IsphConfig) -> FluidConfig {
    cfg.method = FluidMethodName::Isph;
    cfg.isph = Some(settings);
    cfg.sound_speed = None;
    cfg.viscosity_term = false;
    cfg.validate("fluid.water").unwrap_or_else(|e| panic!("{e:?}"));
    cfg
}

/// Runs `cfg` to `t`, takes one more step and checks it term by term (module doc).
fn check_step(cfg: &FluidConfig, t: f64) -> Terms {
    let settings = cfg.isph.unwrap_or_default();
    let form = settings.pressure_gradient;
    let (rho, ds, g) = (cfg.density, cfg.spacing, cfg.gravity);
    let k = Wendland::new(ds, settings.influence_radius);
    let mut solver = FluidSolver::new(cfg);
    solver.advance_to(t).unwrap_or_else(|e| panic!("{e}"));
    let before = solver.particles().clone();
    let dt = cfg.time_step;
    solver.step(dt).unwrap_or_else(|e| panic!("{e}"));
    let after = solver.particles();
    let after_index: HashMap<u32, usize> = (0..after.len()).map(|i| (after.id[i], i)).collect();
    let MethodState::Isph(state) = solver.method_state() else {
        panic!("not an ISPH solver")
    };
    // The step's own result, by particle id: v^{n+1}, p, and whether the particle was a PPE row
    // (the flags after the step are the rows' complement among the fluid particles).
    let result: HashMap<u32, ([f64; 3], f64, bool)> = (0..after.len())
        .map(|i| {
            let row = after.kind[i] == Kind::Fluid.code() && state.surface[i] != SURFACE;
            (after.id[i], (after.velocity(i), after.pressure[i], row))
        })
        .collect();
    // The state the step worked on: r^n, v* = v^n + gΔt for the fluid, and the step's p.
    let mut q: Particles = before;
    for i in 0..q.len() {
        if q.kind[i] == Kind::Fluid.code() {
            q.vx[i] += g[0] * dt;
            q.vy[i] += g[1] * dt;
            q.vz[i] += g[2] * dt;
        }
        q.pressure[i] = result[&q.id[i]].1;
    }
    let d = solver.domain();
    let mut grid = CellGrid::new(d.lo, [d.hi[0], d.hi[1], d.hi[2].max(1.0)], ds);
    grid.sort(&mut q, &mut Vec::new());
    let mut list = NeighbourList::default();
    list.build(&grid, &q, &k);
    let n = q.len();
    let fluid = |i: usize| q.kind[i] == Kind::Fluid.code();
    let row = |i: usize| result[&q.id[i]].2;

    let (mut ratio, mut takes_part, mut lambda) = (Vec::new(), Vec::new(), Vec::new());
    operators::density_ratio(&k, &list, &q, &mut ratio);
    free_surface::fill_flags(&q, &ratio, &mut takes_part);
    free_surface::lambda_min(&k, &list, &q, &takes_part, &mut lambda);
    let mut normals = VectorField::default();
    walls::normals(&k, &list, &q, &mut normals);
    let mut depth = Vec::new();
    walls::depths(&k, &list, &q, &normals, &mut depth);
    let mut convex = Vec::new();
    walls::convex(&k, &list, &q, &mut convex);
    // The step's surface flags, in this sorted order (rows are the fluid that is not surface).
    let surface: Vec<u8> = (0..n)
        .map(|i| if fluid(i) && !row(i) { SURFACE } else { 0 })
        .collect();
    let pair = NeumannPair {
        density: rho,
        gravity: g,
        dt,
        p: &q,
        list: &list,
        normals: &normals,
        convex: &convex,
        surface: &surface,
        depth: &depth,
        spacing: ds,
    };
    let mut grad = VectorField::default();
    operators::pressure_gradient(
        &k,
        &list,
        &q,
        &pair,
        settings.pressure_gradient,
        &Default::default(),
        &mut grad,
    );

    // 1. The step's velocities are the projection's, v* − (Δt/ρ) G p, except where the
    // collision stage acted after it (a particle within its reach of another).
    let projected = |i: usize| {
        [
            q.vx[i] - dt / rho * grad.x[i],
            q.vy[i] - dt / rho * grad.y[i],
            q.vz[i] - dt / rho * grad.z[i],
        ]
    };
    let speed = (0..n)
        .filter(|&i| fluid(i))
        .flat_map(&projected)
        .fold(1e-3f64, |m, v| m.max(v.abs()));
    let reach = (COLLISION_DISTANCE + 0.05) * ds;
    let mut collided = 0;
    for i in (0..n).filter(|&i| fluid(i)) {
        let (v1, v) = (result[&q.id[i]].0, projected(i));
        if (0..3).all(|a| (v1[a] - v[a]).abs() <= 1e-12 * speed) {
            continue;
        }
        collided += 1;
        let k_after = after_index[&q.id[i]];
        let x = after.position(k_after);
        let close = (0..after.len()).any(|j| {
            let y = after.position(j);
            j != k_after && (0..3).map(|a| (x[a] - y[a]).powi(2)).sum::<f64>() < reach * reach
        });
        assert!(
            close,
            "particle {} moves at {v1:?} after the step, not at the projection's {v:?}, and no collision can have acted on it",
            q.id[i]
        );
    }

    // D(v*), D(v^{n+1}) and D(G p) with the one divergence operator.
    let (mut div_star, mut div_after, mut div_grad) = (Vec::new(), Vec::new(), Vec::new());
    operators::divergence(&k, &list, &q, form, &lambda, &mut div_star);
    let with_velocity = |v: &dyn Fn(usize) -> [f64; 3]| {
        let mut c = q.clone();
        for i in (0..n).filter(|&i| fluid(i)) {
            [c.vx[i], c.vy[i], c.vz[i]] = v(i);
        }
        c
    };
    let c = with_velocity(&projected);
    operators::divergence(&k, &list, &c, form, &lambda, &mut div_after);
    let mut div_step = Vec::new();
    let c = with_velocity(&|i| result[&q.id[i]].0);
    operators::divergence(&k, &list, &c, form, &lambda, &mut div_step);
    let c = with_velocity(&|i| [grad.x[i], grad.y[i], grad.z[i]]);
    operators::divergence(&k, &list, &c, form, &lambda, &mut div_grad);

    // L p (S2-9 with the walls' Neumann differences), b, and the solver's right-hand side.
    let alpha = settings.alpha_d;
    let (mut sums, mut r2, mut rhs2, mut step2, mut star2) = ([0.0f64; 5], 0.0, 0.0, 0.0, 0.0);
    let (mut interior, mut interior_rows) = ([0.0f64; 3], 0usize);
    let (mut rows, mut worst_identity, mut scale_identity) = (0, 0.0f64, 0.0f64);
    let mut near_clamped = 0usize;
    for i in (0..n).filter(|&i| row(i)) {
        let (mut lap, mut boundary, mut deep) = (0.0, 0.0, true);
        for &j in list.of(i) {
            let j = j as usize;
            let rij =
                ((q.x[j] - q.x[i]).powi(2) + (q.y[j] - q.y[i]).powi(2) + (q.z[j] - q.z[i]).powi(2)).sqrt();
            let f = -2.0 * k.volume * k.dw_over_r(rij);
            if fluid(j) {
                lap += f * (q.pressure[j] - q.pressure[i]);
                if !row(j) {
                    boundary += f * q.pressure[j];
                    deep = false;
                }
            } else {
                let dp = pair.difference(i, j);
                deep = false;
                lap += f * dp;
                boundary += f * dp;
            }
        }
        let b = rho / dt * div_star[i] + alpha * rho * (1.0 - ratio[i]) / (dt * dt);
        let r = lap - b;
        // The solver writes a negative PPE solution as 0 (no tension, `IsphStep::solve_ppe`):
        // L p then differs from the PPE's own in such a row and its neighbours, so only the
        // other rows measure the solver's residual.
        let clamped = |j: usize| row(j) && q.pressure[j] == 0.0;
        if clamped(i) || list.of(i).iter().any(|&j| clamped(j as usize)) {
            near_clamped += 1;
        } else {
            r2 += r * r;
            rhs2 += (boundary - b).powi(2);
        }
        // 2. The identity, term by term [1/s].
        let mismatch = dt / rho * (lap - div_grad[i]);
        let relaxation = -alpha * (1.0 - ratio[i]) / dt;
        let residual = -dt / rho * r;
        let predicted = mismatch + relaxation + residual;
        worst_identity = worst_identity.max((div_after[i] - predicted).abs());
        scale_identity = scale_identity
            .max(div_star[i].abs())
            .max(dt / rho * lap.abs())
            .max(dt / rho * div_grad[i].abs());
        for (s, v) in sums
            .iter_mut()
            .zip([div_after[i], predicted, mismatch, relaxation, residual])
        {
            *s += v * v;
        }
        step2 += div_step[i] * div_step[i];
        star2 += div_star[i] * div_star[i];
        if deep {
            interior[0] += div_star[i] * div_star[i];
            interior[1] += div_after[i] * div_after[i];
            interior[2] += mismatch * mismatch;
            interior_rows += 1;
        }
        rows += 1;
    }
    assert!(rows > 0, "no PPE rows");
    assert_eq!(rows, state.ppe.unknowns, "the rows are the solver's unknowns");
    assert!(
        worst_identity <= 1e-9 * scale_identity,
        "D(v^(n+1)) differs from (Δt/ρ)(L − D∘G)p − α(1 − ρ̂/ρ0)/Δt − (Δt/ρ)r by {worst_identity:e} 1/s (terms up to {scale_identity:e})"
    );
    // 3. The PPE's part, bounded by its tolerance (1 % for the different summation order).
    let relative = (r2 / rhs2).sqrt();
    println!(
        "PPE relative residual {relative:.3e} over the {} rows with no clamped pressure in their support (the solver's {:.3e}, tolerance {:.0e})",
        rows - near_clamped,
        state.ppe.residual,
        settings.ppe_tolerance
    );
    assert!(
        near_clamped * 10 < rows,
        "{near_clamped} of {rows} rows near a clamped pressure"
    );
    assert!(
        relative <= 1.01 * settings.ppe_tolerance,
        "PPE residual {relative:e} above its tolerance {:e}",
        settings.ppe_tolerance
    );
    let rms = |s: f64| (s / rows as f64).sqrt();
    Terms {
        rows,
        collided,
        before: rms(star2),
        after: rms(sums[0]),
        after_collisions: rms(step2),
        interior_rows,
        interior: interior.map(|v| (v / interior_rows.max(1) as f64).sqrt()),
        predicted: rms(sums[1]),
        mismatch: rms(sums[2]),
        relaxation: rms(sums[3]),
        residual: rms(sums[4]),
    }
}

fn report(name: &str, t: &Terms) {
    println!(
        "{name}: {} PPE rows; RMS [1/s]: D(v*) {:.3e}; D(v^(n+1)) {:.3e} = mismatch (Δt/ρ)(L − D∘G)p {:.3e} + relaxation {:.3e} + PPE residual {:.3e} (sum of the three {:.3e}); after the collision stage ({} particles changed) {:.3e}",
        t.rows, t.before, t.after, t.mismatch, t.relaxation, t.residual, t.predicted, t.collided, t.after_collisions
    );
    println!(
        "{name}: {} rows with a full fluid support: RMS D(v*) {:.3e}, D(v^(n+1)) {:.3e}, mismatch {:.3e} [1/s]",
        t.interior_rows, t.interior[0], t.interior[1], t.interior[2]
    );
}

/// The hydrostatic tank of `isph.rs` (1500 fluid particles, Δs = 0.02 m, Δt = 2e-3 s), the
/// step after t = 0.1 s.
#[test]
fn divergence_after_projection_in_the_hydrostatic_tank() {
    let terms = check_step(&isph(small_tank()), 0.1);
    report("hydrostatic tank", &terms);
    assert_eq!(
        terms.collided, 0,
        "water at rest: the collision stage acts on nothing"
    );
}

/// The same with the symmetric gradient at 2.0 Δs: G is then the uncorrected symmetric sum
/// (its zero-order part included), checked by the same identity.
#[test]
fn divergence_after_projection_in_the_hydrostatic_tank_with_the_symmetric_gradient() {
    let terms = check_step(&symmetric(small_tank()), 0.1);
    report("hydrostatic tank, symmetric gradient", &terms);
    assert_eq!(
        terms.collided, 0,
        "water at rest: the collision stage acts on nothing"
    );
}

fn small_tank() -> FluidConfig {
    let (_, mut cfg) = common::load_case("hydrostatic-tank");
    cfg.spacing = 0.02;
    cfg.tank.max = [0.2, 0.2, 0.4];
    cfg.block[0].max = [0.2, 0.2, 0.3];
    cfg.time_step = 2.0e-3;
    cfg
}

/// The CI dam break of `isph_dam_break.rs` (800 fluid particles, Δs = 0.0146 m, Δt = 1.6e-3 s),
/// the step after t = 0.15 s (the surge is half way to the far wall).
#[test]
fn divergence_after_projection_in_a_dam_break() {
    let terms = check_step(&isph(isph_slab::isph_slab()), 0.15);
    report("dam break", &terms);
}

/// The same dam break with the symmetric gradient at 2.0 Δs.
#[test]
fn divergence_after_projection_in_a_dam_break_with_the_symmetric_gradient() {
    let terms = check_step(&symmetric(isph_slab::isph_slab()), 0.15);
    report("dam break, symmetric gradient", &terms);
}
