//! Contact between a rigid body's particles and the walls (the particle-based contact of S2 §3(2)
//! applied to resolved bodies): without it a released body heavier than the water it displaces,
//! such as a bridge deck of ρ_g = 3000 kg/m³, would sink through its piers and the river bed.
//!
//! A body particle j closer than one spacing Δs to a wall or dummy particle w (particles of a
//! body resting on a wall sit exactly Δs from its first layer) gets a spring–dashpot force along
//! `n = (r_j − r_w)/|r_j − r_w|`: `f = max(0, k (Δs − |r_j − r_w|) − c (u_j · n)) n`, with
//! `k = m ω²` and `c = 2 m ω` (critical damping) for the particle mass m = ρ0 Δs³ and
//! `ω = 2π / (CONTACT_PERIOD_STEPS Δt)`: a particle of water's mass on one contact would bounce
//! with a period of that many steps, which keeps the explicit exchange well inside its stability
//! limit ωΔt < 2 for any body at least as heavy per particle as water, and a body of N particles
//! resting on N_c contacts sinks in by `N g / (N_c ω²)` times its density ratio to water.
//! The walls are fixed: the reaction goes into them (it is part of the fluid participant's
//! reaction, which the coupler's ledger balances against the body's load).

use crate::bodies::pair_law::ExchangeScales;
use crate::bodies::RigidBodies;
use crate::neighbours::neighbour_search::CellGrid;
use crate::particles::kind::{DUMMY, WALL};
use crate::particles::Particles;

/// Steps per period of one water-mass particle on one contact spring.
pub const CONTACT_PERIOD_STEPS: f64 = 10.0;

impl RigidBodies {
    /// Force and moment about `centres` of the walls' contact on each body (6 per body).
    pub fn wall_contact_loads(
        &self,
        grid: &CellGrid,
        p: &Particles,
        centres: &[f64],
        scales: &ExchangeScales,
    ) -> Vec<f64> {
        let is_wall = |w: usize| p.kind[w] == WALL || p.kind[w] == DUMMY;
        self.body_side_sum(
            grid,
            p,
            scales.spacing,
            centres,
            |j| self.counts_body_particle(p, j),
            is_wall,
            wall_contact_pair(scales, p),
        )
    }
}

/// The contact force on body particle j from wall particle w (module doc), or `None` when they
/// are at least Δs apart or the dashpot would pull them together.
fn wall_contact_pair<'a>(
    scales: &ExchangeScales,
    p: &'a Particles,
) -> impl Fn(usize, usize) -> Option<[f64; 3]> + Sync + 'a {
    let reach = scales.spacing;
    let omega = 2.0 * std::f64::consts::PI / (CONTACT_PERIOD_STEPS * scales.dt);
    let stiffness = scales.particle_mass * omega * omega;
    let damping = 2.0 * scales.particle_mass * omega;
    move |w, j| {
        let d = [p.x[j] - p.x[w], p.y[j] - p.y[w], p.z[j] - p.z[w]];
        let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(r < reach && r > 0.0) {
            return None;
        }
        let n = d.map(|v| v / r);
        let closing = p.vx[j] * n[0] + p.vy[j] * n[1] + p.vz[j] * n[2];
        let magnitude = stiffness * (reach - r) - damping * closing;
        (magnitude > 0.0).then(|| n.map(|v| magnitude * v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particles::kind::Kind;

    fn two_particles(gap: f64, body_velocity: f64) -> Particles {
        let mut p = Particles::default();
        p.push([0.0, 0.0, 0.0], Kind::Wall);
        p.push_moving([0.0, 0.0, gap], [0.0, 0.0, body_velocity], Kind::Body, 1);
        p
    }

    fn scales() -> ExchangeScales {
        ExchangeScales {
            spacing: 1.0,
            particle_mass: 2.0,
            viscosity: 0.0,
            dt: 0.1,
        }
    }

    #[test]
    fn the_spring_pushes_the_body_out_of_the_wall_by_k_times_the_overlap() {
        let p = two_particles(0.75, 0.0);
        let f = wall_contact_pair(&scales(), &p)(0, 1).expect("in contact");
        // k = m ω², ω = 2π/(10 Δt) = 2π rad/s: k = 2 · 4π², overlap 0.25
        let expected = 2.0 * 4.0 * std::f64::consts::PI.powi(2) * 0.25;
        assert!((f[2] - expected).abs() < 1e-12 * expected, "{f:?} vs {expected}");
        assert_eq!((f[0], f[1]), (0.0, 0.0));
    }

    #[test]
    fn a_body_particle_one_spacing_away_or_leaving_fast_feels_nothing() {
        assert!(wall_contact_pair(&scales(), &two_particles(1.0, 0.0))(0, 1).is_none());
        // overlap 0.05: spring 3.9 N, dashpot 2 m ω u = 25 N for u = 1 m/s away from the wall
        assert!(wall_contact_pair(&scales(), &two_particles(0.95, 1.0))(0, 1).is_none());
    }

    #[test]
    fn an_approaching_body_particle_is_damped() {
        let still = wall_contact_pair(&scales(), &two_particles(0.9, 0.0))(0, 1).expect("in contact");
        let coming = wall_contact_pair(&scales(), &two_particles(0.9, -1.0))(0, 1).expect("in contact");
        // c = 2 m ω = 8π N s/m, times 1 m/s
        let extra = 8.0 * std::f64::consts::PI;
        assert!((coming[2] - still[2] - extra).abs() < 1e-12 * extra);
    }
}
