//! The energy-balance check: the run's energy account (`energy.rs`) must balance, and when it does
//! not, the steps are wrong (every term is computed on its own, so a residual is energy the solver
//! made or lost). Checked after every step while the account is kept ([`Frame::record_energy`]:
//! runs with a history); the first step whose |residual| exceeds [`ENERGY_WARNING_SHARE`] of the
//! run's energy scale sets a warning, kept for the rest of the run ([`Frame::energy_warning`]).
//!
//! The scale is the largest of |W| (external work), T + U now, T + U when recording started, and
//! the dissipation so far D_p + D_d + D_alg: a free vibration's scale is its initial energy, a
//! pushed structure's the work done on it, a collapse's what its hinges took out.
//!
//! Threshold and margins, measured (|residual| / scale, worst over the run):
//! - good runs: elastic free vibration of a co-rotational cantilever 7e-7 (150 steps at T1/100),
//!   the fixed–fixed beam's plastic collapse 3.6e-4 (`tests/frame_energy.rs`); the benchmark's
//!   3 × 3 × 3 building pushed sideways with σy = 20 MPa (hinges forming and closing, 120 ms,
//!   `tests/frame_energy_check.rs`) iterated at Δt = 1 ms 1.7e-5, one solve per step at
//!   Δt = 0.5 ms 6.7e-4 and at 0.25 ms 5.5e-4.
//! - bad run: the same building with one solve per step at Δt = 1 ms: 1e-3 at step 27, 6.7e-3 at
//!   step 48, 14.5 % at step 52 (the first past 1 %), 76 % at step 120 (residual −3.9e6 J against
//!   W = 2.0e5 J). Its hinges form and close 7 545 times in 120 steps (356 iterated); its plastic
//!   dissipation is 5.1e6 J (8.6e4 J iterated), its kinetic energy 1.8e5 J (1.2e5 J): the solution
//!   is wrong, not the account, which balances the same hinge events in the iterated run. The
//!   unbalanced force each one-solve step carries into the next does the work the residual shows.
//!
//! 1 % is 15 times the worst good run and 1/15 of the bad run at the step it crosses it.
//!
//! Hinge chattering (a hinge forming and closing in successive steps) is the bad run's cause but not
//! a signal of its own: the warning counts it. Measured over 0.12 s of the building, events that
//! undo the change the same hinge made one step before: 5 712 of 7 545 in the bad run (up to 114 in
//! one step, of 288 elements), and in the good runs too, 86 of 356 iterated (up to 8 in a step),
//! 538 of 1 088 at 0.5 ms (up to 14) and 776 of 1 420 at 0.25 ms (up to 10): hinges on the yield
//! surface of a vibrating frame unload and reload, and a count of them does not tell a wrong run
//! from a right one the way the balance does.
//!
//! Cost: nothing while the account is not kept; while it is, one more pass over the nodes and
//! elements per step (the account's row).

use super::hinge_events::{HingeEvent, HingeEventKind};
use super::{Equilibrium, Frame};
use std::collections::HashMap;

/// |residual| / scale above which the energy balance counts as lost (see the module doc).
pub const ENERGY_WARNING_SHARE: f64 = 0.01;

impl Frame {
    /// Sets the energy warning at the first step whose balance residual exceeds
    /// [`ENERGY_WARNING_SHARE`] of the run's energy scale (while the account is kept); `dt`: the
    /// step just taken.
    pub(super) fn check_energy_balance(&mut self, dt: f64) {
        if self.energy_warning().is_some() {
            return;
        }
        let Some(row) = self.energy() else {
            return;
        };
        let start = self.energy_start_mechanical();
        let scale = row
            .external
            .abs()
            .max(row.kinetic + row.strain)
            .max(start)
            .max(row.plastic + row.damping + row.algorithmic);
        // a residual that is not a number counts as lost too
        let lost = row.residual.abs() > ENERGY_WARNING_SHARE * scale || !row.residual.is_finite();
        if !lost {
            return;
        }
        let events = match self.events.as_ref() {
            Some(e) => format!(
                "; its hinges formed or closed {} times in {} steps, {} of them undoing the change the \
                 same hinge made one step before",
                e.len(),
                self.steps + 1,
                reversals(e, dt)
            ),
            None => String::new(),
        };
        let advice = match self.equilibrium {
            Equilibrium::OneSolve => {
                "one solve per step has lost its accuracy (hinges that form and close in successive \
                 steps make energy): set equilibrium_tolerance (e.g. 1e-6) to iterate each step, or \
                 halve time_step"
            }
            Equilibrium::Iterate { .. } => "halve time_step",
        };
        let warning = format!(
            "the energy balance is lost at t = {:.6} s (step {}): residual {:.3e} J is {:.1} % of the run's \
             energy scale {:.3e} J (max of |external work| {:.3e} J, kinetic + strain {:.3e} J, dissipated \
             {:.3e} J; accurate runs stay below {} %){events}; the solution is not to be trusted: {advice}",
            self.elapsed,
            self.steps + 1,
            row.residual,
            100.0 * row.residual.abs() / scale,
            scale,
            row.external,
            row.kinetic + row.strain,
            row.plastic + row.damping + row.algorithmic,
            100.0 * ENERGY_WARNING_SHARE,
        );
        self.set_energy_warning(warning);
    }
}

/// Hinge events that undo the change their element's hinge made at most one step (`dt`) before: a
/// hinge closing right after it formed, or forming right after it closed (chattering). Worked out
/// only for the warning.
fn reversals(events: &[HingeEvent], dt: f64) -> usize {
    let mut last: HashMap<usize, (f64, HingeEventKind)> = HashMap::new();
    let mut count = 0;
    for e in events {
        if let Some(&(t, kind)) = last.get(&e.element) {
            let opposite = matches!(
                (kind, e.kind),
                (HingeEventKind::Forming, HingeEventKind::Closing)
                    | (HingeEventKind::Closing, HingeEventKind::Forming)
            );
            if opposite && e.time - t < 1.5 * dt {
                count += 1;
            }
        }
        last.insert(e.element, (e.time, e.kind));
    }
    count
}
