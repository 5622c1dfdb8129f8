//! One E-MPS time step, S1-9 … S1-15, read top to bottom as a list of named stages, each timed.
//!
//! One addition to the seed: a collision stage after S1-13 ([`crate::neighbours::collision`], as in
//! Koshizuka's MPS codes). The seed is silent on it; without it, at the seed's c = 12.1 m/s a
//! lone fast particle is stopped by the walls' equation-of-state pressure only after it has
//! passed the first wall layer (seen in the seed tank at t ≈ 0.18 s), or is shot out at
//! 15 m/s after a near contact.

use super::kernel::Kernel;
use super::{artificial_viscosity, operators, pair_laws};
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

/// The work buffers of the step (reused every step) and its stage times.
#[derive(Debug, Clone)]
pub struct EmpsStep {
    pub kernel: Kernel,
    pub physics: Physics,
    /// α of the optional artificial viscosity ([`artificial_viscosity`]); 0: off.
    alpha: f64,
    scratch: Vec<f64>,
    accel: VectorField,
    times: StageTimes,
}

impl EmpsStep {
    /// A step for particles of spacing Δs = `kernel.spacing`.
    pub fn new(kernel: Kernel, physics: Physics) -> EmpsStep {
        EmpsStep {
            kernel,
            physics,
            alpha: 0.0,
            scratch: Vec::new(),
            accel: VectorField::default(),
            times: StageTimes::default(),
        }
    }

    /// The same step with the artificial viscosity α (0, the default, is off).
    pub fn with_artificial_viscosity(mut self, alpha: f64) -> EmpsStep {
        self.alpha = alpha;
        self
    }

    /// Wall time per stage since the start.
    pub fn stage_times(&self) -> &StageTimes {
        &self.times
    }

    /// Advances the particles by `dt`: the stages of S1-9 … S1-15 in order. `bodies` is handed
    /// each pair law of an exchange with the bodies with the state it is computed from, before
    /// it is applied: S1-4 at r^k when the viscous term is on ([`Exchange::Viscous`]), S1-3 with
    /// the pressures at r* ([`Exchange::Pressure`]) and the collisions ([`Exchange::Collision`]).
    pub fn advance(
        &mut self,
        p: &mut Particles,
        grid: &mut CellGrid,
        dt: f64,
        mut bodies: impl FnMut(Exchange, &PairLaw, &CellGrid, &Particles),
    ) -> StepTotals {
        let mut totals = StepTotals::default();
        let scales = self.scales(dt);
        let viscous = self.physics.viscous();
        let t = self.times.start();
        if viscous {
            grid.sort(p, &mut self.scratch); // cell lists at r^k
            self.viscous_laplacian(grid, p, &mut totals); // S1-4
            bodies(
                Exchange::Viscous,
                &pair_laws::viscous(&self.kernel, &scales, p),
                grid,
                p,
            );
        }
        let t = self.times.lap(t, "viscous");
        self.predict(p, dt, viscous); // S1-10, S1-11
        let t = self.times.lap(t, "predict");
        grid.sort(p, &mut self.scratch); // cell lists at r*
        let t = self.times.lap(t, "neighbour search");
        totals.candidates += operators::number_density(grid, &self.kernel, p); // S1-15
        self.equation_of_state(p); // S1-14
        let t = self.times.lap(t, "density and pressure");
        self.pressure_gradient(grid, p, &mut totals); // S1-3
        self.artificial_viscosity(grid, p, &mut totals);
        bodies(Exchange::Pressure, &pair_laws::pressure(&self.kernel, p), grid, p);
        self.correct(p, dt); // S1-12, S1-13
        let t = self.times.lap(t, "pressure gradient");
        self.collide(grid, p, dt, &mut totals, |g, p| {
            bodies(Exchange::Collision, &collision::contact_law(&scales, p), g, p)
        });
        self.times.lap(t, "collision");
        totals
    }

    /// The scales that turn velocity changes of a step of `dt` into forces.
    pub fn scales(&self, dt: f64) -> ExchangeScales {
        ExchangeScales {
            spacing: self.kernel.spacing,
            particle_mass: self.particle_mass(),
            viscosity: self.physics.viscosity,
            dt,
        }
    }

    /// S1-3's pressure pair law with the present pressures (the bodies' load before a step).
    pub fn pressure_law<'a>(&self, p: &'a Particles) -> PairLaw<'a> {
        pair_laws::pressure(&self.kernel, p)
    }

    /// Mass of one particle ρ0 Δs³.
    fn particle_mass(&self) -> f64 {
        self.physics.density * self.kernel.spacing.powi(3)
    }

    /// S1-4 on the velocities at r^k, into the acceleration buffer.
    fn viscous_laplacian(&mut self, grid: &CellGrid, p: &Particles, totals: &mut StepTotals) {
        let t = operators::laplacian(grid, &self.kernel, p, &mut self.accel);
        let m_nu = self.particle_mass() * self.physics.viscosity;
        for a in 0..3 {
            totals.force_from_walls[a] += m_nu * t.from_non_fluid[a];
        }
        totals.candidates += t.candidates;
    }

    /// S1-3 on the pressures at r*, into the acceleration buffer.
    fn pressure_gradient(&mut self, grid: &CellGrid, p: &Particles, totals: &mut StepTotals) {
        let t = operators::gradient(grid, &self.kernel, p, &p.pressure, &mut self.accel);
        let volume = self.particle_mass() / self.physics.density;
        for a in 0..3 {
            totals.force_from_walls[a] -= volume * t.from_non_fluid[a];
        }
        totals.candidates += t.candidates;
    }

    /// The optional artificial viscosity's ⟨∇q⟩, added to ⟨∇P⟩ at r*, u* (fluid pairs only, so
    /// the walls' force is unchanged).
    fn artificial_viscosity(&mut self, grid: &CellGrid, p: &Particles, totals: &mut StepTotals) {
        if self.alpha > 0.0 {
            totals.candidates += artificial_viscosity::add_gradient(
                grid,
                &self.kernel,
                p,
                self.alpha,
                self.physics.density,
                self.physics.sound_speed,
                &mut self.accel,
            );
        }
    }

    /// Collisions of close approaching particles (see the module doc), applied like S1-13.
    fn collide(
        &mut self,
        grid: &CellGrid,
        p: &mut Particles,
        dt: f64,
        totals: &mut StepTotals,
        body_contact: impl FnOnce(&CellGrid, &Particles),
    ) {
        let distance = COLLISION_DISTANCE * self.kernel.spacing;
        let t = collision::collision(grid, p, distance, RESTITUTION, &mut self.accel);
        body_contact(grid, p);
        let m = self.particle_mass();
        for a in 0..3 {
            totals.force_from_walls[a] += m * t.from_non_fluid[a] / dt;
        }
        totals.candidates += t.candidates;
        totals.collisions = collision::kicked(&self.accel);
        self.apply_collisions(p, dt);
    }

    /// Sorts the particles and computes the number density and pressure at their present
    /// positions (S1-15, S1-14), e.g. for the initial state's outputs.
    pub fn refresh_pressure(&mut self, p: &mut Particles, grid: &mut CellGrid) {
        grid.sort(p, &mut self.scratch);
        operators::number_density(grid, &self.kernel, p);
        self.equation_of_state(p);
    }

    /// S1-10, S1-11: `u* = u + (ν⟨∇²u⟩ + g)Δt`, `r* = r + u*Δt` for fluid; bodies move with
    /// their own velocity; walls stay.
    fn predict(&self, p: &mut Particles, dt: f64, viscous: bool) {
        let g = self.physics.gravity;
        let nu = if viscous { self.physics.viscosity } else { 0.0 };
        let lap = &self.accel;
        let body = Kind::Body.code();
        (
            &mut p.x, &mut p.y, &mut p.z, &mut p.vx, &mut p.vy, &mut p.vz, &p.kind,
        )
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, (x, y, z, u, v, w, &k))| {
                if k == FLUID {
                    let (lx, ly, lz) = if viscous {
                        (lap.x[i], lap.y[i], lap.z[i])
                    } else {
                        (0.0, 0.0, 0.0)
                    };
                    *u += (nu * lx + g[0]) * dt;
                    *v += (nu * ly + g[1]) * dt;
                    *w += (nu * lz + g[2]) * dt;
                }
                if k == FLUID || k == body {
                    *x += *u * dt;
                    *y += *v * dt;
                    *z += *w * dt;
                }
            });
    }

    /// S1-15 and S1-14: `ρ* = ρ0 n*/n0`, `P = c²(ρ* − ρ0)` where ρ* > ρ0, else 0 (the free
    /// surface). Walls use the same law with their own number density.
    fn equation_of_state(&self, p: &mut Particles) {
        let rho = self.physics.density;
        let c2 = self.physics.sound_speed * self.physics.sound_speed;
        let inv_n0 = 1.0 / self.kernel.n0;
        (&mut p.pressure, &p.number_density)
            .into_par_iter()
            .with_min_len(4096)
            .for_each(|(pr, &n)| {
                let rho_star = rho * n * inv_n0;
                *pr = if rho_star > rho {
                    c2 * (rho_star - rho)
                } else {
                    0.0
                };
            });
    }

    /// Adds the collision velocity change Δu and moves the particle by Δu Δt, as S1-13 does.
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

    /// S1-12, S1-13: `u^{k+1} = u* − Δt/ρ0 ⟨∇P⟩`, `r^{k+1} = r* + (u^{k+1} − u*)Δt` for fluid.
    fn correct(&self, p: &mut Particles, dt: f64) {
        let s = dt / self.physics.density;
        let grad = &self.accel;
        (&mut p.x, &mut p.y, &mut p.z, &mut p.vx, &mut p.vy, &mut p.vz)
            .into_par_iter()
            .enumerate()
            .with_min_len(4096)
            .for_each(|(i, (x, y, z, u, v, w))| {
                let du = [-s * grad.x[i], -s * grad.y[i], -s * grad.z[i]];
                *u += du[0];
                *v += du[1];
                *w += du[2];
                *x += du[0] * dt;
                *y += du[1] * dt;
                *z += du[2] * dt;
            });
    }
}
