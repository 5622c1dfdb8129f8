//! Equilibrium corrections within a step ([`Equilibrium::Iterate`]): after the first solve of S2-14,
//! corrections δ of the step's increment, `(K + M/(βΔt²)) δ = F − R + M (v/(βΔt) + (1/(2β) − 1) a
//! − Δu/(βΔt²))` with R at the trial state, until the unbalanced force is below a share of the first
//! one. A correction that increases it is halved (hinges switching); when [`MAX_CORRECTIONS`] do not
//! suffice, the best iterate is kept and its unbalanced force carries into the next step as in ASI's
//! one-solve steps ([`Frame::unconverged_steps`] counts these).
//!
//! [`Equilibrium::Iterate`]: super::stepping::Equilibrium::Iterate

use super::assembly::NODE_DOFS;
use super::newmark;
use super::stepping::{check_finite, norm};
use super::topology::{Element, Node};
use super::Frame;

/// Corrections per step at most.
pub const MAX_CORRECTIONS: usize = 12;
/// Times a correction that increases the unbalanced force is halved before it is taken anyway.
const MAX_HALVINGS: usize = 3;
/// A correction that reduces the unbalanced force by less than this factor makes the factor be redone.
const SLOW_CONVERGENCE: f64 = 0.25;

impl Frame {
    /// Solves the step's increment to equilibrium (relative `tolerance`); returns it.
    pub(super) fn solve_to_equilibrium(
        &mut self,
        dt: f64,
        loads: &[f64],
        inertia: &[f64],
        tolerance: f64,
    ) -> Result<Vec<f64>, String> {
        self.end_of_step_forces = None;
        let committed_nodes = self.nodes.clone();
        let committed_elements = self.elements.clone();
        let mass_factor = newmark::mass_factor(dt);
        let mut du = vec![0.0; self.nodes.len() * NODE_DOFS];
        let mut first_residual = None;
        let mut last_residual = f64::INFINITY;
        let mut best = (f64::INFINITY, du.clone());
        // the iterate the last correction started from, that correction and the halvings done on it
        let mut last_correction: Option<(Vec<f64>, Vec<f64>)> = None;
        let mut halvings = 0;
        for iteration in 0..=MAX_CORRECTIONS + 1 {
            let mut refactor = !self.system.has_factor_for(dt);
            let contributions = self.contributions();
            let mut rhs = self.residual(&self.gather(&contributions), loads, inertia, &du, mass_factor);
            let residual = norm(&rhs);
            let first = *first_residual.get_or_insert(residual);
            if iteration > 0 && residual <= tolerance * first {
                self.unbalance = residual / first;
                break;
            }
            if iteration > MAX_CORRECTIONS {
                // as in ASI's one-solve steps, the unbalanced force of the best iterate carries into
                // the next step's residual
                self.unconverged += 1;
                self.unbalance = best.0 / first;
                if best.1 != du {
                    du = best.1.clone();
                    self.set_trial(&committed_nodes, &committed_elements, &du);
                }
                break;
            }
            if residual < best.0 {
                best = (residual, du.clone());
            }
            if let Some((from, delta)) = &mut last_correction {
                if residual > last_residual && halvings < MAX_HALVINGS {
                    // the correction overshot (hinges switching): try half of it
                    halvings += 1;
                    delta.iter_mut().for_each(|d| *d *= 0.5);
                    du = from.iter().zip(delta.iter()).map(|(a, b)| a + b).collect();
                    self.set_trial(&committed_nodes, &committed_elements, &du);
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
            self.solve_with_current_tangent(&mut rhs, dt, mass_factor)?;
            let delta = rhs;
            last_correction = Some((du.clone(), delta.clone()));
            for (d, x) in du.iter_mut().zip(&delta) {
                *d += x;
            }
            check_finite(&du)?;
            self.set_trial(&committed_nodes, &committed_elements, &du);
        }
        Ok(du)
    }

    /// Puts the frame in the state the committed one reaches with the increment `du`.
    fn set_trial(&mut self, committed_nodes: &[Node], committed_elements: &[Element], du: &[f64]) {
        self.nodes.clone_from_slice(committed_nodes);
        self.apply_increment(du);
        self.elements.clone_from_slice(committed_elements);
        self.update_elements();
    }
}
