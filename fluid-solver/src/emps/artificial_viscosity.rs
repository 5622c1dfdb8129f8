//! Optional artificial viscosity of E-MPS (`artificial_viscosity = α`, issue 15: the
//! step-to-step pressure noise and the raw impact peaks at wall sensors).
//!
//! The remedy is Monaghan's artificial viscosity of weakly compressible SPH (Monaghan 1992,
//! "Smoothed particle hydrodynamics", Annu. Rev. Astron. Astrophys. 30, 543–574, eq. 4.2), the
//! term WCSPH codes damp their acoustic noise with:
//! `Π_ij = −α c μ_ij / ρ0` for approaching pairs (u_ij · r_ij < 0), else 0, with
//! `μ_ij = h u_ij · r_ij / (|r_ij|² + 0.01 h²)`. In the SPH momentum equation Π_ij stands
//! where `(P_i + P_j)/ρ²` stands, so in S1-3's form it is a pair pressure
//!
//! `q_ij = −α ρ0 c μ_ij ≥ 0`, `⟨∇q⟩_i = d/n0_grad Σ_j q_ij r_ij/|r_ij|² w_grad(|r_ij|)`,
//!
//! added to ⟨∇P⟩_i in S1-12 (`u^{k+1} = u* − Δt/ρ0 (⟨∇P⟩ + ⟨∇q⟩)`), with h = r_e,grad / 2 (SPH's
//! support is 2h) and u, r at the predicted state (u*, r*). Only fluid–fluid pairs take part: the
//! walls and bodies still receive exactly S1-3's pressure pair force, which is what the wall
//! sensors and the bodies' loads read. Each pair term is antisymmetric, so momentum is
//! conserved; it only removes kinetic energy of approaching neighbours. Off (α = 0) by default;
//! WCSPH codes use α ≈ 0.01 … 0.1.
//!
//! Measured (`cases/dam-break-obstacle/README.md`): on the obstacle dam break's sensor P1 it
//! halves the step-to-step noise after the first impact at Δs = 0.04 m (0.91 → 0.45 kPa at
//! α = 0.01, 0.39 kPa at 0.05) but not at 0.08 m (0.65 → 0.58, 0.68 kPa), and it moves the impact
//! peak by −50 % to +25 % without a trend in α: not a reliable remedy for impact peaks at these
//! resolutions. On a tank at rest it leaves the floor load (+0.55 %) and the noise (× 0.99).

use super::kernel::Kernel;
use crate::neighbours::neighbour_search::CellGrid;
use crate::neighbours::vector_field::VectorField;
use crate::particles::kind::FLUID;
use crate::particles::Particles;
use rayon::prelude::*;

/// Adds `⟨∇q⟩_i` (see the module doc) to `grad` for every fluid particle, with the sound speed
/// `c` and the density `rho0`. Returns the candidates examined.
pub fn add_gradient(
    grid: &CellGrid,
    kernel: &Kernel,
    p: &Particles,
    alpha: f64,
    rho0: f64,
    c: f64,
    grad: &mut VectorField,
) -> u64 {
    let re = kernel.re_grad;
    let re2 = re * re;
    let inv_re = 1.0 / re;
    let h = 0.5 * re;
    let eta2 = 0.01 * h * h;
    // q_ij = −α ρ0 c h (u_ij · r_ij) / (r² + η²) for approaching pairs, times d/n0_grad.
    let scale = -alpha * rho0 * c * h * kernel.gradient_factor();
    let reach = grid.reach(re);
    let (x, y, z, kind) = (&p.x, &p.y, &p.z, &p.kind);
    let (vx, vy, vz) = (&p.vx, &p.vy, &p.vz);
    (&mut grad.x, &mut grad.y, &mut grad.z)
        .into_par_iter()
        .enumerate()
        .with_min_len(256)
        .map(|(i, (gx, gy, gz))| {
            if kind[i] != FLUID {
                return 0;
            }
            let (xi, yi, zi) = (x[i], y[i], z[i]);
            let (ui, vi, wi) = (vx[i], vy[i], vz[i]);
            let mut g = [0.0; 3];
            let mut seen = 0u64;
            grid.for_each_range(i, reach, |s, e| {
                seen += (e - s) as u64;
                for j in s..e {
                    let (dx, dy, dz) = (x[j] - xi, y[j] - yi, z[j] - zi);
                    let r2 = dx * dx + dy * dy + dz * dz;
                    let approach = (vx[j] - ui) * dx + (vy[j] - vi) * dy + (vz[j] - wi) * dz;
                    if !(r2 < re2 && r2 > 0.0 && kind[j] == FLUID && approach < 0.0) {
                        continue;
                    }
                    let r = r2.sqrt();
                    let q = scale * approach / (r2 + eta2);
                    let c = q * (re / r - r * inv_re) / r2;
                    g[0] += c * dx;
                    g[1] += c * dy;
                    g[2] += c * dz;
                }
            });
            *gx += g[0];
            *gy += g[1];
            *gz += g[2];
            seen
        })
        .sum()
}
