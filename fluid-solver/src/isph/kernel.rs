//! The SPH smoothing kernel of the ISPH method: Wendland's C2 function in 3D (Wendland 1995,
//! "Piecewise polynomial, positive definite and compactly supported radial functions of minimal
//! degree", Adv. Comput. Math. 4; normalisation as in Dehnen & Aly 2012, MNRAS 425), with support
//! radius r_e = 2.4 Δs (S2, Table 1):
//! `W(r) = 21/(2π r_e³) (1 − q)⁴ (1 + 4q)`, q = r/r_e < 1, and `W'(r) = −(210/(π r_e⁵)) r (1 − q)³`.
//! Chosen over the cubic spline because it has no pairing instability at the ~60 neighbours a
//! 2.4 Δs support holds (Dehnen & Aly 2012).
//!
//! The gradient is renormalised on the lattice: [`Wendland::dw_over_r`] is W'/r divided by
//! `m0 = −Σ_lattice V (W'/r) x²`, so that the first moment `Σ_j V (x_j − x_i) ⊗ ∇W_ij` is exactly
//! −I in a full lattice neighbourhood (a constant-matrix form of Bonet & Lok 1999's correction).
//! Without it the operators of S2-8 and S2-9 carry the kernel's discretisation error m0 ≠ 1
//! (1.5 % at 2.4 Δs), and a column at rest gains 1.5 % of gΔt downwards every step.

use crate::neighbours::moments::{lattice_moment, RadialGradient};

/// The kernel at one support radius, with its sums on the simple cubic lattice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wendland {
    /// Δs [m].
    pub spacing: f64,
    /// Support radius r_e [m].
    pub radius: f64,
    /// 1 / r_e [1/m].
    inv_radius: f64,
    /// Particle volume V = Δs³ [m³].
    pub volume: f64,
    /// `Σ_j V W_ij` on the full lattice, self included: the ρ̂/ρ0 of a full neighbourhood.
    pub lattice_density: f64,
    /// The moment matrix's value on the full lattice (see [`crate::neighbours::moments`]); 1 after the
    /// renormalisation.
    pub lattice_moment: f64,
    /// `1/m0` of the raw kernel (module doc).
    gradient_scale: f64,
    /// W's factor `21/(2π r_e³)` and W'/r's `−210/(π r_e⁵ m0)`, computed once (the passes call
    /// the kernel about 60 times per particle).
    w_factor: f64,
    dw_factor: f64,
}

impl Wendland {
    /// The kernel with support `radius_in_spacings` Δs.
    pub fn new(spacing: f64, radius_in_spacings: f64) -> Wendland {
        let mut k = Wendland {
            spacing,
            radius: radius_in_spacings * spacing,
            inv_radius: 1.0 / (radius_in_spacings * spacing),
            volume: spacing.powi(3),
            lattice_density: 1.0,
            lattice_moment: 1.0,
            gradient_scale: 1.0,
            w_factor: 0.0,
            dw_factor: 0.0,
        };
        k.set_factors();
        let reach = radius_in_spacings.ceil() as i32;
        let mut sum = 0.0;
        for i in -reach..=reach {
            for j in -reach..=reach {
                for l in -reach..=reach {
                    let r = spacing * f64::from(i * i + j * j + l * l).sqrt();
                    sum += k.volume * k.w(r);
                }
            }
        }
        k.lattice_density = sum;
        k.gradient_scale = 1.0 / lattice_moment(&k, spacing);
        k.set_factors();
        k.lattice_moment = lattice_moment(&k, spacing);
        k
    }

    /// Computes [`Self::w_factor`] and [`Self::dw_factor`] from the radius and gradient scale.
    fn set_factors(&mut self) {
        self.w_factor = 21.0 / (2.0 * std::f64::consts::PI * self.radius.powi(3));
        self.dw_factor = -210.0 * self.gradient_scale / (std::f64::consts::PI * self.radius.powi(5));
    }

    /// q = r / r_e, the distance as the kernel reads it (the neighbour list keeps it per pair, so
    /// the passes do not divide: about 5 kernel calls per pair per step).
    #[inline(always)]
    pub fn q(&self, r: f64) -> f64 {
        r * self.inv_radius
    }

    /// W(r) (0 beyond the support).
    #[inline(always)]
    pub fn w(&self, r: f64) -> f64 {
        self.w_at(self.q(r))
    }

    /// W at q = r / r_e.
    #[inline(always)]
    pub fn w_at(&self, q: f64) -> f64 {
        if q < 1.0 {
            let a = 1.0 - q;
            self.w_factor * a * a * a * a * (1.0 + 4.0 * q)
        } else {
            0.0
        }
    }

    /// W'(r)/r, renormalised on the lattice (module doc; 0 beyond the support);
    /// ∇_i W_ij = (W'/r)(x_i − x_j).
    #[inline(always)]
    pub fn dw_over_r(&self, r: f64) -> f64 {
        self.dw_over_r_at(self.q(r))
    }

    /// W'(r)/r at q = r / r_e, renormalised as [`Self::dw_over_r`].
    #[inline(always)]
    pub fn dw_over_r_at(&self, q: f64) -> f64 {
        if q < 1.0 {
            let a = 1.0 - q;
            self.dw_factor * a * a * a
        } else {
            0.0
        }
    }
}

impl RadialGradient for Wendland {
    fn radius(&self) -> f64 {
        self.radius
    }
    fn gradient_over_r(&self, r: f64) -> f64 {
        self.dw_over_r(r)
    }
}
