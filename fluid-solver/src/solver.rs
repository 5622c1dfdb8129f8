//! The fluid solver of one `[fluid.NAME]` participant: the particles, the step, the clock and
//! the stability monitor; advances to a given time and saves/restores its state in memory.

use crate::emps_step::{EmpsStep, Physics, StepTotals};
use crate::kernel::Kernel;
use crate::kind::Kind;
use crate::layout::{self, BodyParticles, Domain};
use crate::neighbour_search::CellGrid;
use crate::particles::Particles;
use crate::stability::{Instability, StabilityMonitor};
use schemas::case::fluid::{Aabb, FluidConfig};

/// Landing on a time: a remainder below this fraction of Δt is rounding, not a step; a step up to
/// (1 + this) Δt is taken whole.
const LANDING_SLACK: f64 = 1e-9;

/// A copy of everything that changes during a step (for implicit coupling).
#[derive(Debug, Clone, PartialEq)]
pub struct SavedState {
    particles: Particles,
    time: f64,
    steps: u64,
    gates_removed: bool,
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
    bodies: Vec<BodyParticles>,
    totals: RunTotals,
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
        let grid = CellGrid::new(layout.domain.lo, layout.domain.hi, cfg.spacing);
        let bodies: Vec<Aabb> = cfg.body.iter().map(|b| Aabb { min: b.min, max: b.max }).collect();
        let monitor = StabilityMonitor::new(layout.domain, layout.tank, &bodies, cfg.spacing, cfg.gravity);
        let mut particles = layout.particles;
        let mut step = EmpsStep::new(kernel, physics, grid);
        step.refresh_pressure(&mut particles);
        FluidSolver {
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
            bodies: layout.bodies,
            totals: RunTotals::default(),
        }
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

    /// The rigid bodies' particle ids.
    pub fn bodies(&self) -> &[BodyParticles] {
        &self.bodies
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
        self.particles.remove_kind(Kind::Gate)
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
        let totals = self.step.advance(&mut self.particles, dt);
        self.steps += 1;
        self.time += dt;
        for a in 0..3 {
            self.totals.wall_impulse[a] += totals.force_from_walls[a] * dt;
        }
        self.totals.candidates += totals.candidates;
        self.totals.particle_steps += self.particles.len() as u64;
        self.monitor.check(&self.particles, self.steps, self.time, dt)?;
        Ok(totals)
    }

    /// Steps with Δt until `t_end`, shortening the last step to land exactly on it.
    pub fn advance_to(&mut self, t_end: f64) -> Result<(), Instability> {
        while self.time < t_end {
            let left = t_end - self.time;
            if left <= self.time_step * LANDING_SLACK {
                self.time = t_end;
                break;
            }
            let dt = if left <= self.time_step * (1.0 + LANDING_SLACK) { left } else { self.time_step };
            self.step(dt)?;
            if dt == left {
                self.time = t_end;
            }
        }
        Ok(())
    }

    /// A copy of the state (particles, clock) for implicit coupling.
    pub fn save_state(&self) -> SavedState {
        SavedState {
            particles: self.particles.clone(),
            time: self.time,
            steps: self.steps,
            gates_removed: self.gates_removed,
        }
    }

    /// Puts back a state saved by [`FluidSolver::save_state`].
    pub fn restore_state(&mut self, s: &SavedState) {
        self.particles.clone_from(&s.particles);
        self.time = s.time;
        self.steps = s.steps;
        self.gates_removed = s.gates_removed;
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
