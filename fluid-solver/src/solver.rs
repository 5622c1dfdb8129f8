//! The fluid solver of one `[fluid.NAME]` participant: the particles, the step, the clock and
//! the stability monitor; advances to a given time and saves/restores its state in memory.

use crate::bodies::{ExchangeScales, RigidBodies};
use crate::emps_step::{EmpsStep, Exchange, Physics, StepTotals};
use crate::kernel::Kernel;
use crate::kind::Kind;
use crate::layout::{self, Domain};
use crate::neighbour_search::CellGrid;
use crate::open_boundary::OpenBoundaries;
use crate::particles::Particles;
use crate::stability::{Instability, StabilityMonitor};
use crate::unresolved;
use schemas::case::fluid::{Aabb, FluidConfig};

/// Landing on a time: a remainder below this fraction of Δt is rounding, not a step; a step up to
/// (1 + this) Δt is taken whole.
const LANDING_SLACK: f64 = 1e-9;

/// A copy of everything that changes during a step (for implicit coupling).
#[derive(Debug, Clone, PartialEq)]
pub struct SavedState {
    particles: Particles,
    /// The cell list matching the particles' order (loads are read through it).
    grid: CellGrid,
    body_pose: Vec<f64>,
    body_velocity: Vec<f64>,
    body_exchange: BodyExchange,
    time: f64,
    steps: u64,
    gates_removed: bool,
    open_boundaries: OpenBoundaries,
    /// Impulse totals (a repeated window must not count its rejected tries).
    totals: RunTotals,
}

/// The forces between fluid and bodies in the last step (6 per body: force, moment about the
/// centre), as the bodies took them and as the fluid gave them: S1-4's viscous pairs (when on),
/// S1-3's pressure pairs at r* and the collision impulses / Δt (see [`crate::bodies`]).
#[derive(Debug, Clone, Default, PartialEq)]
struct BodyExchange {
    loads: Vec<f64>,
    reaction: Vec<f64>,
}

/// Running totals since the solver was made.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunTotals {
    /// Σ force_from_walls·Δt: impulse of walls and bodies on the fluid [N s].
    pub wall_impulse: [f64; 3],
    /// Neighbour candidates examined.
    pub candidates: u64,
    /// Particle-steps done.
    pub particle_steps: u64,
    /// Σ (point reactions spread on the fluid)·Δt: impulse of the drag coupling [N s].
    pub reaction_impulse: [f64; 3],
    /// Σ (point reactions no fluid was near)·Δt: impulse that could not be applied [N s].
    pub unapplied_impulse: [f64; 3],
}

/// An E-MPS fluid with walls.
#[derive(Debug, Clone)]
pub struct FluidSolver {
    particles: Particles,
    step: EmpsStep,
    monitor: StabilityMonitor,
    time_step: f64,
    time: f64,
    steps: u64,
    gates_removed: bool,
    started: bool,
    domain: Domain,
    tank: Aabb,
    bodies: RigidBodies,
    /// Present pose (7 per body: centre, quaternion w x y z) and velocity (6 per body: V, ω).
    body_pose: Vec<f64>,
    body_velocity: Vec<f64>,
    body_exchange: BodyExchange,
    totals: RunTotals,
    /// Inflow and outflow (inactive without `inflow` / `outflow` in the case).
    open_boundaries: OpenBoundaries,
    /// Point reactions of the unresolved coupling (6 each: point, force) and their paired sample
    /// points (3 each), applied at every step until replaced.
    point_reactions: (Vec<f64>, Vec<f64>),
}

impl FluidSolver {
    /// Builds the initial layout of a validated section (gates still in place).
    pub fn new(cfg: &FluidConfig) -> FluidSolver {
        let layout = layout::build(cfg);
        let kernel = Kernel::new(cfg.spacing);
        let physics = Physics {
            density: cfg.density,
            viscosity: cfg.viscosity,
            viscosity_term: cfg.viscosity_term,
            gravity: cfg.gravity,
            sound_speed: cfg.sound_speed(),
        };
        let grid = CellGrid::new(layout.grid_box.lo, layout.grid_box.hi, cfg.spacing);
        let boxes: Vec<([f64; 3], [f64; 3])> = cfg.body.iter().map(|b| (b.min, b.max)).collect();
        let bodies = RigidBodies::new(&layout.bodies, &boxes, &layout.particles);
        let body_pose: Vec<f64> = (0..boxes.len())
            .flat_map(|b| {
                let c = bodies.initial_centre(b);
                [c[0], c[1], c[2], 1.0, 0.0, 0.0, 0.0]
            })
            .collect();
        let body_boxes: Vec<Aabb> = cfg
            .body
            .iter()
            .map(|b| Aabb {
                min: b.min,
                max: b.max,
            })
            .collect();
        let mut monitor = StabilityMonitor::new(
            layout.domain,
            layout.tank,
            &cfg.wall,
            &body_boxes,
            cfg.spacing,
            cfg.gravity,
        );
        let mut particles = layout.particles;
        let open_boundaries = OpenBoundaries::new(cfg, &mut particles);
        if open_boundaries.has_inflow() {
            monitor.set_driven(); // the inflow feeds energy in
        }
        let mut step = EmpsStep::new(kernel, physics, grid);
        step.refresh_pressure(&mut particles);
        let mut solver = FluidSolver {
            particles,
            step,
            monitor,
            time_step: cfg.time_step,
            time: 0.0,
            steps: 0,
            gates_removed: false,
            started: false,
            domain: layout.domain,
            tank: layout.tank,
            body_velocity: vec![0.0; 6 * boxes.len()],
            body_exchange: BodyExchange::default(),
            body_pose,
            bodies,
            totals: RunTotals::default(),
            open_boundaries,
            point_reactions: Default::default(),
        };
        solver.refresh_body_exchange();
        solver
    }

    /// Sets the body loads to the pressure pair forces of the present state (no collisions):
    /// what the bodies feel before the first step.
    fn refresh_body_exchange(&mut self) {
        let (grid, kernel, p, pose) = (
            &self.step.grid,
            &self.step.kernel,
            &self.particles,
            &self.body_pose,
        );
        self.body_exchange = BodyExchange {
            loads: self.bodies.pressure_loads(grid, kernel, p, pose),
            reaction: self.bodies.pressure_reaction(grid, kernel, p, pose),
        };
    }

    /// The inflow and outflow boundaries and their particle balance.
    pub fn open_boundaries(&self) -> &OpenBoundaries {
        &self.open_boundaries
    }

    /// The particles (in cell order; use `id` for identity).
    pub fn particles(&self) -> &Particles {
        &self.particles
    }

    /// Mutable particles, e.g. to set initial velocities or body kinematics.
    pub fn particles_mut(&mut self) -> &mut Particles {
        &mut self.particles
    }

    /// Simulated time [s].
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Δt of the case [s].
    pub fn time_step(&self) -> f64 {
        self.time_step
    }

    /// The operators' radii and lattice constants.
    pub fn kernel(&self) -> &Kernel {
        &self.step.kernel
    }

    /// The physical parameters.
    pub fn physics(&self) -> &Physics {
        &self.step.physics
    }

    /// The box particles must stay in.
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The tank's inner faces.
    pub fn tank(&self) -> Aabb {
        self.tank
    }

    /// Names of the rigid bodies, in interface order.
    pub fn body_names(&self) -> &[String] {
        self.bodies.names()
    }

    /// Moves the bodies' particles to `pose` (7 per body: centre, quaternion w x y z relative to
    /// the initial placement) with `velocity` (6 per body: V, ω); held until the next call.
    pub fn set_body_motion(&mut self, pose: &[f64], velocity: &[f64]) -> Result<(), String> {
        let n = self.bodies.names().len();
        if pose.len() != 7 * n || velocity.len() != 6 * n {
            return Err(format!(
                "body motion for {n} bodies needs 7 pose and 6 velocity values per body, got {} and {}",
                pose.len(),
                velocity.len()
            ));
        }
        if pose.iter().chain(velocity).any(|v| !v.is_finite()) {
            return Err("body motion holds a value that is not finite".into());
        }
        if velocity.iter().any(|&v| v != 0.0) {
            self.monitor.set_driven();
        }
        self.body_pose.copy_from_slice(pose);
        self.body_velocity.copy_from_slice(velocity);
        self.bodies.set_kinematics(&mut self.particles, pose, velocity);
        Ok(())
    }

    /// Force and moment the bodies exerted on the fluid and the walls in the last step (6 per
    /// body), the fluid's share evaluated from the fluid's side; minus [`FluidSolver::body_loads`]
    /// up to round-off.
    pub fn body_reactions(&self) -> Vec<f64> {
        self.body_exchange.reaction.clone()
    }

    /// Force and moment of the fluid on each body in the last step, about the body's centre at
    /// the step's start (6 per body): S1-4's viscous pair forces (when the term is on), S1-3's
    /// pressure pair forces at r* and the fluid–body collision impulses / Δt (see
    /// [`crate::bodies`]), exactly the momentum the fluid gave up to the bodies, plus the walls'
    /// contact ([`crate::body_wall_contact`]). No gravity: the body's weight is the structure
    /// solver's.
    pub fn body_loads(&self) -> Vec<f64> {
        self.body_exchange.loads.clone()
    }

    /// Totals since the start.
    pub fn totals(&self) -> RunTotals {
        self.totals
    }

    /// Bytes held by the particle arrays, the step's buffers and the cell grid.
    pub fn memory_bytes(&self) -> usize {
        let n = self.particles.x.capacity();
        n * (crate::particles::STATE_BYTES_PER_PARTICLE + 3 * 8 + 8) + self.step.grid.memory_bytes()
    }

    /// Removes the partition boards (done automatically before the first step, i.e. at t = 0).
    /// Returns how many particles were removed.
    pub fn remove_gates(&mut self) -> usize {
        self.gates_removed = true;
        let removed = self.particles.remove_kind(Kind::Gate);
        if removed > 0 {
            self.step.refresh_pressure(&mut self.particles);
            self.refresh_body_exchange();
        }
        removed
    }

    /// One step of length `dt` (≤ Δt); stops with a diagnostic if the state became unstable.
    pub fn step(&mut self, dt: f64) -> Result<StepTotals, Instability> {
        if !self.gates_removed {
            self.remove_gates();
        }
        if !self.started {
            self.monitor.start(&self.particles);
            self.started = true;
        }
        self.open_boundaries.apply(&mut self.particles, self.time, dt);
        let scales = ExchangeScales {
            spacing: self.step.kernel.spacing,
            particle_mass: self.particle_mass(),
            viscosity: self.step.physics.viscosity,
            dt,
        };
        self.apply_point_reactions(dt);
        let kernel = self.step.kernel;
        let (bodies, pose, exchange) = (&self.bodies, &self.body_pose, &mut self.body_exchange);
        let zeros = vec![0.0; 6 * bodies.names().len()];
        exchange.loads.clone_from(&zeros);
        exchange.reaction.clone_from(&zeros);
        let totals = self.step.advance(&mut self.particles, dt, |stage, grid, p| {
            if bodies.names().is_empty() {
                return;
            }
            let (loads, reaction) = match stage {
                Exchange::Viscous => (
                    bodies.viscous_loads(grid, &kernel, p, pose, &scales),
                    bodies.viscous_reaction(grid, &kernel, p, pose, &scales),
                ),
                Exchange::Pressure => (
                    bodies.pressure_loads(grid, &kernel, p, pose),
                    bodies.pressure_reaction(grid, &kernel, p, pose),
                ),
                Exchange::Collision => {
                    // the walls' contact on the bodies; the walls take its reaction (see
                    // `body_wall_contact.rs`)
                    let walls = bodies.wall_contact_loads(grid, p, pose, &scales);
                    let mut loads = bodies.contact_loads(grid, p, pose, &scales);
                    let mut reaction = bodies.contact_reaction(grid, p, pose, &scales);
                    add_to(&mut loads, &walls);
                    reaction.iter_mut().zip(&walls).for_each(|(r, w)| *r -= w);
                    (loads, reaction)
                }
            };
            add_to(&mut exchange.loads, &loads);
            add_to(&mut exchange.reaction, &reaction);
        });
        self.steps += 1;
        self.time += dt;
        for a in 0..3 {
            self.totals.wall_impulse[a] += totals.force_from_walls[a] * dt;
        }
        self.totals.candidates += totals.candidates;
        self.totals.particle_steps += self.particles.len() as u64;
        self.monitor
            .check(&self.particles, self.steps, self.time, dt, &self.body_pose)?;
        Ok(totals)
    }

    /// Sets the point reactions of the unresolved coupling (6 per reaction: point, force) with
    /// their paired sample points (3 per reaction), applied from the next step on.
    pub fn set_point_reactions(&mut self, reactions: &[f64], sample_points: &[f64]) {
        let (r, s) = &mut self.point_reactions;
        r.clear();
        r.extend_from_slice(reactions);
        s.clear();
        s.extend_from_slice(sample_points);
    }

    /// The point reactions as accelerations over a step of `dt`: each fluid particle's velocity
    /// changes by its share of the reactions (S2-24) / its mass × dt.
    fn apply_point_reactions(&mut self, dt: f64) {
        let (reactions, samples) = &self.point_reactions;
        if reactions.is_empty() {
            return;
        }
        let spread =
            unresolved::spreading::spread(&self.particles, self.step.kernel.spacing, reactions, samples);
        let scale = dt / self.particle_mass();
        let p = &mut self.particles;
        for (i, f) in spread.force.chunks_exact(3).enumerate() {
            p.vx[i] += f[0] * scale;
            p.vy[i] += f[1] * scale;
            p.vz[i] += f[2] * scale;
        }
        for c in 0..3 {
            self.totals.reaction_impulse[c] += spread.total[c] * dt;
            self.totals.unapplied_impulse[c] += spread.unapplied_force[c] * dt;
        }
    }

    /// Velocity and λ_min at `points` (3 per point) for the unresolved coupling (3 and 1 per point).
    pub fn sample_points(&self, points: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let samples = unresolved::sampling::sample(&self.particles, self.step.kernel.spacing, points);
        (
            samples.iter().flat_map(|s| s.velocity).collect(),
            samples.iter().map(|s| s.lambda_min).collect(),
        )
    }

    /// The next step's length towards `t_end`: Δt, or the remainder when it is at most Δt
    /// (the last step lands exactly); `None` when `t_end` is reached (up to rounding).
    pub fn next_step_towards(&self, t_end: f64) -> Option<f64> {
        let left = t_end - self.time;
        if left <= self.time_step * LANDING_SLACK {
            None
        } else if left <= self.time_step * (1.0 + LANDING_SLACK) {
            Some(left)
        } else {
            Some(self.time_step)
        }
    }

    /// Steps with Δt until `t_end`, shortening the last step to land exactly on it.
    pub fn advance_to(&mut self, t_end: f64) -> Result<(), Instability> {
        while let Some(dt) = self.next_step_towards(t_end) {
            self.step(dt)?;
        }
        self.land_on(t_end);
        Ok(())
    }

    /// Sets the clock to `t_end` when the steps have reached it up to rounding.
    pub fn land_on(&mut self, t_end: f64) {
        if (self.time - t_end).abs() <= self.time_step * LANDING_SLACK {
            self.time = t_end;
        }
    }

    /// A copy of the state (particles, clock) for implicit coupling.
    pub fn save_state(&self) -> SavedState {
        SavedState {
            particles: self.particles.clone(),
            grid: self.step.grid.clone(),
            body_pose: self.body_pose.clone(),
            body_velocity: self.body_velocity.clone(),
            body_exchange: self.body_exchange.clone(),
            time: self.time,
            steps: self.steps,
            gates_removed: self.gates_removed,
            open_boundaries: self.open_boundaries.clone(),
            totals: self.totals,
        }
    }

    /// Puts back a state saved by [`FluidSolver::save_state`].
    pub fn restore_state(&mut self, s: &SavedState) {
        self.particles.clone_from(&s.particles);
        self.step.grid.clone_from(&s.grid);
        self.body_pose.clone_from(&s.body_pose);
        self.body_velocity.clone_from(&s.body_velocity);
        self.body_exchange.clone_from(&s.body_exchange);
        self.time = s.time;
        self.steps = s.steps;
        self.gates_removed = s.gates_removed;
        self.open_boundaries.clone_from(&s.open_boundaries);
        self.totals = s.totals;
    }

    /// Total momentum of the fluid [kg m/s].
    pub fn fluid_momentum(&self) -> [f64; 3] {
        let m = self.step.physics.density * self.step.kernel.spacing.powi(3);
        let p = &self.particles;
        let mut sum = [0.0; 3];
        for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()) {
            sum[0] += m * p.vx[i];
            sum[1] += m * p.vy[i];
            sum[2] += m * p.vz[i];
        }
        sum
    }

    /// Mass of one particle ρ0 Δs³ [kg].
    pub fn particle_mass(&self) -> f64 {
        self.step.physics.density * self.step.kernel.spacing.powi(3)
    }
}

/// `a += b`, element-wise.
fn add_to(a: &mut [f64], b: &[f64]) {
    a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
}
