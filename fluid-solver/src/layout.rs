//! The initial particle layout of a case: tank walls, water blocks, gates and bodies on one
//! simple cubic lattice of spacing Δs.
//!
//! Lattice sites are `tank.min + (i + ½) Δs`; the tank's inner faces lie half a spacing from the
//! nearest sites. Sites outside the tank within `wall_layers` layers are walls: the two layers
//! next to the tank are [`Kind::Wall`] (they carry pressure), the outer ones [`Kind::Dummy`].
//! Sites inside the tank whose centre is inside a gate, a body or a water block get that kind.

use crate::kind::Kind;
use crate::particles::Particles;
use schemas::case::fluid::{Aabb, FluidConfig};

/// Wall layers that carry pressure: a fluid particle half a spacing off the wall reaches
/// r_e,grad = 2.1 Δs, i.e. wall centres 0.5 Δs and 1.5 Δs deep.
pub const PRESSURE_LAYERS: i64 = 2;

/// The box particles must stay in: the walls' outer faces, and above an open tank a headroom
/// of one tank height for splashes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    pub lo: [f64; 3],
    pub hi: [f64; 3],
}

/// The particles of one rigid body, by particle id.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyParticles {
    pub name: String,
    pub ids: Vec<u32>,
}

/// The initial state built from a case section.
#[derive(Debug, Clone)]
pub struct Layout {
    pub particles: Particles,
    pub domain: Domain,
    pub tank: Aabb,
    pub bodies: Vec<BodyParticles>,
}

/// Builds the lattice layout of `cfg` (already validated).
pub fn build(cfg: &FluidConfig) -> Layout {
    let ds = cfg.spacing;
    let tank = cfg.tank.inner();
    let layers = i64::from(cfg.wall_layers);
    let n: [i64; 3] = std::array::from_fn(|a| ((tank.max[a] - tank.min[a]) / ds).round() as i64);
    let top = if cfg.tank.lid { n[2] + layers } else { n[2] };
    let mut particles = Particles::default();
    let mut bodies: Vec<BodyParticles> =
        cfg.body.iter().map(|b| BodyParticles { name: b.name.clone(), ids: Vec::new() }).collect();
    let boxes_of_bodies: Vec<Aabb> = cfg.body.iter().map(|b| Aabb { min: b.min, max: b.max }).collect();
    for k in -layers..top {
        for j in -layers..n[1] + layers {
            for i in -layers..n[0] + layers {
                let idx = [i, j, k];
                let p: [f64; 3] = std::array::from_fn(|a| tank.min[a] + (idx[a] as f64 + 0.5) * ds);
                let depth = (0..3).map(|a| (-idx[a]).max(idx[a] - n[a] + 1)).max().unwrap_or(0);
                if depth > 0 {
                    let kind = if depth <= PRESSURE_LAYERS { Kind::Wall } else { Kind::Dummy };
                    particles.push(p, kind);
                } else if cfg.gate.iter().any(|g| g.contains_point(p)) {
                    particles.push(p, Kind::Gate);
                } else if let Some(b) = boxes_of_bodies.iter().position(|b| b.contains_point(p)) {
                    bodies[b].ids.push(particles.len() as u32);
                    particles.push(p, Kind::Body);
                } else if cfg.block.iter().any(|b| b.contains_point(p)) {
                    particles.push(p, Kind::Fluid);
                }
            }
        }
    }
    let l = layers as f64 * ds;
    let height = tank.max[2] - tank.min[2];
    let domain = Domain {
        lo: std::array::from_fn(|a| tank.min[a] - l),
        hi: [tank.max[0] + l, tank.max[1] + l, tank.max[2] + if cfg.tank.lid { l } else { height }],
    };
    Layout { particles, domain, tank, bodies }
}
