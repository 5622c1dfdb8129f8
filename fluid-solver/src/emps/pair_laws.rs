//! The E-MPS fluid–body pair laws: the pair terms of S1-3 (pressure) and S1-4 (viscosity)
//! between a fluid particle i and a body particle j, as force on j (the fluid gets the reverse).
//! Body particles carry pressure like walls (S1-14) and fill the fluid's number density (S1-15).

use super::kernel::{weight, weight_grad, Kernel};
use crate::bodies::pair_law::{ExchangeScales, PairLaw};
use crate::particles::Particles;

/// S1-3's pressure pair force on body particle j from fluid particle i (r_ij = r_j − r_i):
/// `Δs³ d/n0_grad (P_i + P_j) r_ij/|r_ij|² w_grad(|r_ij|)`, nothing beyond r_e,grad.
pub fn pressure<'a>(kernel: &Kernel, p: &'a Particles) -> PairLaw<'a> {
    let re = kernel.re_grad;
    // Particle volume m/ρ0 = Δs³ times S1-3's d/n0_grad.
    let scale = kernel.spacing.powi(3) * kernel.gradient_factor();
    PairLaw::new(re, move |i, j| {
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < re * re && r2 > 0.0) {
            return None;
        }
        let c = scale * (p.pressure[i] + p.pressure[j]) * weight_grad(r2.sqrt(), re) / r2;
        Some(d.map(|v| c * v))
    })
}

/// S1-4's viscous pair force on body particle j from fluid particle i,
/// `−m ν 2d/(λ0 n0) (u_j − u_i) w(|r_ij|)` (w of S1-6 with r_e), nothing beyond r_e.
pub fn viscous<'a>(kernel: &Kernel, scales: &ExchangeScales, p: &'a Particles) -> PairLaw<'a> {
    let re = kernel.re;
    let scale = -scales.particle_mass * scales.viscosity * kernel.laplacian_factor();
    PairLaw::new(re, move |i, j| {
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < re * re && r2 > 0.0) {
            return None;
        }
        let c = scale * weight(r2.sqrt(), re);
        Some([
            c * (p.vx[j] - p.vx[i]),
            c * (p.vy[j] - p.vy[i]),
            c * (p.vz[j] - p.vz[i]),
        ])
    })
}
