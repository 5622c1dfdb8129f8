//! When the kept factor of the effective matrix `M/(βΔt²) + K` (S2-14) must be redone. A step solves
//! with the kept matrix, which differs from the current one by δ; since the internal forces R are
//! always evaluated exactly, δ Δu is an error of that step only (it is not accumulated), but it acts as
//! an explicit term, stable and small only while δ is small next to the mass term `m/(βΔt²)`.
//!
//! Per element, δ is estimated from the rotation θ of its co-rotational frame since the factorisation
//! (a stiffness rotated by θ differs by about `2θ k`, k its largest section stiffness over its length;
//! the rotary inertia by `2θ` of itself) and from the change of its axial force N (the geometric
//! stiffness `N/l`). The factor is redone when, for some element,
//! `2θ k + |ΔN|/l > η m/(βΔt²)` or `2θ > η` (m: the element's lumped end mass, η: the limit).
//! Hinges forming or closing and fractures change K outright: the step drops the factor then.

use super::newmark;
use super::section::Section;
use super::topology::Element;
use nalgebra::Matrix3;
use rayon::prelude::*;

/// Default η: the kept matrix may differ from the current one by 5 % of the mass term.
pub const DEFAULT_STALE_LIMIT: f64 = 0.05;

/// Each element's co-rotational frame and axial force when the kept factor was made.
#[derive(Clone, Default)]
pub struct FactorAge {
    at_factorization: Vec<(Matrix3<f64>, f64)>,
}

impl FactorAge {
    /// Remembers the elements' state at a factorisation.
    pub fn record(&mut self, elements: &[Element]) {
        self.at_factorization.clear();
        self.at_factorization
            .extend(elements.iter().map(|e| (e.current.frame, e.stress.sigma[0])));
    }

    /// Whether the kept matrix differs too much from the current one for a step of `dt` (the
    /// criterion above with η = `limit`).
    pub fn is_stale(
        &self,
        elements: &[Element],
        sections: &[Section],
        density: f64,
        dt: f64,
        limit: f64,
    ) -> bool {
        if self.at_factorization.len() != elements.len() {
            return true;
        }
        let mass_factor = newmark::mass_factor(dt);
        elements
            .par_iter()
            .zip(&self.at_factorization)
            .with_min_len(super::PARALLEL_CHUNK)
            .any(|(e, (frame, axial))| {
                let section = &sections[e.section];
                // ‖R₁ − R₀‖ = 2√2 sin(θ/2) (Frobenius): θ to second order without an arc cosine
                let theta = (e.current.frame - frame).norm() / std::f64::consts::SQRT_2;
                let stiffness = section.stiffness[..3].iter().fold(0.0_f64, |m, k| m.max(*k)) / e.length0;
                let geometric = (e.stress.sigma[0] - axial).abs() / e.current.length;
                let mass = 0.5 * density * section.area * e.length0;
                2.0 * theta * stiffness + geometric > limit * mass * mass_factor || 2.0 * theta > limit
            })
    }
}
