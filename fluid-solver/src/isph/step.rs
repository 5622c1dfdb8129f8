//! One ISPH time step (S2-3 … S2-5), read top to bottom as a list of named stages, each timed.
//!
//! All passes work at the positions r^n of the step's start, on one neighbour list:
//! 1. neighbour search and list;
//! 2. density ratio ρ̂/ρ0 (S2-7) and free-surface flags ([`super::free_surface`], S2-10 … S2-13);
//! 3. `v* = v^n + (ν∇²v^n + g)Δt` (S2-3, S2-9);
//! 4. the PPE `∇²p = (ρ/Δt_p)∇·v* + α_d(ρ0 − ρ̂)/Δt_p²` (S2-5; Δt_p = Δt but in a short step,
//!    below), ∇·v* corrected in Marrone's
//!    band by the moment matrix, as the gradient is ([`operators::DivergenceSum`]), with p = 0 on
//!    the free surface
//!    (half a spacing beyond the surface particles, [`free_surface::surface_pressure`]) and
//!    the walls' Neumann differences ([`super::walls`]), assembled and solved ([`super::ppe`]);
//!    with `pressure_gradient = "conservative"` the equation is instead built from the gradient
//!    of stage 6 ([`super::exact_projection`], S2-9's assembled equation blended in);
//!    a negative solution is written as 0 (no tension, [`IsphStep::solve_ppe`] says why).
//!    The projection then sets `∇·v^{n+1} = −α_d(1 − ρ̂/ρ0)/Δt_p`, a relaxation by the fraction
//!    α_d per step. A step that lands on an output, probe or coupling-window time after whole
//!    steps is shorter (down to 1e-9 Δt), and there that velocity grew as 1/Δt and its pressure as
//!    1/Δt²: one step of 1e-4 Δt in the CI dam break at t = 0.15 s threw a particle to 38 m/s
//!    (`tests/isph.rs`), and the final step of 0.28 Δt of the `isph_vs_emps` scene (Δs = L/20, to
//!    0.32 s) raised the far-wall probe by 20 kPa. So a step shorter than the step whose pressure
//!    the one before it took (and a step the advective limit cut) runs stages 3–6 at that step's
//!    length Δt_p ([`super::step_length::pressure_step`]) from the step's start and takes only its
//!    share Δt/Δt_p of the velocity change
//!    ([`IsphStep::short_step`]): its pressure is a whole step's (that probe 4.3 → 3.0 kPa at
//!    that step, 7.6 kPa before);
//! 5. the walls' pressure by Adami's extrapolation (for outputs and probes; the gradient reads the
//!    per-pair wall pressure of [`super::walls`]);
//! 6. `v^{n+1} = v* − (Δt/ρ)∇p` (S2-4), `x^{n+1} = x^n + v^{n+1}Δt`; bodies move with their own
//!    velocity;
//! 7. with `shifting = "lind"`, particle shifting ([`super::shifting`]): the shift's direction
//!    `−∇C` at r^n, added to x^{n+1} scaled by D from v^{n+1};
//! 8. the collision stage both methods share ([`crate::neighbours::collision`]) on pairs closer than 0.8 Δs
//!    that approach. S2-8's gradient does not part two particles of equal pressure, so it acts on
//!    more of the flow than in E-MPS: 19 % of the fluid per step in the L/20 dam break to 0.8 s
//!    (E-MPS 3.4 %; `isph_vs_emps`, column `kicked/step`). Without its fluid–fluid part that run
//!    stops at 0.33 s (energy growth).

use super::body_completion::BodyCompletion;
use super::exact_projection;
use super::free_surface::{self, SURFACE};
use super::kernel::Wendland;
use super::kernel_correction::{self, PairVectors};
use super::neighbour_list::NeighbourList;
use super::operators::{self, DivergenceSum};
use super::pair_gradients::PairGradients;
use super::pair_laws;
use super::ppe::{PpeFailure, PpeReport, PpeSystem, NOT_AN_UNKNOWN};
use super::ppe_two_level;
use super::shifting;
use super::step_length::pressure_step;
use super::surface_walls;
use super::walls::{self, NeumannPair, WallFields};
use crate::bodies::pair_law::{Exchange, ExchangeScales, PairLaw};
use crate::method::StepTotals;
use crate::neighbours::collision::{self, COLLISION_DISTANCE, RESTITUTION};
use crate::neighbours::neighbour_search::CellGrid;
use crate::neighbours::vector_field::VectorField;
use crate::particles::kind::{Kind, FLUID};
use crate::particles::Particles;
use crate::physics::Physics;
use crate::stage_timer::StageTimes;
use rayon::prelude::*;
use schemas::case::fluid::{IsphConfig, KernelCorrection, PpeSolver, PressureGradient, Shifting, WallSlip};

/// Unknowns per block of the parallel PPE assembly.
const ROW_BLOCK: usize = 256;

/// Assembled PPE rows of one block: off-diagonal entries (unknown, value) contiguous, the end of
/// each row's entries, its diagonal and right-hand side; kept from step to step, so the buffers
/// are not allocated again.
#[derive(Debug, Clone, Default)]
struct RowBlock {
    col: Vec<u32>,
    val: Vec<f32>,
    end: Vec<u32>,
    diag: Vec<f64>,
    rhs: Vec<f64>,
    anchored: Vec<bool>,
}

/// What ISPH keeps between steps beyond the particles (whose pressure is the PPE's warm start).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct IsphState {
    /// Free-surface flag of each particle in the present order ([`SURFACE`] or 0), from the last
    /// step's detection (for outputs).
    pub surface: Vec<u8>,
    /// How the last PPE solve went.
    pub ppe: PpeReport,
    /// The length of the step whose pressure the last step took (its own, or a longer one's
    /// over a short step; [`super::step_length::pressure_step`]).
    pub last_pressure_step: Option<f64>,
}

/// The ISPH step: parameters, work buffers and stage times.
#[derive(Debug, Clone)]
pub struct IsphStep {
    pub kernel: Wendland,
    pub physics: Physics,
    pub settings: IsphConfig,
    /// n0 of the MPS lattice (S1-8): the fluid's `number_density` is written as n0 ρ̂/ρ0, the
    /// measure the shared probes read.
    n0_mps: f64,
    /// Δt of the case (the initial pressure's projection uses it).
    time_step: f64,
    list: NeighbourList,
    scratch: Vec<f64>,
    ratio: Vec<f64>,
    lambda: Vec<f64>,
    takes_part: Vec<u8>,
    /// The walls' normals and depths and the surface flags of the last PPE assembly, for the
    /// wall differences ([`super::walls`]).
    walls: WallFields,
    accel: VectorField,
    /// The shift per unit D of every particle ([`shifting::directions`]).
    shift: VectorField,
    /// The velocities at the step's start, kept over a short step ([`IsphStep::short_step`]).
    start_velocity: VectorField,
    ppe: PpeSystem,
    row_blocks: Vec<RowBlock>,
    solution: Vec<f64>,
    /// The bodies' face forces of the last pressure solve ([`pair_laws::body_faces`]).
    faces: pair_laws::BodyFaces,
    /// The bodies' completion of the exact projection ([`BodyCompletion`]).
    completion: BodyCompletion,
    /// The Dirichlet pressure of each surface particle ([`free_surface::surface_pressure`]).
    dirichlet: Vec<f64>,
    /// The exact projection's `(ρ/Δt) v* − c` ([`exact_projection::blend_right_hand_side`]).
    known_gradient: VectorField,
    /// The exact projection's kernel gradients of the step's pairs.
    pair_gradients: PairGradients,
    /// Whether each particle has a body neighbour (the kernel correction's scratch).
    beside_body: Vec<bool>,
    /// Pockets of water enclosed by solids whose pressure level was tied to the last step's
    /// ([`IsphStep::solve_with_pockets_tied`]), over the run.
    pockets_tied: u64,
    times: StageTimes,
}

/// `completion` where the exact projection uses it (`"conservative"`): the other gradients
/// load bodies by the face law. (A function of the two fields, so that a pass writing another
/// field of the step can borrow it.)
fn completion_of<'a>(settings: &IsphConfig, completion: &'a BodyCompletion) -> Option<&'a BodyCompletion> {
    (settings.pressure_gradient == PressureGradient::Conservative).then_some(completion)
}

impl IsphStep {
    /// A step with kernel support `settings.support()` Δs.
    pub fn new(
        spacing: f64,
        physics: Physics,
        settings: IsphConfig,
        n0_mps: f64,
        time_step: f64,
    ) -> IsphStep {
        IsphStep {
            kernel: Wendland::new(spacing, settings.support()),
            physics,
            settings,
            n0_mps,
            time_step,
            list: NeighbourList::default(),
            scratch: Vec::new(),
            ratio: Vec::new(),
            lambda: Vec::new(),
            takes_part: Vec::new(),
            walls: WallFields::default(),
            accel: VectorField::default(),
            shift: VectorField::default(),
            start_velocity: VectorField::default(),
            ppe: PpeSystem::default(),
            row_blocks: Vec::new(),
            solution: Vec::new(),
            dirichlet: Vec::new(),
            known_gradient: VectorField::default(),
            pair_gradients: PairGradients::default(),
            beside_body: Vec::new(),
            faces: pair_laws::BodyFaces::default(),
            completion: BodyCompletion::default(),
            pockets_tied: 0,
            times: StageTimes::default(),
        }
    }

    /// Pockets of water enclosed by solids whose pressure level was tied, over the run.
    pub fn pockets_tied(&self) -> u64 {
        self.pockets_tied
    }

    /// Wall time per stage since the start.
    pub fn stage_times(&self) -> &StageTimes {
        &self.times
    }

    /// The present neighbour list (after a step or [`IsphStep::refresh_pressure`]).
    pub fn neighbour_list(&self) -> &NeighbourList {
        &self.list
    }

    /// The scales that turn velocity changes of a step of `dt` into forces.
    pub fn scales(&self, dt: f64) -> ExchangeScales {
        ExchangeScales {
            spacing: self.kernel.spacing,
            particle_mass: self.physics.density * self.kernel.volume,
            viscosity: self.physics.viscosity,
            dt,
        }
    }

    /// The pressure pair law on the present pressures (at rest: the fluid's velocities are
    /// taken as the step's start), with the walls' Neumann differences of the step whose pressure
    /// the last step took (the case's Δt before the first).
    pub fn pressure_law<'a>(&'a self, p: &'a Particles, state: &IsphState) -> PairLaw<'a> {
        let dt = state.last_pressure_step.unwrap_or(self.time_step);
        pair_laws::pressure(&self.kernel, self.neumann(p, dt), &self.faces, self.completion())
    }

    /// The bodies' completion where the exact projection uses it ([`completion_of`]).
    fn completion(&self) -> Option<&BodyCompletion> {
        completion_of(&self.settings, &self.completion)
    }

    /// The solids turned rigidly from rest at the present positions (a flap paddle), whose kept
    /// wall normals turn with them ([`walls::TurnedSolids`]).
    pub fn turn_solids(&mut self, turned: Option<walls::TurnedSolids>) {
        self.walls.turned = turned;
    }

    /// The walls' Neumann differences for a step of `dt` with v* in the particles.
    fn neumann<'a>(&'a self, p: &'a Particles, dt: f64) -> NeumannPair<'a> {
        self.walls
            .pair(&self.physics, self.kernel.spacing, &self.list, p, dt)
    }

    /// Advances the particles by `dt` through the stages of the module doc (`cut`: the advective
    /// limit cut this step short, [`super::step_length`]); `bodies` is handed each pair law with
    /// the state it acts in. A PPE that misses its tolerance stops the step.
    pub fn advance(
        &mut self,
        p: &mut Particles,
        grid: &mut CellGrid,
        state: &mut IsphState,
        (dt, cut): (f64, bool),
        mut bodies: impl FnMut(Exchange, &PairLaw, &CellGrid, &Particles),
    ) -> Result<StepTotals, PpeFailure> {
        let mut totals = StepTotals::default();
        let scales = self.scales(dt);
        let t = self.times.start();
        totals.candidates += self.neighbours(p, grid);
        let t = self.times.lap(t, "neighbour search");
        self.density_and_surface(p, state);
        let t = self.times.lap(t, "density and free surface");
        let no_slip = self.settings.wall_slip == WallSlip::NoSlip;
        if self.physics.viscous() {
            let pass = operators::laplacian(&self.kernel, &self.list, p, no_slip, &mut self.accel); // S2-9
            let m_nu = scales.particle_mass * self.physics.viscosity;
            (0..3).for_each(|a| totals.force_from_walls[a] += m_nu * pass.from_non_fluid[a]);
            if no_slip {
                bodies(
                    Exchange::Viscous,
                    &pair_laws::viscous(&self.kernel, &scales, p),
                    grid,
                    p,
                );
            }
        }
        // The pressure stages' step: a longer one's over a short step (`IsphStep::short_step`).
        let pdt = pressure_step(dt, self.time_step, cut, state.last_pressure_step);
        let short = pdt > dt;
        if short {
            keep(p, &mut self.start_velocity);
        }
        self.predict_velocity(p, pdt); // S2-3
        let t = self.times.lap(t, "viscous and prediction");
        self.assemble(p, state, pdt); // S2-5
        self.aggregate(grid);
        let t = self.times.lap(t, "PPE assembly");
        state.ppe = self.solve_ppe(p)?;
        totals.ppe_iterations = state.ppe.iterations;
        let t = self.times.lap(t, "PPE solve");
        self.wall_pressure(p, pdt);
        let t = self.times.lap(t, "wall pressure");
        self.update_body_faces(p, pdt);
        let walls = self
            .walls
            .pair(&self.physics, self.kernel.spacing, &self.list, p, pdt);
        let form = self.settings.pressure_gradient;
        let pass = operators::pressure_gradient(
            &self.kernel,
            &self.list,
            p,
            &walls,
            form,
            (&self.faces, completion_of(&self.settings, &self.completion)),
            &mut self.accel,
        );
        (0..3).for_each(|a| totals.force_from_walls[a] -= self.kernel.volume * pass.from_non_fluid[a]);
        // With the symmetric gradient the bodies' loads are in `from_non_fluid` (their face-law
        // shares are the fluid's pair terms with them).
        if form == PressureGradient::CorrectedDifference {
            let on_bodies = self.faces.total();
            (0..3).for_each(|a| totals.force_from_walls[a] -= on_bodies[a]);
        }
        bodies(
            Exchange::Pressure,
            &pair_laws::pressure(&self.kernel, self.neumann(p, pdt), &self.faces, self.completion()),
            grid,
            p,
        );
        let shifting = self.settings.shifting == Shifting::Lind;
        let t = if shifting {
            let t = self.times.lap(t, "pressure gradient and correction");
            shifting::directions(
                &self.kernel,
                &self.list,
                p,
                &self.lambda,
                &self.takes_part,
                &self.walls.normals,
                &mut self.shift,
            );
            self.times.lap(t, "shifting")
        } else {
            t
        };
        if short {
            self.short_step(p, dt / pdt);
        }
        self.correct(p, dt); // S2-4
        let t = self.times.lap(t, "pressure gradient and correction");
        let t = if shifting {
            let a = self.settings.shifting_coefficient;
            shifting::apply(p, &self.shift, a, &self.kernel, dt);
            self.times.lap(t, "shifting")
        } else {
            t
        };
        let distance = COLLISION_DISTANCE * self.kernel.spacing;
        let pass = collision::collision(grid, p, distance, RESTITUTION, &mut self.accel);
        bodies(Exchange::Collision, &collision::contact_law(&scales, p), grid, p);
        (0..3).for_each(|a| totals.force_from_walls[a] += scales.particle_mass * pass.from_non_fluid[a] / dt);
        totals.candidates += pass.candidates;
        totals.collisions = collision::kicked(&self.accel);
        self.apply_collisions(p, dt);
        self.times.lap(t, "collision");
        state.last_pressure_step = Some(pdt);
        Ok(totals)
    }

    /// The pressure of the present state: the projection of a step of the case's Δt from the
    /// present velocities, without moving anything (the initial outputs and loads; hydrostatic
    /// for water at rest). Velocities are left unchanged.
    pub fn refresh_pressure(
        &mut self,
        p: &mut Particles,
        grid: &mut CellGrid,
        state: &mut IsphState,
    ) -> Result<(), PpeFailure> {
        let dt = self.time_step;
        self.neighbours(p, grid);
        self.density_and_surface(p, state);
        let v = (p.vx.clone(), p.vy.clone(), p.vz.clone());
        self.predict_velocity_by_gravity(p, dt);
        self.assemble(p, state, dt);
        self.aggregate(grid);
        let solved = self.solve_ppe(p);
        self.wall_pressure(p, dt);
        self.update_body_faces(p, dt);
        (p.vx, p.vy, p.vz) = v;
        state.ppe = solved?;
        Ok(())
    }

    /// A short step (one that lands on an output, probe or window time after whole steps, or one
    /// the advective limit cut: [`pressure_step`]) takes the pressure of a longer step Δt_p:
    /// v*, the PPE (S2-5), the walls' and bodies' pressure and the gradient are those of Δt_p from
    /// the step's start, and only then is the predicted velocity cut back to the short step's,
    /// `v* = v^n + r (v*_p − v^n)` with the share `r = Δt/Δt_p`, before the correction
    /// `v^{n+1} = v* − (Δt/ρ)∇p` (S2-4). So a short step removes its share r of the divergence the
    /// particles carry into it, and leaves the rest to the next step. (Removed in one short step,
    /// that divergence, which does not shrink with the step, drew a pressure ∝ 1/Δt: the final
    /// step of 0.28 Δt to 0.6 s of `isph_vs_emps` at L/30 raised the far-wall probe from 960 to
    /// 2 298 Pa.)
    fn short_step(&self, p: &mut Particles, r: f64) {
        let v0 = &self.start_velocity;
        (&mut p.vx, &mut p.vy, &mut p.vz, &p.kind)
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .filter(|(_, t)| *t.3 == FLUID)
            .for_each(|(i, (u, v, w, _))| {
                *u = v0.x[i] + r * (*u - v0.x[i]);
                *v = v0.y[i] + r * (*v - v0.y[i]);
                *w = v0.z[i] + r * (*w - v0.z[i]);
            });
    }

    /// Sorts the particles into the cells at r^n and builds the neighbour list.
    fn neighbours(&mut self, p: &mut Particles, grid: &mut CellGrid) -> u64 {
        grid.sort(p, &mut self.scratch);
        self.list.build(grid, p, &self.kernel)
    }

    /// ρ̂/ρ0, λ_min and the surface flags; the fluid's `number_density` becomes n0 ρ̂/ρ0.
    fn density_and_surface(&mut self, p: &mut Particles, state: &mut IsphState) {
        operators::density_ratio(&self.kernel, &self.list, p, &mut self.ratio);
        free_surface::fill_flags(p, &self.ratio, &mut self.takes_part);
        free_surface::lambda_min(&self.kernel, &self.list, p, &self.takes_part, &mut self.lambda);
        free_surface::detect(
            &self.kernel,
            &self.list,
            p,
            &self.takes_part,
            &self.lambda,
            &mut state.surface,
        );
        let n0 = self.n0_mps;
        (&mut p.number_density, &p.kind, &self.ratio)
            .into_par_iter()
            .with_min_len(4096)
            .for_each(|(n, &k, &r)| *n = if k == FLUID { n0 * r } else { 0.0 });
    }

    /// S2-3 for fluid particles (the Laplacian is in `accel` when the viscous term is on).
    fn predict_velocity(&mut self, p: &mut Particles, dt: f64) {
        if !self.physics.viscous() {
            return self.predict_velocity_by_gravity(p, dt);
        }
        let (g, nu, lap) = (self.physics.gravity, self.physics.viscosity, &self.accel);
        (&mut p.vx, &mut p.vy, &mut p.vz, &p.kind)
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .filter(|(_, t)| *t.3 == FLUID)
            .for_each(|(i, (u, v, w, _))| {
                *u += (nu * lap.x[i] + g[0]) * dt;
                *v += (nu * lap.y[i] + g[1]) * dt;
                *w += (nu * lap.z[i] + g[2]) * dt;
            });
    }

    /// S2-3 without the viscous term.
    fn predict_velocity_by_gravity(&self, p: &mut Particles, dt: f64) {
        let g = self.physics.gravity;
        (&mut p.vx, &mut p.vy, &mut p.vz, &p.kind)
            .into_par_iter()
            .with_min_len(4096)
            .filter(|t| *t.3 == FLUID)
            .for_each(|(u, v, w, _)| {
                *u += g[0] * dt;
                *v += g[1] * dt;
                *w += g[2] * dt;
            });
    }

    /// Assembles S2-5 over the non-surface fluid particles (see [`super::ppe`]) with v* in the
    /// particles; a fluid particle without fluid neighbours is put on the surface.
    fn assemble(&mut self, p: &Particles, state: &mut IsphState, dt: f64) {
        let k = self.kernel;
        // The faces' normals at walls' convex edges, and at bodies' with S2-8's gradient only
        // (walls module doc).
        let body_edges = self.settings.pressure_gradient == PressureGradient::CorrectedDifference;
        self.walls.update_geometry(&k, &self.list, p, body_edges);
        let list = &self.list;
        let surface = &mut state.surface;
        // Unknowns: fluid, not on the surface, with at least one fluid neighbour.
        surface
            .par_iter_mut()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, s)| {
                if p.kind[i] == FLUID
                    && *s != SURFACE
                    && !list.of(i).iter().any(|&j| p.kind[j as usize] == FLUID)
                {
                    *s = SURFACE;
                }
            });
        free_surface::surface_pressure(
            &k,
            list,
            p,
            &self.takes_part,
            surface,
            self.physics.density,
            self.physics.gravity,
            &mut self.dirichlet,
        );
        self.walls.surface.clone_from(surface);
        if self.settings.pressure_gradient.is_symmetric() {
            surface_walls::completions(&k, list, p, surface, &mut self.walls.surface_completion);
        } else {
            self.walls.surface_completion.clear();
        }
        if self.settings.kernel_correction() == KernelCorrection::Moment {
            let scratch = &mut self.beside_body;
            kernel_correction::corrections(&k, list, p, surface, scratch, &mut self.walls.kernel_correction);
        } else {
            self.walls.kernel_correction.clear();
        }
        let ppe = &mut self.ppe;
        ppe.row_of.clear();
        ppe.row_of.resize(p.len(), NOT_AN_UNKNOWN);
        ppe.particle.clear();
        for (i, &s) in surface.iter().enumerate() {
            if p.kind[i] == FLUID && s != SURFACE {
                ppe.row_of[i] = ppe.particle.len() as u32;
                ppe.particle.push(i as u32);
            }
        }
        let pair = self
            .walls
            .pair(&self.physics, self.kernel.spacing, &self.list, p, dt);
        // `dt` is the pressure's step Δt_p, the density relaxation's too (module doc, 4).
        let (rho, alpha) = (self.physics.density, self.settings.alpha_d);
        let (form, lambda) = (self.settings.pressure_gradient, &self.lambda);
        let (row_of, ratio, dirichlet) = (&ppe.row_of, &self.ratio, &self.dirichlet);
        // Rows in blocks of ROW_BLOCK unknowns, each block's entries contiguous in its own
        // reused buffers, then copied into the CSR arrays block by block in parallel.
        let blocks = &mut self.row_blocks;
        blocks.resize_with(ppe.particle.len().div_ceil(ROW_BLOCK), RowBlock::default);
        blocks
            .par_iter_mut()
            .zip(ppe.particle.par_chunks(ROW_BLOCK))
            .for_each(|(out, block)| {
                out.col.clear();
                out.val.clear();
                out.end.clear();
                out.diag.clear();
                out.rhs.clear();
                out.anchored.clear();
                for &i in block {
                    let i = i as usize;
                    let row = row_of[i];
                    // Σ_j F_ij, the known terms, and the divergence of v* in the same pass.
                    let (mut diag, mut rhs, mut anchored) = (0.0, 0.0, false);
                    let mut div = DivergenceSum::new(form, lambda[i]);
                    for (j, q) in list.pairs(i) {
                        div.add(&k, p, i, j, q);
                        // F_ij rounded to f32 once (the matrix is stored in f32), the diagonal and
                        // the known terms built from the same rounded weight, so A keeps zero row
                        // sums over the fluid and stays symmetric: a Laplacian whose weights
                        // differ from S2-9's by 6e-8 relative.
                        let f32 = (-2.0 * k.volume * k.dw_over_r_at(q)) as f32;
                        let f = f64::from(f32);
                        if p.kind[j] == FLUID {
                            diag += f;
                            if row_of[j] == NOT_AN_UNKNOWN {
                                rhs += f * dirichlet[j];
                                anchored = true;
                            } else if row_of[j] > row {
                                // The upper triangle only (super::ppe).
                                out.col.push(row_of[j]);
                                out.val.push(-f32);
                            }
                        } else {
                            rhs += f * pair.difference(i, j);
                        }
                    }
                    let div = div.value(&k);
                    out.end.push(out.col.len() as u32);
                    out.diag.push(diag);
                    out.anchored.push(anchored);
                    out.rhs
                        .push(rhs - (rho / dt * div + alpha * rho * (1.0 - ratio[i]) / (dt * dt)));
                }
            });
        let rows = ppe.particle.len();
        let entries: usize = blocks.iter().map(|b| b.col.len()).sum();
        ppe.start.resize(rows + 1, 0);
        ppe.col.resize(entries, 0);
        ppe.val.resize(entries, 0.0);
        ppe.diag.resize(rows, 0.0);
        ppe.rhs.resize(rows, 0.0);
        ppe.anchored.clear();
        ppe.anchored
            .extend(blocks.iter().flat_map(|b| b.anchored.iter().copied()));
        ppe.start[0] = 0;
        // Each block's slice of every CSR array, split off in order.
        let (mut start, mut col, mut val) = (&mut ppe.start[1..], &mut ppe.col[..], &mut ppe.val[..]);
        let (mut diag, mut rhs) = (&mut ppe.diag[..], &mut ppe.rhs[..]);
        let mut parts = Vec::with_capacity(blocks.len());
        let mut offset = 0u32;
        for b in blocks.iter() {
            let (s, s_rest) = std::mem::take(&mut start).split_at_mut(b.end.len());
            let (c, c_rest) = std::mem::take(&mut col).split_at_mut(b.col.len());
            let (v, v_rest) = std::mem::take(&mut val).split_at_mut(b.col.len());
            let (d, d_rest) = std::mem::take(&mut diag).split_at_mut(b.end.len());
            let (r, r_rest) = std::mem::take(&mut rhs).split_at_mut(b.end.len());
            (start, col, val, diag, rhs) = (s_rest, c_rest, v_rest, d_rest, r_rest);
            parts.push((b, offset, s, c, v, d, r));
            offset += b.col.len() as u32;
        }
        parts.into_par_iter().for_each(|(b, offset, s, c, v, d, r)| {
            s.iter_mut().zip(&b.end).for_each(|(s, e)| *s = offset + e);
            c.copy_from_slice(&b.col);
            v.copy_from_slice(&b.val);
            d.copy_from_slice(&b.diag);
            r.copy_from_slice(&b.rhs);
        });
        if self.settings.pressure_gradient == PressureGradient::Conservative {
            let rho_g = self.physics.gravity.map(|g| self.physics.density * g);
            let row_of = &self.ppe.row_of;
            let unknown = |i: usize| row_of[i] != NOT_AN_UNKNOWN;
            let vectors = PairVectors(&self.walls.kernel_correction);
            self.completion.update(&k, &self.list, p, rho_g, unknown, vectors);
            self.pair_gradients.build(&k, &self.list, p, vectors);
            let walls = self
                .walls
                .pair(&self.physics, self.kernel.spacing, &self.list, p, dt);
            exact_projection::blend_right_hand_side(
                &k,
                &self.list,
                &walls,
                &self.dirichlet,
                &self.ratio,
                self.settings.alpha_d,
                dt,
                (&self.pair_gradients, &self.completion),
                &mut self.ppe,
                &mut self.known_gradient,
            );
        }
    }

    /// The unknowns' aggregates by cells, for the two-level solver only.
    fn aggregate(&mut self, grid: &CellGrid) {
        if matches!(
            self.settings.ppe_solver,
            PpeSolver::TwoLevelPcg | PpeSolver::AdditiveTwoLevelPcg
        ) {
            ppe_two_level::aggregate_by_cells(grid, &mut self.ppe);
        }
    }

    /// Solves the PPE warm-started from the particles' pressure and writes the fluid pressures
    /// (the Dirichlet value on the surface), `p = max(0, p_PPE)`: no tension, as E-MPS's
    /// equation of state (S1-14) and S2's p = 0 at the free surface. A negative solution is water
    /// the projection would pull back together within one step where it is parting (below a
    /// surface that opens, at a wall it leaves), at `p ≈ −ρ u Δs/Δt`, so the smaller Δt the
    /// stronger; the difference-form gradient next to the surface then threw the particle
    /// outwards instead. On the Koshizuka dam break at Δs = L/10 (10 × 20 × 5 particles,
    /// Δt = 4e-4 s) two particles below the surface near the left wall at t ≈ 0.26 s read
    /// −35 … −62 kPa and went from 2.5 to 5.7 m/s in five steps; the detector's mechanical
    /// energy `Σ ½|u|² + g z` (1 430 J/kg at the start) gained 144 J/kg over the steps in which
    /// it grew, to 0.3 s, and 1.1 with this limit (at 6e-4 and 3e-4 s: 3.7 and 0.4;
    /// `tests/isph_dam_break.rs`, ignored test); the detector had stopped the report's ISPH rung
    /// (Δt = 6e-4 s) for such growth at t = 0.22 s. Where nothing is clamped the projection is the
    /// PPE's unchanged (`tests/isph_divergence.rs` checks its divergence identity to 1e-9).
    fn solve_ppe(&mut self, p: &mut Particles) -> Result<PpeReport, PpeFailure> {
        self.warm_start(p);
        let ppe = &self.ppe;
        let s = &self.settings;
        let report = if s.pressure_gradient == PressureGradient::Conservative {
            exact_projection::solve(
                &self.list,
                p,
                (&self.pair_gradients, &self.completion),
                ppe,
                s.ppe_solver,
                &mut self.solution,
                s.ppe_tolerance,
                s.ppe_max_iterations,
            )?
        } else {
            let solved = ppe.solve(
                s.ppe_solver,
                &mut self.solution,
                s.ppe_tolerance,
                s.ppe_max_iterations,
            );
            match solved {
                Err(failure) => self.solve_with_pockets_tied(p, failure)?,
                Ok(report) => report,
            }
        };
        let ppe = &self.ppe;
        let (row_of, x, dirichlet) = (&ppe.row_of, &self.solution, &self.dirichlet);
        (&mut p.pressure, &p.kind)
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .filter(|(_, t)| *t.1 == FLUID)
            .for_each(|(i, (pr, _))| {
                *pr = if row_of[i] == NOT_AN_UNKNOWN {
                    dirichlet[i]
                } else {
                    x[row_of[i] as usize].max(0.0)
                };
            });
        Ok(report)
    }

    /// The PPE's warm start: each unknown's pressure of the last step.
    fn warm_start(&mut self, p: &Particles) {
        self.solution.clear();
        self.solution
            .extend(self.ppe.particle.iter().map(|&i| p.pressure[i as usize]));
    }

    /// After a failed solve: when the water holds pockets enclosed by solids
    /// ([`PpeSystem::enclosed_pockets`]), ties each to its last pressure ([`PpeSystem::tie`]) and
    /// solves again from the warm start; otherwise (or when that fails too) the failure stands.
    fn solve_with_pockets_tied(
        &mut self,
        p: &Particles,
        failure: PpeFailure,
    ) -> Result<PpeReport, PpeFailure> {
        let rows = self.ppe.enclosed_pockets();
        if rows.is_empty() {
            return Err(failure);
        }
        let level: Vec<f64> = rows
            .iter()
            .map(|&r| p.pressure[self.ppe.particle[r] as usize])
            .collect();
        self.ppe.tie(&rows, &level);
        if self.pockets_tied == 0 {
            eprintln!(
                "ISPH: {} pocket(s) of water enclosed by solids (no free surface): the pressure Poisson equation is singular there; each pocket's pressure level is tied to its last step's (said once per run)",
                rows.len()
            );
        }
        self.pockets_tied += rows.len() as u64;
        self.warm_start(p);
        let s = &self.settings;
        self.ppe.solve(
            s.ppe_solver,
            &mut self.solution,
            s.ppe_tolerance,
            s.ppe_max_iterations,
        )
    }

    /// The bodies' face laws ([`pair_laws::body_faces`]) from the present pressures, with v* of a
    /// step of `dt` in the particles.
    fn update_body_faces(&mut self, p: &Particles, dt: f64) {
        let walls = self
            .walls
            .pair(&self.physics, self.kernel.spacing, &self.list, p, dt);
        pair_laws::body_faces(
            &self.kernel,
            &self.list,
            &walls,
            &self.takes_part,
            &mut self.faces,
        );
    }

    /// Adami's extrapolation onto the wall, dummy, body and inflow particles.
    fn wall_pressure(&mut self, p: &mut Particles, dt: f64) {
        let pair = self.neumann(p, dt);
        let solid = walls::extrapolated(&self.kernel, &self.list, &pair);
        for (w, pw) in solid {
            p.pressure[w] = pw;
        }
    }

    /// S2-4 for fluid particles, `x^{n+1} = x^n + v^{n+1}Δt`; bodies move with their velocity.
    fn correct(&self, p: &mut Particles, dt: f64) {
        let s = dt / self.physics.density;
        let grad = &self.accel;
        let body = Kind::Body.code();
        (
            &mut p.x, &mut p.y, &mut p.z, &mut p.vx, &mut p.vy, &mut p.vz, &p.kind,
        )
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, (x, y, z, u, v, w, &k))| {
                if k == FLUID {
                    *u -= s * grad.x[i];
                    *v -= s * grad.y[i];
                    *w -= s * grad.z[i];
                }
                if k == FLUID || k == body {
                    *x += *u * dt;
                    *y += *v * dt;
                    *z += *w * dt;
                }
            });
    }

    /// Adds the collision velocity change Δu and moves the particle by Δu Δt.
    fn apply_collisions(&self, p: &mut Particles, dt: f64) {
        let du = &self.accel;
        (&mut p.x, &mut p.y, &mut p.z, &mut p.vx, &mut p.vy, &mut p.vz)
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, (x, y, z, u, v, w))| {
                *u += du.x[i];
                *v += du.y[i];
                *w += du.z[i];
                *x += du.x[i] * dt;
                *y += du.y[i] * dt;
                *z += du.z[i] * dt;
            });
    }
}

/// Copies the particles' velocities into `out`.
fn keep(p: &Particles, out: &mut VectorField) {
    out.x.clone_from(&p.vx);
    out.y.clone_from(&p.vy);
    out.z.clone_from(&p.vz);
}
