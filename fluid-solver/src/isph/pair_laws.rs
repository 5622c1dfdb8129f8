//! The ISPH fluid–body pair laws, as force on body particle j from fluid particle i (the fluid
//! gets the reverse in the exchange's bookkeeping). Pressure: the symmetric pair term
//! `V² (p_i + p_j^(i)) ∇_i W_ij`, antisymmetric in the pair, so a body's load is
//! `−Σ_body V ⟨∇p⟩` (buoyancy on a submerged body, ρgV) and walls' loads sum to the water's
//! weight; the fluid's own acceleration uses S2-8's corrected difference form instead
//! ([`super::operators::pressure_gradient`], which says why). Viscous, with no-slip walls: the
//! pair terms of [`super::operators::laplacian`]. Body particles carry the pressure
//! extrapolated onto them ([`super::walls`]) for outputs; the pair laws read the per-pair
//! pressure `p_i + Δp_ij` that fluid particle i's PPE saw.

use super::kernel::Wendland;
use super::walls::NeumannPair;
use crate::pair_law::{ExchangeScales, PairLaw};
use crate::particles::Particles;

/// `V² (p_i + p_j^(i)) ∇_i W_ij`, p_j^(i) = p_i + Δp_ij the body particle's pressure as fluid
/// particle i's PPE saw it ([`super::walls`]): the reverse of the fluid's pressure force from j.
pub fn pressure<'a>(k: &Wendland, walls: NeumannPair<'a>) -> PairLaw<'a> {
    let k = *k;
    let p = walls.p;
    PairLaw::new(k.radius, move |i, j| {
        let d = [p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < k.radius * k.radius && r2 > 0.0) {
            return None;
        }
        let c = k.volume * k.volume * (2.0 * p.pressure[i] + walls.difference(i, j)) * k.dw_over_r(r2.sqrt());
        Some(d.map(|v| c * v))
    })
}

/// `−m ν F_ij (v_j − v_i)`, F_ij = −2 V W'/r: the reverse of the fluid's viscous force from j.
pub fn viscous<'a>(k: &Wendland, scales: &ExchangeScales, p: &'a Particles) -> PairLaw<'a> {
    let k = *k;
    let m_nu = scales.particle_mass * scales.viscosity;
    PairLaw::new(k.radius, move |i, j| {
        let d = [p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if !(r2 < k.radius * k.radius && r2 > 0.0) {
            return None;
        }
        let c = m_nu * 2.0 * k.volume * k.dw_over_r(r2.sqrt());
        Some([
            c * (p.vx[j] - p.vx[i]),
            c * (p.vy[j] - p.vy[i]),
            c * (p.vz[j] - p.vz[i]),
        ])
    })
}
