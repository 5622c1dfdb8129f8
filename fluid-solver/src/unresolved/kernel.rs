//! The kernel of the unresolved coupling's interpolation and spreading: Wendland's C2 function
//! in 3D (Wendland 1995, Adv. Comput. Math. 4), `W(r) = 21/(2π R³) (1 − q)⁴ (1 + 4q)`, q = r/R,
//! with support R = 2.4 Δs (S2 Table 1's influence radius). It is smooth, positive inside its
//! support and integrates to one, so the moment matrix of a full support is the identity
//! (S2-10 … S2-13) and a flat free surface gives λ_min = 0.5. The E-MPS weights (S1-5, S1-6) are
//! singular at r = 0 and would put a whole reaction on a particle that happens to sit on the
//! centroid; this kernel does not.

use std::f64::consts::PI;

/// Support radius in particle spacings (S2 Table 1; the contract's value).
pub const SUPPORT_IN_SPACINGS: f64 = schemas::case::drag::KERNEL_SUPPORT_IN_SPACINGS;

/// Wendland C2 with support `radius`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wendland {
    pub radius: f64,
    norm: f64,
}

impl Wendland {
    /// The kernel for particles of spacing `spacing`.
    pub fn for_spacing(spacing: f64) -> Wendland {
        Wendland::new(SUPPORT_IN_SPACINGS * spacing)
    }

    /// The kernel with support `radius`.
    pub fn new(radius: f64) -> Wendland {
        Wendland {
            radius,
            norm: 21.0 / (2.0 * PI * radius.powi(3)),
        }
    }

    /// W(r).
    #[inline]
    pub fn value(&self, r: f64) -> f64 {
        let q = r / self.radius;
        if q >= 1.0 {
            0.0
        } else {
            self.norm * (1.0 - q).powi(4) * (1.0 + 4.0 * q)
        }
    }

    /// W(r) and dW/dr together (the same operations as [`Wendland::value`] and
    /// [`Wendland::derivative`], q computed once).
    #[inline]
    pub fn value_and_derivative(&self, r: f64) -> (f64, f64) {
        let q = r / self.radius;
        if q >= 1.0 {
            (0.0, 0.0)
        } else {
            (
                self.norm * (1.0 - q).powi(4) * (1.0 + 4.0 * q),
                -20.0 * self.norm * q * (1.0 - q).powi(3) / self.radius,
            )
        }
    }

    /// dW/dr (≤ 0).
    #[inline]
    pub fn derivative(&self, r: f64) -> f64 {
        let q = r / self.radius;
        if q >= 1.0 {
            0.0
        } else {
            -20.0 * self.norm * q * (1.0 - q).powi(3) / self.radius
        }
    }
}
