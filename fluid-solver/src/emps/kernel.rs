//! MPS weight functions (S1-5, S1-6) and the lattice constants n0_grad, n0, λ0 (S1-7, S1-8).

/// Space dimension d.
pub const DIM: f64 = 3.0;
/// Influence radius of the gradient, in spacings (r_e = 2.1 Δs).
pub const RE_GRAD_IN_SPACINGS: f64 = 2.1;
/// Influence radius of the number density and the Laplacian, in spacings (r_e = 3.1 Δs).
pub const RE_IN_SPACINGS: f64 = 3.1;

/// S1-5: `w_grad(r) = r_e/r − r/r_e` for 0 < r < r_e, else 0.
#[inline(always)]
pub fn weight_grad(r: f64, re: f64) -> f64 {
    if r > 0.0 && r < re {
        re / r - r / re
    } else {
        0.0
    }
}

/// S1-6 as read in docs/physics.md: `w(r) = r_e/r + r/r_e − 2 = (r_e − r)²/(r r_e)` for 0 < r < r_e, else 0.
#[inline(always)]
pub fn weight(r: f64, re: f64) -> f64 {
    if r > 0.0 && r < re {
        (re - r) * (re - r) / (r * re)
    } else {
        0.0
    }
}

/// Radii and the reference sums of the E-MPS operators for one spacing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kernel {
    /// Δs [m].
    pub spacing: f64,
    /// r_e of the gradient [m].
    pub re_grad: f64,
    /// r_e of the number density and the Laplacian [m].
    pub re: f64,
    /// S1-7: Σ_j w_grad on the lattice.
    pub n0_grad: f64,
    /// S1-8: Σ_j w on the lattice.
    pub n0: f64,
    /// λ0 = Σ_j r² w / Σ_j w on the lattice (Laplacian correction of S1-4).
    pub lambda0: f64,
}

impl Kernel {
    /// Computes n0_grad, n0 and λ0 on a simple cubic lattice of spacing `spacing`.
    pub fn new(spacing: f64) -> Kernel {
        let re_grad = RE_GRAD_IN_SPACINGS * spacing;
        let re = RE_IN_SPACINGS * spacing;
        let reach = RE_IN_SPACINGS.ceil() as i32;
        let (mut n0_grad, mut n0, mut r2w) = (0.0, 0.0, 0.0);
        for i in -reach..=reach {
            for j in -reach..=reach {
                for k in -reach..=reach {
                    let r = spacing * f64::from(i * i + j * j + k * k).sqrt();
                    n0_grad += weight_grad(r, re_grad);
                    let w = weight(r, re);
                    n0 += w;
                    r2w += r * r * w;
                }
            }
        }
        Kernel {
            spacing,
            re_grad,
            re,
            n0_grad,
            n0,
            lambda0: r2w / n0,
        }
    }

    /// S1-3's factor d / n0_grad.
    pub fn gradient_factor(&self) -> f64 {
        DIM / self.n0_grad
    }

    /// S1-4's factor 2d / (λ0 n0).
    pub fn laplacian_factor(&self) -> f64 {
        2.0 * DIM / (self.lambda0 * self.n0)
    }
}
