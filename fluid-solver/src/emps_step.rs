//! One E-MPS time step, S1-9 … S1-15, read top to bottom as a list of stages.
//!
//! One addition to the seed: a collision stage after S1-13 ([`operators::collision`], as in
//! Koshizuka's MPS codes). The seed is silent on it; without it, at the seed's c = 12.1 m/s a
//! lone fast particle is stopped by the walls' equation-of-state pressure only after it has
//! passed the first wall layer (seen in the seed tank at t ≈ 0.18 s), or is shot out at
//! 15 m/s after a near contact.

use crate::kernel::Kernel;
use crate::kind::{Kind, FLUID};
use crate::neighbour_search::CellGrid;
use crate::operators::{self, VectorField};
use crate::particles::Particles;
use rayon::prelude::*;

/// Particles closer than this many spacings that approach each other collide.
pub const COLLISION_DISTANCE: f64 = 0.8;
/// Coefficient of restitution of a collision.
pub const RESTITUTION: f64 = 0.2;

/// The physical parameters of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Physics {
    /// ρ0 [kg/m³].
    pub density: f64,
    /// ν [m²/s].
    pub viscosity: f64,
    /// Whether ν⟨∇²u⟩ is computed (S1-10).
    pub viscosity_term: bool,
    /// g [m/s²].
    pub gravity: [f64; 3],
    /// c [m/s] (S1-16).
    pub sound_speed: f64,
}

/// What one step exchanged and how much work it did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepTotals {
    /// Force of the walls, dummies and bodies on the fluid during the step [N]
    /// (pressure of S1-3, viscous no-slip of S1-4 and collisions).
    pub force_from_walls: [f64; 3],
    /// Neighbour candidates examined over all passes.
    pub candidates: u64,
}

/// The stage of the step at which the bodies read their share of an exchange with the fluid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exchange {
    /// S1-4's viscous pair terms, at r^k (only when the viscous term is on).
    Viscous,
    /// S1-3's pressure pair forces, at r* with the pressures of S1-14.
    Pressure,
    /// The collision stage's impulses, before they are applied.
    Collision,
}

/// The work buffers of the step (reused every step).
#[derive(Debug, Clone)]
pub struct EmpsStep {
    pub kernel: Kernel,
    pub physics: Physics,
    pub grid: CellGrid,
    scratch: Vec<f64>,
    accel: VectorField,
}

impl EmpsStep {
    /// A step for particles of spacing Δs = `kernel.spacing` inside `grid`.
    pub fn new(kernel: Kernel, physics: Physics, grid: CellGrid) -> EmpsStep {
        EmpsStep {
            kernel,
            physics,
            grid,
            scratch: Vec::new(),
            accel: VectorField::default(),
        }
    }

    /// Advances the particles by `dt`: the stages of S1-9 … S1-15 in order. `bodies` is shown
    /// the state each exchange with the bodies is computed from, before it is applied: the
    /// velocities at r^k when the viscous term is on ([`Exchange::Viscous`]), the pressures at r*
    /// ([`Exchange::Pressure`]) and the collision stage ([`Exchange::Collision`]).
    pub fn advance(
        &mut self,
        p: &mut Particles,
        dt: f64,
        mut bodies: impl FnMut(Exchange, &CellGrid, &Particles),
    ) -> StepTotals {
        let mut totals = StepTotals::default();
        let viscous = self.physics.viscosity_term && self.physics.viscosity > 0.0;
        if viscous {
            self.grid.sort(p, &mut self.scratch); // cell lists at r^k
            self.viscous_laplacian(p, &mut totals); // S1-4
            bodies(Exchange::Viscous, &self.grid, p);
        }
        self.predict(p, dt, viscous); // S1-10, S1-11
        self.grid.sort(p, &mut self.scratch); // cell lists at r*
        totals.candidates += operators::number_density(&self.grid, &self.kernel, p); // S1-15
        self.equation_of_state(p); // S1-14
        self.pressure_gradient(p, &mut totals); // S1-3
        bodies(Exchange::Pressure, &self.grid, p);
        self.correct(p, dt); // S1-12, S1-13
        self.collide(p, dt, &mut totals, |g, p| bodies(Exchange::Collision, g, p));
        totals
    }

    /// Mass of one particle ρ0 Δs³.
    fn particle_mass(&self) -> f64 {
        self.physics.density * self.kernel.spacing.powi(3)
    }

    /// S1-4 on the velocities at r^k, into the acceleration buffer.
    fn viscous_laplacian(&mut self, p: &Particles, totals: &mut StepTotals) {
        let t = operators::laplacian(&self.grid, &self.kernel, p, &mut self.accel);
        let m_nu = self.particle_mass() * self.physics.viscosity;
        for a in 0..3 {
            totals.force_from_walls[a] += m_nu * t.from_non_fluid[a];
        }
        totals.candidates += t.candidates;
    }

    /// S1-3 on the pressures at r*, into the acceleration buffer.
    fn pressure_gradient(&mut self, p: &Particles, totals: &mut StepTotals) {
        let t = operators::gradient(&self.grid, &self.kernel, p, &p.pressure, &mut self.accel);
        let volume = self.particle_mass() / self.physics.density;
        for a in 0..3 {
            totals.force_from_walls[a] -= volume * t.from_non_fluid[a];
        }
        totals.candidates += t.candidates;
    }

    /// Collisions of close approaching particles (see the module doc), applied like S1-13.
    fn collide(
        &mut self,
        p: &mut Particles,
        dt: f64,
        totals: &mut StepTotals,
        body_contact: impl FnOnce(&CellGrid, &Particles),
    ) {
        let distance = COLLISION_DISTANCE * self.kernel.spacing;
        let t = operators::collision(&self.grid, p, distance, RESTITUTION, &mut self.accel);
        body_contact(&self.grid, p);
        let m = self.particle_mass();
        for a in 0..3 {
            totals.force_from_walls[a] += m * t.from_non_fluid[a] / dt;
        }
        totals.candidates += t.candidates;
        self.apply_collisions(p, dt);
    }

    /// Sorts the particles and computes the number density and pressure at their present
    /// positions (S1-15, S1-14), e.g. for the initial state's outputs.
    pub fn refresh_pressure(&mut self, p: &mut Particles) {
        self.grid.sort(p, &mut self.scratch);
        operators::number_density(&self.grid, &self.kernel, p);
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
