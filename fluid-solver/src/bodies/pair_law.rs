//! Pair laws between a fluid particle and a solid (body) particle: the one function from which
//! the body exchange takes both a body's load and the reaction on the fluid.
//!
//! A fluid method owns its pair laws (E-MPS: [`crate::emps::pair_laws`]) and hands them to the
//! body exchange at the stage where they act ([`Exchange`]); [`crate::bodies`] sums one law over
//! the body's side and over the fluid's side, so action = reaction holds by construction, not by
//! two copies of a formula agreeing.

/// The stage of a step at which the bodies read their share of an exchange with the fluid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exchange {
    /// The viscous pair terms, at the step's start (only when the viscous term is on).
    Viscous,
    /// The pressure pair forces, with the pressures the step moves the fluid by.
    Pressure,
    /// The collision stage's impulses, before they are applied ([`crate::neighbours::collision`]); the walls'
    /// contact on the bodies ([`crate::bodies::body_wall_contact`]) is added here.
    Collision,
}

/// The force on solid particle j from fluid particle i (reversed, the force on i from j), or
/// `None` when the pair does not interact; pairs farther apart than `radius` never do.
pub struct PairLaw<'a> {
    /// Reach of the law [m].
    pub radius: f64,
    force: Box<dyn Fn(usize, usize) -> Option<[f64; 3]> + Sync + 'a>,
}

impl<'a> PairLaw<'a> {
    /// A law of reach `radius` with force `force(i, j)` on solid j from fluid i.
    pub fn new(radius: f64, force: impl Fn(usize, usize) -> Option<[f64; 3]> + Sync + 'a) -> PairLaw<'a> {
        PairLaw {
            radius,
            force: Box::new(force),
        }
    }

    /// The force on solid particle `j` from fluid particle `i`.
    #[inline]
    pub fn force(&self, i: usize, j: usize) -> Option<[f64; 3]> {
        (self.force)(i, j)
    }
}

/// What turns the viscous and collision stages' velocity changes into forces: Δs, m = ρ0 Δs³,
/// ν and the step Δt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExchangeScales {
    pub spacing: f64,
    pub particle_mass: f64,
    pub viscosity: f64,
    pub dt: f64,
}
