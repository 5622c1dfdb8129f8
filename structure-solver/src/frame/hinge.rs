//! Plastic hinges of ASI-Gauss elements (S2 §3, docs/physics.md §5): a section that reaches the full-plastic
//! yield surface becomes a hinge; the integration point moves so that the hinge sits on the node, the
//! flow follows the normality rule, and the hinge closes again when it unloads.

use super::element::{moments_at, move_integration_point, strains, ELEMENT_DOFS};
use super::section::{Resultants, Section, YIELDING};

/// The end of an element where a hinge sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum End {
    /// ξ = −1, the element's first node.
    Start,
    /// ξ = +1, the element's second node.
    Finish,
}

impl End {
    /// Natural coordinate of this end.
    pub fn xi(self) -> f64 {
        match self {
            End::Start => -1.0,
            End::Finish => 1.0,
        }
    }

    /// Integration point that puts the stress-evaluation point r = −s on this end.
    pub fn integration_point(self) -> f64 {
        -self.xi()
    }

    /// Index (0 or 1) of this end's node in the element.
    pub fn node(self) -> usize {
        match self {
            End::Start => 0,
            End::Finish => 1,
        }
    }
}

/// Stress state of one element: resultants at its stress-evaluation point, where that point is, and
/// the hinge if any.
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
pub struct StressState {
    /// Integration point ξ = s; resultants are read at r = −s.
    pub s: f64,
    /// `[N, Qy, Qz, T, My, Mz]` at r = −s.
    pub sigma: Resultants,
    /// Accumulated generalised strains at the integration point (for fracture, S2-17).
    pub strain: Resultants,
    pub hinge: Option<End>,
    /// Plastic work dissipated in this element so far [J]: the trapezoid `l ⟨σ⟩ · Δε_p` of every
    /// plastic step, `Δε_p = D⁻¹ (σ_trial − σ)` the part of the strain increment the return to the
    /// yield surface took out of the elastic trial (normality flow; `energy.rs`).
    pub dissipated: f64,
    /// Change of [`StressState::strain_energy`] made by moving the integration point so far [J]:
    /// the end forces stay, the one-point strain energy does not (a hinge forming puts the point at
    /// the hinge, where |M| is largest).
    pub shifted: f64,
}

impl StressState {
    /// An unstressed elastic element with its integration point at `s`.
    pub fn elastic(s: f64) -> StressState {
        StressState {
            s,
            sigma: [0.0; 6],
            strain: [0.0; 6],
            hinge: None,
            dissipated: 0.0,
            shifted: 0.0,
        }
    }

    /// Moves the integration point to `s_new`, keeping the end forces.
    #[inline]
    pub fn move_to(&mut self, section: &Section, length: f64, s_new: f64) {
        if s_new != self.s {
            self.shift_to(section, length, s_new);
        }
    }

    /// [`StressState::move_to`] a point other than its own: the end forces stay, the one-point
    /// strain energy changes (added to `shifted`). Apart, so that the test above is inlined into
    /// the per-step pass over all elements, which moves almost none.
    fn shift_to(&mut self, section: &Section, length: f64, s_new: f64) {
        let before = self.strain_energy(section, length);
        move_integration_point(length, self.s, s_new, &mut self.sigma);
        self.shifted += self.strain_energy(section, length) - before;
        self.s = s_new;
    }

    /// Section stiffness relating resultant and strain increments: elastic D, or at a hinge the
    /// normality-rule `D − D a aᵀ D / (aᵀ D a)` (docs/physics.md §5); at the surface's apex (the
    /// squash load, no moment) none in N, My and Mz, since the return keeps every nearby trial state
    /// there ([`Section::at_apex`]).
    pub fn tangent(&self, section: &Section) -> [[f64; 6]; 6] {
        let d = section.stiffness;
        let mut t = [[0.0; 6]; 6];
        let apex = self.hinge.is_some() && section.at_apex(&self.sigma);
        for (i, row) in t.iter_mut().enumerate() {
            if !(apex && YIELDING.contains(&i)) {
                row[i] = d[i];
            }
        }
        if self.hinge.is_some() && !apex {
            let a = section.yield_gradient(&self.sigma);
            let ada: f64 = YIELDING.iter().map(|&i| a[i] * d[i] * a[i]).sum();
            if ada > 0.0 {
                for &i in &YIELDING {
                    for &j in &YIELDING {
                        t[i][j] -= d[i] * a[i] * a[j] * d[j] / ada;
                    }
                }
            }
        }
        t
    }

    /// Advances the resultants by the natural deformation increment `dd` (local, 12): forms a hinge
    /// where an elastic element's end reaches the yield surface (the whole increment is then taken
    /// with the integration point already at the hinge, which keeps the response consistent with the
    /// hinge's tangent), flows plastically at a loading hinge (closest-point return) and closes a
    /// hinge whose elastic trial falls inside the surface. This state becomes `start` so advanced
    /// (`stress_states.rs` keeps both). No hinge forms at a `free` end (its node held by no other
    /// element and no support, `fracture.rs`): nothing lies beyond it to turn about it, and the
    /// section force there is only what its node's own load and inertia ask.
    pub fn update_from(
        &mut self,
        start: &StressState,
        section: &Section,
        length: f64,
        dd: &[f64; ELEMENT_DOFS],
        free: [bool; 2],
    ) {
        *self = *start;
        self.elastic_trial(section, length, dd);
        match self.hinge {
            None => {
                let f_at = |end: End| {
                    if free[end.node()] {
                        return f64::NEG_INFINITY;
                    }
                    let (my, mz) = moments_at(length, self.s, &self.sigma, end.xi());
                    section.yield_function(self.sigma[0], my, mz)
                };
                let (f_start, f_finish) = (f_at(End::Start), f_at(End::Finish));
                if f_start.max(f_finish) >= 0.0 {
                    let end = if f_start >= f_finish {
                        End::Start
                    } else {
                        End::Finish
                    };
                    *self = *start;
                    self.move_to(section, length, end.integration_point());
                    self.hinge = Some(end);
                    let before = self.sigma;
                    self.elastic_trial(section, length, dd);
                    let trial = self.sigma;
                    section.return_to_surface(&mut self.sigma);
                    self.dissipate(section, length, &before, &trial);
                }
            }
            Some(_) => {
                if section.yield_function(self.sigma[0], self.sigma[4], self.sigma[5]) > 0.0 {
                    let trial = self.sigma;
                    section.return_to_surface(&mut self.sigma);
                    self.dissipate(section, length, &start.sigma, &trial);
                } else {
                    self.hinge = None;
                }
            }
        }
    }

    /// Adds the plastic work of a step from resultants `before` through the elastic `trial` to the
    /// returned `self.sigma`: `l Σᵢ ⟨σᵢ⟩ (trialᵢ − σᵢ) / Dᵢ` (a few products, at hinges only).
    fn dissipate(&mut self, section: &Section, length: f64, before: &Resultants, trial: &Resultants) {
        let mut work = 0.0;
        for i in 0..6 {
            let d = section.stiffness[i];
            if d > 0.0 {
                work += 0.5 * (before[i] + self.sigma[i]) * (trial[i] - self.sigma[i]) / d;
            }
        }
        self.dissipated += length * work;
    }

    /// Elastic strain energy of the element's section forces, `½ l Σᵢ σᵢ² / Dᵢ` (one-point rule).
    pub fn strain_energy(&self, section: &Section, length: f64) -> f64 {
        let mut u = 0.0;
        for i in 0..6 {
            let d = section.stiffness[i];
            if d > 0.0 {
                u += self.sigma[i] * self.sigma[i] / d;
            }
        }
        0.5 * length * u
    }

    /// Adds the elastic response `D B(s) dd` to the resultants and `B(s) dd` to the strains.
    fn elastic_trial(&mut self, section: &Section, length: f64, dd: &[f64; ELEMENT_DOFS]) {
        let de = strains(length, self.s, dd);
        for (i, de) in de.iter().enumerate() {
            self.strain[i] += de;
            self.sigma[i] += section.stiffness[i] * de;
        }
    }
}
