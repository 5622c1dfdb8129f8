//! The seam between the fluid solver and its method: [`FluidMethod`] runs one step of the
//! method the case picks, owns the method's pair laws and hands them to the body exchange.
//!
//! An enum, not a trait object: the methods are a closed set chosen by one case key; the solver
//! clones the whole method for checkpoints (a `Box<dyn Trait>` would need its own clone hook);
//! each method's hot loops stay statically dispatched; and one `match` per entry point shows what
//! each method does there.

use crate::bodies::pair_law::{Exchange, ExchangeScales, PairLaw};
use crate::emps::step::EmpsStep;
use crate::isph::ppe::PpeFailure;
use crate::isph::step::{IsphState, IsphStep};
use crate::isph::walls::TurnedSolids;
use crate::neighbours::neighbour_search::CellGrid;
use crate::particles::Particles;
use crate::stability::Instability;
use crate::stage_timer::StageTimes;

/// What one step exchanged and how much work it did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepTotals {
    /// Force of the walls, dummies and bodies on the fluid during the step [N]
    /// (pressure, viscous no-slip and collisions).
    pub force_from_walls: [f64; 3],
    /// Neighbour candidates examined over all passes.
    pub candidates: u64,
    /// Iterations of the pressure Poisson equation's solver (ISPH; 0 for E-MPS).
    pub ppe_iterations: u32,
    /// Fluid particles whose velocity the collision stage changed ([`crate::neighbours::collision::kicked`];
    /// not counted on the GPU path, 0 there).
    pub collisions: u64,
}

/// The fluid method of a participant.
#[derive(Debug, Clone)]
pub enum FluidMethod {
    /// Explicit MPS (seed 000), [`crate::emps`].
    Emps(Box<EmpsStep>),
    /// Incompressible SPH (seed 003), [`crate::isph`].
    Isph(Box<IsphStep>),
}

impl FluidMethod {
    /// Advances the particles by `dt` (see each method's step; `cut`: ISPH's advective limit cut
    /// it short, [`crate::isph::step_length`]) as step number `step` ending at `time` (for
    /// diagnostics); `bodies` is handed each pair law with the state it acts in.
    pub fn advance(
        &mut self,
        p: &mut Particles,
        grid: &mut CellGrid,
        state: &mut MethodState,
        (dt, cut, step, time): (f64, bool, u64, f64),
        bodies: impl FnMut(Exchange, &PairLaw, &CellGrid, &Particles),
    ) -> Result<StepTotals, Instability> {
        match (self, state) {
            (FluidMethod::Emps(s), _) => Ok(s.advance(p, grid, dt, bodies)),
            (FluidMethod::Isph(s), MethodState::Isph(st)) => {
                let tol = s.settings.ppe_tolerance;
                s.advance(p, grid, st, (dt, cut), bodies)
                    .map_err(|f| ppe_failure(f, tol, step, time))
            }
            (FluidMethod::Isph(_), MethodState::Emps) => unreachable!("ISPH is always built with its state"),
        }
    }

    /// Sorts the particles and sets the pressure of the present state (the initial outputs, and
    /// after particles were removed). An ISPH pressure that misses its tolerance here is
    /// reported by the next step, whose PPE is the same system.
    pub fn refresh_pressure(&mut self, p: &mut Particles, grid: &mut CellGrid, state: &mut MethodState) {
        match (self, state) {
            (FluidMethod::Emps(s), _) => s.refresh_pressure(p, grid),
            (FluidMethod::Isph(s), MethodState::Isph(st)) => {
                // A failure leaves p of the last iterate; the first step reports it.
                let _ = s.refresh_pressure(p, grid, st);
            }
            (FluidMethod::Isph(_), MethodState::Emps) => unreachable!("ISPH is always built with its state"),
        }
    }

    /// The solids turned rigidly from rest at the present positions (a flap paddle; `None`: none),
    /// whose kept wall normals ISPH turns with them ([`crate::isph::walls::TurnedSolids`]); E-MPS
    /// keeps no wall geometry.
    pub fn turn_solids(&mut self, turned: Option<TurnedSolids>) {
        if let FluidMethod::Isph(s) = self {
            s.turn_solids(turned);
        }
    }

    /// The pressure pair law on the present state: the bodies' load before a step.
    pub fn pressure_law<'a>(&'a self, p: &'a Particles, state: &MethodState) -> PairLaw<'a> {
        match (self, state) {
            (FluidMethod::Emps(s), _) => s.pressure_law(p),
            (FluidMethod::Isph(s), MethodState::Isph(st)) => s.pressure_law(p, st),
            (FluidMethod::Isph(_), MethodState::Emps) => unreachable!("ISPH is always built with its state"),
        }
    }

    /// The scales of a step of `dt`.
    pub fn scales(&self, dt: f64) -> ExchangeScales {
        match self {
            FluidMethod::Emps(s) => s.scales(dt),
            FluidMethod::Isph(s) => s.scales(dt),
        }
    }

    /// Wall time per stage since the start.
    pub fn stage_times(&self) -> &StageTimes {
        match self {
            FluidMethod::Emps(s) => s.stage_times(),
            FluidMethod::Isph(s) => s.stage_times(),
        }
    }
}

/// The part of a method's state that a checkpoint must keep beyond the particles (whose
/// pressure is the warm start of the next step).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum MethodState {
    /// E-MPS keeps nothing beyond the particles.
    Emps,
    /// ISPH's surface flags and last PPE record.
    Isph(IsphState),
}

/// The diagnostic of a PPE that missed its tolerance: the run stops with it.
pub(crate) fn ppe_failure(f: PpeFailure, tol: f64, step: u64, time: f64) -> Instability {
    Instability {
        step,
        time,
        particle: None,
        quantity: "pressure Poisson equation",
        message: format!(
            "the PPE ({} unknowns) did not reach its relative tolerance {tol:e}: residual {:.3e} after {} iterations; raise isph.ppe_max_iterations, loosen isph.ppe_tolerance or shorten time_step",
            f.unknowns, f.residual, f.iterations
        ),
    }
}
