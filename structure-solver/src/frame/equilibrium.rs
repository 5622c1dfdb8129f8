//! Equilibrium corrections within a step ([`Equilibrium::Iterate`]): after the first solve of S2-14,
//! corrections δ of the step's increment, `(K + M/(βΔt²)) δ = F − R + M (v/(βΔt) + (1/(2β) − 1) a
//! − Δu/(βΔt²))` with R at the trial state, until the unbalanced force is below a share of the first
//! one. A correction that switched hinges and increased the unbalanced force is halved (a hinge
//! flipping between elastic and plastic); any other correction is taken whole: a Newton correction
//! of a rotating member stretches its chord to second order, so its first correction often raises
//! the unbalanced force and the next ones bring it down. A step that does not reach the tolerance
//! within [`MAX_CORRECTIONS`] keeps its last iterate when that left less unbalanced force than the
//! step began with (the rest carries into the next step as in a one-solve step; such steps are
//! counted and [`Frame::accuracy_warning`] reports them) and is an error otherwise. It never ends on
//! an earlier iterate: keeping the best one kept the zero increment of a quasi-static cantilever,
//! whose first correction always raised the unbalanced force, and froze it.
//!
//! [`Equilibrium::Iterate`]: super::stepping::Equilibrium::Iterate

use super::assembly::NODE_DOFS;
use super::hinge::End;
use super::stepping::{check_finite, norm};
use super::Frame;

/// Corrections per step at most.
pub const MAX_CORRECTIONS: usize = 12;
/// Times a correction that switched hinges and increased the unbalanced force is halved before it
/// is taken anyway.
const MAX_HALVINGS: usize = 3;
/// A correction that reduces the unbalanced force by less than this factor makes the factor be redone.
const SLOW_CONVERGENCE: f64 = 0.25;
/// Share of the step's target unbalanced force (`tolerance` times its first one) to which a
/// correction's linear solve by conjugate gradients is carried (besides their relative tolerance,
/// whichever is reached first): the error of the solve adds to the next unbalanced force.
const LINEAR_SOLVE_SHARE: f64 = 0.01;
/// A correction: the iterate it started from, the correction and the hinges before it.
type Correction = (Vec<f64>, Vec<f64>, Vec<Option<End>>);

impl Frame {
    /// Solves the step's increment to equilibrium (relative `tolerance`); returns it, or an error
    /// when [`MAX_CORRECTIONS`] do not reach the tolerance.
    pub(super) fn solve_to_equilibrium(
        &mut self,
        dt: f64,
        loads: &[f64],
        inertia: &[f64],
        tolerance: f64,
    ) -> Result<Vec<f64>, String> {
        self.end_of_step_forces = None;
        // the committed state, which every iterate starts from
        self.kept.keep(&self.nodes, &self.elements, &self.stresses);
        let mass_factor = self.effective_mass_factor(dt);
        let mut du = vec![0.0; self.nodes.len() * NODE_DOFS];
        let mut first_residual = None;
        let mut last_residual = f64::INFINITY;
        // the iterate the last correction started from, that correction, the hinges before it and
        // the halvings done on it
        let mut last_correction: Option<Correction> = None;
        let mut halvings = 0;
        let round_off = self.round_off_unbalance();
        for iteration in 0..=MAX_CORRECTIONS + 1 {
            let mut refactor = !self.system.has_factor_for(dt);
            let contributions = self.contributions();
            let mut rhs = self.residual(&self.gather(&contributions), loads, inertia, &du, mass_factor, dt);
            let residual = norm(&rhs);
            let first = *first_residual.get_or_insert(residual);
            if residual <= round_off {
                // in balance to round-off: a step that starts so has nothing left to share out
                self.unbalance = 0.0;
                break;
            }
            if residual <= tolerance * first {
                self.unbalance = residual / first;
                break;
            }
            if iteration > MAX_CORRECTIONS {
                self.unconverged += 1;
                self.unbalance = residual / first;
                if residual < first {
                    // as in a one-solve step, the unbalanced force left carries into the next step;
                    // counted, and reported by `accuracy_warning`
                    break;
                }
                return Err(format!(
                    "frame step {}: {MAX_CORRECTIONS} equilibrium corrections left {:.2e} times the step's first \
                     unbalanced force (equilibrium_tolerance = {tolerance}): the corrections diverge; halve \
                     time_step",
                    self.steps + 1,
                    residual / first
                ));
            }
            if let Some((from, delta, hinges)) = &mut last_correction {
                let switched = || {
                    self.stresses
                        .current()
                        .iter()
                        .zip(hinges.iter())
                        .any(|(s, h)| s.hinge != *h)
                };
                if residual > last_residual && halvings < MAX_HALVINGS && switched() {
                    // the correction overshot (hinges switching): try half of it
                    halvings += 1;
                    delta.iter_mut().for_each(|d| *d *= 0.5);
                    du = from.iter().zip(delta.iter()).map(|(a, b)| a + b).collect();
                    self.set_trial(&du);
                    continue;
                }
                if residual > SLOW_CONVERGENCE * last_residual && !refactor {
                    // the kept factor is a poor iteration matrix now: redo it from the current tangent
                    self.system.drop_values();
                    refactor = true;
                }
            }
            halvings = 0;
            last_residual = residual;
            if refactor {
                self.refactor(Some(&contributions), dt, mass_factor)?;
            }
            // the linear solve need not be finer than a share of what the step must reach
            let enough = LINEAR_SOLVE_SHARE * tolerance * first;
            self.solve_with_current_tangent(&mut rhs, dt, mass_factor, enough)?;
            let delta = rhs;
            let hinges = self.stresses.current().iter().map(|s| s.hinge).collect();
            last_correction = Some((du.clone(), delta.clone(), hinges));
            for (d, x) in du.iter_mut().zip(&delta) {
                *d += x;
            }
            check_finite(&du)?;
            self.set_trial(&du);
        }
        Ok(du)
    }

    /// Puts the frame in the state the committed one (kept at the start of the step) reaches with
    /// the increment `du`.
    fn set_trial(&mut self, du: &[f64]) {
        self.kept
            .restore(&mut self.nodes, &mut self.elements, &mut self.stresses);
        self.apply_increment(du);
        self.update_elements();
    }
}
