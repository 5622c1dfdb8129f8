//! The seam between the fluid solver and its method: [`FluidMethod`] runs one step of the
//! method the case picks, owns the method's pair laws and hands them to the body exchange.
//!
//! An enum, not a trait object: the methods are a closed set chosen by one case key; the solver
//! clones the whole method for checkpoints (a `Box<dyn Trait>` would need its own clone hook);
//! each method's hot loops stay statically dispatched; and one `match` per entry point shows what
//! each method does there.

use crate::emps::step::EmpsStep;
use crate::neighbour_search::CellGrid;
use crate::pair_law::{Exchange, ExchangeScales, PairLaw};
use crate::particles::Particles;
use crate::stage_timer::StageTimes;

/// What one step exchanged and how much work it did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepTotals {
    /// Force of the walls, dummies and bodies on the fluid during the step [N]
    /// (pressure, viscous no-slip and collisions).
    pub force_from_walls: [f64; 3],
    /// Neighbour candidates examined over all passes.
    pub candidates: u64,
}

/// The fluid method of a participant.
#[derive(Debug, Clone)]
pub enum FluidMethod {
    /// Explicit MPS (seed 000), [`crate::emps`].
    Emps(EmpsStep),
}

impl FluidMethod {
    /// Advances the particles by `dt` (see each method's step); `bodies` is handed each pair law
    /// with the state it acts in.
    pub fn advance(
        &mut self,
        p: &mut Particles,
        grid: &mut CellGrid,
        dt: f64,
        bodies: impl FnMut(Exchange, &PairLaw, &CellGrid, &Particles),
    ) -> StepTotals {
        match self {
            FluidMethod::Emps(s) => s.advance(p, grid, dt, bodies),
        }
    }

    /// Sorts the particles and sets the pressure of the present state (the initial outputs, and
    /// after particles were removed).
    pub fn refresh_pressure(&mut self, p: &mut Particles, grid: &mut CellGrid) {
        match self {
            FluidMethod::Emps(s) => s.refresh_pressure(p, grid),
        }
    }

    /// The pressure pair law on the present state: the bodies' load before a step.
    pub fn pressure_law<'a>(&self, p: &'a Particles) -> PairLaw<'a> {
        match self {
            FluidMethod::Emps(s) => s.pressure_law(p),
        }
    }

    /// The scales of a step of `dt`.
    pub fn scales(&self, dt: f64) -> ExchangeScales {
        match self {
            FluidMethod::Emps(s) => s.scales(dt),
        }
    }

    /// Wall time per stage since the start.
    pub fn stage_times(&self) -> &StageTimes {
        match self {
            FluidMethod::Emps(s) => s.stage_times(),
        }
    }
}

/// The part of a method's state that a checkpoint must keep beyond the particles (whose
/// pressure is the warm start of the next step).
#[derive(Debug, Clone, PartialEq)]
pub enum MethodState {
    /// E-MPS keeps nothing beyond the particles.
    Emps,
}
