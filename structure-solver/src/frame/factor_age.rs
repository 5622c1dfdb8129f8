//! When the kept factor of the effective matrix `M/(βΔt²) + K` (S2-14) must be redone, and whether
//! its values must be assembled anew for that. A step solves with the kept matrix, which differs from
//! the current one by δ; since the internal forces R are always evaluated exactly, δ Δu is an error of
//! that step only (it is not accumulated), but it acts as an explicit term, stable and small only
//! while δ is small next to the mass term `m/(βΔt²)`.
//!
//! Per element, δ is estimated from the rotation θ of its co-rotational frame since the values were
//! assembled (a stiffness rotated by θ differs by about `2θ k`, k its largest section stiffness over
//! its length; the rotary inertia by `2θ` of itself) and from the change of its axial force N (the
//! geometric stiffness `N/l`). The values are assembled anew and factorised when, for some element,
//! `2θ k + |ΔN|/l > η m/(βΔt²)` or `2θ > η` (m: the element's lumped end mass, η: the limit).
//! Hinges forming or closing (and the integration points moving with them) change an element's K
//! outright: such elements are found by their hinge and integration point and their members are
//! re-condensed alone (`condensed_system.rs`); the steps then solve by conjugate gradients with the
//! kept factor as preconditioner (`preconditioned_cg.rs`). The values as they are then (assembled,
//! with those members re-condensed) are factorised again when those iterations have cost about one
//! refactorisation since the factor was made ([`CG_PRODUCTS_LIMIT`]), or when so many elements
//! changed that they would ([`CHANGED_ELEMENTS_LIMIT`]): that skips the assembly and condensation
//! of every other member, about a third of a refactorisation on the benchmark's 7 × 7 × 7 grid. A
//! fracture changes the connectivity and everything is redone.

use super::hinge::{End, StressState};
use super::newmark;
use super::section::Section;
use super::topology::Element;
use nalgebra::Matrix3;

/// Default η: the kept matrix may differ from the current one by 5 % of the mass term.
pub const DEFAULT_STALE_LIMIT: f64 = 0.05;

/// Products with the matrix in conjugate-gradient solves after which the factor is redone. At 10⁴
/// DOFs (the benchmark's 7 × 7 × 7 grid, hinges forming) a product with its preconditioning solve
/// takes about 0.2 ms, a factorisation of the kept values 2.1 ms (3.4 ms with a new assembly); with
/// 25 (and [`CHANGED_ELEMENTS_LIMIT`] = 48) steps took as long as with 12, 16 or 40 (and 24, 32 or
/// 96), within the ±8 % scatter between runs.
pub const CG_PRODUCTS_LIMIT: usize = 25;

/// Elements with a changed hinge or integration point above which the factor is redone rather than
/// iterated with: on the benchmark's 7 × 7 × 7 grid a solve took about 5 + n/4 products for n
/// changed elements, so 48 changed elements already cost about 17 of [`CG_PRODUCTS_LIMIT`].
pub const CHANGED_ELEMENTS_LIMIT: usize = 48;

/// What the kept factor needs before the next step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Staleness {
    /// Nothing: it serves.
    Fresh,
    /// A factorisation of the current values (members whose tangent changed re-condensed first).
    Refactor,
    /// New values, assembled at the current state, and their factorisation.
    Reassemble,
}

/// Each element's co-rotational frame and axial force when the values were assembled, and its hinge
/// and integration point when its matrix was last made.
#[derive(Clone, Default)]
pub struct FactorAge {
    at_assembly: Vec<(Matrix3<f64>, f64)>,
    tangents: Vec<(Option<End>, f64)>,
    /// Products with the matrix in conjugate-gradient solves since the factorisation.
    cg_products: usize,
}

impl FactorAge {
    /// Remembers the elements' state at an assembly of the values (which a factorisation follows).
    pub fn record(&mut self, elements: &[Element], stresses: &[StressState]) {
        self.at_assembly.clear();
        self.at_assembly.extend(
            elements
                .iter()
                .zip(stresses)
                .map(|(e, s)| (e.current.frame, s.sigma[0])),
        );
        self.tangents.clear();
        self.tangents.extend(stresses.iter().map(tangent_of));
        self.cg_products = 0;
    }

    /// Notes a factorisation of the values as they are, without a new assembly.
    pub fn factorized(&mut self) {
        self.cg_products = 0;
    }

    /// Counts products with the matrix done in a conjugate-gradient solve.
    pub fn add_cg_products(&mut self, products: usize) {
        self.cg_products += products;
    }

    /// Elements whose hinge or integration point differs from when their matrix was made.
    pub fn changed_tangents(&self, stresses: &[StressState]) -> Vec<usize> {
        stresses
            .iter()
            .zip(&self.tangents)
            .enumerate()
            .filter(|(_, (s, made))| tangent_of(s) != **made)
            .map(|(i, _)| i)
            .collect()
    }

    /// Remembers the hinge and integration point of `changed` elements, whose matrices were remade.
    pub fn record_tangents(&mut self, stresses: &[StressState], changed: &[usize]) {
        for &e in changed {
            self.tangents[e] = tangent_of(&stresses[e]);
        }
    }

    /// What the kept factor needs before a step of `dt` (the criteria above with η = `limit`): new
    /// values when the kept ones differ too much from the current matrix, a factorisation of them
    /// when the conjugate-gradient iterations with the old one cost (or would cost) more than that. On
    /// one thread: a few dozen operations per element, which rayon's tasks did not speed up.
    pub fn staleness(
        &self,
        elements: &[Element],
        stresses: &[StressState],
        sections: &[Section],
        density: f64,
        dt: f64,
        limit: f64,
    ) -> Staleness {
        if self.at_assembly.len() != elements.len() {
            return Staleness::Reassemble;
        }
        let mass_factor = newmark::mass_factor(dt);
        let mut at_assembly = elements.iter().zip(stresses).zip(&self.at_assembly);
        let drifted = at_assembly.any(|((e, s), (frame, axial))| {
            let section = &sections[e.section];
            // ‖R₁ − R₀‖ = 2√2 sin(θ/2) (Frobenius): θ to second order without an arc cosine
            let theta = (e.current.frame - frame).norm() / std::f64::consts::SQRT_2;
            let stiffness = section.stiffness[..3].iter().fold(0.0_f64, |m, k| m.max(*k)) / e.length0;
            let geometric = (s.sigma[0] - axial).abs() / e.current.length;
            let mass = 0.5 * density * section.area * e.length0;
            2.0 * theta * stiffness + geometric > limit * mass * mass_factor || 2.0 * theta > limit
        });
        if drifted {
            Staleness::Reassemble
        } else if self.cg_products > CG_PRODUCTS_LIMIT
            || self.changed_tangents(stresses).len() > CHANGED_ELEMENTS_LIMIT
        {
            Staleness::Refactor
        } else {
            Staleness::Fresh
        }
    }
}

/// What an element's tangent stiffness is made with besides its state: its hinge and integration point.
fn tangent_of(s: &StressState) -> (Option<End>, f64) {
    (s.hinge, s.s)
}
